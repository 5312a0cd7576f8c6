#!/usr/bin/env bash
# Renders the figures and the mean-colour table of docs/spectral.md:
# the spectral Cornell box (16 wavelengths) next to its colours run in RGB
# (--colour rgb) and next to the RGB Cornell box, with and without the
# equal-energy white balance. Usage: tools/spectral_figures.sh [build-dir]
#
# Every image is the path tracer at 256 spp, 256 × 256, shown with the same
# linear mapping (exposure 0), so brightness and colour compare directly.
source "$(dirname "$0")/figures_common.sh"
spectral="$here/scenes/cornell-box-spectral/scene.json"
rgb="$here/scenes/cornell-box/scene.json"
common=(--spp 256 --width 256 --height 256 -q)

render() {  # name scene [flags…]
  local name=$1 scene=$2
  shift 2
  "$radiant" render "$scene" "${common[@]}" "$@" -o "$work/$name.exr" -o "$out/spectral-$name.png"
}
render rgb-box "$rgb"
render box "$spectral"
render box-as-rgb "$spectral" --colour rgb
render box-balanced "$spectral" --white-balance equal-energy
render box-as-rgb-balanced "$spectral" --colour rgb --white-balance equal-energy
"$radiant" render "$spectral" --method interpolate --width 256 --height 256 -q -o "$out/spectral-box-interpolate.png"

ratios() {  # test reference: mean ratio per channel
  "$radiant" compare "$work/$1.exr" "$work/$2.exr" --json |
    python3 -c 'import json,sys; d=json.load(sys.stdin); print(" | ".join("%.3f" % d[c]["mean_ratio"] for c in "RGB"))'
}
echo "| spectral image | against | R | G | B |"
echo "|---|---|---|---|---|"
echo "| box | box-as-rgb | $(ratios box box-as-rgb) |"
echo "| box-balanced | box-as-rgb-balanced | $(ratios box-balanced box-as-rgb-balanced) |"
echo "| box | rgb-box | $(ratios box rgb-box) |"
echo "| box-balanced | rgb-box | $(ratios box-balanced rgb-box) |"
echo "| box-as-rgb | rgb-box | $(ratios box-as-rgb rgb-box) |"
