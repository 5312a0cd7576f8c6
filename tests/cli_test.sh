#!/usr/bin/env bash
# Command-line tests: the real program's exit codes, messages and output files.
# Usage: cli_test.sh path/to/radiant SOURCE_DIR
set -u
radiant=$1
source_dir=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
passed=0
failed=0

pass() { passed=$((passed + 1)); }
fail() { echo "FAIL: $*"; failed=$((failed + 1)); }

# expect_error NAME PATTERN COMMAND... : non-zero exit, stderr matches PATTERN
expect_error() {
  local name=$1 pattern=$2
  shift 2
  if "$@" >out.txt 2>err.txt; then
    fail "$name: expected a non-zero exit"
  elif ! grep -qE "$pattern" err.txt; then
    fail "$name: stderr does not match '$pattern':"; cat err.txt
  else
    pass
  fi
}

cornell="$source_dir/scenes/cornell-box/scene.json"

# --version and --help
"$radiant" --version | grep -q "radiant [0-9]" && pass || fail "--version"
"$radiant" render --help | grep -q -- "--spp" && pass || fail "render --help lists --spp"
"$radiant" render --help | grep -q "path" && pass || fail "render --help lists the methods"
"$radiant" render --help | grep -q "Option Group: --method kok" && pass || fail "render --help groups by method"
# docs/cli.md's parameter tables are the registries' (radiant methods --markdown), word for word.
sed -n '/^<!-- BEGIN radiant methods --markdown -->$/,/^<!-- END radiant methods --markdown -->$/p' \
  "$source_dir/docs/cli.md" | sed '1d;$d' >documented.md
"$radiant" methods --markdown >generated.md
if [ -s documented.md ] && diff -u documented.md generated.md >drift.txt; then pass; else
  fail "docs/cli.md's parameter tables differ from radiant methods --markdown (regenerate them):"; head -20 drift.txt
fi

# A small render writes every requested format.
if "$radiant" render "$cornell" --spp 2 --width 32 --height 32 -o a.exr -o a.png -o a.pfm --variance v.exr -q; then
  for f in a.exr a.png a.pfm v.exr; do [ -s "$f" ] && pass || fail "render did not write $f"; done
else
  fail "small render failed"
fi
# The default output name comes from the scene's folder.
"$radiant" render "$cornell" --spp 1 --width 16 --height 16 -q && [ -s cornell-box.png ] && [ -s cornell-box.exr ] \
  && pass || fail "default outputs cornell-box.png/.exr"

# compare: an image against itself is exact.
if "$radiant" compare a.exr a.exr --diff d.png >cmp.txt; then
  grep -qE "^all +.* 1\.000000 +0 +0" cmp.txt && pass || { fail "compare a a is not exact"; cat cmp.txt; }
  [ -s d.png ] && pass || fail "compare --diff wrote nothing"
else
  fail "compare failed"
fi
"$radiant" compare a.exr a.exr --test-variance v.exr | grep -q "R +0.00  G +0.00  B +0.00" && pass \
  || fail "compare --test-variance: an image against itself has z = 0"
expect_error "variance size mismatch" "variance image size" "$radiant" compare a.exr a.exr --test-variance cornell-box.exr
"$radiant" compare a.pfm a.exr --json | grep -q '"mean_ratio": 1' && pass || fail "compare pfm vs exr, --json"

# Bad input: clear message, non-zero exit, and no partial output over a good file.
cp a.png keep.png
expect_error "missing scene" "no-such-scene.json" "$radiant" render no-such-scene.json -o keep.png -q
cmp -s a.png keep.png && pass || fail "a failed render touched the output"
expect_error "absurd size" "out of range" "$radiant" render "$cornell" --width 100000 --height 100000 -q
expect_error "absurd spp" "samples per pixel" "$radiant" render "$cornell" --spp 0 -q
expect_error "unknown method" "unknown method 'pth'" "$radiant" render "$cornell" --method pth -q
expect_error "bad vector" "three comma-separated" "$radiant" render "$cornell" --eye 1,2 -q
expect_error "bad extension" "unknown image extension" "$radiant" render "$cornell" -o x.jpg -q
expect_error "compare size mismatch" "reference" "$radiant" compare a.exr cornell-box.exr
expect_error "compare missing file" "nothing.exr" "$radiant" compare nothing.exr a.exr
printf '{"camera": {"eye": [0,0,0],' > truncated.json
expect_error "truncated json" "truncated.json:1" "$radiant" render truncated.json -q

