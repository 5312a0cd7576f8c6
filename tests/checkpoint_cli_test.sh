#!/usr/bin/env bash
# radiant render --checkpoint/--resume as a user runs them (docs/cluster.md):
# a render killed with SIGKILL (no chance to save) or stopped with SIGTERM (it
# saves), then resumed, writes the very image of a run never stopped, a
# spectral one too; the
# flags' misuse is refused. Usage: checkpoint_cli_test.sh path/to/radiant SOURCE_DIR
source "$(dirname "$0")/cli_common.sh"

# Under the sanitizers (CI sets RADIANT_SANITIZED_RUN=1) a render takes ten times as long: a quarter of
# the pixels still runs for seconds, long enough to be stopped after its first checkpoint.
sanitized=0
[ "${RADIANT_SANITIZED_RUN:-0}" = 1 ] && sanitized=1
size=(--width 64 --height 64)
rsize=(--width 48 --height 48)
[ $sanitized = 1 ] && size=(--width 32 --height 32) && rsize=(--width 24 --height 24)
"$radiant" render "$cornell" "${size[@]}" --spp 512 -o whole.exr -q || fail "the uninterrupted render"

# wait_for FILE: until it exists (the first checkpoint), at most 60 s.
wait_for() {
  for _ in $(seq 600); do [ -f "$1" ] && return 0; sleep 0.1; done
  return 1
}

# stop_and_resume SIGNAL: start, stop with SIGNAL after the first checkpoint, resume, compare.
stop_and_resume() {
  local signal=$1
  rm -f ck.bin resumed.exr
  "$radiant" render "$cornell" "${size[@]}" --spp 512 -o resumed.exr -q --checkpoint ck.bin \
    --checkpoint-interval 0.2 2>/dev/null &
  local pid=$!
  wait_for ck.bin || fail "$signal: no checkpoint within 60 s"
  kill -"$signal" $pid
  wait $pid 2>/dev/null
  [ -f ck.bin ] || { fail "$signal: the render finished before it was stopped (make it longer)"; return; }
  "$radiant" render "$cornell" "${size[@]}" --spp 512 -o resumed.exr --checkpoint ck.bin --resume 2>err.txt ||
    fail "$signal: the resumed render"
  grep -q "resumed from ck.bin" err.txt || fail "$signal: did not say it resumed"
  cmp -s whole.exr resumed.exr && pass || fail "$signal: the resumed image differs from the uninterrupted one"
  [ ! -f ck.bin ] && pass || fail "$signal: a finished render left its checkpoint"
}
stop_and_resume KILL
stop_and_resume TERM

# A method that reads a radiosity solution solves it first: the stochastic solve checkpoints beside the film
# (ck.solve.bin) and keeps its final state, so that a render killed in its image phase does not solve again.
rs=(--method rushmeier --solver stochastic "${rsize[@]}" --spp 1024)
"$radiant" render "$cornell" "${rs[@]}" -q -o rwhole.exr || fail "the uninterrupted rushmeier render"
"$radiant" render "$cornell" "${rs[@]}" -q -o rresumed.exr --checkpoint rk.bin --checkpoint-interval 0.2 2>/dev/null &
pid=$!
wait_for rk.bin || fail "rushmeier: no checkpoint within 60 s"
kill -KILL $pid
wait $pid 2>/dev/null
[ -f rk.solve.bin ] && pass || fail "rushmeier: no checkpoint of its solve beside the film's"
"$radiant" render "$cornell" "${rs[@]}" -o rresumed.exr --checkpoint rk.bin --resume 2>rerr.txt || fail "rushmeier: resumed"
grep -q "resumed from rk.solve.bin after iteration" rerr.txt && grep -q "resumed from rk.bin" rerr.txt && pass ||
  { fail "rushmeier: did not resume both the solve and the film:"; cat rerr.txt; }
cmp -s rwhole.exr rresumed.exr && pass || fail "rushmeier: the resumed image differs from the uninterrupted one"
compgen -G "rk*.bin" >/dev/null && fail "rushmeier: a finished render left its checkpoints" || pass

