#!/usr/bin/env bash
# Issue 44's test on a real Slurm (docs/FARM.md): starts a one-node cluster on this machine (tests/slurm/cluster.sh),
# submits two short walkthroughs through deploy/slurm/submit.sh, and checks every frame against a render by one
# process, bit for bit:
#   run 1: an animated scene (benchmarks/make_moving_scenes.py's crossing block: a mesh moves, so every key frame's
#          records carry their time and each frame brings them to its own), the pre-pass over 2 array tasks, the
#          frames over 3;
#   run 2: an orbit of the built-in Cornell box, the pre-pass in 1 task, the frames over 3 run one after another; the
#          last is requeued mid-render
#          (`scontrol requeue`: killed, then pending again) after the others have ended, so its second run must render
#          only the frames the first did not finish, and the finish step must wait for it.
# Each run must also leave the merged cache file equal to the one process's, an MP4 and no temporary file. The
# daemons are stopped and every file removed on exit. Needs root, slurm-wlm and munge (scripts/install-debian-packages.sh)
# and build/rcsplat (scripts/setup.sh).
set -euo pipefail
cd "$(dirname "$0")/../.."
root=$PWD
bin="$root/build/rcsplat"
[ -x "$bin" ] || { echo "run_test.sh: build rcsplat first (bash scripts/setup.sh)" >&2; exit 1; }
work=$(mktemp -d /tmp/rcsplat-slurm.XXXXXX)
cleanup() {
  bash tests/slurm/cluster.sh stop "$work/cluster" || true
  if [ -n "${RCSPLAT_KEEP_SLURM_TEST:-}" ]; then echo "slurm test: files kept in $work"; else rm -rf "$work"; fi
}
trap cleanup EXIT
export POCL_CACHE_DIR="${POCL_CACHE_DIR:-$root/build/pocl-cache}"
mkdir -p "$POCL_CACHE_DIR"
fail() { echo "slurm test: FAILED: $*" >&2; exit 1; }
start=$SECONDS

frames=12 key_every=4
# The Cornell box's orbit, and the crossing block (5 s of animation: 12 frames at 2.2 frames/s).
orbit=(--orbit 2 --orbit-degrees 30 --width 96 --height 96) orbit_fps=6
python3 benchmarks/make_moving_scenes.py "$work/scenes" > /dev/null
moving=("$work/scenes/crossing.gltf" --width 64 --height 48 --quality draft --bounces 1) moving_fps=2.2

# One process: the pre-pass over every key frame, its merge (of one part), every frame from the merged file.
one_process() {  # FOLDER FPS ANIMATE-ARGS...
  local one=$1 fps=$2
  shift 2
  mkdir -p "$one"
  "$bin" -q animate "$@" --fps "$fps" --cache-every $key_every --last-frame $((frames - 1)) \
    --cache-out "$one/part.rccache" > /dev/null
  "$bin" -q animate "$@" --fps "$fps" --cache-merge "$one/part.rccache" --cache-out "$one/walk.rccache" > /dev/null
  "$bin" -q animate "$@" --fps "$fps" --cache-in "$one/walk.rccache" --cache-fixed --last-frame $((frames - 1)) \
    -o "$one/%05d.exr" -o "$one/%05d.png" > /dev/null
}
one_process "$work/one" $orbit_fps "${orbit[@]}"
one_process "$work/one_moving" $moving_fps "${moving[@]}"
echo "slurm test: one process rendered $frames frames of each walkthrough ($((SECONDS - start)) s)"

bash tests/slurm/cluster.sh start "$work/cluster"
export SLURM_CONF="$work/cluster/slurm.conf"
echo "slurm test: a one-node cluster is up ($(sinfo -h -o '%D node, %c CPUs'))"

# Waits for a job (all its array tasks) to leave the queue; fails unless every task completed.
wait_for() {
  local job=$1 deadline=$((SECONDS + 300))
  while [ -n "$(squeue -h -j "$job" 2>/dev/null)" ]; do
    [ $SECONDS -lt $deadline ] || fail "job $job still queued after 300 s: $(squeue -j "$job")"
    sleep 0.5
  done
  local states
  states=$(scontrol show job "$job" | grep -o 'JobState=[A-Z_]*' | sort -u | tr '\n' ' ')
  [ "$states" = "JobState=COMPLETED " ] || fail "job $job ended $states(logs: $(ls "$out"/logs))"
}

