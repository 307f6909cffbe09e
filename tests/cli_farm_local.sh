#!/usr/bin/env bash
# prism farm without a cluster: a plan's tasks and merge run by hand as Slurm would run them, and
# every error a user can meet on the way (bad splits, missing parts, a stale part, a stopped task,
# a damaged plan, no sbatch). farm.slurm runs the same on a real Slurm.
# Usage: cli_farm_local.sh PRISM SOURCE_DIR WORK_DIR
set -u
prism=$1 src=$2 work=$3
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
fail() { echo "FAIL: $*" >&2; exit 1; }
# expect CODE PATTERN COMMAND...: the command exits CODE and prints PATTERN (stdout or stderr)
expect() {
  local code=$1 pattern=$2
  shift 2
  "$@" >out.txt 2>&1
  local got=$?
  [ $got -eq "$code" ] || { cat out.txt; fail "'$*' exited $got, expected $code"; }
  grep -Eq -- "$pattern" out.txt || { cat out.txt; fail "'$*' does not say /$pattern/"; }
}
scene=$src/scenes/cornell-box/cornell-box.gltf
job() {  # job NAME SPP [EXTRA_KEYS]: a small float render of the Cornell box
  printf '{"scene": "%s", "output": "%s.exr", "resolution": [48, 36], "spp": %s, "pixel_type": "float", "aovs": "albedo,depth"%s}\n' \
    "$scene" "$1" "$2" "${3:-}" >"$1.json"
}

echo "-- splits that cannot be made"
job box 16
expect 2 "--by: .*slices" "$prism" farm plan box.json --by slices --parts 2
expect 2 "give --parts" "$prism" farm plan box.json --by samples
expect 2 "has only 16 spp" "$prism" farm plan box.json --by samples --parts 17
expect 2 "no grid of 7 tiles fits the 3x2 image" bash -c "sed 's/\[48, 36\]/[3, 2]/' box.json >tiny.json && '$prism' farm plan tiny.json --by tiles --parts 7"
expect 2 "has only 1 job" "$prism" farm plan box.json --by frames --parts 2
job noisy 16 ', "noise": 0.05'
expect 2 "noise budget" "$prism" farm plan noisy.json --by samples --parts 2
job sliced 16 ', "crop": [0, 0, 8, 8]'
expect 2 "is a slice already" "$prism" farm plan sliced.json --by tiles --parts 2
printf '{"scene": "%s", "spp": 4}\n' "$scene" >nooutput.json
expect 3 "nooutput.json: \\$: no \"output\"" "$prism" farm plan nooutput.json --by samples --parts 2
expect 2 "give a job file or a batch file" "$prism" farm plan "$scene" --by tiles --parts 2
[ ! -e box.farm ] || fail "a refused plan left box.farm behind"

echo "-- by samples, run by hand: identical to one render"
"$prism" render box.json -o single.exr -q || fail "the single render failed"
expect 0 "plan .*box.farm: 4 tasks by samples" "$prism" farm plan box.json --by samples --parts 4
for f in plan.json task.sbatch merge.sbatch; do [ -s box.farm/$f ] || fail "box.farm/$f is missing"; done
grep -q '^exec .*prism farm task .*box.farm \$SLURM_ARRAY_TASK_ID$' box.farm/task.sbatch || fail "task.sbatch does not run the task"
expect 0 "plan unchanged|plan .*box.farm" "$prism" farm plan box.json --by samples --parts 4
expect 2 "holds a different plan.*--replace" "$prism" farm plan box.json --by samples --parts 2
expect 2 "tasks 0 to 3" "$prism" farm task box.farm 4
for t in 0 1 3; do "$prism" farm task box.farm $t -q || fail "task $t failed"; done
expect 9 "not submitted" "$prism" farm status box.farm
expect 3 "box.farm: parts: 1 file is not complete: .*part002.exr" "$prism" farm merge box.farm
[ ! -e box.exr ] || fail "the merge wrote box.exr with a part missing"
expect 0 "is complete already" "$prism" farm task box.farm 0
"$prism" farm task box.farm 2 -q || fail "task 2 failed"
expect 0 "merged 4 parts" "$prism" farm merge box.farm
expect 0 "done: 1 output complete" "$prism" farm status box.farm
"$prism" compare box.exr single.exr --metric maxabs --threshold 1e-5 -q || fail "box.exr differs from single.exr"
exrheader box.exr | grep -q 'prism/assembly.*in 4 parts by samples' || fail "box.exr does not record its assembly"
expect 0 "is merged already" "$prism" farm merge box.farm

