#!/usr/bin/env bash
# default_scenes — what a user gets from the default command, against the
# path tracer given the same wall time, on scenes of three sizes and two real
# models (issue 36). Prints a Markdown table for docs/PERFORMANCE.md.
#
# For each scene, at one image size (--size, default 256x256, whatever the
# scene file says):
#
#   1. `radiant info SCENE --json`: its faces and the solver `auto` picks.
#   2. The default radiosity image, timed by GNU time (wall s, peak resident
#      memory):
#        radiant render SCENE --method interpolate --width W --height H -q -o interp.exr
#      (no --spp unless --interpolate-spp is given: the true default command).
#   3. The path tracer given the same wall time:
#        radiant render SCENE --width W --height H --time T -q -o path.exr
#      T = the interpolate run's wall time − the path tracer's start-up, the
#      wall time of one `--spp 1` run of the same scene and size (loading,
#      BVH, one sample per pixel, writing the image), measured once per scene.
#      So both commands take about the same time from start to exit; the
#      "path s" column shows what the path run really took. (Without --spp,
#      --time alone decides the path tracer's sample count.)
#   4. A converged reference, cached (--cache), as two independent halves:
#        radiant render SCENE --spp N/2 --seed 987654321 --width W --height H -q -o half1.pfm
#        radiant render SCENE --spp N/2 --seed 123456789 --width W --height H -q -o half2.pfm
#      averaged pixel by pixel into REF (a .pfm: N samples per pixel in all).
#      The halves' noise is independent, so half the RMSE between them,
#      RMSE(half1, half2) / 2, is the noise of REF itself, printed under the
#      table: an image's RMSE near it says little. (The variance file of
#      `render --variance` cannot give it: it treats the stratified samples as
#      independent and overstated the Cornell box's noise 3× in RMSE at 64²,
#      256 spp.) The seeds are not the scenes' own (1), so the reference's
#      samples are not the first samples of the path image it judges, which
#      would correlate their noise and flatter the path tracer. The file name
#      holds the scene's path, a hash of the scene file's text, the size, N
#      and the seeds, so a changed setting renders a new reference; delete
#      the cache after changing the path tracer itself.
#   5. `radiant compare IMAGE REF --json` for both images: RMSE over all
#      pixels and the three channels (the light included), and the mean ratio
#      test/reference per channel of the interpolate image (its bias).
#
# --repeats K runs steps 2-3 K times: the table gives the medians of the
# times, peak memory, RMSEs and mean ratios (the same seed each time: the
# interpolate image repeats exactly, the path image's sample count varies with
# its time).
#
# Scenes (--scenes a,b,... picks some, in this order):
#   cornell     scenes/cornell-box/scene.json (17 faces)
#   sphere-1e4  scenes/cornell-sphere-1m/scene.json with the sphere's
#               "segments" 140 (9807 faces, 19 332 triangles), written to the cache
#   knots       scenes/cornell-knots/scene.json (10⁵ triangles)
#   sphere-1m   scenes/cornell-sphere-1m/scene.json (10⁶ triangles)
#   engine      assimp's glTF 2CylinderEngine (a CAD model, intersecting
#               parts) on the floor of the Cornell box without its blocks
#   wuson       assimp's WusonOBJ (smooth low-poly OBJ with vertex normals)
#               in the Cornell box without its blocks
# engine and wuson need Debian's assimp-testmodels
# (apt-get install assimp-testmodels); without it they are skipped.
#
# Usage: bench/default_scenes.sh [--scenes a,b,...] [--size WxH]
#          [--repeats K] [--reference-spp N] [--interpolate-spp N]
#          [--cache DIR] [--radiant PATH]
#   --size WxH            image size (default 256x256)
#   --repeats K           runs of steps 2-3 per scene, medians (default 1)
#   --reference-spp N     the reference's samples per pixel, even (default 4096)
#   --interpolate-spp N   pass --spp N to the interpolate run (default: none)
#   --cache DIR           references and generated scenes (default
#                         bench-cache/ under the current directory)
#   --radiant PATH        the binary (default build/radiant of this checkout)
#
# How long: each scene costs about 2 × its interpolate time × K, plus one
# short 1-spp run, plus its reference the first time. The references
# dominate a first run: 4096 spp at 256² is 2.7·10⁸ paths per scene, about
# 5 minutes on 2 cores for the Cornell box (0.8 Msamples/s) and more for the
# larger scenes, so a first run of all six takes the order of an hour; later
# runs reuse them and take a few minutes. Every command uses all cores (no
# --threads), as a user's default command does, so run it on an idle machine
# (the load before and after is printed with the table).
set -euo pipefail

