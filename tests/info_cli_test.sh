#!/usr/bin/env bash
# radiant info as a user runs it (docs/cli.md, `radiant info`): the bounds,
# units and counts it prints are checked against values derived here from the
# scene files themselves (python3 reads the JSON), never against its own
# earlier output; --json is parsed; an empty scene, a missing file and bad
# flags. Usage: info_cli_test.sh path/to/radiant SOURCE_DIR
source "$(dirname "$0")/cli_common.sh"

command -v python3 >/dev/null || { echo "FAIL: python3 is needed to read the scene files and --json"; exit 1; }

# check NAME PYTHON_EXPRESSIONS... : runs python3 with `info` (the parsed
# --json of info.json), `scene` (scene.json, the scene file, when there is one)
# and `expected` (expected.json, values derived from it, when there is one);
# each expression must be true.
check() {
  local name=$1
  shift
  if python3 - "$@" >check.txt 2>&1 <<'PY'; then pass; else fail "$name:"; cat check.txt; fi
import json, math, os, sys
info = json.load(open('info.json'))
scene = json.load(open('scene.json')) if os.path.exists('scene.json') else None
expected = json.load(open('expected.json')) if os.path.exists('expected.json') else None
close = lambda a, b: len(a) == len(b) and all(math.isclose(x, y, rel_tol=1e-9, abs_tol=1e-12) for x, y in zip(a, b))
failed = [e for e in sys.argv[1:] if not eval(e)]
for e in failed: print('  not true:', e)
sys.exit(1 if failed else 0)
PY
}

# --- The Cornell box: everything derived from scenes/cornell-box/scene.json. ---
cp "$cornell" scene.json
if "$radiant" info "$cornell" -q >info.txt 2>err.txt && "$radiant" info "$cornell" --json -q >info.json 2>>err.txt; then
  pass
else
  fail "info on the Cornell box"; cat err.txt
fi
# What the scene file says: its units (millimetres → 0.001 m), every vertex
# (bounds), a triangle per triangle and two per quad, and the faces: one per
# planar quad (they are all convex; the left wall is 3.2 mm off its plane, so
# the loader cuts it in two triangles, scene-format.md), one per triangle.
python3 - <<'PY' >expected.txt
import json
scene = json.load(open('scene.json'))
unit = {'millimetres': 0.001}[scene['units']]
vertices = [v for o in scene['objects'] for v in o['vertices']]
lo = [min(v[a] for v in vertices) for a in range(3)]
hi = [max(v[a] for v in vertices) for a in range(3)]
def sub(a, b): return [a[i] - b[i] for i in range(3)]
def cross(a, b): return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
def dot(a, b): return sum(a[i] * b[i] for i in range(3))
def off_plane(q):  # the fourth corner's distance from the plane of the first three
    n = cross(sub(q[1], q[0]), sub(q[2], q[0]))
    return abs(dot(sub(q[3], q[0]), n)) / dot(n, n) ** 0.5
def face_count(o): return 1 if len(o['vertices']) == 3 or off_plane(o['vertices']) < 1e-6 else 2
faces = sum(face_count(o) for o in scene['objects'])
triangles = sum(len(o['vertices']) - 2 for o in scene['objects'])
emitting = [name for name, m in scene['materials'].items() if 'emission' in m]
emitting_faces = sum(face_count(o) for o in scene['objects'] if o['material'] in emitting)
g = lambda p: '(' + ', '.join('{:.6g}'.format(x) for x in p) + ')'
print(f"bounds:    min {g(lo)}, max {g(hi)} mm")
print(f"           min {g([x * unit for x in lo])}, max {g([x * unit for x in hi])} m")
print(f"faces:     {faces} input faces, {triangles} triangles")
print(f"objects:   {len(scene['objects'])}")
print(f"materials: {len(scene['materials'])} ({len(emitting)} emitting: {', '.join(emitting)})")
print(f"emitters:  {emitting_faces} emitting face{'' if emitting_faces == 1 else 's'}, 0 lights")
json.dump({'min_metres': [x * unit for x in lo], 'max_metres': [x * unit for x in hi], 'min': lo, 'max': hi,
           'size_metres': [(hi[a] - lo[a]) * unit for a in range(3)], 'faces': faces, 'triangles': triangles,
           'emitting_faces': emitting_faces, 'emitting_materials': emitting}, open('expected.json', 'w'))
