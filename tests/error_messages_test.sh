#!/usr/bin/env bash
# Error messages name the file and the line (OBJ/MTL, JSON syntax) or JSON
# path (JSON values) of the bad input, or the flag (issue 17). A representative
# subset of tools/error_corpus.py's cases, each asserting the exact location;
# no case may crash or be accepted.
# Usage: error_messages_test.sh path/to/radiant SOURCE_DIR
set -u
radiant=$(realpath "$1")
source_dir=$(realpath "$2")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
passed=0
failed=0

fail() { echo "FAIL: $*"; failed=$((failed + 1)); }

# expect NAME PATTERN COMMAND... : exit status 1 or 2 (not 0, not a signal), and
# a "radiant: error:" line (or CLI11's message) on stderr that matches PATTERN.
expect() {
  local name=$1 pattern=$2
  shift 2
  "$@" >out.txt 2>err.txt
  local status=$?
  if [ "$status" -ge 126 ]; then
    fail "$name: killed or not run (status $status)"; cat err.txt
  elif [ "$status" -eq 0 ]; then
    fail "$name: accepted, expected an error matching '$pattern'"
  elif ! grep -qE -e "$pattern" err.txt; then
    fail "$name: stderr does not match '$pattern':"; cat err.txt
  else
    passed=$((passed + 1))
  fi
}

small=(--spp 1 --width 4 --height 4 -q)
# render SCENE [FLAGS]: a tiny render, by path unless FLAGS give -m
render() {
  local method=(-m path)
  case " ${*:2} " in *" -m "*) method=() ;; esac
  "$radiant" render "$1" "${method[@]}" "${small[@]}" -o "$work/out.exr" "${@:2}"
}
cornell="$source_dir/scenes/cornell-box/scene.json"

# ---- JSON values: the JSON path. A copy of the Cornell box, one value changed.
mutate() {  # mutate NAME SED-EXPRESSION: writes NAME.json
  sed -e "$2" "$cornell" >"$1.json"
}
mutate type 's/"reflectance": \[0.105421, 0.37798/"reflectance": [0.105421, "x"/'
expect "wrong type" '^radiant: error: type\.json: at /materials/green/reflectance/1: expected a number, got a string' \
  render type.json
mutate key 's/"fov": 39.3077/"fovv": 39.3077/'
expect "unknown key" "^radiant: error: key\.json: at /camera/fovv: unknown key 'fovv'; did you mean 'fov'\?" render key.json
mutate material '0,/"material": "white"/s//"material": "whit"/'
expect "unknown material" "material\.json: at /objects/0/material: material 'whit' is not defined in /materials; did you mean 'white'" \
  render material.json
mutate width 's/"width": 512/"width": 0/'
expect "image width 0" 'width\.json: at /image/width: expected an integer in \[1, 16384\], got 0' render width.json
mutate spp 's/"spp": 64/"spp": 1.5/'
expect "spp 1.5" 'spp\.json: at /render/spp: expected an integer' render spp.json
sed -e 's/"u": \[3, 0, 0\], "v": \[0, 0, 2\]/"u": [3, 0, 0], "v": [6, 0, 0]/' \
  "$source_dir/scenes/validation/closed-room.json" >grid.json
expect "grid without area" 'grid\.json: at /grids/0/v: u and v span no area \(zero or parallel\)' \
  "$radiant" solve grid.json --grid-report "$work/grid.csv" -q
sed -e 's/"intensity": 1000/"intensity": 1000, "lumens": 5/' "$source_dir/scenes/validation/point-source.json" >light.json
expect "light with two amounts" 'light\.json: at /lights/0: give the light.s "intensity" \(cd\) or its "lumens" \(lm\), one of them' \
  "$radiant" solve light.json -q
sed -e 's/"type": "point"/"type": "spotlight"/' "$source_dir/scenes/validation/point-source.json" >lighttype.json
expect "unknown light type" "lighttype\.json: at /lights/0/type: unknown light type 'spotlight'; known: point, spot" \
  "$radiant" solve lighttype.json -q