# The spectral and multipass runs below are stopped and resumed in Release builds only: under the
# sanitizers (CI sets RADIANT_SANITIZED_RUN=1) each would take minutes, and the unit tests
# (Multipass.AResumedRenderEndsWithTheUninterruptedImage, SolveCheckpoint.*) run the same code there.
heavy=1
[ $sanitized = 1 ] && heavy=0 && echo "skipped under the sanitizers: the spectral and multipass stops"
ssize=(--width 32 --height 32)

if [ $heavy = 1 ]; then
  # A spectral render (6 passes of 3 wavelengths) checkpoints each pass in a file of its own, kept to the end:
  # killed in its second pass, then resumed, it does not redo the first and writes the uninterrupted image.
  "$radiant" render "$spectral" "${ssize[@]}" --spp 256 -o swhole.exr -q || fail "the uninterrupted spectral render"
  "$radiant" render "$spectral" "${ssize[@]}" --spp 256 -o sresumed.exr -q --checkpoint sck.bin \
    --checkpoint-interval 0.2 2>/dev/null &
  pid=$!
  wait_for sck.pass2.bin || fail "spectral: no second pass's checkpoint within 60 s"
  kill -KILL $pid
  wait $pid 2>/dev/null
  if [ -f sck.pass6.bin ] || [ ! -f sck.pass1.bin ]; then
    fail "spectral: killed in pass 2, expected sck.pass1.bin and no sck.pass6.bin:"; ls sck*
  fi
  expect_error "a spectral pass's checkpoint without --resume" "sck.pass1.bin' exists: add --resume" \
    "$radiant" render "$spectral" "${ssize[@]}" --spp 256 -o sresumed.exr --checkpoint sck.bin
  "$radiant" render "$spectral" "${ssize[@]}" --spp 256 -o sresumed.exr --checkpoint sck.bin --resume 2>serr.txt ||
    fail "spectral: the resumed render"
  grep -q "resumed from sck.pass1.bin (256 spp done)" serr.txt && pass || { fail "spectral: pass 1 redone:"; cat serr.txt; }
  cmp -s swhole.exr sresumed.exr && pass || fail "spectral: the resumed image differs from the uninterrupted one"
  compgen -G "sck.pass*.bin" >/dev/null && fail "spectral: a finished render left its checkpoints" || pass
fi

# Misuse.
expect_error "--resume alone" "--resume: needs --checkpoint" "$radiant" render "$cornell" --spp 1 --resume -o x.exr
echo "not a checkpoint at all, but long enough to hold a header" >old.bin
expect_error "an existing checkpoint without --resume" "old.bin' exists: add --resume" \
  "$radiant" render "$cornell" --spp 1 --checkpoint old.bin -o x.exr
expect_error "not a checkpoint" "old.bin.*not a usable render checkpoint" \
  "$radiant" render "$cornell" --spp 1 --checkpoint old.bin --resume -o x.exr
# Another job's checkpoint: saved by a stopped render, offered to a different seed.
"$radiant" render "$cornell" "${size[@]}" --spp 512 -o y.exr -q --checkpoint other.bin --checkpoint-interval 0.2 \
  2>/dev/null &
pid=$!
wait_for other.bin && kill -KILL $pid
wait $pid 2>/dev/null
expect_error "another job's checkpoint" "other.bin.*belongs to another job" \
  "$radiant" render "$cornell" "${size[@]}" --spp 512 --seed 7 -o y.exr --checkpoint other.bin --resume