PY
while IFS= read -r line; do
  grep -qxF -- "$line" info.txt && pass || { fail "info on the Cornell box: no line '$line' in:"; cat info.txt; }
done <expected.txt
grep -q '^units: *millimetres (1 unit = 0.001 m), given by the scene file.s "units"$' info.txt && pass \
  || fail "info names the Cornell box's units and where they came from"
grep -qE '^  left-wall +2 faces, ' info.txt && pass || fail "info lists the left wall, cut in two"
grep -q '^warnings: *none$' info.txt && pass || fail "the Cornell box has no warnings"
grep -qE '^solver: +hierarchical-exact \(auto\): ' info.txt && pass || fail "auto picks hierarchical-exact for the box"
check "--json on the Cornell box" \
  "info['units'] == {'name': 'millimetres', 'metres_per_unit': 0.001, 'source': 'given by the scene file\\'s \"units\"'}" \
  "close(info['bounds']['min_metres'], expected['min_metres'])" \
  "close(info['bounds']['max_metres'], expected['max_metres'])" \
  "close(info['bounds']['min'], expected['min']) and close(info['bounds']['max'], expected['max'])" \
  "close(info['bounds']['size_metres'], expected['size_metres'])" \
  "info['size_warning'] is None" \
  "info['faces'] == expected['faces'] and info['triangles'] == expected['triangles']" \
  "info['back_faces'] == 0" \
  "info['emitting_faces'] == expected['emitting_faces']" \
  "info['emitting_materials'] == expected['emitting_materials']" \
  "[o['name'] for o in info['objects']] == [o['name'] for o in scene['objects']]" \
  "sum(o['faces'] for o in info['objects']) == info['faces']" \
  "info['materials'] == len(scene['materials']) and info['lights'] == [] and info['grids'] == []" \
  "info['textures'] == 0 and info['shading_normals'] is False and info['spectral'] == {'enabled': False}" \
  "info['dropped_degenerate_faces'] == 0 and info['warnings'] == []" \
  "info['nothing_to_solve'] is False and info['solver']['name'] == 'hierarchical-exact'" \
  "info['solver']['requested'] == 'auto' and str(info['faces']) in info['solver']['reason']"
rm scene.json expected.json

# --solver and the solver flags work as in solve.
"$radiant" info "$cornell" -q --solver stochastic | grep -qE '^solver: +stochastic: named by --solver$' && pass \
  || fail "info --solver stochastic"
"$radiant" info "$cornell" -q --importance | grep -qE '^solver: +hierarchical \(auto\): --importance' && pass \
  || fail "info --importance: auto picks hierarchical for the box's 17 patches"
expect_error "unknown solver" "unknown solver 'foo'" "$radiant" info "$cornell" --solver foo
expect_error "a parameter of another solver" "--quality: solver stochastic does not use it" \
  "$radiant" info "$cornell" --solver stochastic --quality best
"$radiant" info "$cornell" --solver foo >/dev/null 2>&1
[ $? -eq 2 ] && pass || fail "an unknown solver exits 2"

# --- A bare OBJ of two triangles: bounds (-1, 0, -4) to (3, 5, 2), in metres. ---
cat >two.obj <<'OBJ'
o first
v -1 0 2
v 3 0 2
v 3 5 2
f 1 2 3
o second
v 0 0 -4
v 1 0 -4
v 0 2 -4
f 4 5 6
OBJ
if "$radiant" info two.obj -q >info.txt 2>err.txt && "$radiant" info two.obj --json -q >info.json 2>>err.txt; then
  pass
else
  fail "info two.obj"; cat err.txt
fi
grep -qxF 'units:     metres (1 unit = 1 m), as a bare OBJ is always read' info.txt && pass \
  || { fail "a bare OBJ is in metres:"; cat info.txt; }
