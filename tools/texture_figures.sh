#!/usr/bin/env bash
# Renders the figures of docs/textures.md: the textured, bump-mapped Cornell
# box (scenes/cornell-textured) by every method, to compare with `path`.
# Usage: tools/texture_figures.sh [build-dir]
#
# 256 × 256, the same linear display mapping for all. Methods that read a
# solution share one (hierarchical, the default), saved once.
source "$(dirname "$0")/figures_common.sh"
scene="$here/scenes/cornell-textured/scene.json"
common=(--width 256 --height 256 -q)

"$radiant" solve "$scene" -o "$work/box.rad" -q
"$radiant" render "$scene" "${common[@]}" --spp 1024 -o "$out/textures-path.png"
for method in flat interpolate; do
  "$radiant" render "$scene" "${common[@]}" --method "$method" --solution "$work/box.rad" --spp 4 -o "$out/textures-$method.png"
done
for method in rushmeier shirley kok; do
  "$radiant" render "$scene" "${common[@]}" --method "$method" --solution "$work/box.rad" --spp 64 -o "$out/textures-$method.png"
done
"$radiant" render "$scene" "${common[@]}" --method reichert --solution "$work/box.rad" --spp 8 -o "$out/textures-reichert.png"
