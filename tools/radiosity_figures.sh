#!/usr/bin/env bash
# Renders the figures of docs/radiosity.md's "Accuracy of the default
# solution" into docs/images/ (needs ImageMagick's `convert`): the Cornell box
# and the two-rooms leak scene, each as the default `interpolate` image
# beside `path` and their difference (blue darker, red brighter, ±10 %).
# Usage: tools/radiosity_figures.sh [build-dir]   (default: build)
source "$(dirname "$0")/figures_common.sh"
size=(--width 256 --height 256 -q)

box="$here/scenes/cornell-box/scene.json"
"$radiant" render "$box" --method path --spp 4096 "${size[@]}" -o "$work/box-path.exr" -o "$work/box-path.png"
"$radiant" render "$box" --method interpolate "${size[@]}" -o "$work/box-default.exr" -o "$work/box-default.png"
"$radiant" render "$box" --method interpolate --solver hierarchical "${size[@]}" -o "$work/box-hsa.exr" \
  -o "$work/box-hsa.png"
"$radiant" compare "$work/box-default.exr" "$work/box-path.exr" --diff "$work/box-diff.png" > /dev/null
"$radiant" compare "$work/box-hsa.exr" "$work/box-path.exr" --diff "$work/box-hsa-diff.png" > /dev/null
convert "$work"/box-{default,path,diff}.png +append "$out/radiosity-default-cornell.png"
convert "$work"/box-{hsa,hsa-diff}.png +append "$out/radiosity-hsa-cornell.png"

rooms="$here/scenes/two-rooms/scene.json"
dark=(--eye 3900,1300,100 --target 3000,1150,2500)
"$radiant" render "$rooms" --method path --spp 1024 "${size[@]}" -o "$work/rooms-path.exr" -o "$work/rooms-path.png"
"$radiant" render "$rooms" --method interpolate "${size[@]}" -o "$work/rooms-default.exr" -o "$work/rooms-default.png"
"$radiant" compare "$work/rooms-default.exr" "$work/rooms-path.exr" --diff "$work/rooms-diff.png" > /dev/null
# The dark room, exposed 8 stops up so that any leak would show.
"$radiant" render "$rooms" --method interpolate "${dark[@]}" --exposure 8 "${size[@]}" -o "$work/dark-default.png"
"$radiant" render "$rooms" --method interpolate --solver hierarchical "${dark[@]}" --exposure 8 "${size[@]}" \
  -o "$work/dark-hsa.png"
convert "$work"/rooms-{default,path,diff}.png +append "$out/radiosity-default-rooms.png"
convert "$work"/dark-{default,hsa}.png +append "$out/radiosity-dark-room.png"
echo "wrote $out/radiosity-default-cornell.png, radiosity-hsa-cornell.png, radiosity-default-rooms.png," \
  "radiosity-dark-room.png"
