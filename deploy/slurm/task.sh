#!/usr/bin/env bash
# shellcheck disable=SC2154  # farm.env (sourced below) sets rcsplat, frames, fps, key_every, the tasks, formats
# One step of a walkthrough submitted by deploy/slurm/submit.sh, run by Slurm: task.sh STEP OUT, STEP one of prepass,
# merge, frames, finish; OUT the run's folder (farm.env and animate.args there say what to render). An array task's
# share comes from SLURM_ARRAY_TASK_ID (or JOB_COMPLETION_INDEX: a Kubernetes Indexed Job, docs/FARM.md). Every step
# may be run again (a requeue, a rerun by hand): outputs are written whole or not at all (rcsplat writes beside the
# target and renames), a step finds what is done and does the rest.
set -euo pipefail
step=${1:?usage: task.sh prepass|merge|frames|finish OUT} out=${2:?usage: task.sh STEP OUT}
# shellcheck source=/dev/null
source "$out"/farm.env
mapfile -d '' args < "$out"/animate.args
task=${SLURM_ARRAY_TASK_ID:-${JOB_COMPLETION_INDEX:-0}}
key_frames=$(( (frames - 1) / key_every + 1 ))
merged="$out"/cache/walk.rccache
part() { printf '%s/cache/part_%04d.rccache' "$out" "$1"; }
log() { echo "task.sh $step $task on $(hostname -s): $*"; }

case $step in
prepass)
  # Key frames k * key_every for k in [task * key_frames / tasks, (task + 1) * key_frames / tasks): contiguous shares.
  first_key=$(( task * key_frames / prepass_tasks )) last_key=$(( (task + 1) * key_frames / prepass_tasks - 1 ))
  first=$(( first_key * key_every )) last=$(( (last_key + 1) * key_every - 1 ))
  [ "$last" -lt "$frames" ] || last=$(( frames - 1 ))
  if [ -f "$(part "$task")" ]; then log "$(part "$task") is there already"; exit 0; fi
  log "key frames $first_key to $last_key (frames $first to $last)"
  "$rcsplat" animate "${args[@]}" --fps "$fps" --cache-every "$key_every" --first-frame "$first" --last-frame "$last" \
    --cache-out "$(part "$task")" --json "$out/logs/prepass_$task.json"
  ;;
merge)
  parts=()
  for ((t = 0; t < prepass_tasks; ++t)); do parts+=("$(part "$t")"); done
  "$rcsplat" animate "${args[@]}" --fps "$fps" --cache-merge "${parts[@]}" --cache-out "$merged" \
    --json "$out/logs/merge.json"
  ;;
frames)
  first=$(( task * frames / frame_tasks )) last=$(( (task + 1) * frames / frame_tasks - 1 ))
  outputs=()
  for f in $formats; do outputs+=(-o "$out/frames/%05d.$f"); done
  # A task killed mid-frame may have left its temporary file beside the frame (.NNNNN.tmpPID.ext): this task owns
  # these frames, so what is there of them unfinished is stale.
  for ((f = first; f <= last; ++f)); do rm -f "$out/frames/.$(printf %05d "$f").tmp"*; done
  log "frames $first to $last"
  "$rcsplat" animate "${args[@]}" --fps "$fps" --cache-in "$merged" --cache-fixed --skip-existing \
    --first-frame "$first" --last-frame "$last" "${outputs[@]}" --json "$out/logs/frames_$task.json"
  ;;
finish)
  # A frames task requeued after the job had ended (a node failure, an administrator) is pending or running again:
  # wait for it.
  if [ -n "${frames_job:-}" ] && command -v squeue > /dev/null; then
    while [ -n "$(squeue -h -j "$frames_job" 2> /dev/null)" ]; do sleep 2; done
  fi
  missing=0
  for ((f = 0; f < frames; ++f)); do
    for format in $formats; do
      file="$out/frames/$(printf %05d "$f").$format"
      [ -s "$file" ] || { echo "finish: missing $file" >&2; missing=$((missing + 1)); }
    done
  done
  [ "$missing" -eq 0 ] || { echo "finish: $missing frame files missing; rerun the frames job" >&2; exit 1; }
  log "all $frames frames there ($formats)"
  case " $formats " in
  *" png "*)
    if command -v ffmpeg > /dev/null; then
      ffmpeg -y -loglevel error -framerate "$fps" -start_number 0 -i "$out/frames/%05d.png" -frames:v "$frames" \
        -c:v libx264 -pix_fmt yuv420p -vf 'pad=ceil(iw/2)*2:ceil(ih/2)*2' -f mp4 "$out/.walk.mp4.tmp"
      mv "$out/.walk.mp4.tmp" "$out/walk.mp4"
      log "wrote $out/walk.mp4"
    else
      log "ffmpeg is not installed here: no MP4 (apt-get install ffmpeg)"
    fi
    ;;
  esac
  ;;
*)
  echo "task.sh: unknown step '$step'" >&2
  exit 2
  ;;
esac