mp=(--method multipass --width 48 --height 48 --spp 2048 --solver stochastic)
if [ $heavy = 1 ]; then
  # multipass: its state saved at the start of every pass from 3 on, the pass in progress beside it (m.passK.bin);
  # killed in one of its long last passes, then resumed, it ends with the uninterrupted run's image.
  "$radiant" render "$specular" "${mp[@]}" -q -o mwhole.exr || fail "the uninterrupted multipass render"
  "$radiant" render "$specular" "${mp[@]}" -q -o mresumed.exr --checkpoint m.bin --checkpoint-interval 0.2 2>/dev/null &
  pid=$!
  for _ in $(seq 1200); do compgen -G "m.pass1[23].bin" >/dev/null && break; sleep 0.05; done
  kill -KILL $pid
  wait $pid 2>/dev/null
  if [ -f m.bin ]; then
    "$radiant" render "$specular" "${mp[@]}" -o mresumed.exr --checkpoint m.bin --resume 2>merr.txt ||
      fail "multipass: the resumed render"
    grep -q "resumed from m.bin at pass 1[23]" merr.txt && pass || { fail "multipass: did not resume:"; cat merr.txt; }
    cmp -s mwhole.exr mresumed.exr && pass || fail "multipass: the resumed image differs from the uninterrupted one"
    compgen -G "m*.bin" >/dev/null && fail "multipass: a finished render left its checkpoints" || pass
  else
    fail "multipass: the render finished before it was stopped (make it longer)"
  fi
fi
expect_error "multipass: not a checkpoint" "old.bin.*not a usable multipass checkpoint: it does not start with" \
  "$radiant" render "$specular" "${mp[@]}" --checkpoint old.bin --resume -o m.exr

# The stochastic solve's checkpoints (the stop and resume: SolveCheckpoint.* in the unit tests).
"$radiant" solve "$cornell" --solver stochastic -q -o plain.rad || fail "solve without a checkpoint"
"$radiant" solve "$cornell" --solver stochastic -q -o saved.rad --checkpoint solve.bin --checkpoint-interval 0 ||
  fail "solve with a checkpoint"
[ ! -f solve.bin ] && pass || fail "a finished solve left its checkpoint"
"$radiant" render "$cornell" --width 32 --height 32 --spp 2 --method flat --solution plain.rad -q -o plain.exr
"$radiant" render "$cornell" --width 32 --height 32 --spp 2 --method flat --solution saved.rad -q -o saved.exr
cmp -s plain.exr saved.exr && pass || fail "checkpointing changed the solution"
if [ $heavy = 1 ]; then
  # A spectral solve: a checkpoint per pass, kept to the end; killed after its first pass, resumed, the same solution.
  ssolve=(--solver stochastic --rays-per-element 30)
  "$radiant" solve "$spectral" "${ssolve[@]}" -q -o splain.rad || fail "spectral solve without a checkpoint"
  "$radiant" solve "$spectral" "${ssolve[@]}" -q -o sresumed.rad --checkpoint ssolve.bin --checkpoint-interval 0 \
    2>/dev/null &
  pid=$!
  wait_for ssolve.pass2.bin || fail "spectral solve: no second pass's checkpoint within 60 s"
  kill -KILL $pid
  wait $pid 2>/dev/null
  [ -f ssolve.pass1.bin ] && [ ! -f sresumed.rad ] && pass ||
    fail "spectral solve: killed after pass 1, expected ssolve.pass1.bin and no solution"
  "$radiant" solve "$spectral" "${ssolve[@]}" -o sresumed.rad --checkpoint ssolve.bin --resume 2>sserr.txt ||
    fail "spectral solve: resumed"
  grep -q "resumed from ssolve.pass1.bin" sserr.txt && pass || { fail "spectral solve: did not resume pass 1:"; cat sserr.txt; }
  for f in splain sresumed; do
    "$radiant" render "$spectral" --width 32 --height 32 --spp 2 --method flat --solution $f.rad -q -o $f.exr
  done
  cmp -s splain.exr sresumed.exr && pass || fail "spectral solve: the resumed solution differs from the uninterrupted one"
  compgen -G "ssolve.pass*.bin" >/dev/null && fail "spectral solve: a finished solve left its checkpoints" || pass
fi
expect_error "solve --checkpoint with another solver" "only the stochastic solver saves its state" \
  "$radiant" solve "$cornell" --solver gauss-seidel --checkpoint g.bin -o g.rad
expect_error "solve --resume alone" "--resume: needs --checkpoint" "$radiant" solve "$cornell" --resume -o g.rad

finish