grep -qxF 'bounds:    min (-1, 0, -4), max (3, 5, 2) m' info.txt && pass || { fail "two.obj bounds:"; cat info.txt; }
grep -qxF 'size:      4 × 5 × 6 m' info.txt && pass || { fail "two.obj size:"; cat info.txt; }
grep -qxF 'faces:     2 input faces, 2 triangles' info.txt && pass || { fail "two.obj faces:"; cat info.txt; }
grep -q '^warning: no emitter and no light' info.txt && pass || fail "two.obj: the loader's warning is printed"
check "--json on two.obj" \
  "info['format'] == 'OBJ model' and info['units']['metres_per_unit'] == 1" \
  "info['bounds']['min_metres'] == [-1, 0, -4] and info['bounds']['max_metres'] == [3, 5, 2]" \
  "info['bounds']['size'] == [4, 5, 6]" \
  "info['faces'] == 2 and info['triangles'] == 2 and info['emitting_faces'] == 0" \
  "[(o['name'], o['faces']) for o in info['objects']] == [('two/first', 1), ('two/second', 1)]" \
  "info['objects'][1]['bounds']['min'] == [0, 0, -4] and info['objects'][1]['bounds']['max'] == [1, 2, -4]" \
  "info['size_warning'] is None"

# The same model in a JSON scene in centimetres: the same numbers in scene units, a hundredth in metres.
cat >cm.json <<'JSON'
{"units": "cm", "objects": [{"name": "model", "type": "obj", "file": "two.obj"}]}
JSON
"$radiant" info cm.json -q >info.txt 2>err.txt && "$radiant" info cm.json --json -q >info.json 2>>err.txt \
  && pass || { fail "info cm.json"; cat err.txt; }
grep -qxF 'units:     cm (1 unit = 0.01 m), given by the scene file'\''s "units"' info.txt && pass \
  || { fail "cm.json units:"; cat info.txt; }
grep -qxF 'bounds:    min (-1, 0, -4), max (3, 5, 2) cm' info.txt && pass || { fail "cm.json bounds:"; cat info.txt; }
grep -qxF '           min (-0.01, 0, -0.04), max (0.03, 0.05, 0.02) m' info.txt && pass \
  || { fail "cm.json bounds in metres:"; cat info.txt; }
check "--json on cm.json" \
  "info['units']['name'] == 'cm' and info['units']['metres_per_unit'] == 0.01" \
  "close(info['bounds']['min'], [-1, 0, -4]) and close(info['bounds']['max'], [3, 5, 2])" \
  "close(info['bounds']['size_metres'], [0.04, 0.05, 0.06])"
# No "units": the default, metres, said so.
echo '{"objects": [{"name": "model", "type": "obj", "file": "two.obj"}]}' >default.json
"$radiant" info default.json -q | grep -qxF 'units:     metres (1 unit = 1 m), the default, as the scene file gives no "units"' \
  && pass || fail "default.json: the default units"

# A model drawn in millimetres, read as metres: 5 km across, and info says what to do.
cat >room-mm.obj <<'OBJ'
v 0 0 0
v 5000 0 0
v 5000 0 4000
v 0 0 4000
f 1 2 3 4
OBJ
"$radiant" info room-mm.obj -q >info.txt 2>&1
grep -q '^warning: the scene is 5000 m across, .*is this model in millimetres? give "units": "mm" in a JSON scene' info.txt \
  && pass || { fail "a 5 km OBJ: no warning about its units:"; cat info.txt; }
echo '{"units": "mm", "objects": [{"name": "room", "type": "obj", "file": "room-mm.obj"}]}' >room-mm.json
"$radiant" info room-mm.json -q >info.txt 2>&1 && grep -qxF 'size:      5000 × 0 × 4000 mm' info.txt \
  && ! grep -q '^warning: the scene is' info.txt && pass || { fail "room-mm.json, in mm: 5 m across, no warning:"; cat info.txt; }

