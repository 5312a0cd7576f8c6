#!/usr/bin/env bash
# A scene with nothing to light or show (issue 38): every subcommand and
# every rendering method, on every kind of faceless input a user or a broken
# exporter produces, ends cleanly. `path` renders what is there (nothing:
# a black image, with a warning); whatever needs a radiosity solution, or a
# model to show, stops with an error that names the file, exit status 2, and
# leaves an existing output file as it was. No crash, no hang, no partial file.
# Usage: empty_scene_cli_test.sh path/to/radiant SOURCE_DIR
source "$(dirname "$0")/cli_common.sh"

# The faceless inputs.
printf '# nothing but a comment\n' >comment.obj
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\n' >vertices.obj
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\np 1\nl 1 2\nl 2 3\n' >points-and-lines.obj
echo '{"version": 1, "objects": []}' >no-objects.json
cat >lamp-and-grid.json <<'EOF'
{"version": 1, "objects": [],
 "lights": [{"type": "point", "position": [0, 2, 0], "intensity": 1000}],
 "grids": [{"name": "floor", "origin": [-1, 0, -1], "u": [0, 0, 2], "v": [2, 0, 0], "nu": 3, "nv": 3}]}
EOF
scenes=(comment.obj vertices.obj points-and-lines.obj no-objects.json lamp-and-grid.json)

# The methods, as `radiant methods` lists them (so a new one is covered without editing this test).
mapfile -t methods < <("$radiant" methods |
  awk '/^Rendering methods/ { on = 1; next } /^[^ ]/ { on = 0 } on && /^  [a-z-]+: / { sub(":.*", "", $1); print $1 }')
[ "${#methods[@]}" -ge 8 ] && pass || fail "radiant methods listed ${#methods[@]} methods: ${methods[*]}"

# run_guarded NAME COMMAND...: no signal, no hang (20 s); sets $status.
run_guarded() {
  local name=$1
  shift
  timeout 20 "$@" >out.txt 2>err.txt
  status=$?
  if [ "$status" -ge 124 ]; then
    fail "$name: killed or crashed (status $status)"
    cat err.txt
    return 1
  fi
}

# refused NAME OUTPUT MESSAGE COMMAND...: exit 2, MESSAGE on stderr, OUTPUT unchanged.
refused() {
  local name=$1 output=$2 message=$3
  shift 3
  echo "an earlier result" >"$output"
  run_guarded "$name" "$@" || return
  if [ "$status" -ne 2 ]; then
    fail "$name: exit status $status, expected 2"
    cat err.txt
  elif ! grep -qF "$message" err.txt; then
    fail "$name: the error does not say '$message':"
    cat err.txt
  elif [ "$(cat "$output")" != "an earlier result" ]; then
    fail "$name: the earlier $output was replaced"
  elif ls -a | grep -q '\.tmp'; then
    fail "$name: a temporary file was left behind"
  else
    pass
  fi
}

# lamp_grid_report: the faceless lamp-and-grid.json's grid report. 1000 cd at 2 m above the grid's centre, its
# normal up: E = I·cos θ/d², 250 lx at the centre, 1000·2/(4 + 2·(2/3)²)^(3/2) = 185.018 lx at a corner; nothing
# reflected, since nothing is there to reflect.
lamp_grid_report() {
  rm -f grid.csv
  run_guarded "lamp-and-grid.json grid report" "$radiant" solve lamp-and-grid.json --grid-report grid.csv || return
  if [ "$status" -ne 0 ]; then
    fail "lamp-and-grid.json grid report: exit status $status"
    cat err.txt
    return
  fi
  grep -q "the grids get the lights' direct illuminance alone" err.txt && pass ||
    { fail "the faceless grid report does not say what it computes"; cat err.txt; }
  awk -F, '$1 == "floor" && $2 == 1 && $3 == 1 { c = $7 } $1 == "floor" && $2 == 0 && $3 == 0 { k = $7; r = $10 }
    END { exit !(c > 249.999 && c < 250.001 && k > 185.0182 && k < 185.0184 && r == 0) }' grid.csv && pass ||
    { fail "the faceless grid report is not the inverse-square law:"; cat grid.csv; }
}

for scene in "${scenes[@]}"; do
  faceless="$scene: the scene has no faces: there is nothing to solve"
  for method in "${methods[@]}"; do
    if [ "$method" = path ]; then
      # The path tracer renders what there is: a black image, said so.
      rm -f black.pfm
      run_guarded "$scene path" "$radiant" render "$scene" --method path --spp 2 --width 8 --height 6 -o black.pfm ||
        continue
      if [ "$status" -ne 0 ] || [ ! -s black.pfm ]; then
        fail "$scene path: status $status, image written: $([ -s black.pfm ] && echo yes || echo no)"
        cat err.txt
      elif ! grep -q "warning: the scene has no faces" err.txt; then
        fail "$scene path: no warning that the scene has no faces"
        cat err.txt
      else
        # Every pixel black: the PFM's data after its three header lines.
        tail -n +4 black.pfm | od -An -tx1 -v | tr -d ' \n' | grep -q '[1-9a-f]' &&
          fail "$scene path: the image is not black" || pass
      fi
      continue
    fi
    refused "$scene $method" image.png "$faceless" "$radiant" render "$scene" --method "$method" --spp 1 \
      --width 8 --height 6 -o image.png
  done
  refused "$scene solve" solution.rad "$faceless" "$radiant" solve "$scene" -o solution.rad
  # Only lamp-and-grid.json has a grid (the others are refused for having none, before anything is read
  # further). Its grid gets the lamp's direct light, and a solution asked for beside it is refused.
  if [ "$scene" = lamp-and-grid.json ]; then
    refused "$scene grid report with a solution" grid.csv "$faceless" "$radiant" solve "$scene" --grid-report grid.csv \
      -o solution.rad
    lamp_grid_report
  else
    refused "$scene grid report" grid.csv "the scene has no calculation grids" "$radiant" solve "$scene" \
      --grid-report grid.csv
  fi
  refused "$scene export glb" model.glb "$faceless" "$radiant" export "$scene" -o model.glb
  refused "$scene export ply" model.ply "$faceless" "$radiant" export "$scene" -o model.ply
  run_guarded "$scene info" "$radiant" info "$scene" -q && { [ "$status" -eq 0 ] && pass || fail "$scene info: $status"; }
done

# radiant serve shows a model: one without faces, or not a glTF at all, is refused before it listens.
python3 - <<'EOF'
import json, struct
j = json.dumps({"asset": {"version": "2.0"}}).encode()
j += b" " * (-len(j) % 4)
open("empty.glb", "wb").write(struct.pack("<III", 0x46546C67, 2, 20 + len(j)) + struct.pack("<II", len(j), 0x4E4F534A) + j)
EOF
printf 'glTF' >truncated.glb
# A viewer folder of our own: the test needs no npm packages (a machine without the npm registry has none).
mkdir -p viewer/node_modules/three/build
echo "<html>viewer</html>" >viewer/index.html
echo "export {};" >viewer/node_modules/three/build/three.module.js
run_guarded "serve empty.glb" "$radiant" serve empty.glb --port 0 --viewer viewer -q &&
  { [ "$status" -eq 2 ] && grep -qF "empty.glb: the model has no faces" err.txt && pass ||
    { fail "serve empty.glb: status $status"; cat err.txt; }; }
run_guarded "serve truncated.glb" "$radiant" serve truncated.glb --port 0 --viewer viewer -q &&
  { [ "$status" -eq 2 ] && grep -qF "truncated.glb:" err.txt && pass ||
    { fail "serve truncated.glb: status $status"; cat err.txt; }; }

finish