mutate units 's/"millimetres"/"furlongs"/'
expect "unknown units" 'units\.json: at /units: unknown units' render units.json
mutate fov 's/"fov": 39.3077/"fov": 200/'
expect "fov 200" 'fov\.json: at /camera/fov: camera fov 200° is outside' render fov.json
mutate rho 's/"reflectance": \[0.885809, 0.698859, 0.666422\]/"reflectance": 1.2/'
expect "reflectance 1.2" "rho\.json: at /materials/white/reflectance: material 'white': reflectance 1.2" render rho.json
mutate far 's/\[552.8, 0, 0\], \[0, 0, 0\]/[552.8, 0, 0], [0, 1e300, 0]/'
expect "vertex beyond 1e9 m" 'far\.json: at /objects/0/vertices/1: a vertex at .* more than 1e\+09 m from the origin' \
  render far.json
mutate noobjects 's/"objects"/"objectz"/'
expect "misspelt objects" "noobjects\.json: at /objectz: unknown key 'objectz'; did you mean 'objects'" render noobjects.json
mutate objfile 's/"type": "quad",/"type": "obj", "file": "nosuch.obj",/; s/"vertices": \[\[552.8, 0, 0\], \[0, 0, 0\], \[0, 0, 559.2\], \[549.6, 0, 559.2\]\],//'
expect "missing OBJ" "objfile\.json: at /objects/0/file: cannot open OBJ file '.*nosuch\.obj'" render objfile.json
cat >sphere.json <<'EOF'
{"objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1e300}],
 "camera": {"eye": [0, 0, 5], "target": [0, 0, 0]}}
EOF
expect "sphere beyond 1e9 m" 'sphere\.json: at /objects/0/radius: a vertex at .* more than 1e\+09 m' render sphere.json

# ---- JSON text: line and column.
cat >comma.json <<'EOF'
{
  "version": 1,
  "objects": [
    {"type": "quad", "vertices": [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]},
  ]
}
EOF
expect "trailing comma" '^radiant: error: comma\.json:5:3: invalid JSON' render comma.json
head -c 120 "$cornell" >truncated.json
expect "truncated JSON" '^radiant: error: truncated\.json:3:[0-9]+: invalid JSON: .*missing closing quote' \
  render truncated.json
: >empty.json
expect "empty JSON" '^radiant: error: empty\.json:1:1: invalid JSON' render empty.json
printf '\x00\x01\x02\xff garbage' >garbage.json
expect "binary JSON" '^radiant: error: garbage\.json:1:1: invalid JSON' render garbage.json
printf '{\n  "version": 1e999,\n  "objects": []\n}\n' >huge.json
expect "1e999" '^radiant: error: huge\.json:2:14: the number 1e999 is too large' render huge.json

# ---- OBJ and MTL: the line. A quad and an emitting triangle; each case in its own folder.
obj_case() {  # obj_case DIR OBJ-SED MTL-SED: writes DIR/box.obj, DIR/box.mtl, DIR/checker.png, DIR/scene.json
  mkdir -p "$1"
  sed -e "$2" >"$1/box.obj" <<'EOF'
# a quad and an emitting triangle
mtllib box.mtl
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
vt 0 0
vt 1 0
vt 1 1
usemtl white
f 1/1 2/2 3/3 4/3
usemtl light
f 1 2 3
EOF
  sed -e "$3" >"$1/box.mtl" <<'EOF'
newmtl white
Kd 0.5 0.5 0.5
illum 1
newmtl light
Kd 0.5 0.5 0.5
Ke 1 1 1
newmtl checker
Kd 1 1 1
map_Kd checker.png
EOF
  cp "$source_dir/scenes/cornell-textured/textures/checker.png" "$1/checker.png"
  printf '{"objects": [{"type": "obj", "file": "box.obj"}]}\n' >"$1/scene.json"
}
obj_case o1 '4s/.*/v 1 x 0/' ''
expect "OBJ bad number" "^radiant: error: o1/box\.obj:4: 'v' expects finite decimal numbers, got 'x'" render o1/box.obj
expect "OBJ bad number, from JSON" "^radiant: error: .*o1/box\.obj:4: 'v' expects finite" render o1/scene.json
obj_case o2 '13s/.*/f 1 2 9/' ''
expect "OBJ index out of range" '^radiant: error: o2/box\.obj:13: vertex index 9 is out of range \(the file has 4\)' \
  render o2/box.obj