# A bare OBJ renders with flags for the camera.
cat > quad.obj <<'OBJ'
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
f 1 2 3 4
OBJ
"$radiant" render quad.obj --eye 0.5,0.5,2 --target 0.5,0.5,0 --up 0,1,0 --fov 30 --width 8 --height 8 --spp 1 \
  -o q.exr -q 2>err.txt && pass || { fail "bare OBJ render"; cat err.txt; }

# Radiosity: solve, save, reuse, report; refuse a solution for another scene.
furnace="$source_dir/scenes/furnace/scene.json"
if "$radiant" solve "$cornell" --mesh-size 150 --quality draft -o box.rad --report box.csv -q; then
  [ -s box.rad ] && pass || fail "solve -o wrote nothing"
  head -1 box.csv | grep -q "^object,area_m2," && grep -q "^floor," box.csv && pass || fail "solve --report"
  "$radiant" render "$cornell" --method interpolate --solution box.rad --spp 1 --width 16 --height 16 -o i.exr -q \
    && [ -s i.exr ] && pass || fail "render --solution"
  expect_error "solution for another scene" "another scene" \
    "$radiant" render "$furnace" --method flat --solution box.rad --width 8 --height 8 -q
else
  fail "solve failed"
fi
for solver in gauss-seidel progressive hierarchical; do
  "$radiant" render "$cornell" --method flat --solver "$solver" --mesh-size 200 --spp 1 --width 16 --height 16 \
    -o "flat-$solver.png" -q && pass || fail "render --method flat --solver $solver"
done
printf 'garbage' > bad.rad
expect_error "not a solution file" "not a Radiant solution" "$radiant" render "$cornell" --method flat --solution bad.rad -q
expect_error "unused radiosity option" "has no effect" "$radiant" render "$cornell" --mesh-size 50 -q
expect_error "progressive-only option" "solver hierarchical does not use it .used by progressive" \
  "$radiant" solve "$cornell" --solver hierarchical --form-factor hemicube -q
expect_error "another estimator's parameter" "form-factor estimator hemicube does not use it .used by analytic, ray-cast" \
  "$radiant" solve "$cornell" --solver progressive --form-factor hemicube --ff-samples 9 -q
"$radiant" solve "$cornell" --solver gauss-seidel --mesh-size 200 --adaptive-rounds 1 -q && pass || fail "solve --adaptive-rounds"
expect_error "adaptive with hierarchical" "refines by itself" "$radiant" solve "$cornell" --adaptive-rounds 1 -q
expect_error "bad tolerance" "must be in" "$radiant" solve "$cornell" --tolerance 0 -q
expect_error "unknown solver" "solver" "$radiant" solve "$cornell" --solver jacobi -q

# Two-pass methods: each renders the README's scene with one flag, on a stored solution and solving itself.
for method in rushmeier reichert shirley kok; do
  "$radiant" render "$cornell" --method "$method" --solution box.rad --spp 1 --width 16 --height 16 \
    -o "two-pass-$method.exr" -q && [ -s "two-pass-$method.exr" ] && pass || fail "render --method $method"
done
"$radiant" render "$cornell" --method shirley --mesh-size 200 --quality draft --spp 1 --width 16 --height 16 -o s.png -q \
  && pass || fail "shirley solving the scene itself"
