#!/usr/bin/env bash
# Fuzzing campaign (docs/fuzzing.md): builds the libFuzzer targets of fuzz/
# in build-fuzz/ (clang, ASan + UBSan) if needed, runs each target to N
# executions, one at a time and nice'd, saves every new crash, timeout or
# out-of-memory input to fuzz/findings/<target>/, and prints a table.
#
#   tools/fuzz.sh [target…] [--runs N] [--seeds]
#
#   target   scene_json, obj_mtl, texture, image, solution_file, photometry,
#            gltf, mgf, hdr
#            (default: all, in that order)
#   --runs N executions per target (default 1000000)
#   --seeds  first rewrite the generated seeds (fuzz/corpus/{texture,image,solution_file}/)
#
# Not run by CI: a campaign takes hours on two cores. Each target starts from
# its seeds (fuzz/corpus/<target>/, in git), the regression inputs
# (tests/fuzz-regressions/<target>/) and the corpus it grew before
# (build-fuzz/corpus/<target>/, not in git). libFuzzer runs in fork mode, so
# that a finding does not end the campaign: the executions count every child.
# A finding goes to fuzz/findings/<target>/; once fixed, `git mv` it to
# tests/fuzz-regressions/<target>/ in the fix's commit, where
# tests/fuzz_regressions_test.cpp replays it in every build.
#
# Environment: FUZZ_BUILD_JOBS (build parallelism, default nproc),
# FUZZ_FORKS (fuzzing processes per target, default 1; nproc on a machine
# left to the campaign), FUZZ_NICE (default 10), RADIANT_BINARY (a built
# radiant, for --seeds).
set -euo pipefail
cd "$(dirname "$0")/.."

all_targets=(scene_json obj_mtl texture image solution_file photometry gltf mgf hdr)
# The largest input libFuzzer makes, per format: a scene or model of a few
# hundred lines, an image of a few kilobytes (the seeds are 5 × 3 texels), a
# solution of a few hundred elements (the seeds are 1.5–12 kB), a photometric
# file of a few hundred angles (the seeds are 0.1–3 kB).
declare -A max_len=([scene_json]=16384 [obj_mtl]=16384 [texture]=32768 [image]=32768 [solution_file]=65536
  [photometry]=16384 [gltf]=16384 [mgf]=16384 [hdr]=32768)

usage() { sed -n '2,/^set -euo/p' "$0" | sed '$d' | sed 's/^# \{0,1\}//'; }

targets=()
runs=1000000
seeds=0
while [ $# -gt 0 ]; do
  case "$1" in
    --runs) runs=${2:?--runs needs a number}; shift 2 ;;
    --runs=*) runs=${1#--runs=}; shift ;;
    --seeds) seeds=1; shift ;;
    -h | --help) usage; exit 0 ;;
    -*) echo "fuzz.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
    *)
      [ -n "${max_len[$1]:-}" ] || { echo "fuzz.sh: unknown target '$1' (one of: ${all_targets[*]})" >&2; exit 2; }
      targets+=("$1"); shift ;;
  esac
