#!/usr/bin/env bash
# radiant under mpirun (docs/cluster.md): two and three ranks on one machine
# write the very image and solution of one process, for the per-pixel methods
# and every distributed solver; a render stopped under mpirun resumes
# with another rank count; an error on the ranks ends the job. Skipped (77)
# where radiant was built without MPI or mpirun is missing, unless
# RADIANT_REQUIRE_MPI_TESTS=1 (CI). Usage: mpi_cli_test.sh path/to/radiant SOURCE_DIR
source "$(dirname "$0")/cli_common.sh"

if ! "$radiant" --version | grep -q "(MPI)" || ! command -v mpirun >/dev/null; then
  echo "radiant built without MPI, or no mpirun: install libopenmpi-dev openmpi-bin and rebuild"
  [ "${RADIANT_REQUIRE_MPI_TESTS:-0}" = 1 ] && exit 1
  exit 77
fi
# CI runs as root; more ranks than cores; waiting ranks yield the core (two cores here).
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_mpi_yield_when_idle=1
mpi() { timeout 300 mpirun --oversubscribe -np "$@"; }
# A machine where mpirun cannot start two processes at all (a container without shared memory or network
# interfaces) has no MPI to test: say so and skip, unless required.
if ! mpi 2 true >mpi-probe.txt 2>&1; then
  echo "mpirun cannot start 2 processes here:"; head -20 mpi-probe.txt
  [ "${RADIANT_REQUIRE_MPI_TESTS:-0}" = 1 ] && exit 1
  exit 77
fi

size=(--width 48 --height 48)
# same_image NAME ARGS...: 1, 2 and 3 ranks, the same bytes.
same_image() {
  local name=$1
  shift
  "$radiant" render "$@" -q -o one.exr || { fail "$name: one process"; return; }
  for n in 2 3; do
    mpi "$n" "$radiant" render "$@" -q -o "ranks$n.exr" || { fail "$name: $n ranks"; continue; }
    cmp -s one.exr "ranks$n.exr" && pass || fail "$name: $n ranks give another image than one process"
  done
}
same_image path "$cornell" "${size[@]}" --spp 16
same_image "interpolate (stochastic solve)" "$cornell" "${size[@]}" --spp 16 --method interpolate --solver stochastic
same_image "rushmeier" "$cornell" "${size[@]}" --spp 8 --method rushmeier --solver stochastic
same_image "kok" "$cornell" "${size[@]}" --spp 8 --method kok --solver stochastic
same_image "path, a 1-pixel tile" "$cornell" "${size[@]}" --spp 4 --pixel 20,30
same_image "multipass" "$specular" --width 32 --height 32 --spp 6 --method multipass --solver stochastic

# The distributed stochastic solve: the same solution (its file differs only in the time it took: compare images of it).
"$radiant" solve "$cornell" --solver stochastic -q -o one.rad || fail "solve: one process"
mpi 3 "$radiant" solve "$cornell" --solver stochastic -q -o three.rad || fail "solve: 3 ranks"
# interpolate reads the node values: the exact direct light and the reflected light's density estimate.
for method in flat interpolate; do
  "$radiant" render "$cornell" "${size[@]}" --spp 4 --method $method --solution one.rad -q -o solved1.exr
  "$radiant" render "$cornell" "${size[@]}" --spp 4 --method $method --solution three.rad -q -o solved3.exr
  cmp -s solved1.exr solved3.exr && pass || fail "solve: 3 ranks give another solution than one process ($method)"
done

# The distributed hierarchical-exact solve (named: auto's is solved by rank 0 alone, below): each rank
# estimates the links into the receivers it owns and the direct light at every N-th point, and the ranks
# share them: the same solution.
"$radiant" solve "$cornell" -q -o exact1.rad || fail "hierarchical-exact: one process"
mpi 2 "$radiant" solve "$cornell" --solver hierarchical-exact -o exact2.rad >exact2.log 2>&1 ||
  fail "hierarchical-exact: 2 ranks"
grep -q "hierarchical-exact solved" exact2.log && grep -q "summed" exact2.log && ! grep -q "summed 0.0 MB" exact2.log &&
  ! grep -q "alone" exact2.log && pass || { fail "hierarchical-exact on 2 ranks shared no work:"; cat exact2.log; }
"$radiant" render "$cornell" "${size[@]}" --spp 4 --method interpolate --solution exact1.rad -q -o exact1.exr
"$radiant" render "$cornell" "${size[@]}" --spp 4 --method interpolate --solution exact2.rad -q -o exact2.exr
cmp -s exact1.exr exact2.exr && pass || fail "hierarchical-exact: 2 ranks give another solution than one process"

