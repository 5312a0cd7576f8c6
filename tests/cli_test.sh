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
if "$radiant" solve "$cornell" --mesh-size 150 -o box.rad --report box.csv -q; then
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
expect_error "progressive-only option" "only to --solver progressive" \
  "$radiant" solve "$cornell" --solver hierarchical --form-factor hemicube -q
"$radiant" solve "$cornell" --solver gauss-seidel --mesh-size 200 --adaptive-rounds 1 -q && pass || fail "solve --adaptive-rounds"
expect_error "adaptive with hierarchical" "refines by itself" "$radiant" solve "$cornell" --adaptive-rounds 1 -q
expect_error "bad tolerance" "must be in" "$radiant" solve "$cornell" --tolerance 0 -q
expect_error "unknown solver" "solver" "$radiant" solve "$cornell" --solver jacobi -q

# Two-pass methods: each renders the README's scene with one flag, on a stored solution and solving itself.
for method in rushmeier reichert shirley kok; do
  "$radiant" render "$cornell" --method "$method" --solution box.rad --spp 1 --width 16 --height 16 \
    -o "two-pass-$method.exr" -q && [ -s "two-pass-$method.exr" ] && pass || fail "render --method $method"
done
"$radiant" render "$cornell" --method shirley --mesh-size 200 --spp 1 --width 16 --height 16 -o s.png -q \
  && pass || fail "shirley solving the scene itself"
"$radiant" render "$cornell" --method shirley --solution box.rad --selective --selective-map map.png --spp 1 \
  --width 16 --height 16 -o s.png 2>err.txt && [ -s map.png ] && grep -q "of pixels re-evaluated" err.txt \
  && pass || { fail "--selective-map"; cat err.txt; }
"$radiant" render "$cornell" --method reichert --selective --mesh-size 200 --selective-map links.png --spp 1 \
  --width 16 --height 16 -o r.png 2>err.txt && grep -q "links per pixel" err.txt \
  && pass || { fail "--selective link mode"; cat err.txt; }
expect_error "--ff for another method" "only reichert" "$radiant" render "$cornell" --method shirley --ff point -q
expect_error "--ff value" "not in" "$radiant" render "$cornell" --method reichert --ff pt -q
expect_error "--selective with path" "two-pass methods" "$radiant" render "$cornell" --selective -q
expect_error "--sources and --source-fraction" "not both" \
  "$radiant" render "$cornell" --method kok --sources 2 --source-fraction 0.5 -q
expect_error "--selective-map without --selective" "needs --selective" \
  "$radiant" render "$cornell" --method kok --selective-map m.png -q
[ ! -e m.png ] && pass || fail "a refused render wrote an image"

echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
