#!/usr/bin/env bash
# Submits a walkthrough to Slurm as four jobs, each waiting for the one before with --dependency=afterok
# (docs/FARM.md):
#   1. prepass  a job array: each task renders its share of the key frames (every K-th frame), each from no records,
#               and writes a part cache file (`rcsplat animate --cache-every K`);
#   2. merge    one job: the parts merged into one cache file (`rcsplat animate --cache-merge`), the same records in the
#               same order whatever the number of prepass tasks;
#   3. frames   a job array: each task renders a range of frames from that file alone (`--cache-fixed`), skipping the
#               frames already written (`--skip-existing`), so a requeued or rerun task renders only what is missing;
#   4. finish   one job, once the frames job has ended and none of its tasks is queued again: checks that every
#               frame is there and writes the MP4 with ffmpeg.
# Every file goes under --out, which must be on storage every node sees. Usage:
#   bash deploy/slurm/submit.sh --out /shared/walk --frames 240 [options] -- [scene.gltf] [animate options]
# Everything after -- is given to every `rcsplat animate` (the scene, the camera path, --width, --quality, ...); the
# frame range, the cache options and -o are set here.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
usage() {
  cat >&2 <<'USAGE'
usage: submit.sh --out DIR --frames N [options] -- [scene] [rcsplat animate options]
  --out DIR            the run's folder on shared storage: cache/, frames/, logs/, walk.mp4
  --frames N           frames 0 to N-1 of the camera path
  --fps F              frames a second of the path's time (default 24), given to rcsplat and to the MP4
  --key-every K        a key frame every K frames for the cache pre-pass (default 8)
  --prepass-tasks P    array tasks of the pre-pass (default 1; at most the number of key frames)
  --frame-tasks T      array tasks rendering frames (default 1; at most N)
  --formats "exr png"  the frames' files (default both; png is needed for the MP4)
  --cpus C             CPUs a task (default 1)        --mem M   memory a task, as sbatch --mem (default 4G)
  --gpus G             GPUs a task (--gres=gpu:G; default 0)
  --partition P        --time T (sbatch's)            --rcsplat PATH (default: build/rcsplat of this checkout)
  --sbatch-args "..."  more sbatch options for every job (an account, a QOS, constraints)
USAGE
  exit 2
}
out="" frames="" fps=24 key_every=8 prepass_tasks=1 frame_tasks=1 formats="exr png" cpus=1 mem=4G gpus=0
partition="" time_limit="" rcsplat="$here/../../build/rcsplat" extra=""
while [ $# -gt 0 ]; do
  case $1 in
    --out) out=$2; shift 2 ;;
    --frames) frames=$2; shift 2 ;;
    --fps) fps=$2; shift 2 ;;
    --key-every) key_every=$2; shift 2 ;;
    --prepass-tasks) prepass_tasks=$2; shift 2 ;;
    --frame-tasks) frame_tasks=$2; shift 2 ;;
    --formats) formats=$2; shift 2 ;;
    --cpus) cpus=$2; shift 2 ;;
    --mem) mem=$2; shift 2 ;;
    --gpus) gpus=$2; shift 2 ;;
    --partition) partition=$2; shift 2 ;;
    --time) time_limit=$2; shift 2 ;;
    --rcsplat) rcsplat=$2; shift 2 ;;
    --sbatch-args) extra=$2; shift 2 ;;
    --) shift; break ;;
    *) echo "submit.sh: unknown option '$1'" >&2; usage ;;
  esac
done
[ -n "$out" ] && [ -n "$frames" ] || usage
integer() { [[ $2 =~ ^[0-9]+$ ]] && [ "$2" -ge 1 ] || { echo "submit.sh: $1 must be a whole number >= 1 (got '$2')" >&2; exit 2; }; }
integer --frames "$frames"; integer --key-every "$key_every"; integer --prepass-tasks "$prepass_tasks"
integer --frame-tasks "$frame_tasks"; integer --cpus "$cpus"
[[ $gpus =~ ^[0-9]+$ ]] || { echo "submit.sh: --gpus must be a whole number (got '$gpus')" >&2; exit 2; }
key_frames=$(( (frames - 1) / key_every + 1 ))
[ "$prepass_tasks" -le "$key_frames" ] ||
  { echo "submit.sh: --prepass-tasks $prepass_tasks: only $key_frames key frames to share" >&2; exit 2; }