here=$(cd "$(dirname "$0")/.." && pwd)
command_line="bench/default_scenes.sh"
for arg in "$@"; do
  if [[ $arg =~ ^[A-Za-z0-9_./,=:+-]+$ ]]; then command_line+=" $arg"; else command_line+=" $(printf '%q' "$arg")"; fi
done

all_scenes=(cornell sphere-1e4 knots sphere-1m engine wuson)
scenes_option=$(IFS=,; echo "${all_scenes[*]}")
size=256x256
repeats=1
reference_spp=4096
interpolate_spp=""
cache="$PWD/bench-cache"
radiant="$here/build/radiant"
reference_seeds=(987654321 123456789)
engine_model=/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb
wuson_model=/usr/share/assimp/models/OBJ/WusonOBJ.obj

usage() {
  sed -n '/^# Usage:/,/^#   --radiant/p' "$0" | sed 's/^# \{0,1\}//' >&2
  exit 2
}
fail() {
  echo "default_scenes: $*" >&2
  exit 2
}
log() { echo "default_scenes: $*" >&2; }
positive_integer() { [[ $1 =~ ^[1-9][0-9]*$ ]] || fail "$2 wants a positive integer, not '$1'"; }

while (($# > 0)); do
  case "$1" in
    --scenes | --size | --repeats | --reference-spp | --interpolate-spp | --cache | --radiant)
      (($# >= 2)) || fail "$1 needs a value"
      case "$1" in
        --scenes) scenes_option=$2 ;;
        --size) size=$2 ;;
        --repeats) repeats=$2 ;;
        --reference-spp) reference_spp=$2 ;;
        --interpolate-spp) interpolate_spp=$2 ;;
        --cache) cache=$2 ;;
        --radiant) radiant=$2 ;;
      esac
      shift 2
      ;;
    -h | --help) usage ;;
    *) echo "default_scenes: unknown argument '$1'" >&2 && usage ;;
  esac
done

[[ $size =~ ^([1-9][0-9]*)x([1-9][0-9]*)$ ]] || fail "--size wants WxH, e.g. 256x256, not '$size'"
width=${BASH_REMATCH[1]}
height=${BASH_REMATCH[2]}
positive_integer "$repeats" --repeats
positive_integer "$reference_spp" --reference-spp
((reference_spp % 2 == 0)) || fail "--reference-spp must be even (two halves of N/2 samples), not $reference_spp"
[[ -z $interpolate_spp ]] || positive_integer "$interpolate_spp" --interpolate-spp
IFS=, read -r -a scenes <<<"$scenes_option"
for name in "${scenes[@]}"; do
  [[ " ${all_scenes[*]} " == *" $name "* ]] || fail "unknown scene '$name' (known: ${all_scenes[*]})"
done
[[ -x $radiant ]] || fail "no radiant binary at $radiant (build it, or give --radiant PATH)"
[[ -x /usr/bin/time ]] || fail "needs GNU time at /usr/bin/time (apt-get install time)"
command -v python3 > /dev/null || fail "needs python3"

