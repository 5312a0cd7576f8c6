#!/usr/bin/env bash
# Command-line tests, second half (cli_test.sh has the first): spectral scenes,
# irradiance images, tonemap, outputs checked before work, Ctrl-C.
# Usage: cli_output_test.sh path/to/radiant SOURCE_DIR
source "$(dirname "$0")/cli_common.sh"

# Spectral scenes (docs/spectral.md): passes of three wavelengths, colour at display.
if "$radiant" render "$spectral" --spp 2 --width 24 --height 24 -o sp.exr -o sp.png --variance spv.exr 2>sp.txt; then
  for f in sp.exr sp.png spv.exr; do [ -s "$f" ] && pass || fail "spectral render did not write $f"; done
  grep -q "700 nm (6/6)" sp.txt && pass || { fail "spectral progress does not name the passes"; cat sp.txt; }
  grep -q "× 6 passes" sp.txt && pass || { fail "spectral summary does not count the passes"; cat sp.txt; }
else
  fail "spectral render failed"; cat sp.txt
fi
"$radiant" render "$spectral" --colour rgb --white-balance equal-energy --spp 1 --width 16 --height 16 -o sprgb.png \
  -q && [ -s sprgb.png ] && pass || fail "render --colour rgb of a spectral scene"
# Gauss–Seidel: the solver is not what is tested here, and it solves the six passes in 0.4 s under the sanitizers.
if "$radiant" solve "$spectral" --solver gauss-seidel --mesh-size 200 -o sp.rad --report sp.csv -q; then
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
# An interrupted render never replaces a file that was there (issue 38: it may hold a finished
# image): the image so far goes beside it, as NAME.interrupted.EXT; a new output is written as asked.
echo "an earlier image" > finished.exr
rm -f fresh.png finished.interrupted.exr
"$radiant" render "$cornell" --spp 1000000 --width 32 --height 32 -o finished.exr -o fresh.png 2> finished.err &
pid=$!
sleep 3
kill -INT $pid
wait $pid
status=$?
if [ "$status" -eq 130 ] && [ "$(cat finished.exr)" = "an earlier image" ] && [ -s finished.interrupted.exr ] &&
  [ -s fresh.png ] && grep -q "kept the earlier finished.exr" finished.err &&
  "$radiant" tonemap finished.interrupted.exr -o finished.png -q; then
  pass
else
  fail "render; kill -INT over an earlier file: exit $status, $(ls -la finished* fresh.png 2>&1), $(cat finished.err)"
fi
# Ctrl-C before every pixel has a sample (issue 38): nothing is written, and an earlier file of
# that name stays as it was (it was replaced by a black image). The first round, 1 spp of 2000²
# pixels on one thread, takes several seconds; the interrupt comes 1.5 s after the start.
echo "an earlier image" > early.png
"$radiant" render "$cornell" --spp 1000000 --width 2000 --height 2000 --threads 1 -o early.png 2> early.err &
pid=$!
sleep 1.5
kill -INT $pid
wait $pid
status=$?
if [ "$status" -eq 130 ] && [ "$(cat early.png)" = "an earlier image" ] && grep -q "nothing written" early.err; then
  pass
else
  fail "render; kill -INT before the first sample: exit $status, early.png $(ls -la early.png), $(cat early.err)"
fi

# A job too large for the memory it may use is refused before anything is
# solved or allocated (here a process limit of 1.5 GB, as a batch system sets;
# the free memory counts the same way), naming the size; an existing file is
# left alone. Not under ASan, which reserves terabytes of address space.
if [ "${RADIANT_SANITIZED_RUN:-0}" != 1 ]; then
  echo "an earlier image" > big.png
  expect_error "an image larger than the memory allowed" \
    "--width/--height: a 8192x8192 image needs at least 5.1 GB .* only 1.5 GB is available to this process" \
    bash -c "ulimit -v 1500000 && exec \"$radiant\" render \"$cornell\" --width 8192 --height 8192 --spp 1 -o big.png"
  [ "$(cat big.png)" = "an earlier image" ] && ! grep -q "solved" err.txt && pass ||
    fail "a refused large job solved or wrote: $(cat err.txt)"
fi
# A large job that fits says what it holds and traces before it starts (here
# 1.6·10¹⁰ samples; stopped after 2 s).
timeout -s INT 2 "$radiant" render "$cornell" --method path --width 128 --height 128 --spp 1000000 -o large.png \
  2>large.err
grep -q "a large job: 128x128 = 16384 pixels, 1.64e+10 samples (1000000 per pixel); the film and images hold 1 MB" \
  large.err && pass || fail "a large job's announcement: $(cat large.err)"
# Then its time, from a pilot's rate: 1.64·10¹⁰ samples at R M samples/s take 1.64·10⁴/R s, said in the unit that fits.
python3 - large.err <<'PY' && pass || fail "a large job's time: $(cat large.err)"
import re, sys
text = open(sys.argv[1]).read()
m = re.search(r"a pilot of (\d+) samples ran at ([0-9.e+]+) M samples/s: the 1.64e\+10 samples take about "
              r"([0-9.]+) (s|min|h|days)\n", text)
assert m and int(m.group(1)) > 0, text
seconds = float(m.group(3)) * {"s": 1, "min": 60, "h": 3600, "days": 86400}[m.group(4)]
expected = 16384 * 1e6 / (float(m.group(2)) * 1e6)
assert abs(seconds - expected) <= 0.05 * expected + 60, (seconds, expected)
PY

finish