"$radiant" render "$cornell" --method shirley --solution box.rad --selective --selective-map map.png --spp 1 \
  --width 16 --height 16 -o s.png 2>err.txt && [ -s map.png ] && grep -q "% of the image re-evaluated" err.txt \
  && pass || { fail "--selective-map"; cat err.txt; }
"$radiant" render "$cornell" --method reichert --solver hierarchical --selective --mesh-size 200 --selective-map links.png --spp 1 \
  --width 16 --height 16 -o r.png 2>err.txt && grep -q "links per pixel" err.txt \
  && pass || { fail "--selective link mode"; cat err.txt; }
expect_error "a misspelt method parameter" "did you mean --sources" "$radiant" render "$cornell" --method kok --sorces 3 -q
expect_error "--ff for another method" "method shirley does not use it .used by reichert" "$radiant" render "$cornell" --method shirley --ff point -q
expect_error "--ff value" "expected one of point, mc" "$radiant" render "$cornell" --method reichert --ff pt -q
expect_error "--selective with path" "used by rushmeier, reichert, shirley, kok" "$radiant" render "$cornell" --selective -q
expect_error "--sources and --source-fraction" "not both" \
  "$radiant" render "$cornell" --method kok --sources 2 --source-fraction 0.5 -q
expect_error "--selective-map without --selective" "needs --selective" \
  "$radiant" render "$cornell" --method kok --selective-map m.png -q
[ ! -e m.png ] && pass || fail "a refused render wrote an image"

# Spectral scenes (docs/spectral.md): passes of three wavelengths, colour at display.
spectral="$source_dir/scenes/cornell-box-spectral/scene.json"
if "$radiant" render "$spectral" --spp 2 --width 24 --height 24 -o sp.exr -o sp.png --variance spv.exr 2>sp.txt; then
  for f in sp.exr sp.png spv.exr; do [ -s "$f" ] && pass || fail "spectral render did not write $f"; done
  grep -q "700 nm (6/6)" sp.txt && pass || { fail "spectral progress does not name the passes"; cat sp.txt; }
  grep -q "× 6 passes" sp.txt && pass || { fail "spectral summary does not count the passes"; cat sp.txt; }
else
  fail "spectral render failed"; cat sp.txt
fi
"$radiant" render "$spectral" --colour rgb --white-balance equal-energy --spp 1 --width 16 --height 16 -o sprgb.png \
  -q && [ -s sprgb.png ] && pass || fail "render --colour rgb of a spectral scene"
if "$radiant" solve "$spectral" --mesh-size 200 --quality draft -o sp.rad --report sp.csv -q; then
  head -1 sp.csv | grep -q "radiosity_700nm_W_m2_nm" && pass || fail "spectral report lacks the wavelength columns"
  "$radiant" render "$spectral" --solution sp.rad --method interpolate --width 16 --height 16 -o spi.exr -q \
    && pass || fail "render --solution of a spectral solution"
  expect_error "spectral solution for the RGB run" "another scene" \
    "$radiant" render "$spectral" --colour rgb --solution sp.rad --method interpolate -o x.exr -q
else
  fail "spectral solve failed"
fi
expect_error "--white-balance on an RGB scene" "applies to spectral scenes only" \
  "$radiant" render "$cornell" --white-balance equal-energy -o x.exr -q
sed 's/"reflectance": 0.78,/"reflectance": [0.78, 0.7, 0.6],/' "$spectral" > rgb-in-spectral.json
expect_error "an RGB colour in a spectral scene" "/materials/light/reflectance: .*spectral" \
  "$radiant" render rgb-in-spectral.json -o x.exr -q

# Irradiance images for illuminance maps (docs/tone-mapping.md#false-colour).
if "$radiant" render "$cornell" --method interpolate --quantity irradiance --mesh-size 100 --quality draft --width 24 --height 24 \
    -o irr.exr -q; then
  "$radiant" tonemap irr.exr --falsecolor --legend --quantity illuminance -o lux.png 2>lux.txt && [ -s lux.png ] \
    && grep -q "illuminance .* lux" lux.txt && pass || { fail "tonemap of an irradiance render"; cat lux.txt; }