done
[[ "$runs" =~ ^[0-9]+$ ]] || { echo "fuzz.sh: --runs expects a number, got '$runs'" >&2; exit 2; }
[ ${#targets[@]} -gt 0 ] || targets=("${all_targets[@]}")

build=build-fuzz
jobs=${FUZZ_BUILD_JOBS:-$(nproc)}
niceness=${FUZZ_NICE:-10}
forks=${FUZZ_FORKS:-1}

# ---- Build ----
compiler=$(command -v clang++-14 || command -v clang++ || true)
[ -n "$compiler" ] || { echo "fuzz.sh: clang++ not found (libFuzzer comes with clang)" >&2; exit 1; }
if [ ! -f "$build/build.ninja" ] && [ ! -f "$build/Makefile" ]; then
  generator=()
  command -v ninja >/dev/null && generator=(-G Ninja)
  # -O2 -g1 as CI's sanitizer build; assertions stay on: a failed one is a finding.
  cmake -S . -B "$build" "${generator[@]}" -DCMAKE_CXX_COMPILER="$compiler" -DRADIANT_FUZZ=ON \
    -DRADIANT_BUILD_TESTS=OFF -DRADIANT_BUILD_BENCH=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g1"
fi
build_targets=()
for t in "${targets[@]}"; do build_targets+=("fuzz_$t"); done
[ "$seeds" = 1 ] && build_targets+=(fuzz_make_seeds)
nice -n "$niceness" cmake --build "$build" -j"$jobs" --target "${build_targets[@]}"

# ---- Generated seeds ----
if [ "$seeds" = 1 ]; then
  "$build/fuzz/fuzz_make_seeds" fuzz/corpus
  # Solutions of the furnace (the scene the solution_file target reads them
  # for), one per kind of content: plain elements, hierarchical trees and
  # links, the node irradiance and cut faces of hierarchical-exact.
  radiant=${RADIANT_BINARY:-build/radiant}
  [ -x "$radiant" ] || { echo "fuzz.sh: --seeds needs a built radiant ($radiant; set RADIANT_BINARY)" >&2; exit 1; }
  furnace=scenes/furnace/scene.json
  "$radiant" solve "$furnace" --solver progressive --mesh-size 0.5 -o fuzz/corpus/solution_file/progressive.rad
  "$radiant" solve "$furnace" --solver hierarchical --mesh-size 0.5 -o fuzz/corpus/solution_file/hierarchical.rad
  # Held to 60 elements: the target's -max_len is 64 kB, and the default
  # refinement makes a 4 MB file of the furnace.
  "$radiant" solve "$furnace" --solver hierarchical-exact --mesh-size 0.5 --quality draft --max-elements 60 \
    -o fuzz/corpus/solution_file/hierarchical-exact.rad
  # fuzz/corpus/solution_file/stored-geometry.rad (a mesh stored in full: the
  # progressive furnace with one node moved by an ulp) was written once by a
  # test-only writer and is kept as it is; no command here remakes it.
fi

# ---- Campaign ----
scratch=$(mktemp -d "${TMPDIR:-/tmp}/radiant-fuzz-XXXXXX")
[ -d /dev/shm ] && { rmdir "$scratch"; scratch=$(mktemp -d /dev/shm/radiant-fuzz-XXXXXX); }
trap 'rm -rf "$scratch"' EXIT
summary="$build/fuzz-summary.tsv"
[ -f "$summary" ] || printf 'date\ttarget\texecutions\texec_per_s\tcrashes\ttimeouts\tooms\tnew_findings\tseconds\n' >"$summary"

rows=()
status=0
for t in "${targets[@]}"; do
  corpus="$build/corpus/$t"
  artifacts="$build/artifacts/$t"
  findings="fuzz/findings/$t"
  log="$build/logs/$t.log"
  mkdir -p "$corpus" "$artifacts" "$build/logs" "tests/fuzz-regressions/$t"
  inputs=("$corpus" "fuzz/corpus/$t" "tests/fuzz-regressions/$t")
  dictionary=()
  [ -f "fuzz/dict/$t.dict" ] && dictionary=(-dict="fuzz/dict/$t.dict")
  echo "== $t: $runs executions (log: $log)"
  start=$(date +%s)
  # halt_on_error: a UBSan report is a finding, not a line in the log.
  RADIANT_FUZZ_SCRATCH="$scratch" UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
    nice -n "$niceness" "$build/fuzz/fuzz_$t" -fork="$forks" -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1 \
    -runs="$runs" -max_len="${max_len[$t]}" -timeout=10 -rss_limit_mb=2048 -print_funcs=0 "${dictionary[@]}" \
    -artifact_prefix="$artifacts/" "${inputs[@]}" >"$log" 2>&1 || true
  seconds=$(($(date +%s) - start))
  # Fork mode's status lines: "#N: cov: … exec/s E oom/timeout/crash: O/T/C time: …", and at
  # the end "INFO: fuzzed for N iterations". The rate is the campaign's mean.
  last=$(grep -E '^#[0-9]+: cov:' "$log" | tail -1 || true)
  executions=$(sed -nE 's/^INFO: fuzzed for ([0-9]+) iterations.*/\1/p' "$log" | tail -1)
  [ -n "$executions" ] || executions=$(sed -nE 's/^#([0-9]+):.*/\1/p' <<<"$last")
  rate=$([ -n "$executions" ] && echo $((executions / (seconds > 0 ? seconds : 1))) || true)
  IFS=/ read -r ooms timeouts crashes < <(sed -nE 's/.*oom\/timeout\/crash: ([0-9]+\/[0-9]+\/[0-9]+).*/\1/p' <<<"$last")
  # New: no file with the same bytes among the findings and regression inputs
  # (which are renamed for what they test once triaged).
  new=0
  known=$(find "$findings" "tests/fuzz-regressions/$t" -type f -exec sha1sum {} + 2>/dev/null | cut -d' ' -f1 || true)
  for file in "$artifacts"/*; do
    [ -f "$file" ] || continue
    grep -qx "$(sha1sum "$file" | cut -d' ' -f1)" <<<"$known" && continue
    mkdir -p "$findings"
    cp "$file" "$findings/$(basename "$file")"
    new=$((new + 1))
  done
  [ "$new" -gt 0 ] && status=1
  rows+=("$t ${executions:-?} ${rate:-?} ${crashes:-?} ${timeouts:-?} ${ooms:-?} $new ${seconds}")
  printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$(date -u +%FT%TZ)" "$t" "${executions:-?}" "${rate:-?}" \
    "${crashes:-?}" "${timeouts:-?}" "${ooms:-?}" "$new" "$seconds" >>"$summary"
done

echo
printf '%-14s %12s %8s %8s %9s %6s %13s %9s\n' target executions exec/s crashes timeouts ooms new-findings seconds
for row in "${rows[@]}"; do
  # shellcheck disable=SC2086  # the row's fields, split on purpose
  printf '%-14s %12s %8s %8s %9s %6s %13s %9s\n' $row
done
echo "(also appended to $summary; new findings are in fuzz/findings/<target>/)"
exit "$status"
