#!/usr/bin/env bash
# Issue 44, item 5: one walkthrough rendered on a one-node Slurm cluster (tests/slurm/cluster.sh) by
# deploy/slurm/submit.sh with 1, 2 and 4 array tasks, against one process doing the same three steps (pre-pass, merge,
# every frame). Prints a table: wall time from submission to the finish job's end, the pre-pass's share (pre-pass and
# merge until the frames start), and each frames task's own time (its JSON's seconds.wall); checks every frame
# against the one process's, bit for bit. As root; needs build/rcsplat, slurm-wlm, munge and ../shared/scenes.
#   bash benchmarks/farm/one_node.sh OUT_DIR
# SCENE, WALK (the camera path and size), FRAMES, KEY_EVERY, TASKS ("1 2 4") change the walkthrough.
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
out=$(mkdir -p "$1" && cd "$1" && pwd)
bin="$root/build/rcsplat"
scene="${SCENE:-$root/../shared/scenes/sponza_dabrovic/sponza.gltf}"
read -r -a walk <<<"${WALK:---keyframes $root/benchmarks/walkthrough/sponza_walk.txt --width 256 --height 192}"
frames=${FRAMES:-48} key_every=${KEY_EVERY:-8} fps=24
export POCL_CACHE_DIR="${POCL_CACHE_DIR:-$root/build/pocl-cache}"
args=("$scene" "${walk[@]}")
now() { date +%s.%N; }
elapsed() { python3 -c "print(f'{$2 - $1:.1f}')"; }

# One process: pre-pass, merge, frames (the kernel caches warmed by a first frame, as the tasks will find them).
"$bin" -q animate "${args[@]}" --fps $fps --last-frame 0 -o "$out/warm%d.png" > /dev/null
one="$out/one"
mkdir -p "$one"
t0=$(now)
"$bin" -q animate "${args[@]}" --fps $fps --cache-every $key_every --last-frame $((frames - 1)) \
  --cache-out "$one/part.rccache" > /dev/null
"$bin" -q animate "${args[@]}" --fps $fps --cache-merge "$one/part.rccache" --cache-out "$one/walk.rccache" \
  --json "$one/merge.json" > /dev/null
t1=$(now)
"$bin" -q animate "${args[@]}" --fps $fps --cache-in "$one/walk.rccache" --cache-fixed --last-frame $((frames - 1)) \
  -o "$one/%05d.exr" -o "$one/%05d.png" --json "$one/frames.json" > /dev/null
t2=$(now)
echo "| one process | $(elapsed "$t0" "$t2") | $(elapsed "$t0" "$t1") | $(elapsed "$t1" "$t2") |" | tee "$out/table.md"

cluster="$out/cluster"
trap 'bash "$root/tests/slurm/cluster.sh" stop "$cluster"' EXIT
bash "$root/tests/slurm/cluster.sh" start "$cluster"
export SLURM_CONF="$cluster/slurm.conf"
gone() { [ -z "$(squeue -h -j "$1" 2>/dev/null)" ]; }
for tasks in ${TASKS:-1 2 4}; do
  run="$out/tasks_$tasks"
  key_frames=$(( (frames - 1) / key_every + 1 ))
  pre=$(( tasks < key_frames ? tasks : key_frames ))
  t0=$(now)
  eval "$(bash "$root/deploy/slurm/submit.sh" --out "$run" --frames "$frames" --fps $fps --key-every "$key_every" \
    --prepass-tasks "$pre" --frame-tasks "$tasks" --cpus 1 --mem 4G -- "${args[@]}" | sed 's/^/job_/')"
  until gone "$job_merge"; do sleep 0.2; done
  t1=$(now)
  until gone "$job_finish"; do sleep 0.2; done
  t2=$(now)
  for ((f = 0; f < frames; ++f)); do
    cmp -s "$one/$(printf %05d $f).exr" "$run/frames/$(printf %05d $f).exr" || { echo "frame $f differs" >&2; exit 1; }
  done
  per_task=$(for ((t = 0; t < tasks; ++t)); do
    python3 -c "import json; print(f\"{json.load(open('$run/logs/frames_$t.json'))['seconds']['wall']:.1f}\")"
  done | paste -sd/)
  echo "| $tasks tasks ($pre pre-pass) | $(elapsed "$t0" "$t2") | $(elapsed "$t0" "$t1") | $per_task |" |
    tee -a "$out/table.md"
done
echo "cache: $(stat -c %s "$one/walk.rccache") bytes; merge: $(tr -d '\n ' < "$one/merge.json")" | tee -a "$out/table.md"