else
  fail "render --quantity irradiance"
fi
expect_error "irradiance from a two-pass method" "quantity: irradiance images come from" \
  "$radiant" render "$cornell" --method shirley --quantity irradiance -o x.exr -q

# Texture and bump maps (docs/textures.md): the textured box renders with each method.
textured="$source_dir/scenes/cornell-textured/scene.json"
for method in path interpolate shirley; do
  mesh=(--mesh-size 150 --quality draft)  # the solve's speed, not its accuracy, is what this tests
  [ "$method" = path ] && mesh=()
  "$radiant" render "$textured" --method "$method" --spp 1 --width 16 --height 16 "${mesh[@]}" -o "tex-$method.png" -q \
    && [ -s "tex-$method.png" ] && pass || fail "textured box with --method $method"
done
expect_error "--bump-orientations with path" "used by interpolate, shirley, kok, multipass" \
  "$radiant" render "$textured" --bump-orientations 8 -o x.exr -q
expect_error "odd --bump-orientations" "must be even" \
  "$radiant" render "$textured" --method interpolate --bump-orientations 9 -o x.exr -q

# Multipass (docs/multipass.md): every pass written, the latest under the plain name.
specular="$source_dir/scenes/cornell-specular/scene.json"
if "$radiant" render "$specular" --method multipass --solver stochastic --spp 16 --width 16 --height 16 --mesh-size 200 -o mp.exr -o mp.png \
    2>mp.txt; then
  for f in mp.pass1.exr mp.pass2.png mp.pass5.exr mp.exr mp.png; do [ -s "$f" ] && pass || fail "multipass did not write $f"; done
  grep -q "multipass 3 (unbiased, the solution as control variate)" mp.txt && grep -q "multipass 4 (low frequency" mp.txt &&
    pass || { fail "multipass does not report its passes"; cat mp.txt; }
else
  fail "multipass render"; cat mp.txt
fi
"$radiant" render "$specular" --method multipass --solver gauss-seidel --spp 4 --width 8 --height 8 --mesh-size 200 \
  -o mpgs.exr -q && [ -s mpgs.exr ] && pass || fail "multipass reading a Gauss-Seidel solution"
"$radiant" render "$cornell" --method multipass --solver hierarchical --importance --spp 2 --width 8 --height 8 \
  -o mpimp.exr -q && [ -s mpimp.exr ] && pass || fail "multipass reading an importance-driven hierarchical solution"
expect_error "multipass with a saved solution" "solves itself" \
  "$radiant" render "$specular" --method multipass --solution x.rad -o x.exr -q
expect_error "multipass of a spectral scene" "spectral" \
  "$radiant" render "$spectral" --method multipass -o x.exr -q