mkdir -p "$cache/scenes"
cache=$(cd "$cache" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
results="$work/results.jsonl"
: > "$results"
size_args=(--width "$width" --height "$height")
load_before=$(cut -d' ' -f1 /proc/loadavg)

# The Cornell box's walls, light, camera and materials with MODEL (an object
# of TYPE) in place of its blocks, written to the cache as NAME.json.
cornell_with_model() {
  local name=$1 type=$2 model=$3 transform=$4 reflectance=$5
  python3 - "$here/scenes/cornell-box/scene.json" "$cache/scenes/$name.json" "$name" "$type" "$model" \
    "$transform" "$reflectance" <<'EOF'
import json, sys
source, target, name, kind, model, transform, reflectance = sys.argv[1:]
scene = json.load(open(source))
scene["comment"] = ("Generated by bench/default_scenes.sh from scenes/cornell-box/scene.json: its walls, "
                    f"light, camera and materials, the blocks replaced by {model}.")
scene["objects"] = [o for o in scene["objects"]
                    if not o["name"].startswith(("short-block-", "tall-block-"))]
scene["materials"][name] = {"reflectance": json.loads(reflectance)}
scene["objects"].append({"name": name, "type": kind, "file": model, "material": name,
                         "transform": json.loads(transform)})
json.dump(scene, open(target, "w"), indent=1)
EOF
}

# Sets scene_path for the short NAME (generating it into the cache if it is
# one of ours), or returns 1 with the reason in skip_reason.
resolve_scene() {
  local name=$1
  skip_reason=""
  case "$name" in
    cornell) scene_path="$here/scenes/cornell-box/scene.json" ;;
    knots) scene_path="$here/scenes/cornell-knots/scene.json" ;;
    sphere-1m) scene_path="$here/scenes/cornell-sphere-1m/scene.json" ;;
    sphere-1e4)
      scene_path="$cache/scenes/sphere-1e4.json"
      python3 - "$here/scenes/cornell-sphere-1m/scene.json" "$scene_path" <<'EOF'
import json, sys
source, target = sys.argv[1:]
scene = json.load(open(source))
scene["comment"] = ("Generated by bench/default_scenes.sh from scenes/cornell-sphere-1m/scene.json "
                    "with the sphere at 140 segments.")
spheres = [o for o in scene["objects"] if o["type"] == "sphere"]
assert len(spheres) == 1, "expected one sphere in " + source
spheres[0]["segments"] = 140
json.dump(scene, open(target, "w"), indent=1)
EOF
      ;;
    engine | wuson)
      local model=$engine_model
      [[ $name == wuson ]] && model=$wuson_model
      if [[ ! -f $model ]]; then
        skip_reason="$model is missing (Debian package assimp-testmodels: apt-get install assimp-testmodels)"
        return 1
      fi
      scene_path="$cache/scenes/$name.json"
      if [[ $name == engine ]]; then
        cornell_with_model engine gltf "$model" '{"scale": 0.5, "translate": [278, 90.5, 280]}' '[0.6, 0.6, 0.6]'
      else
        cornell_with_model wuson obj "$model" \
          '{"scale": 120, "rotate": [{"axis": [0, 1, 0], "degrees": 90}], "translate": [278, 0.07, 280]}' \
          '[0.7, 0.6, 0.4]'
      fi
      ;;
  esac
  if [[ ! -f $scene_path ]]; then
    skip_reason="$scene_path is missing"
    return 1
  fi
}

