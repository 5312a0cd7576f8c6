#!/usr/bin/env bash
# radiant solve --grid-report / --grid-image and render -o x.hdr as a user runs
# them (docs/scene-format.md "grids", docs/validation.md, docs/cli.md).
# Usage: grid_cli_test.sh path/to/radiant SOURCE_DIR
source "$(dirname "$0")/cli_common.sh"

validation="$source_dir/scenes/validation"

# Validation 2: the closed room, every point at Φ/(A(1−ρ)) = 536.4 lx.
if "$radiant" solve "$validation/closed-room.json" --grid-report room.csv --grid-image room.png 2>room.txt; then
  head -1 room.csv | grep -q "^grid,i,j,x,y,z,illuminance_lux,standard_error_lux" && pass || fail "grid CSV header"
  [ "$(grep -c '^desk,' room.csv)" -eq 24 ] && [ "$(grep -c '^wall,' room.csv)" -eq 20 ] && pass \
    || fail "grid CSV rows"
  grep -q "^# grid desk: points 24 E_min_lux" room.csv && grep -q "^# grid wall: points 20" room.csv && pass \
    || fail "grid CSV summary"
  awk -F, '!/^#/ && NR > 1 { e = $7 - 536.4; if (e < 0) e = -e; if (e > 0.01 * 536.4) bad = 1 } END { exit bad }' \
    room.csv && pass || fail "closed room not within 1 % of 536.4 lx"
  [ -s room-desk.png ] && [ -s room-wall.png ] && pass || fail "one plan per grid"
  grep -q "grid desk: E_min" room.txt && pass || fail "summary on stderr"
else
  fail "solve --grid-report"; cat room.txt
fi
# Validation 1, one grid: the plan is the path given.
"$radiant" solve "$validation/rectangle-source.json" --grid-report rect.csv --grid-image rect.png -q && [ -s rect.png ] \
  && [ -s rect.csv ] && pass || fail "rectangle source"
# Validation 3: 1000 cd 2 m above the floor, E = I h / (h² + r²)^{3/2} at every point (nine digits).
if "$radiant" solve "$validation/point-source.json" --grid-report point.csv 2>point.txt; then
  awk -F, '!/^#/ && NR > 1 { r2 = $4 * $4 + $6 * $6; e = 2000 / (4 + r2) ^ 1.5; d = $7 - e; if (d < 0) d = -d;
    if (d > 1e-6 * e) bad = 1; n++ } END { exit bad || n != 81 }' point.csv && pass \
    || fail "point source not I h / (h² + r²)^1.5"
  grep -q "^# light 'bulb': 12566 lm, at most 1000 cd" point.csv && pass || fail "light in the grid report"
  grep -q "radiant: light 'bulb': 12566 lm" point.txt && pass || fail "light on stderr"
else
  fail "solve point-source"; cat point.txt
fi
# The README's office: six IES downlights, both desks at about 517 lx with U0 ≥ 0.6 (EN 12464-1's 500 lx).
if "$radiant" solve "$source_dir/scenes/office/scene.json" --grid-report office.csv --grid-image office.png -q; then
  for desk in desk-1 desk-2; do
    grep "^# grid $desk:" office.csv | awk '{ e = $9; u = $13; if (e < 512 || e > 522 || u < 0.6) exit 1 }' && pass \
      || fail "office $desk: $(grep "^# grid $desk:" office.csv)"
  done
  [ "$(grep -c "^# light 'downlight-[1-6]': 2000 lm" office.csv)" -eq 6 ] && pass || fail "office: six 2000 lm lights"
  [ -s office-work-plane.png ] && pass || fail "office work-plane plan"
else
  fail "solve office"
fi
expect_error "no grids" "--grid-report: the scene has no calculation grids" \
  "$radiant" solve "$cornell" --grid-report x.csv -q
expect_error "grid image not png" "--grid-image: 'x.jpg': expected a .png file" \
  "$radiant" solve "$validation/closed-room.json" --grid-image x.jpg -q
[ ! -e x.csv ] && pass || fail "wrote a CSV before refusing"

# .hdr beside EXR: Radiance RGBE, and read back by tonemap.
if "$radiant" render "$cornell" --spp 1 --width 16 --height 16 -o a.hdr -o a.exr -q; then
  head -c 10 a.hdr | grep -q "#?RADIANCE" && pass || fail "a.hdr header"
  "$radiant" tonemap a.hdr -o a.png -q && [ -s a.png ] && pass || fail "tonemap a.hdr"
  # RGBE keeps 8 bits of mantissa per pixel's largest band: the means over all bands agree within 1 %
  # (a band far below the pixel's largest, blue in the Cornell box, loses more).
  "$radiant" compare a.hdr a.exr --json | grep -o '"all": {[^}]*' | grep -o '"mean_ratio": [0-9.e+-]*' \
    | awk '{ r = $2 - 1; if (r < 0) r = -r; if (r > 0.01) bad = 1; n++ } END { exit bad || n == 0 }' && pass \
    || fail "hdr and exr agree within 1 %"
else
  fail "render -o a.hdr"
fi

finish
