#!/usr/bin/env bash
# radiant export and radiant serve (docs/export.md) as a user runs them: the
# files each format writes, determinism, refusals that write nothing, and a
# server that answers only for the viewer's folder and the model.
# Usage: export_cli_test.sh path/to/radiant SOURCE_DIR
source "$(dirname "$0")/cli_common.sh"
server=""
trap '[ -n "$server" ] && kill $server 2>/dev/null; rm -rf "$work"' EXIT

quick=(--solver gauss-seidel --mesh-size 150 --width 64 --height 64 -q)

# Each format: glTF binary (magic "glTF", version 2), glTF JSON, PLY.
"$radiant" export "$cornell" -o box.glb "${quick[@]}" && [ "$(head -c 4 box.glb)" = "glTF" ] && pass ||
  fail "export .glb"
"$radiant" export "$cornell" -o box.gltf "${quick[@]}" && grep -q '"_RADIANCE"' box.gltf &&
  grep -q '"KHR_materials_unlit"' box.gltf && grep -q 'data:application/octet-stream;base64,' box.gltf && pass ||
  fail "export .gltf (one file, buffers embedded)"
"$radiant" export "$cornell" -o box.ply "${quick[@]}" && [ "$(head -n 2 box.ply | tail -n 1)" = "format binary_little_endian 1.0" ] &&
  pass || fail "export .ply"
"$radiant" export "$cornell" -o box2.ply --format ply "${quick[@]}" && cmp -s box.ply box2.ply && pass ||
  fail "--format ply writes what the extension does"

# A spectral scene: solved per pass, exported in linear sRGB.
"$radiant" export "$source_dir/scenes/cornell-box-spectral/scene.json" -o spectral.glb "${quick[@]}" &&
  [ "$(head -c 4 spectral.glb)" = "glTF" ] && pass || fail "export of a spectral scene"

# Deterministic: the same file whatever the thread count, and from a saved solution.
"$radiant" export "$cornell" -o one.glb "${quick[@]}" --threads 1 && cmp -s box.glb one.glb && pass ||
  fail "export with --threads 1 differs from all threads"
# A saved solution holds its values as f32 (docs/solution-format.md, version 7):
# exports of one file are the same bytes, and the same layout as solving in
# place; the light differs only by f32 rounding (relMSE of the image ~1e-16).
"$radiant" solve "$cornell" --solver gauss-seidel --mesh-size 150 -o box.rad -q &&
  "$radiant" export "$cornell" --solution box.rad -o saved.glb --width 64 --height 64 -q &&
  "$radiant" export "$cornell" --solution box.rad -o saved1.glb --width 64 --height 64 -q --threads 1 &&
  cmp -s saved.glb saved1.glb && [ "$(stat -c %s saved.glb)" = "$(stat -c %s box.glb)" ] &&
  pass || fail "export --solution is not deterministic, or its layout differs from solving in place"
"$radiant" render "$cornell" --method interpolate --solver gauss-seidel --mesh-size 150 --width 64 --height 64 \
  -o inplace.exr -q && "$radiant" render "$cornell" --method interpolate --solution box.rad --width 64 --height 64 \
  -o saved.exr -q && "$radiant" compare saved.exr inplace.exr >compare.txt &&
  awk '$1 == "all" { exit !($6 < 1e-10) }' compare.txt && pass ||
  fail "a saved solution's light differs from solving in place by more than f32 rounding: $(cat compare.txt)"

# --lightmap (docs/export.md, "Lightmaps"): the scene's own triangles with TEXCOORD_1 and the lightmap's two
# images in the file, its irradiance as an EXR beside; the same bytes whatever the thread count.
"$radiant" export "$cornell" -o lit.glb --lightmap --lightmap-size 128 "${quick[@]}" &&
  [ "$(head -c 4 lit.glb)" = "glTF" ] && grep -aq '"TEXCOORD_1"' lit.glb && grep -aq '"RADIANT_lightmap"' lit.glb &&
  [ -s lit.lightmap.exr ] && pass || fail "export --lightmap"
"$radiant" export "$cornell" -o lit1.glb --lightmap --lightmap-size 128 "${quick[@]}" --threads 1 &&
  cmp -s lit.glb lit1.glb && cmp -s lit.lightmap.exr lit1.lightmap.exr && pass ||
  fail "export --lightmap with --threads 1 differs from all threads"
"$radiant" export "$cornell" -o lit.gltf --lightmap --texel-size 10 "${quick[@]}" &&
  grep -q '"TEXCOORD_1"' lit.gltf && grep -q 'data:application/octet-stream;base64,' lit.gltf && [ -s lit.lightmap.exr ] && pass ||
  fail "export --lightmap to .gltf (one file, images in the embedded buffer)"