# tonemap: a saved EXR mapped again without rendering (docs/tone-mapping.md).
# expect_exit2 NAME PATTERN COMMAND... : bad input exits with status 2 and names the culprit
expect_exit2() {
  local name=$1 pattern=$2
  shift 2
  "$@" >out.txt 2>err.txt
  local status=$?
  if [ "$status" -ne 2 ]; then
    fail "$name: expected exit status 2, got $status"; cat err.txt
  elif ! grep -qE -- "$pattern" err.txt; then
    fail "$name: stderr does not match '$pattern':"; cat err.txt
  else
    pass
  fi
}
png_width() { od -An -tu1 -j16 -N4 "$1" | awk '{print $1*16777216 + $2*65536 + $3*256 + $4}'; }
png_depth() { od -An -tu1 -j24 -N1 "$1" | tr -d ' '; }
if "$radiant" render "$cornell" --spp 4 --width 32 --height 32 -o t.exr -o t.png -o t.pfm -q \
  && "$radiant" render "$cornell" --spp 4 --width 32 --height 32 --tonemap max-reflected -o tm.png -q \
  && "$radiant" render "$cornell" --spp 4 --width 32 --height 32 --exposure 1.5 -o te.png -q; then
  "$radiant" tonemap t.exr -o same.png -q && cmp -s same.png t.png && pass \
    || fail "tonemap with the defaults differs from render's PNG"
  "$radiant" tonemap t.exr --exposure 1.5 -o same-e.png -q && cmp -s same-e.png te.png && pass \
    || fail "tonemap --exposure differs from render --exposure"
  "$radiant" tonemap t.exr --tonemap max-reflected -o same-m.png 2>err.txt && cmp -s same-m.png tm.png \
    && ! grep -q warning err.txt && pass || { fail "max-reflected from the EXR's emitter channel"; cat err.txt; }
  "$radiant" tonemap t.pfm --tonemap max-reflected -o pfm-m.png 2>err.txt && grep -q "no \"emitter\" channel" err.txt \
    && pass || { fail "max-reflected without emitter information warns"; cat err.txt; }
  for op in linear max-reflected tumblin-rushmeier ward reinhard aces; do
    "$radiant" tonemap t.exr --tonemap "$op" -o "op-$op.png" -q && [ -s "op-$op.png" ] && pass \
      || fail "tonemap --tonemap $op"
  done
  "$radiant" tonemap t.exr --tonemap tumblin-rushmeier --display-max 100 --display-contrast 50 --adaptation 20 \
    --gamma 2.2 --gamut hue -o tr.png -q && pass || fail "tumblin-rushmeier with every parameter"
  "$radiant" tonemap t.exr --tonemap reinhard --key 0.3 --white 500 --bits 16 -o r16.png -q \
    && [ "$(png_depth r16.png)" = 16 ] && pass || fail "--bits 16 writes a 16-bit PNG"
  [ "$(png_depth t.png)" = 8 ] && pass || fail "render's PNG is 8-bit"
  # The firefly and the searchlight: normalising mappings show them identically, Ward does not.
  for op in "max-reflected" "linear --exposure auto"; do
    "$radiant" tonemap t.exr --scale 1e-4 --tonemap $op -o dim.png -q \
      && "$radiant" tonemap t.exr --scale 1e4 --tonemap $op -o bright.png -q && cmp -s dim.png bright.png && pass \
      || fail "firefly and searchlight differ under $op"
  done
  "$radiant" tonemap t.exr --scale 1e-4 --tonemap ward -o dim.png -q \
    && "$radiant" tonemap t.exr --scale 1e4 --tonemap ward -o bright.png -q && ! cmp -s dim.png bright.png && pass \
    || fail "ward shows the firefly and the searchlight alike"
  "$radiant" tonemap t.exr --falsecolor --legend --log -o fc.png 2>err.txt && [ "$(png_width fc.png)" -gt 32 ] \
    && grep -q "false colour luminance" err.txt && pass || { fail "--falsecolor --legend"; cat err.txt; }
  "$radiant" tonemap t.exr --falsecolor --range 0,500 -o fc2.png -q && [ "$(png_width fc2.png)" = 32 ] && pass \
    || fail "--falsecolor --range"
  "$radiant" tonemap t.pfm --falsecolor --quantity illuminance -o lux.png 2>err.txt \
    && grep -q "as irradiance" err.txt && pass || { fail "--quantity illuminance on an unmarked image"; cat err.txt; }
  cp t.png keep.png
  expect_exit2 "tonemap missing file" "no-such.exr: no such file" "$radiant" tonemap no-such.exr -o t.png
  cmp -s t.png keep.png && pass || fail "a failed tonemap touched the output"
  expect_exit2 "unknown operator" "unknown tone operator 'wrd'" "$radiant" tonemap t.exr --tonemap wrd -o x.png
  expect_exit2 "parameter of another operator" "--white: tone operator ward does not use it .used by reinhard" \
    "$radiant" tonemap t.exr --tonemap ward --white 100 -o x.png
  expect_exit2 "--key with a fixed exposure" "--key: linear uses it only with exposure auto" \
    "$radiant" tonemap t.exr --key 0.2 -o x.png
  expect_exit2 "bad exposure" "--exposure: expected a number or 'auto'" \
    "$radiant" tonemap t.exr --exposure bright -o x.png
  expect_exit2 "--gamma and --srgb" "excludes" "$radiant" tonemap t.exr --gamma 2.2 --srgb -o x.png
  expect_exit2 "bad --bits" "bits" "$radiant" tonemap t.exr --bits 12 -o x.png
  expect_exit2 "bad --gamut" "gamut" "$radiant" tonemap t.exr --gamut keep -o x.png
  expect_exit2 "tonemap to jpg" "--output: 'x.jpg': expected a .png file" "$radiant" tonemap t.exr -o x.jpg
  expect_exit2 "tonemap without -o" "output" "$radiant" tonemap t.exr
  expect_exit2 "--legend without --falsecolor" "--legend: needs --falsecolor" "$radiant" tonemap t.exr --legend -o x.png
  expect_exit2 "--tonemap with --falsecolor" "--tonemap: does not apply to --falsecolor" \
    "$radiant" tonemap t.exr --falsecolor --tonemap ward -o x.png
  expect_exit2 "illuminance of radiance" "holds radiance" \
    "$radiant" tonemap t.exr --falsecolor --quantity illuminance -o x.png
  expect_exit2 "reversed range" "--range: MIN must be below MAX" "$radiant" tonemap t.exr --falsecolor --range 5,1 -o x.png
  expect_exit2 "log range from 0" "--range: a --log scale needs MIN > 0" \
    "$radiant" tonemap t.exr --falsecolor --log --range 0,100 -o x.png
  expect_exit2 "not an image" "cannot read OpenEXR" bash -c "printf junk > junk.exr; '$radiant' tonemap junk.exr -o x.png"
  [ ! -e x.png ] && pass || fail "a refused tonemap wrote an image"
  expect_exit2 "render --tonemap without a PNG" "--tonemap: applies to .png outputs" \
    "$radiant" render "$cornell" --tonemap ward -o only.exr -q
  expect_exit2 "render: operator flag of another" "--display-max: tone operator reinhard does not use it .used by tumblin-rushmeier, ward" \
    "$radiant" render "$cornell" --tonemap reinhard --display-max 80 -o x.png -q
  "$radiant" render "$cornell" --spp 1 --width 16 --height 16 --exposure auto -o auto.png -q && pass \
    || fail "render --exposure auto"
