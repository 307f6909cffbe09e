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

# Waits until process $1 has written file $2 (its first checkpoint); fails if the process ends
# first or nothing comes within 120 s.
wait_for_checkpoint() {
  local pid=$1 file=$2 waited=0
  until [ -f "$file" ]; do
    kill -0 "$pid" 2>/dev/null || fail "the process writing $file ended before its first checkpoint"
    sleep 0.05
    waited=$((waited + 1))
    [ $waited -lt 2400 ] || { kill -KILL "$pid"; fail "no checkpoint of $file within 120 s"; }
  done
}

# Starts a render writing $1 in the background, waits for its first checkpoint, sends signal $2,
# and checks the distinct exit code and the file's status.
interrupt() {
  local out=$1 signal=$2
  shift 2
  "$prism" "${args[@]}" -o "$out" --checkpoint 0.3 "$@" &
  local pid=$!
  wait_for_checkpoint $pid "$out"
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

# --skip-existing skips a complete output but renders over a stopped one.
cat > skip.json <<JSON
{"defaults": {"scene": "$scene", "resolution": [16, 16], "spp": 2, "aovs": "all", "seed": 3},
 "jobs": [{"output": "whole.exr"}, {"output": "part.exr"}]}
JSON
"$prism" batch skip.json --skip-existing >out.txt 2>&1 || fail "batch --skip-existing failed: $(cat out.txt)"
grep -Eq "1 +skipped .* whole.exr" out.txt || fail "a complete output was not skipped: $(cat out.txt)"
grep -Eq "2 +ok .* part.exr" out.txt || fail "a stopped output was skipped: $(cat out.txt)"

# A signal stops a batch: the job under way writes what it has, the rest do not run, exit 6.
cat > long.json <<JSON
{"defaults": {"scene": "$scene", "resolution": [64, 64], "spp": 4096, "checkpoint": 0.3},
 "jobs": [{"output": "long1.exr"}, {"output": "long2.exr"}]}
JSON
"$prism" batch long.json >out.txt 2>&1 &
pid=$!
wait_for_checkpoint $pid long1.exr
kill -INT $pid
wait $pid
code=$?
[ $code -eq 6 ] || fail "expected exit code 6 from a stopped batch, got $code: $(cat out.txt)"
grep -Eq "1 +stopped .* long1.exr" out.txt || fail "the stopped job is not reported: $(cat out.txt)"
grep -Eq "2 +not run" out.txt || fail "the job after the stop is not reported as not run: $(cat out.txt)"
[ -f long2.exr ] && fail "a job after the stop ran"
echo "PASS: stopped by SIGINT, resumed, stopped by SIGTERM, resumed: identical to one render; batches skip and stop"
