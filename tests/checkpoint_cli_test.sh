#!/usr/bin/env bash
# radiant render --checkpoint/--resume as a user runs them (docs/cluster.md):
# a render killed with SIGKILL (no chance to save) or stopped with SIGTERM (it
# saves), then resumed, writes the very image of a run never stopped; the
# flags' misuse is refused. Usage: checkpoint_cli_test.sh path/to/radiant SOURCE_DIR
source "$(dirname "$0")/cli_common.sh"

size=(--width 64 --height 64)
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

# Misuse.
expect_error "--resume alone" "--resume: needs --checkpoint" "$radiant" render "$cornell" --spp 1 --resume -o x.exr
echo "not a checkpoint at all, but long enough to hold a header" >old.bin
expect_error "an existing checkpoint without --resume" "old.bin' exists: add --resume" \
  "$radiant" render "$cornell" --spp 1 --checkpoint old.bin -o x.exr
expect_error "not a checkpoint" "old.bin.*not a usable render checkpoint" \
  "$radiant" render "$cornell" --spp 1 --checkpoint old.bin --resume -o x.exr
# Another job's checkpoint: saved by a stopped 96² render, offered to a different seed.
"$radiant" render "$cornell" "${size[@]}" --spp 512 -o y.exr -q --checkpoint other.bin --checkpoint-interval 0.2 \
  2>/dev/null &
pid=$!
wait_for other.bin && kill -KILL $pid
wait $pid 2>/dev/null
expect_error "another job's checkpoint" "other.bin.*belongs to another job" \
  "$radiant" render "$cornell" "${size[@]}" --spp 512 --seed 7 -o y.exr --checkpoint other.bin --resume
expect_error "multipass" "--checkpoint: --method multipass writes an image per pass" \
  "$radiant" render "$specular" --method multipass --spp 4 --checkpoint m.bin -o m.exr

# The stochastic solve's checkpoints (the stop and resume: SolveCheckpoint.* in the unit tests).
"$radiant" solve "$cornell" --solver stochastic -q -o plain.rad || fail "solve without a checkpoint"
"$radiant" solve "$cornell" --solver stochastic -q -o saved.rad --checkpoint solve.bin --checkpoint-interval 0 ||
  fail "solve with a checkpoint"
[ ! -f solve.bin ] && pass || fail "a finished solve left its checkpoint"
"$radiant" render "$cornell" --width 32 --height 32 --spp 2 --method flat --solution plain.rad -q -o plain.exr
"$radiant" render "$cornell" --width 32 --height 32 --spp 2 --method flat --solution saved.rad -q -o saved.exr
cmp -s plain.exr saved.exr && pass || fail "checkpointing changed the solution"
expect_error "solve --checkpoint with another solver" "only the stochastic solver saves its state" \
  "$radiant" solve "$cornell" --solver gauss-seidel --checkpoint g.bin -o g.rad
expect_error "solve --resume alone" "--resume: needs --checkpoint" "$radiant" solve "$cornell" --resume -o g.rad

finish