[ "$frame_tasks" -le "$frames" ] || { echo "submit.sh: --frame-tasks $frame_tasks: only $frames frames" >&2; exit 2; }
for f in $formats; do
  case $f in exr|png) ;; *) echo "submit.sh: --formats: exr or png, not '$f'" >&2; exit 2 ;; esac
done
[ -x "$rcsplat" ] || { echo "submit.sh: $rcsplat is not an executable (build rcsplat, or give --rcsplat)" >&2; exit 2; }
command -v sbatch > /dev/null || { echo "submit.sh: sbatch not found: is this a Slurm login node?" >&2; exit 2; }

mkdir -p "$out"/cache "$out"/frames "$out"/logs
out=$(cd "$out" && pwd)
rcsplat=$(cd "$(dirname "$rcsplat")" && pwd)/$(basename "$rcsplat")
# The run's settings, read by every task (deploy/slurm/task.sh): scalars as shell assignments, the animate options
# NUL-separated so that any argument survives as it was given.
settings=$(printf 'rcsplat=%q\nframes=%q\nfps=%q\nkey_every=%q\nprepass_tasks=%q\nframe_tasks=%q\nformats=%q\n' \
  "$rcsplat" "$frames" "$fps" "$key_every" "$prepass_tasks" "$frame_tasks" "$formats")
# A folder that holds a run is resumed only with the same settings: its parts and frames were made with them.
if [ -f "$out"/farm.env ]; then
  if [ "$(grep -v '^frames_job=' "$out"/farm.env)" != "$settings" ] || ! cmp -s <(printf '%s\0' "$@") "$out"/animate.args
  then
    echo "submit.sh: $out holds a run with other settings (farm.env, animate.args): give a new --out, or remove" \
      "that folder to start again" >&2
    exit 2
  fi
  echo "submit.sh: $out holds this run already: its parts and frames are kept, the rest is rendered" >&2
fi
printf '%s\n' "$settings" > "$out"/farm.env
printf '%s\0' "$@" > "$out"/animate.args

common=(--parsable --chdir="$out" --cpus-per-task="$cpus" --mem="$mem" --export=ALL)
rendering=()  # the jobs that render ask for the GPUs; the finish step needs none
[ "$gpus" -gt 0 ] && rendering+=(--gres=gpu:"$gpus")
[ -n "$partition" ] && common+=(--partition="$partition")
[ -n "$time_limit" ] && common+=(--time="$time_limit")
# shellcheck disable=SC2206  # word splitting wanted: the user's sbatch options
[ -n "$extra" ] && common+=($extra)
task="$here/task.sh"
# --requeue: a task whose node fails, or that an administrator requeues, starts again and renders what is missing.
prepass=$(sbatch "${common[@]}" "${rendering[@]}" --job-name=rcsplat-prepass --array=0-$((prepass_tasks - 1)) --requeue \
  --output="$out/logs/prepass_%a.log" --open-mode=append "$task" prepass "$out")
merge=$(sbatch "${common[@]}" "${rendering[@]}" --job-name=rcsplat-merge --dependency=afterok:"$prepass" --requeue \
  --output="$out/logs/merge.log" --open-mode=append "$task" merge "$out")
render=$(sbatch "${common[@]}" "${rendering[@]}" --job-name=rcsplat-frames --array=0-$((frame_tasks - 1)) --requeue \
  --dependency=afterok:"$merge" --output="$out/logs/frames_%a.log" --open-mode=append "$task" frames "$out")
# The finish step waits for the frames job's end whatever it was (afterany), then for any of its tasks requeued since,
# and checks the frames itself: Slurm decides a dependency once, so an afterok on a task requeued after the others
# had finished fails for good (sbatch(1), --dependency), though the task then renders its frames.
echo "frames_job=$render" >> "$out"/farm.env
finish=$(sbatch "${common[@]}" --job-name=rcsplat-finish --dependency=afterany:"$render" \
  --output="$out/logs/finish.log" --open-mode=append "$task" finish "$out")
printf 'prepass=%s\nmerge=%s\nframes=%s\nfinish=%s\n' "$prepass" "$merge" "$render" "$finish" | tee "$out"/jobs.txt