obj_case o3 '13s/.*/f 1 2 -7/' ''
expect "OBJ relative index" '^radiant: error: o3/box\.obj:13: relative vertex index -7 is out of range' render o3/box.obj
obj_case o4 '13s/.*/f 1 2/' ''
expect "OBJ two-vertex face" '^radiant: error: o4/box\.obj:13: a face needs at least 3 vertices, got 2' render o4/box.obj
obj_case o5 '11s/.*/f 1\/x 2 3/' ''
expect "OBJ bad reference" "^radiant: error: o5/box\\.obj:11: '1/x' is not a vertex reference" render o5/box.obj
obj_case o6 '2s/.*/mtllib missing.mtl/' ''
expect "OBJ missing mtllib" "^radiant: error: o6/box\\.obj:2: cannot open material library '.*missing\\.mtl'" render o6/box.obj
obj_case o7 '5s/.*/v 2e9 0 0/' ''
expect "OBJ vertex beyond 1e9 m" '^radiant: error: o7/box\.obj:5: this vertex lies at \(2e\+09, 0, 0\) m' render o7/box.obj
printf '{"objects": [{"type": "obj", "file": "box.obj", "transform": {"scale": 1e10}}]}\n' >o7/scaled.json
expect "OBJ vertex placed beyond 1e9 m" \
  '^radiant: error: .*o7/box\.obj:4: this vertex lies at \(1e\+10, 0, 0\) m in the scene \(placed by .*o7/scaled\.json: at /objects/0/file\)' \
  render o7/scaled.json
obj_case m1 '' '2s/.*/Kd 0.5 x 0.5/'
expect "MTL bad number" "^radiant: error: .*m1/box\\.mtl:2: 'Kd' expects finite decimal numbers, got 'x'" render m1/box.obj
obj_case m2 '' '5s/.*/Kd -1 0.5 0.5/'
expect "MTL negative Kd, at its line" "^radiant: error: .*m2/box\\.mtl:5: material 'light': Kd -1 \\(band R\\) is negative" \
  render m2/box.obj
obj_case m3 '' '3s/.*/illum 4\nNi 0/'
expect "MTL Ni 0, at its line" "^radiant: error: .*m3/box\\.mtl:4: material 'white': Ni 0 is not a valid index" \
  render m3/box.obj
obj_case m7 '' '3s/.*/Ks -1 0 0/'
expect "MTL negative Ks, at its line" "^radiant: error: .*m7/box\\.mtl:3: Ks = -1 0 0 is negative" render m7/box.obj
obj_case m8 '' '3s/.*/Tf 0.5 -1 0.5\nillum 4\nNi 1.5/'
expect "MTL negative Tf, at its line" "^radiant: error: .*m8/box\\.mtl:3: Tf = 0.5 -1 0.5 is negative" render m8/box.obj
obj_case m4 '10s/.*/usemtl checker/' '9s/.*/map_Kd nosuch.png/'
expect "MTL missing texture" "^radiant: error: .*m4/box\\.mtl:9: cannot open texture '.*nosuch\\.png' named by map_Kd" \
  render m4/box.obj
obj_case m5 '10s/.*/usemtl checker/' '9s/.*/map_Kd -s 2 2 checker.png/'
expect "MTL map_Kd -s u v" '^radiant: error: .*m5/box\.mtl:9: map_Kd names no image file' render m5/box.obj
obj_case m6 '10s/.*/usemtl checker/' ''
head -c 60 m6/checker.png >m6/cut.png && mv m6/cut.png m6/checker.png
expect "MTL truncated texture" \
  "^radiant: error: .*m6/box\\.mtl:9: texture .*m6/checker\\.png: cannot decode the 512x512 image from the file's 60 bytes" \
  render m6/box.obj
obj_case s1 '' '2s/.*/Kd 0.5 0.4 0.5/'
cat >s1/spectral.json <<'EOF'
{"spectral": {"range": [400, 700], "samples": 16},
 "objects": [{"type": "obj", "file": "box.obj"}]}