# --- An empty OBJ: described, not refused (exit 0), with nothing to solve. ---
printf '# no geometry\n' >empty.obj
if "$radiant" info empty.obj -q >info.txt 2>err.txt; then pass; else fail "info empty.obj exits non-zero"; cat err.txt; fi
grep -qxF 'faces:     0 input faces, 0 triangles' info.txt && pass || { fail "empty.obj counts:"; cat info.txt; }
grep -qxF 'bounds:    none (no faces)' info.txt && pass || fail "empty.obj bounds"
grep -qE '^solver: +nothing to solve' info.txt && pass || fail "empty.obj: nothing to solve"
"$radiant" info empty.obj --json -q >info.json && pass || fail "info --json empty.obj"
check "--json on empty.obj" "info['faces'] == 0 and info['objects'] == [] and info['bounds'] is None" \
  "info['nothing_to_solve'] is True and info['solver'] is None" "'the scene has no faces' in info['warnings']"

# --- What loading dropped: a repeated face and a degenerate one. ---
cat >dropped.obj <<'OBJ'
v 0 0 0
v 1 0 0
v 1 1 0
v 2 2 0
f 1 2 3
f 1 2 3
f 1 3 4
OBJ
"$radiant" info dropped.obj --json -q >info.json && pass || fail "info dropped.obj"
check "--json on dropped.obj" "info['faces'] == 1 and info['dropped_degenerate_faces'] == 1" \
  "any('repeat another face' in w for w in info['warnings'])" "any('degenerate' in w for w in info['warnings'])"

# --- What loading dropped or merged, by object and position (not face number). ---
# Two named objects. The floor: a quad, the same quad again (repeated), a
# triangle of three points on a line (zero area) and one of two distinct
# corners. The wall: a quad, one that collapses to two corners, and, apart
# at z = 6, a quad with three corners on a line (kept as the triangle it is).
# Each position is the centroid of the face's corners, derived here.
cat >named.obj <<'OBJ'
v 0 0 0
v 2 0 0
v 2 0 2
v 0 0 2
v 1 0 1
v 5 1 5
v 6 1 5
v 6 2 5
v 5 2 5
v 5 1 6
v 6 1 6
v 7 1 6
v 6 2 6
o floor
f 1 4 3 2
f 1 4 3 2
f 1 5 3
f 1 1 2
o wall
f 6 7 8 9
f 6 7 7 6
f 10 11 12 13
OBJ
"$radiant" info named.obj -q >info.txt && "$radiant" info named.obj --json -q >info.json && pass || fail "info named.obj"
cat >expected.json <<'JSON'
{"degenerate": [["named/floor", [1, 0, 1], "zero area"],
                ["named/floor", [0.6666666666666666, 0, 0], "fewer than three distinct corners"],
                ["named/wall", [5.5, 1, 5], "fewer than three distinct corners"]],
 "repeated": [["named/floor", [1, 0, 1]]],
 "collinear": [["named/wall", [6, 1.25, 6]]]}
JSON
check "--json lists what named.obj lost, by object and position" \
  "info['dropped_degenerate_faces'] == 3" \
  "{k: (c['count'], c['action']) for k, c in info['load_changes'].items()} == {'degenerate_faces': (3, 'dropped'), 'repeated_faces': (1, 'dropped'), 'collinear_quads': (1, 'merged'), 'back_to_back_pairs': (0, 'merged'), 'welded_vertices': (0, 'merged')}" \
  "all(c['object'] == e[0] and close(c['position'], e[1]) and close(c['position_metres'], e[1]) and c['reason'] == e[2] for c, e in zip(info['load_changes']['degenerate_faces']['listed'], expected['degenerate']))" \
  "len(info['load_changes']['degenerate_faces']['listed']) == 3" \
  "[(c['object'], c['position']) for c in info['load_changes']['repeated_faces']['listed']] == [tuple(e) for e in expected['repeated']]" \
  "[(c['object'], c['position']) for c in info['load_changes']['collinear_quads']['listed']] == [tuple(e) for e in expected['collinear']]"