# Every frame, the merged cache and the MP4 as one process (in folder ONE) made them; nothing half-written left.
check_run() {  # OUT ONE
  local out=$1 one=$2
  cmp -s "$one/walk.rccache" "$out/cache/walk.rccache" || fail "$out: the merged cache differs from one process's"
  for ((f = 0; f < frames; ++f)); do
    for format in exr png; do
      local name
      name=$(printf %05d "$f").$format
      cmp -s "$one/$name" "$out/frames/$name" || fail "$out: frame $name differs from one process's (or is missing)"
    done
  done
  [ -s "$out/walk.mp4" ] || fail "$out: no walk.mp4"
  if find "$out" -name '.*tmp*' | grep -q .; then fail "$out: temporary files left: $(find "$out" -name '.*tmp*')"; fi
}

# The walkthrough: fps and the animate arguments in `fps` and `walk`.
submit() {  # OUT PREPASS_TASKS FRAME_TASKS [CPUS]; sets job_prepass, job_merge, job_frames, job_finish
  eval "$(bash deploy/slurm/submit.sh --out "$1" --frames $frames --fps $fps --key-every $key_every --prepass-tasks "$2" \
    --frame-tasks "$3" --cpus "${4:-1}" --mem 1G -- "${walk[@]}" | sed 's/^/job_/')"
}

out="$work/run1"
walk=("${moving[@]}") fps=$moving_fps
submit "$out" 2 3
wait_for "$job_finish"
check_run "$out" "$work/one_moving"
echo "slurm test: run 1 (an animated scene; pre-pass over 2 tasks, frames over 3) matches one process bit for bit" \
  "($((SECONDS - start)) s)"
# The same folder with other settings is refused before anything is submitted.
if bash deploy/slurm/submit.sh --out "$out" --frames $frames --fps $fps --key-every 3 -- "${walk[@]}" 2> /dev/null
then
  fail "submit.sh took run 1's folder with another --key-every"
fi

out="$work/run2"
walk=("${orbit[@]}") fps=$orbit_fps
# The frames over 3 tasks of 2 CPUs each, so one runs at a time; task 2 (frames 8 to 11) is requeued once its first
# frame is written: in the middle of the next, after the job's other tasks have ended (the case where an afterok on the
# frames job would fail for good).
submit "$out" 1 3 2
deadline=$((SECONDS + 240))
until [ -f "$out/frames/00008.png" ]; do
  [ $SECONDS -lt $deadline ] || fail "task 2 of job $job_frames wrote no frame in 240 s"
  sleep 0.05
done
scontrol requeue "${job_frames}_2"
# Slurm holds a requeued job back for two minutes (its begin time, set once the killed task has ended); an
# administrator may let it go at once.
deadline=$((SECONDS + 60))
until [ "$(squeue -h -j "${job_frames}_2" -o %T)" = PENDING ]; do
  [ $SECONDS -lt $deadline ] || fail "task 2 of job $job_frames not pending again 60 s after its requeue"
  sleep 0.1
done
scontrol update jobid="${job_frames}_2" StartTime=now
wait_for "$job_finish"
check_run "$out" "$work/one"
rendered_runs=$(grep -c '^task.sh frames 2 ' "$out/logs/frames_2.log")
[ "$rendered_runs" -eq 2 ] || fail "task 2 ran $rendered_runs times, not twice (requeued once)"
skipped=$(grep -o '"skipped_frames": [0-9]*' "$out/logs/frames_2.json" | grep -o '[0-9]*$')
[ "$skipped" -ge 1 ] && [ "$skipped" -lt 4 ] ||
  fail "task 2's second run skipped $skipped of its 4 frames: it was not requeued mid-render"
echo "slurm test: run 2 (the last task requeued mid-render, its second run skipped the $skipped frames written) matches" \
  "one process bit for bit ($((SECONDS - start)) s)"
