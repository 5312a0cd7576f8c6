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
#
# Usage: bench/input_scale.sh [--radiant PATH] [--counts "10000 30000 100000"]
set -euo pipefail

radiant=build/radiant
counts="10000 30000 100000"
while [[ $# -gt 0 ]]; do
  case "$1" in
    --radiant) radiant="$2"; shift 2 ;;
    --counts) counts="$2"; shift 2 ;;
    *) echo "usage: $0 [--radiant PATH] [--counts \"N1 N2 …\"]" >&2; exit 2 ;;
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
for case in objects materials luminaires; do
  previous=""
  for n in $counts; do
    file="$(generate "$case" "$n")"
    if [[ "$case" == luminaires ]]; then
      command=("$radiant" render "$file" --spp 1 --width 64 --height 48 -q -o "$work/l.png")
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
