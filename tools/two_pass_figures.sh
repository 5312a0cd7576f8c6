#!/usr/bin/env bash
# Renders the figures of docs/two-pass.md into docs/images/ (needs ImageMagick's
# `convert`). Usage: tools/two_pass_figures.sh [build-dir]   (default: build)
source "$(dirname "$0")/figures_common.sh"
scene="$here/scenes/cornell-box/scene.json"
size=(--width 256 --height 256 -q)

"$radiant" solve "$scene" --solver progressive --mesh-size 40 -o "$work/fine.rad" -q
"$radiant" solve "$scene" --solver progressive --mesh-size 100 -o "$work/coarse.rad" -q

"$radiant" render "$scene" --method path --spp 1024 "${size[@]}" -o "$work/path.png"
"$radiant" render "$scene" --method interpolate --solution "$work/fine.rad" --spp 4 "${size[@]}" -o "$work/interpolate.png"
for method in rushmeier shirley kok; do
  "$radiant" render "$scene" --method "$method" --solution "$work/fine.rad" --spp 64 "${size[@]}" -o "$work/$method.png"
done
"$radiant" render "$scene" --method reichert --ff point --solution "$work/fine.rad" --spp 4 "${size[@]}" \
  -o "$work/reichert.png"
convert "$work"/{path,interpolate,rushmeier,reichert,shirley,kok}.png +append "$out/two-pass-methods.png"

for ff in point mc; do
  "$radiant" render "$scene" --method reichert --ff "$ff" --solution "$work/coarse.rad" --spp 4 "${size[@]}" \
    -o "$work/reichert-$ff.png"
done
convert "$work"/reichert-{point,mc}.png +append "$out/two-pass-reichert-ff.png"

"$radiant" render "$scene" --method shirley --solution "$work/fine.rad" --selective --selective-map "$work/elements.png" \
  --spp 1 --width 256 --height 256 -o "$work/selective.png"
"$radiant" render "$scene" --method reichert --selective --selective-map "$work/links.png" \
  --spp 1 --width 256 --height 256 -o "$work/links-image.png"
convert "$work"/{elements,links}.png +append "$out/two-pass-selective.png"
specular="$here/scenes/cornell-specular/scene.json"
small=(--width 128 --height 128 -q)
"$radiant" render "$specular" --method path --spp 256 "${small[@]}" -o "$work/specular-path.png"
for method in rushmeier shirley kok; do
  "$radiant" render "$specular" --method "$method" --spp 32 "${small[@]}" -o "$work/specular-$method.png"
done
convert "$work"/specular-{path,rushmeier,shirley,kok}.png +append -scale 150% "$out/two-pass-specular.png"
echo "wrote $out/two-pass-methods.png, two-pass-reichert-ff.png, two-pass-selective.png, two-pass-specular.png"
