#!/usr/bin/env bash
# mpi_cpu — the CPU time that `mpirun -np N radiant solve` costs against one
# process (issue 36: at most 1.6× for 3 ranks on one machine). Runs, alternating,
# `radiant solve SCENE` as one process (its default threads) and under
# `mpirun -np N` (one thread per rank), and prints the user + system CPU time
# of each run (summed over mpirun's ranks, which it waits for) and the ratio of
# the medians. The solutions are the same (tests/mpi_cli_test.sh checks that).
#
#   bench/mpi_cpu.sh SCENE [--ranks N] [--runs K] [--radiant PATH] [-- SOLVE OPTIONS…]
#
# Defaults: 3 ranks, 5 runs, build/radiant. Needs GNU time (/usr/bin/time)
# and Open MPI's mpirun; as root, set OMPI_ALLOW_RUN_AS_ROOT=1 and
# OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
radiant=$here/build/radiant ranks=3 runs=5 scene=
while [ $# -gt 0 ]; do
  case $1 in
    --ranks) ranks=$2; shift 2 ;;
    --runs) runs=$2; shift 2 ;;
    --radiant) radiant=$2; shift 2 ;;
    --) shift; break ;;
    -*) echo "mpi_cpu.sh: unknown option $1" >&2; exit 2 ;;
    *) scene=$1; shift ;;
  esac
done
[ -n "$scene" ] || { echo "usage: bench/mpi_cpu.sh SCENE [--ranks N] [--runs K] [--radiant PATH] [-- OPTIONS]" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# Waiting in MPI's start and end gives the core back (radiant's own collectives sleep anyway).
export OMPI_MCA_mpi_yield_when_idle=1
cpu() { awk '{ printf "%.2f", $1 + $2 }' "$work/time"; }
one=() many=()
for ((i = 0; i < runs; ++i)); do
  /usr/bin/time -o "$work/time" -f "%U %S" "$radiant" solve "$scene" -q -o "$work/one.rad" "$@" >/dev/null
  one+=("$(cpu)")
  /usr/bin/time -o "$work/time" -f "%U %S" mpirun --oversubscribe --bind-to none -np "$ranks" \
    "$radiant" solve "$scene" -q -o "$work/many.rad" --threads 1 "$@" >/dev/null
  many+=("$(cpu)")
done
median() { printf "%s\n" "$@" | sort -n | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
m1=$(median "${one[@]}") mn=$(median "${many[@]}")
echo "| $(basename "$(dirname "$scene")")/$(basename "$scene") $* | ${one[*]} (median $m1 s) | ${many[*]} (median $mn s) | $(awk -v a="$mn" -v b="$m1" 'BEGIN { printf "%.2f", a / b }') |"