EOF
expect "RGB MTL in a spectral scene" "^radiant: error: .*s1/box\\.mtl:1: material 'white' has an RGB colour, but this scene is spectral" \
  render s1/spectral.json

# ---- Textures named by a JSON scene: the JSON path and the texture file.
texture_case() {  # texture_case DIR: a copy of the textured Cornell box
  cp -r "$source_dir/scenes/cornell-textured" "$1"
}
texture_case t1 && head -c 60 "$source_dir/scenes/cornell-textured/textures/checker.png" >t1/textures/checker.png
expect "truncated PNG" \
  "^radiant: error: t1/scene\\.json: at /materials/checker/texture: texture t1/textures/checker\\.png: cannot decode the 512x512 image from the file's 60 bytes" \
  render t1/scene.json
texture_case t2 && echo "not an image" >t2/textures/egg-crate.png
expect "text file as a bump map" \
  '^radiant: error: t2/scene\.json: at /materials/bumpy-white/bump: bump map t2/textures/egg-crate\.png: not an image this program reads' \
  render t2/scene.json
texture_case t3 && : >t3/textures/checker.png
expect "empty PNG" '^radiant: error: t3/scene\.json: at /materials/checker/texture: texture t3/textures/checker\.png: the file is empty' \
  render t3/scene.json
texture_case t4 && rm t4/textures/checker.png
expect "missing texture" "^radiant: error: t4/scene\\.json: at /materials/checker/texture: cannot open texture file 't4/textures/checker\\.png'" \
  render t4/scene.json

# ---- Linear images (compare, tonemap): the file, and what is wrong.
"$radiant" render "$cornell" --spp 1 --width 8 --height 8 -q -o a.exr -o a.pfm || fail "render a.exr"
"$radiant" render "$cornell" "${small[@]}" -o small.exr || fail "render small.exr"
head -c 100 a.exr >cut.exr
expect "truncated EXR" '^radiant: error: cut\.exr: cannot read OpenEXR image' "$radiant" compare cut.exr a.exr
texture_case t5 && cp cut.exr t5/textures/checker.png
expect "truncated EXR texture" '^radiant: error: t5/scene\.json: at /materials/checker/texture: texture t5/textures/checker\.png: cannot read OpenEXR image' \
  render t5/scene.json
{ printf 'PF\n512 512\n-1\n'; head -c 100 /dev/zero; } >cut.pfm
expect "truncated PFM" '^radiant: error: cut\.pfm: truncated: the header says 512x512 colour, 3145728 bytes of pixels, and the file holds 100' \
  "$radiant" compare a.exr cut.pfm
printf 'P6\n2 2\n255\n' >magic.pfm
expect "not a PFM" "^radiant: error: magic\\.pfm: not a PFM file" "$radiant" tonemap magic.pfm -o m.png
expect "size mismatch" "^radiant: error: small\\.exr: image is 4x4 but the reference 'a\\.exr' is 8x8" \
  "$radiant" compare small.exr a.exr
expect "missing image" '^radiant: error: nosuch\.exr: no such file' "$radiant" tonemap nosuch.exr -o m.png

# ---- Solution files: the file, and what is wrong.
furnace="$source_dir/scenes/furnace/scene.json"
"$radiant" solve "$furnace" --solver progressive -o f.sol -q || fail "solve the furnace"
head -c 40 f.sol >cut.sol
expect "truncated solution" '^radiant: error: cut\.sol: the file is truncated: it ends after 40 bytes' \
  render "$furnace" -m flat --solution cut.sol
expect "solution of another scene" '^radiant: error: f\.sol: the solution was made for another scene' \
  render "$cornell" -m flat --solution f.sol
expect "scene given as a solution" '^radiant: error: .*furnace/scene\.json: not a Radiant solution file' \
  render "$furnace" -m flat --solution "$furnace"
expect "solution given as a scene" '^radiant: error: f\.sol: this is a Radiant solution file' render f.sol
{ cat f.sol; printf 'x'; } >long.sol
expect "data after the solution" '^radiant: error: long\.sol: unexpected data after the solution' \
  render "$furnace" -m flat --solution long.sol