else
  fail "renders for the tonemap tests failed"
fi

# Outputs are checked before any work (issue 17): a folder, a missing folder, the same file twice, the input.
mkdir -p outdir
expect_error "solve --report DIR" "error: --report: cannot write 'outdir': it is a folder" \
  "$radiant" solve "$cornell" -o kept.rad --report outdir -q
[ ! -e kept.rad ] && pass || fail "solve wrote its solution before refusing --report"
expect_error "render into a missing folder" "folder 'missing/dir' does not exist" \
  "$radiant" render "$cornell" --spp 100000 -o missing/dir/x.exr -q
expect_error "render the same output twice" "given twice" "$radiant" render "$cornell" -o a.exr -o ./a.exr -q
expect_error "seed beyond 64 bits" "expected an integer from 0 to 18446744073709551615" \
  "$radiant" render "$cornell" --seed 99999999999999999999999 -q
# Ctrl-C during a render writes the image so far and exits 130.
"$radiant" render "$cornell" --spp 1000000 --width 32 --height 32 -o int.exr -q &
pid=$!
sleep 3
kill -INT $pid
wait $pid
status=$?
if [ "$status" -eq 130 ] && [ -s int.exr ] && "$radiant" tonemap int.exr -o int.png -q; then pass; else
  fail "render; kill -INT: exit $status, int.exr $(ls -la int.exr 2>&1)"
fi

echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
