#!/usr/bin/env bash
# Renders the figures of docs/multipass.md: the specular Cornell box by
# --method multipass for 60 s, every pass written, beside path for 60 s.
# Usage: tools/multipass_figures.sh [build-dir]
source "$(dirname "$0")/figures_common.sh"
scene="$here/scenes/cornell-specular/scene.json"
"$radiant" render "$scene" --method multipass --time 60 --width 256 --height 256 -o "$work/mp.png" 2>&1 | grep "radiant: multipass"
for pass in 1 2 4 8; do cp "$work/mp.pass$pass.png" "$out/multipass-pass$pass.png"; done
cp "$work/mp.png" "$out/multipass-final.png"
"$radiant" render "$scene" --time 60 --width 256 --height 256 -o "$out/multipass-path-60s.png" -q