# The cached reference's file name: the scene's path (relative to the
# checkout or the cache), a hash of its text, size, samples and seeds.
reference_path_for() {
  local scene=$1 relative slug hash seeds
  case "$scene" in
    "$here"/*) relative=${scene#"$here"/} ;;
    "$cache"/*) relative=cache/${scene#"$cache"/} ;;
    *) relative=${scene#/} ;;
  esac
  slug=${relative//\//_}
  hash=$(sha1sum < "$scene" | cut -c1-10)
  seeds=$(IFS=-; echo "${reference_seeds[*]}")
  echo "$cache/ref_${slug%.json}_${hash}_${width}x${height}_${reference_spp}spp_seeds$seeds.pfm"
}

# Writes the pixel-by-pixel mean of two PFM images of one size to a third.
average_pfm() {
  python3 - "$@" <<'EOF'
import array, sys

def read_pfm(path):
    with open(path, "rb") as f:
        header = [f.readline() for _ in range(3)]
        pixels = array.array("f", f.read())
    if float(header[2]) > 0:  # big-endian
        pixels.byteswap()
    return header, pixels

first, second, target = sys.argv[1:]
header, a = read_pfm(first)
header_b, b = read_pfm(second)
assert header[:2] == header_b[:2], "the halves differ in size"
mean = array.array("f", ((x + y) * 0.5 for x, y in zip(a, b)))
with open(target, "wb") as out:
    out.write(header[0] + header[1] + b"-1.0\n")
    if sys.byteorder == "big":
        mean.byteswap()
    out.write(mean.tobytes())
EOF
}

# Runs radiant under GNU time; sets wall_seconds and peak_kb.
timed_radiant() {
  /usr/bin/time -f '%e %M' -o "$work/time" "$radiant" "$@"
  read -r wall_seconds peak_kb < "$work/time"
}

# Appends one JSON line to the results: KIND then key=value pairs, where a
# value of @FILE is the JSON in FILE.
record() {
  python3 - "$results" "$@" <<'EOF'
import json, sys
results, kind, *pairs = sys.argv[1:]
entry = {"kind": kind}
for pair in pairs:
    key, value = pair.split("=", 1)
    if value.startswith("@"):
        entry[key] = json.load(open(value[1:]))
    else:
        try:
            entry[key] = float(value)
        except ValueError:
            entry[key] = value
with open(results, "a") as out:
    out.write(json.dumps(entry) + "\n")
EOF
}

for name in "${scenes[@]}"; do
  if ! resolve_scene "$name"; then
    log "skipping $name: $skip_reason"
    record skipped scene="$name" reason="$skip_reason"
    continue
  fi
  log "$name: $scene_path"
  "$radiant" info "$scene_path" --json > "$work/info.json"

  reference=$(reference_path_for "$scene_path")
  reference_halves=${reference%.pfm}.halves.json
  if [[ -f $reference && -f $reference_halves ]]; then
    log "$name: reusing the reference $reference"
  else
    log "$name: rendering the reference, $reference_spp spp at ${width}x$height in two halves (cached as $reference)"
    for half in 1 2; do
      "$radiant" render "$scene_path" --spp $((reference_spp / 2)) --seed "${reference_seeds[half - 1]}" \
        "${size_args[@]}" -q -o "$work/half$half.pfm"
    done
    "$radiant" compare "$work/half1.pfm" "$work/half2.pfm" --json > "$work/halves.json"
    average_pfm "$work/half1.pfm" "$work/half2.pfm" "$work/ref.pfm"
    # Moved into the cache only once complete, so that a stopped run leaves no
    # partial reference to be reused.
    mv "$work/halves.json" "$reference_halves"
    mv "$work/ref.pfm" "$reference"
  fi

  timed_radiant render "$scene_path" --spp 1 "${size_args[@]}" -q -o "$work/startup.exr"
  startup_seconds=$wall_seconds
  record scene scene="$name" path="$scene_path" info="@$work/info.json" reference="$reference" \
    halves="@$reference_halves" startup_seconds="$startup_seconds"

  interpolate_args=(--method interpolate "${size_args[@]}" -q)
  [[ -z $interpolate_spp ]] || interpolate_args+=(--spp "$interpolate_spp")
  for ((repeat = 1; repeat <= repeats; ++repeat)); do
    timed_radiant render "$scene_path" "${interpolate_args[@]}" -o "$work/interp.exr"
    interpolate_seconds=$wall_seconds
    interpolate_kb=$peak_kb
    # At least 10 ms: a start-up longer than the whole interpolate run still
    # renders one round (the row is then marked).
    budget=$(python3 -c 'import sys; print(f"{max(0.01, float(sys.argv[1]) - float(sys.argv[2])):.3f}")' \
      "$interpolate_seconds" "$startup_seconds")
    timed_radiant render "$scene_path" "${size_args[@]}" --time "$budget" -q -o "$work/path.exr"
    "$radiant" compare "$work/interp.exr" "$reference" --json > "$work/interp-compare.json"
    "$radiant" compare "$work/path.exr" "$reference" --json > "$work/path-compare.json"
    record run scene="$name" interpolate_seconds="$interpolate_seconds" interpolate_kb="$interpolate_kb" \
      path_budget="$budget" path_seconds="$wall_seconds" interpolate="@$work/interp-compare.json" \
      path="@$work/path-compare.json"
    log "$name: run $repeat/$repeats: interpolate ${interpolate_seconds} s, path --time $budget: ${wall_seconds} s"
  done
done

load_after=$(cut -d' ' -f1 /proc/loadavg)
cpu=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -1)
version=$("$radiant" --version 2>&1 | head -1)
commit=$(git -C "$here" rev-parse --short HEAD 2> /dev/null || echo unknown)
[[ -z $(git -C "$here" status --porcelain --untracked-files=no 2> /dev/null) ]] || commit+=" (with local changes)"

machine="nproc = $(nproc), $cpu; load $load_before before, $load_after after; $version, commit $commit."
date=$(date '+%Y-%m-%d %H:%M %Z')
export BENCH_REPEATS=$repeats BENCH_SIZE="${width}x$height" BENCH_INTERPOLATE_SPP=$interpolate_spp \
  BENCH_REFERENCE_SPP=$reference_spp BENCH_REFERENCE_SEEDS="${reference_seeds[*]}" BENCH_COMMAND=$command_line \
  BENCH_MACHINE=$machine BENCH_DATE=$date
python3 - "$results" <<'EOF'
import json, os, statistics, sys

env = os.environ
entries = [json.loads(line) for line in open(sys.argv[1])]
median = statistics.median
print("| scene | faces | auto | interpolate s | path s | peak MB | interpolate RMSE | path RMSE, equal time "
      "| interpolate / path | mean ratio R / G / B (worst) |")
print("|---|---:|---|---:|---:|---:|---:|---:|---:|---|")
notes, any_overrun = [], False
for scene in (e for e in entries if e["kind"] == "scene"):
    runs = [e for e in entries if e["kind"] == "run" and e["scene"] == scene["scene"]]
    interpolate_rmse = median(r["interpolate"]["all"]["rmse"] for r in runs)
    path_rmse = median(r["path"]["all"]["rmse"] for r in runs)
    ratios = [median(r["interpolate"][band]["mean_ratio"] for r in runs) for band in "RGB"]
    worst = max(ratios, key=lambda ratio: abs(ratio - 1))
    # The path tracer's start-up as long as the interpolate run: it got the 10 ms floor, not equal time.
    overrun = "*" if any(r["path_budget"] <= 0.01 for r in runs) else ""
    any_overrun = any_overrun or bool(overrun)
    ratio_text = " / ".join(f"{ratio:.4f}" for ratio in ratios)
    print(f"| {scene['scene']} | {scene['info']['faces']} | {scene['info']['solver']['name']} "
          f"| {median(r['interpolate_seconds'] for r in runs):.2f} "
          f"| {median(r['path_seconds'] for r in runs):.2f}{overrun} "
          f"| {median(r['interpolate_kb'] for r in runs) / 1024:.0f} | {interpolate_rmse:.5f} | {path_rmse:.5f} "
          f"| {interpolate_rmse / path_rmse:.2f} | {ratio_text} ({100 * (worst - 1):+.2f} %) |")
    notes.append(f"{scene['scene']}: path start-up {scene['startup_seconds']:.2f} s, "
                 f"reference noise {scene['halves']['all']['rmse'] / 2:.5f}")
for skipped in (e for e in entries if e["kind"] == "skipped"):
    notes.append(f"{skipped['scene']} skipped: {skipped['reason']}")
spp = env["BENCH_INTERPOLATE_SPP"]
print()
print(f"Medians of {env['BENCH_REPEATS']} run(s) at {env['BENCH_SIZE']}. interpolate: the default command"
      + (f" with --spp {spp}" if spp else "")
      + "; path: --time (interpolate s − path start-up), the start-up being one --spp 1 run; reference: "
      f"{env['BENCH_REFERENCE_SPP']} spp path, two halves (seeds {env['BENCH_REFERENCE_SEEDS']}), its noise "
      "RMSE(half 1, half 2) / 2. RMSE over all pixels and channels; mean ratio: interpolate / reference per "
      "channel."
      + (" *: start-up ≥ the interpolate run, so path ran its 10 ms floor." if any_overrun else ""))
for note in notes:
    print(f"- {note}")
print()
print(f"Machine: {env['BENCH_MACHINE']}")
print(f"Date: {env['BENCH_DATE']}.")
print()
print("```")
print(env["BENCH_COMMAND"])
print("```")
EOF
