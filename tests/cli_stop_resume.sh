#!/bin/bash
# Stop a render with SIGINT, continue it, stop the continuation with SIGTERM, continue again: the
# final file is byte for byte the file of one uninterrupted render.
# Usage: cli_stop_resume.sh PRISM SCENE WORK_DIR
set -u
prism=$1 scene=$2 work=$3
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
fail() { echo "FAIL: $*" >&2; exit 1; }

# Enough work (64x64 x 2048 spp, about 3 s on a fast core) that a signal sent at the first
# checkpoint lands well before the end.
args=(render "$scene" --res 64x64 --spp 2048 --aovs all --seed 3 -q)
"$prism" "${args[@]}" -o whole.exr --checkpoint 1000 || fail "the uninterrupted render failed"

# Starts a render writing $1 in the background, waits for its first checkpoint, sends signal $2,
# and checks the distinct exit code and the file's status.
interrupt() {
  local out=$1 signal=$2
  shift 2
  "$prism" "${args[@]}" -o "$out" --checkpoint 0.3 "$@" &
  local pid=$! waited=0
  until [ -f "$out" ]; do
    kill -0 $pid 2>/dev/null || fail "the render of $out ended before its first checkpoint"
    sleep 0.05
    waited=$((waited + 1))
    [ $waited -lt 2400 ] || { kill -KILL $pid; fail "no checkpoint of $out within 120 s"; }
  done
  grep -aq "checkpoint" "$out" || fail "$out's first checkpoint does not say it is one"
  kill -"$signal" $pid
  wait $pid
  local code=$?
  [ $code -eq 6 ] || fail "expected exit code 6 after SIG$signal, got $code (did the render finish first?)"
  grep -aq "stopped" "$out" || fail "$out does not record that it was stopped"
  ls "$work" | grep -q "\.tmp" && fail "a temporary file was left behind: $(ls "$work")"
  cmp -s "$out" whole.exr && fail "$out is already complete: the signal came too late to test anything"
  return 0
}

interrupt part.exr INT
interrupt part2.exr TERM --resume part.exr
"$prism" "${args[@]}" -o final.exr --resume part2.exr || fail "resuming part2.exr failed"
cmp whole.exr final.exr || fail "the resumed render differs from the uninterrupted one"

# A stopped render cannot be resumed with settings that change its pixels.
"$prism" render "$scene" --res 64x64 --spp 2048 --aovs all --seed 4 -q -o x.exr --resume part.exr 2>err.txt
[ $? -eq 3 ] || fail "resuming with another seed was not an input error"
grep -q "part.exr: prism/seed: '3' differs" err.txt || fail "unclear message: $(cat err.txt)"
"$prism" render "$scene" --res 64x64 --spp 2048 --aovs albedo --seed 3 -q -o x.exr --resume whole.exr 2>err.txt
[ $? -eq 3 ] || fail "resuming with other AOVs was not an input error"
grep -q "prism/aovs" err.txt || fail "unclear message: $(cat err.txt)"
[ -f x.exr ] && fail "a refused resume wrote its output"
echo "PASS: stopped by SIGINT, resumed, stopped by SIGTERM, resumed: identical to one render"
