#!/usr/bin/env bash
# Renders the figures of docs/tone-mapping.md into docs/images/: the Cornell box
# under every tone operator, the firefly/searchlight pair and the false-colour
# maps. Usage: tools/tonemap_figures.sh [build-dir]   (default: build)
#
# The box is rendered once (path tracer, 256 spp, 256 × 256) to a linear EXR;
# every picture is `radiant tonemap` of that one file. The firefly and the
# searchlight are the same EXR with --scale 1e-4 and 1e4: the scene is linear in
# its emission, so scaling every emitter by s scales every radiance by s, which
# is exactly what --scale does to the image.
source "$(dirname "$0")/figures_common.sh"
scene="$here/scenes/cornell-box/scene.json"

"$radiant" render "$scene" --spp 256 --width 256 --height 256 -o "$work/box.exr" -q

for operator in linear max-reflected tumblin-rushmeier ward reinhard aces; do
  "$radiant" tonemap "$work/box.exr" --tonemap "$operator" -o "$out/tonemap-$operator.png" -q
done
"$radiant" tonemap "$work/box.exr" --tonemap linear --exposure auto -o "$out/tonemap-linear-auto.png" -q

for operator in max-reflected tumblin-rushmeier ward; do
  "$radiant" tonemap "$work/box.exr" --scale 1e-4 --tonemap "$operator" -o "$out/tonemap-firefly-$operator.png" -q
  "$radiant" tonemap "$work/box.exr" --scale 1e4 --tonemap "$operator" -o "$out/tonemap-searchlight-$operator.png" -q
done

"$radiant" tonemap "$work/box.exr" --falsecolor --legend -o "$out/tonemap-falsecolor.png" -q
"$radiant" tonemap "$work/box.exr" --falsecolor --legend --log -o "$out/tonemap-falsecolor-log.png" -q
echo "wrote $out/tonemap-*.png"
