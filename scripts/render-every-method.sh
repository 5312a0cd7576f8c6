#!/bin/bash
# scripts/render-every-method.sh RADIANT OUTDIR — renders the bundled scenes with every method at
# a fixed seed and sample count (small images), for before/after comparisons:
# cmp the EXRs of two OUTDIRs (or `radiant compare`).
set -e
R=$1; O=$2; mkdir -p "$O"
S=$(cd "$(dirname "$0")/.." && pwd)/scenes
common="--width 64 --height 64 --seed 7 --threads 2 -q"
for scene in cornell-box cornell-textured cornell-specular two-rooms; do
  f=$S/$scene/scene.json
  "$R" solve "$f" --quality draft -o "$O/$scene.sol" -q 2>/dev/null || "$R" solve "$f" --quality draft -o "$O/$scene.sol"
  "$R" render "$f" $common --spp 8 --method path -o "$O/$scene-path.exr"
  "$R" render "$f" $common --spp 8 --method path --quantity irradiance -o "$O/$scene-path-irr.exr"
  for m in flat interpolate rushmeier reichert shirley kok; do
    "$R" render "$f" $common --spp 4 --method $m --solution "$O/$scene.sol" -o "$O/$scene-$m.exr"
  done
  "$R" render "$f" $common --spp 4 --method interpolate --quantity irradiance --solution "$O/$scene.sol" -o "$O/$scene-interpolate-irr.exr"
  "$R" render "$f" $common --spp 4 --method reichert --ff point --solution "$O/$scene.sol" -o "$O/$scene-reichert-point.exr"
  "$R" render "$f" $common --spp 4 --method kok --sources 8 --solution "$O/$scene.sol" -o "$O/$scene-kok8.exr"
  "$R" render "$f" $common --spp 4 --method shirley --selective --selective-map "$O/$scene-shirley-sel-map.png" --solution "$O/$scene.sol" -o "$O/$scene-shirley-sel.exr"
  "$R" render "$f" $common --spp 4 --method reichert --selective --solution "$O/$scene.sol" -o "$O/$scene-reichert-sel.exr"
  "$R" render "$f" $common --spp 4 --method interpolate --quality draft -o "$O/$scene-interpolate-solved.exr"
  "$R" render "$f" $common --spp 8 --method multipass --quality draft -o "$O/$scene-multipass.exr"
done
"$R" render $S/cornell-box/scene.json $common --spp 4 --method interpolate --solver stochastic -o "$O/cornell-box-stochastic.exr"
"$R" render $S/cornell-box/scene.json $common --spp 4 --method interpolate --solver progressive --max-iterations 50 -o "$O/cornell-box-progressive.exr"
"$R" render $S/cornell-box/scene.json $common --spp 4 --method interpolate --solver hierarchical --mesh-size 100 -o "$O/cornell-box-hierarchical.exr"
"$R" render $S/cornell-box/scene.json $common --spp 4 --method interpolate --solver gauss-seidel --mesh-size 100 -o "$O/cornell-box-gs.exr"
"$R" render $S/cornell-box-spectral/scene.json $common --spp 4 --method shirley --quality draft -o "$O/spectral-shirley.exr"
echo done