cp lit.glb lit-kept.glb
expect_error "lightmap to PLY" "--lightmap: a lightmap needs glTF" "$radiant" export "$cornell" -o lit.ply --lightmap -q
expect_error "lightmap size without --lightmap" "--lightmap-size: needs --lightmap" \
  "$radiant" export "$cornell" -o lit.glb --lightmap-size 64 -q
expect_error "size and texel size" "--texel-size: give --lightmap-size or --texel-size, not both" \
  "$radiant" export "$cornell" -o lit.glb --lightmap --lightmap-size 64 --texel-size 10 -q
expect_error "texel too small" "--texel-size: a texel of" \
  "$radiant" export "$cornell" -o lit.glb --lightmap --texel-size 0.01 "${quick[@]}"
expect_error "spectral lightmap" "--lightmap: a spectral scene's lightmap is not written yet" \
  "$radiant" export "$source_dir/scenes/cornell-box-spectral/scene.json" -o lit.glb --lightmap -q
cmp -s lit.glb lit-kept.glb && pass || fail "a refused lightmap export changed the existing file"
[ -e lit.ply ] && fail "a refused lightmap export wrote lit.ply" || pass

# Refusals name the flag or file, exit non-zero, and leave a good file alone.
cp box.glb kept.glb
expect_error "unknown extension" "unknown extension .expected .glb, .gltf or .ply" "$radiant" export "$cornell" -o box.obj -q
expect_error "format and extension disagree" "--format ply does not match" "$radiant" export "$cornell" -o kept.glb --format ply -q
expect_error "gamma on glTF" "--gamma: glTF vertex colours are linear" "$radiant" export "$cornell" -o kept.glb --gamma 2.2 -q
expect_error "bits" "--bits" "$radiant" export "$cornell" -o kept.glb --bits 16 -q
echo "not a solution" >bad.rad
expect_error "bad solution" "bad.rad" "$radiant" export "$cornell" --solution bad.rad -o kept.glb -q
expect_error "no output" "--output is required" "$radiant" export "$cornell" -q
cmp -s box.glb kept.glb && pass || fail "a refused export changed the existing file"
ls -a | grep -q '\.tmp' && fail "a temporary file was left behind" || pass

# radiant serve: a viewer folder of our own, so the test needs no npm packages.
mkdir -p viewer/node_modules/three/build
echo "<html>viewer</html>" >viewer/index.html
echo "export {};" >viewer/node_modules/three/build/three.module.js
echo "secret" >secret.txt
# GET over bash's /dev/tcp: status line and body of one request.
http() {
  local port=$1 method=$2 path=$3
  exec 3<>"/dev/tcp/127.0.0.1/$port" || return 1
  printf '%s %s HTTP/1.0\r\nHost: 127.0.0.1\r\nConnection: close\r\nContent-Length: 0\r\n\r\n' "$method" "$path" >&3
  cat <&3
  exec 3<&-
}
"$radiant" serve box.glb --port 0 --viewer viewer -q >url.txt 2>serve.err &
server=$!
for _ in $(seq 50); do [ -s url.txt ] && break; sleep 0.1; done
url=$(head -n 1 url.txt)
port=$(echo "$url" | sed -nE 's|^http://127\.0\.0\.1:([0-9]+)/index\.html\?model=model\.glb$|\1|p')
if [ -z "$port" ]; then
  fail "serve printed '$url', expected http://127.0.0.1:PORT/index.html?model=model.glb"
else
  pass
  http "$port" GET /index.html | grep -q "<html>viewer</html>" && pass || fail "serve: index.html"
  http "$port" GET /model.glb >model.http
  # The body after the blank line is the file, byte for byte.
  tail -c "$(stat -c %s box.glb)" model.http | cmp -s - box.glb && pass || fail "serve: the model differs"
  http "$port" GET /../secret.txt | head -n 1 | grep -q " 404" && pass || fail "serve: a path out of the folder"
  http "$port" GET /%2e%2e/secret.txt | head -n 1 | grep -qE " 40[04]" && pass || fail "serve: an escaped .."
  http "$port" GET /box.glb | head -n 1 | grep -q " 404" && pass || fail "serve: the model's folder is not served"
  http "$port" POST /index.html | head -n 1 | grep -qE " (400|404|405)" && pass || fail "serve: POST"
  if command -v ss >/dev/null; then
    ss -ltn | grep -q "127.0.0.1:$port " && pass || fail "serve does not listen on 127.0.0.1 only: $(ss -ltn)"
  fi
fi
kill -INT $server
wait $server
status=$?
server=""
[ "$status" -eq 0 ] && pass || fail "serve: Ctrl-C exit $status"
expect_error "serve: not a glTF" "expected a .glb or .gltf" "$radiant" serve box.ply --port 0 --viewer viewer
expect_error "serve: missing model" "nothing.glb: no such file" "$radiant" serve nothing.glb --port 0 --viewer viewer
rm -r viewer/node_modules
expect_error "serve: viewer without its packages" "run scripts/install-deps.sh" \
  "$radiant" serve box.glb --port 0 --viewer viewer

finish