expect "missing solution" '^radiant: error: nosuch\.sol: cannot open the solution file' \
  render "$furnace" -m flat --solution nosuch.sol
expect "missing scene" "^radiant: error: nosuch\\.json: cannot open scene file" render nosuch.json

# ---- glTF: the glTF file and the JSON path inside it. One triangle, one value changed.
gltf() {  # gltf NAME MODE COUNT: writes NAME.gltf
  cat >"$1.gltf" <<EOF
{"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
 "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "mode": $2}]}],
 "accessors": [{"bufferView": 0, "componentType": 5126, "count": $3, "type": "VEC3"}],
 "bufferViews": [{"buffer": 0, "byteLength": 36}],
 "buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}]}
EOF
}
gltf points 0 3
expect "glTF points" '^radiant: error: points\.gltf: at /meshes/0/primitives/0/mode: mode 0 \(points\)' render points.gltf
gltf count 4 10
expect "glTF accessor count" '^radiant: error: count\.gltf: at /accessors/0: count 10 exceeds buffer view 0' \
  render count.gltf
echo '{"objects": [{"type": "gltf", "file": "nosuch.glb"}]}' >gltf-entry.json
expect "glTF file missing" "^radiant: error: gltf-entry\\.json: at /objects/0/file: cannot open glTF file '.*nosuch\\.glb'" \
  render gltf-entry.json

# ---- MGF: the file and the line of the entity.
printf 'v a =\n p 0 0 0\nv b =\n p 1 0 0\nf a b c\n' >undef.mgf
expect "MGF undefined vertex" "^radiant: error: undef\\.mgf:5: vertex 'c' is not defined" render undef.mgf
printf 'm x =\n rd 1.5\n' >rd.mgf
expect "MGF reflectance above 1" "^radiant: error: rd\\.mgf:2: 'rd' 1\\.5: expected 0 … 1" render rd.mgf
printf '# includes itself\ni self.mgf\n' >self.mgf
expect "MGF self include" '^radiant: error: self\.mgf:2: includes nested more than 16 deep' render self.mgf
printf 'v a =\n p 0 0 0\nxf -t 1 0 0\n' >xf.mgf
expect "MGF unended xf" '^radiant: error: xf\.mgf:3: the file ends inside an xf context' render xf.mgf
echo '{"objects": [{"type": "mgf", "file": "nosuch.mgf"}]}' >mgf-entry.json
expect "MGF file missing" "^radiant: error: mgf-entry\\.json: at /objects/0/file: cannot open MGF file '.*nosuch\\.mgf'" \
  render mgf-entry.json

# ---- Flags: the flag.
expect "--spp 0" '^radiant: error: --spp: samples per pixel must be in' "$radiant" render "$cornell" --spp 0 -q
expect "--eye 1,2" '^radiant: error: --eye: expected three comma-separated numbers' \
  "$radiant" render "$cornell" "${small[@]}" --eye 1,2
expect "--method nosuch" "^radiant: error: --method: unknown method 'nosuch'" \
  "$radiant" render "$cornell" "${small[@]}" -m nosuch
expect "-o x.bmp" '^radiant: error: --output: .x\.bmp.: unknown image extension' \
  "$radiant" render "$cornell" "${small[@]}" -o x.bmp
expect "--mesh-size -1" '^radiant: error: --mesh-size: must be in > 0, got -1' \
  "$radiant" solve "$furnace" -q --mesh-size -1
expect "--range a,b" "^radiant: error: --range: expected MIN,MAX like 0,500, got 'a,b'" \
  "$radiant" tonemap a.exr -o m.png --falsecolor --range a,b
expect "--variance v.png" "^radiant: error: --variance: 'v\\.png': expected a \\.exr, \\.pfm or \\.hdr file" \
  "$radiant" render "$cornell" "${small[@]}" --variance v.png
expect "--diff x.exr" "^radiant: error: --diff: 'x\\.exr': expected a \\.png file" "$radiant" compare a.exr a.exr --diff x.exr
expect "--spp x (CLI11)" 'spp' "$radiant" render "$cornell" --spp x -q

echo "error messages: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