echo "-- a part of another plan is rendered again, not taken"
job other 8
"$prism" farm plan other.json --by samples --parts 4 -q && "$prism" farm task other.farm 0 -q || fail "other plan failed"
cp other.farm/parts/part000.exr box.farm/parts/part001.exr
expect 0 "other plan.s" "$prism" farm status box.farm
expect 0 "samples 4\.\.7 -> .*part001.exr" "$prism" farm task box.farm 1

echo "-- a stopped task continues where it stopped"
job slow 4000 ', "checkpoint": 0.3'
"$prism" render slow.json -o slow-single.exr -q || fail "the single slow render failed"
"$prism" farm plan slow.json --by tiles --parts 2 -q || fail "plan slow failed"
"$prism" farm task slow.farm 0 -q &
pid=$!
for _ in $(seq 1 2400); do [ -f slow.farm/parts/part000.exr ] && break; kill -0 $pid 2>/dev/null || break; sleep 0.05; done
kill -TERM $pid
wait $pid
code=$?
[ $code -eq 6 ] || fail "the stopped task exited $code, expected 6 (did it finish before the signal?)"
expect 9 "stopped +pixels 0 0 24 36" "$prism" farm status slow.farm
expect 0 "continuing the stopped render" "$prism" farm task slow.farm 0
"$prism" farm task slow.farm 1 -q && "$prism" farm merge slow.farm -q || fail "slow plan failed"
"$prism" compare slow.exr slow-single.exr --metric maxabs --threshold 1e-5 -q || fail "the continued task's image differs"

echo "-- frames of a batch, and a damaged plan"
printf '{"defaults": {"scene": "%s", "resolution": [16, 16], "spp": 4}, "jobs": [{"output": "f0.exr"}, {"output": "f1.exr", "seed": 2}, {"output": "f2.exr", "preview": "f2.png"}]}\n' "$scene" >frames.json
expect 0 "2 tasks by frames" "$prism" farm plan frames.json --by frames --parts 2
"$prism" farm task frames.farm 1 -q || fail "frames task 1 failed"
expect 3 "1 file is not complete: .*f0.exr" "$prism" farm merge frames.farm
"$prism" farm task frames.farm 0 -q && "$prism" farm merge frames.farm -q || fail "frames failed"
[ -s f2.png ] || fail "a frame's preview is missing"
expect 0 "done: 3 outputs complete" "$prism" farm status frames.farm
# The merge job writes its outputs, then previews, then exits: until Slurm says it ended, status
# is not done and a poller must not submit again. A stand-in scontrol plays Slurm's part.
mkdir -p fakebin
printf '#!/bin/sh\necho "JobId=$4 JobName=prism-merge JobState=$(cat %s/merge-state) Reason=None ExitCode=0:0"\n' \
  "$work" >fakebin/scontrol && chmod +x fakebin/scontrol
echo '[{"array_job": "", "tasks": [], "merge_job": "77"}]' >frames.farm/submissions.json
echo RUNNING >merge-state
expect 9 "3 outputs complete; merge job 77 still running; not finished" env PATH="$work/fakebin:$PATH" "$prism" farm status frames.farm
echo COMPLETED >merge-state
expect 0 "done: 3 outputs complete" env PATH="$work/fakebin:$PATH" "$prism" farm status frames.farm
rm frames.farm/submissions.json
sed -i 's/"spp": 4/"spp": 5/' frames.farm/plan.json 2>/dev/null
sed -i 's/"by": "frames"/"by": "tiles"/' frames.farm/plan.json
expect 3 "plan.json: \\$\\.id: does not match" "$prism" farm status frames.farm
expect 3 "plan.json: missing" "$prism" farm status "$work"

echo "-- a job edited after planning is refused, not mixed"
sed -i 's/"spp": 16/"spp": 17/' box.json
expect 3 "box.json: changed since it was planned" "$prism" farm task box.farm 0
expect 3 "box.json: changed since it was planned" "$prism" farm merge box.farm
sed -i 's/"spp": 17/"spp": 16/' box.json

echo "-- no Slurm here"
expect 2 "sbatch is not on PATH.*sbatch --array=0-3 .*task.sbatch" env PATH=/nonexistent "$prism" farm submit box.farm
echo "all local farm cases passed"
