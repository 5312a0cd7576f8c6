#!/usr/bin/env bash
# input_scale — time and peak memory against the count of objects, materials
# and luminaires in the input (issue 38): the costs must grow about linearly,
# since one loop per item over all the others (a name looked up by scanning
# every name) makes a file of 10⁵ items take minutes. Prints a Markdown table
# for docs/PERFORMANCE.md: per case and count N, the wall time and peak
# resident memory of the command, the time per item, and the ratio of each
# time to the previous count's (≈ N ratio for linear growth, its square for
# quadratic).
#
# The cases, each generated into a temporary folder:
#   objects    an OBJ of N `o` objects, one quad each (4 vertices), lit by a
#              ceiling quad:  radiant solve FILE --solver stochastic -q
#   materials  the same quads, each with its own `usemtl` material of the MTL
#   luminaires a JSON scene of one floor quad and N luminaires of one IES file:
#              radiant render FILE --spp 1 --width 64 --height 48 -q
#   nodes      a glTF of N nodes that each place the one quad mesh, and a
#              scene node above them all:  radiant info FILE
#   includes   an MGF file of N `i quad.mgf -t x 0 z` lines (each include
#              opened, read and transformed):  radiant info FILE
#
# Usage: bench/input_scale.sh [--radiant PATH] [--counts "10000 30000 100000"] [--cases "objects …"]
set -euo pipefail

radiant=build/radiant
counts="10000 30000 100000"
cases="objects materials luminaires nodes includes"
while [[ $# -gt 0 ]]; do
  case "$1" in
    --radiant) radiant="$2"; shift 2 ;;
    --counts) counts="$2"; shift 2 ;;
    --cases) cases="$2"; shift 2 ;;
    *) echo "usage: $0 [--radiant PATH] [--counts \"N1 N2 …\"] [--cases \"objects materials …\"]" >&2; exit 2 ;;
  esac
done
source_dir="$(cd "$(dirname "$0")/.." && pwd)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

generate() {  # case N → the file to run
  python3 - "$1" "$2" "$work" "$source_dir" <<'EOF'
import json, math, os, shutil, sys
case, n, work, source = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4]
side = math.isqrt(n) + 1
if case in ("objects", "materials"):
    obj, mtl = os.path.join(work, f"{case}-{n}.obj"), os.path.join(work, f"{case}-{n}.mtl")
    with open(obj, "w") as f, open(mtl, "w") as m:
        f.write(f"mtllib {case}-{n}.mtl\n")
        m.write("newmtl light\nKd 0.5 0.5 0.5\nKe 10 10 10\n")
        f.write(f"v {-side} 50 {-side}\nv {side} 50 {-side}\nv {side} 50 {side}\nv {-side} 50 {side}\n")
        f.write("usemtl light\nf 4 3 2 1\n")
        for i in range(n):
            x, z = (i % side) * 2.0 - side, (i // side) * 2.0 - side
            if case == "objects":
                f.write(f"o item{i}\n")
            else:
                m.write(f"newmtl m{i}\nKd 0.{1 + i % 8} 0.5 0.5\n")
                f.write(f"usemtl m{i}\n")
            v = 4 + 4 * i
            f.write(f"v {x} 0 {z}\nv {x + 1} 0 {z}\nv {x + 1} 0 {z + 1}\nv {x} 0 {z + 1}\n")
            f.write(f"f {v + 1} {v + 2} {v + 3} {v + 4}\n")
    print(obj)
elif case == "nodes":
    import base64, struct
    quad = struct.pack("<12f", 0, 0, 0, 1, 0, 0, 1, 0, 1, 0, 0, 1) + struct.pack("<6H", 0, 2, 1, 0, 3, 2)
    uri = "data:application/octet-stream;base64," + base64.b64encode(quad).decode()
    nodes = [{"children": list(range(1, n + 1))}]
    nodes += [{"mesh": 0, "translation": [(i % side) * 2.0, 0, (i // side) * 2.0]} for i in range(n)]
    gltf = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": nodes,
            "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
            "buffers": [{"byteLength": len(quad), "uri": uri}],
            "bufferViews": [{"buffer": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 12}],
            "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                           "min": [0, 0, 0], "max": [1, 0, 1]},
                          {"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"}]}
    path = os.path.join(work, f"nodes-{n}.gltf")
    json.dump(gltf, open(path, "w"))
    print(path)
elif case == "includes":
    with open(os.path.join(work, "quad.mgf"), "w") as f:
        f.write("m grey =\n c\n rd 0.5\nv a =\n p 0 0 0\nv b =\n p 1 0 0\nv c =\n p 1 0 1\nv d =\n p 0 0 1\n"
                "f a b c d\n")
    path = os.path.join(work, f"includes-{n}.mgf")
    with open(path, "w") as f:
        for i in range(n):
            f.write(f"i quad.mgf -t {(i % side) * 2.0} 0 {(i // side) * 2.0}\n")
    print(path)
else:
    shutil.copy(os.path.join(source, "tests/photometry/lambertian_downlight.ies"), work)
    scene = {"version": 1, "materials": {"grey": {"reflectance": 0.5}},
             "objects": [{"type": "quad", "material": "grey",
                          "vertices": [[0, 0, 0], [0, 0, side], [side, 0, side], [side, 0, 0]]}],
             "camera": {"eye": [side / 2, side, -side / 2], "target": [side / 2, 0, side / 2], "fov": 60},
             "luminaires": [{"ies": "lambertian_downlight.ies", "position": [(i % side) + 0.5, 2.5, (i // side) + 0.5]}
                            for i in range(n)]}
    path = os.path.join(work, f"luminaires-{n}.json")
    json.dump(scene, open(path, "w"))
    print(path)
EOF
}

echo "| case | N | wall s | peak MB | µs per item | time ratio to previous N |"
echo "|---|---:|---:|---:|---:|---:|"
for case in $cases; do
  previous=""
  for n in $counts; do
    file="$(generate "$case" "$n")"
    if [[ "$case" == luminaires ]]; then
      command=("$radiant" render "$file" --spp 1 --width 64 --height 48 -q -o "$work/l.png")
    elif [[ "$case" == nodes || "$case" == includes ]]; then
      command=("$radiant" info "$file")
    else
      command=("$radiant" solve "$file" --solver stochastic -q)
    fi
    /usr/bin/time -f "%e %M" -o "$work/time" "${command[@]}" > /dev/null
    read -r seconds kilobytes < "$work/time"
    ratio="–"
    [[ -n "$previous" ]] && ratio=$(python3 -c "print(f'{$seconds / $previous:.2f}')")
    python3 -c "print(f'| $case | $n | {$seconds:.2f} | {$kilobytes / 1024:.0f} | {$seconds / $n * 1e6:.0f} | $ratio |')"
    previous="$seconds"
    rm -f "$work"/"$case"-*
  done
done
