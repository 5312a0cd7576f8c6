#!/usr/bin/env bash
# Command-line tests: the real program's exit codes, messages and output files:
# help, render outputs, compare, bad input, bare OBJ, solve, the two-pass methods, textures, multipass.
# cli_output_test.sh has the rest. Usage: cli_test.sh path/to/radiant SOURCE_DIR
source "$(dirname "$0")/cli_common.sh"


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
# --without-emitters reads the light's pixels from an EXR's emitter channel; a PFM has none.
"$radiant" compare a.exr a.exr --without-emitters --json | grep -qE '"left_out_pixels": [1-9]' && pass ||
  fail "compare --without-emitters left no pixel of the Cornell box's light out"
expect_error "--without-emitters without a channel" "has an emitter channel" "$radiant" compare a.pfm a.pfm --without-emitters

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

# Texture and bump maps (docs/textures.md): the textured box renders with each method.
for method in path interpolate shirley; do
  mesh=(--mesh-size 150 --quality draft)  # the solve's speed, not its accuracy, is what this tests
  [ "$method" = path ] && mesh=()
  "$radiant" render "$textured" --method "$method" --spp 1 --width 16 --height 16 "${mesh[@]}" -o "tex-$method.png" -q \
    && [ -s "tex-$method.png" ] && pass || fail "textured box with --method $method"
done
expect_error "--bump-orientations with path" "used by interpolate, shirley, kok, multipass" \
  "$radiant" render "$textured" --bump-orientations 8 -o x.exr -q
# Refused when the command line is read, not after a solve of seconds (minutes on a large scene).
odd=$("$radiant" render "$textured" --method interpolate --bump-orientations 9 -o x.exr 2>&1)
grep -q "bump-orientations: must be even, got 9" <<<"$odd" && ! grep -q "solved" <<<"$odd" && pass ||
  fail "odd --bump-orientations: refused before the solve: $odd"

# Multipass (docs/multipass.md): every pass written, the latest under the plain name.
if "$radiant" render "$specular" --method multipass --solver stochastic --spp 16 --width 16 --height 16 --mesh-size 200 -o mp.exr -o mp.png \
    2>mp.txt; then
  for f in mp.pass1.exr mp.pass2.png mp.pass5.exr mp.exr mp.png; do [ -s "$f" ] && pass || fail "multipass did not write $f"; done
  grep -q "multipass 3 (paired: path samples that correct the solution)" mp.txt && grep -q "multipass 4 (low frequency" mp.txt &&
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

finish