# auto's hierarchical-exact (a scene of at most 2000 faces, a solve of seconds) is too small to share:
# rank 0 solves it alone, the others only wait, and the solution is one process's.
mpi 3 "$radiant" solve "$cornell" -o alone3.rad >alone3.log 2>&1 || fail "auto's hierarchical-exact: 3 ranks"
grep -q "^radiant: 3 ranks: rank 0 solves alone (auto's hierarchical-exact" alone3.log &&
  grep -q "hierarchical-exact solved" alone3.log && ! grep -q "summed" alone3.log && pass ||
  { fail "auto's hierarchical-exact on 3 ranks was not rank 0's alone:"; cat alone3.log; }
"$radiant" render "$cornell" "${size[@]}" --spp 4 --method interpolate --solution alone3.rad -q -o alone3.exr
cmp -s exact1.exr alone3.exr && pass || fail "auto's hierarchical-exact alone on rank 0 gives another solution"
# A parameter given (here the default tolerance, written out) shares it again.
mpi 2 "$radiant" solve "$cornell" --tolerance 0.001 -o given2.rad >given2.log 2>&1 && grep -q "summed" given2.log &&
  ! grep -q "alone" given2.log && pass || { fail "auto's solve with a parameter given was not shared"; cat given2.log; }

# The classic hierarchical solver: each rank measures the form factors of the links into the receivers it
# owns, and the ranks share them; 3 ranks on the Cornell box give one process's solution.
"$radiant" solve "$cornell" --solver hierarchical -q -o hsa1.rad || fail "hierarchical: one process"
mpi 3 "$radiant" solve "$cornell" --solver hierarchical -o hsa3.rad >hsa3.log 2>&1 || fail "hierarchical: 3 ranks"
grep -q "summed" hsa3.log && ! grep -q "summed 0.0 MB" hsa3.log && pass ||
  { fail "hierarchical on 3 ranks shared no work:"; cat hsa3.log; }
"$radiant" render "$cornell" "${size[@]}" --spp 4 --method interpolate --solution hsa1.rad -q -o hsa1.exr
"$radiant" render "$cornell" "${size[@]}" --spp 4 --method interpolate --solution hsa3.rad -q -o hsa3.exr
cmp -s hsa1.exr hsa3.exr && pass || fail "hierarchical: 3 ranks give another solution than one process"

# gauss-seidel (its matrix's rows split over the ranks) and progressive (each shot's receivers split).
for solver in gauss-seidel progressive; do
  "$radiant" solve "$cornell" --solver $solver -q -o "$solver-1.rad" || fail "$solver: one process"
  mpi 2 "$radiant" solve "$cornell" --solver $solver -q -o "$solver-2.rad" || fail "$solver: 2 ranks"
  "$radiant" render "$cornell" "${size[@]}" --spp 4 --method flat --solution "$solver-1.rad" -q -o "$solver-1.exr"
  "$radiant" render "$cornell" "${size[@]}" --spp 4 --method flat --solution "$solver-2.rad" -q -o "$solver-2.exr"
  cmp -s "$solver-1.exr" "$solver-2.exr" && pass || fail "$solver: 2 ranks give another solution than one process"
done

# A render stopped under mpirun (SIGTERM, as a batch system's time limit sends) resumes with another rank count.
"$radiant" render "$cornell" --width 96 --height 96 --spp 512 -q -o whole.exr
# mpirun itself in the background, not the mpi function: $! of a function is its subshell, and
# SIGTERM to that would leave mpirun running on to the end beside the resumed job.
mpirun --oversubscribe -np 2 "$radiant" render "$cornell" --width 96 --height 96 --spp 512 -q -o part.exr \
  --checkpoint ck.bin --checkpoint-interval 0.2 2>/dev/null &
pid=$!
for _ in $(seq 600); do [ -f ck.bin ] && break; sleep 0.1; done
sleep 0.5
kill -TERM $pid
wait $pid 2>/dev/null
if [ -f ck.bin ]; then
  mpi 3 "$radiant" render "$cornell" --width 96 --height 96 --spp 512 -o part.exr --checkpoint ck.bin --resume \
    2>err.txt || fail "resume on 3 ranks"
  grep -q "resumed from ck.bin" err.txt || fail "resume on 3 ranks: did not say it resumed"
  cmp -s whole.exr part.exr && pass || fail "stopped on 2 ranks, resumed on 3: another image"
else
  fail "the 2-rank render finished before it was stopped, or saved no checkpoint"
fi

# An error ends the whole job (no rank left waiting), printed once by rank 0, exit non-zero.
expect_error "missing scene under mpirun" "^radiant: error: .*nothing.json" mpi 3 "$radiant" render nothing.json -o x.exr
[ "$(grep -c '^radiant: error' err.txt)" = 1 ] && pass || fail "the error printed more than once by rank 0"

finish