grep -qxF 'dropped:   3 degenerate faces, 1 repeated face' info.txt && pass || { fail "named.obj dropped row:"; cat info.txt; }
grep -qxF "  degenerate face in 'named/wall' at (5.5, 1, 5) m: fewer than three distinct corners" info.txt && pass ||
  { fail "named.obj: the wall's degenerate face by object and position:"; cat info.txt; }
grep -qxF "  quad made a triangle in 'named/wall' at (6, 1.25, 6) m: three of its corners on one line" info.txt && pass ||
  { fail "named.obj: the merged quad:"; cat info.txt; }
# In a JSON scene in millimetres the positions are in its units, and in metres beside.
cat >named-mm.json <<'JSON'
{"version": 1, "units": "mm", "objects": [{"name": "model", "type": "obj", "file": "named.obj"}]}
JSON
"$radiant" info named-mm.json --json -q >info.json && pass || fail "info named-mm.json"
check "--json positions in millimetres" \
  "close(info['load_changes']['degenerate_faces']['listed'][2]['position'], [5.5, 1, 5])" \
  "close(info['load_changes']['degenerate_faces']['listed'][2]['position_metres'], [0.0055, 0.001, 0.005])"
# The list is bounded: the first 20 of a kind, then a count of the rest.
{
  echo "v 0 0 0"; echo "v 1 0 0"; echo "v 0 0 1"
  echo "o sheet"; echo "f 1 3 2"
  for i in $(seq 1 25); do echo "v $i 5 0"; echo "f 1 1 $((3 + i))"; done
} >many.obj
"$radiant" info many.obj -q >info.txt && "$radiant" info many.obj --json -q >info.json && pass || fail "info many.obj"
check "--json lists 20 of 25 degenerate faces" "info['load_changes']['degenerate_faces']['count'] == 25" \
  "len(info['load_changes']['degenerate_faces']['listed']) == 20"
[ "$(grep -c "^  degenerate face in 'many/sheet'" info.txt)" = 20 ] && pass || { fail "many.obj: 20 listed:"; cat info.txt; }
grep -qxF '  … and 5 more (25 degenerate faces in all; the first 20 of each kind are listed)' info.txt && pass ||
  { fail "many.obj: the rest counted:"; cat info.txt; }
rm expected.json

# --- Lights, grids, spectral: counted from the scene files. ---
cp "$source_dir/scenes/office/scene.json" scene.json
"$radiant" info "$source_dir/scenes/office/scene.json" --json -q >info.json && pass || fail "info office"
check "--json on the office" \
  "len(info['lights']) == len(scene.get('lights', [])) + len(scene.get('luminaires', []))" \
  "[l['name'] for l in info['lights']] == [l['name'] for l in scene['luminaires']]" \
  "all(l['kind'] == 'photometric' for l in info['lights'])" \
  "[(g['name'], g['points']) for g in info['grids']] == [(g['name'], g['nu'] * g['nv']) for g in scene['grids']]"
cp "$spectral" scene.json
"$radiant" info "$spectral" --json -q >info.json && pass || fail "info spectral"
check "--json on the spectral box" "info['spectral']['enabled'] is True" \
  "len(info['spectral']['wavelengths_nm']) == scene['spectral']['samples']" \
  "info['spectral']['wavelengths_nm'][0] == scene['spectral']['range'][0]" \
  "info['spectral']['wavelengths_nm'][-1] == scene['spectral']['range'][1]"
rm scene.json

# --- Bad input: the errors every command gives. ---
expect_error "missing scene" "no-such-scene.json" "$radiant" info no-such-scene.json
expect_error "missing OBJ" "no-such-model.obj" "$radiant" info no-such-model.obj
"$radiant" info no-such-scene.json >/dev/null 2>&1
[ $? -eq 2 ] && pass || fail "a missing scene exits 2"
printf '{"objects": [' >truncated.json
expect_error "truncated json" "truncated.json:1" "$radiant" info truncated.json
expect_error "a flag typo" "did you mean --json" "$radiant" info "$cornell" --jsn

finish
