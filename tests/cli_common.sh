#!/usr/bin/env bash
# What the command-line test scripts share: the program, a scratch folder, the
# pass/fail counters and checks. Sourced by every command-line test script
# (cli_test.sh and cli_output_test.sh are two so that ctest -j runs them side by
# side: as one they took 190 s under the sanitizers). Usage of each: SCRIPT
# path/to/radiant SOURCE_DIR
set -u
radiant=$1
source_dir=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
passed=0
failed=0

pass() { passed=$((passed + 1)); }
fail() { echo "FAIL: $*"; failed=$((failed + 1)); }

# expect_error NAME PATTERN COMMAND... : non-zero exit, stderr matches PATTERN
expect_error() {
  local name=$1 pattern=$2
  shift 2
  if "$@" >out.txt 2>err.txt; then
    fail "$name: expected a non-zero exit"
  elif ! grep -qE -- "$pattern" err.txt; then
    fail "$name: stderr does not match '$pattern':"; cat err.txt
  else
    pass
  fi
}

cornell="$source_dir/scenes/cornell-box/scene.json"
furnace="$source_dir/scenes/furnace/scene.json"
spectral="$source_dir/scenes/cornell-box-spectral/scene.json"
textured="$source_dir/scenes/cornell-textured/scene.json"
specular="$source_dir/scenes/cornell-specular/scene.json"

# finish: prints the counts; the script's status is 0 when nothing failed.
finish() {
  echo "$passed passed, $failed failed"
  [ "$failed" -eq 0 ]
}
