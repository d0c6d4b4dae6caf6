#!/usr/bin/env bash
# Runs on a lent GPU machine from the repository root, with .gpu/ from bundle.sh carried. Sets up OpenCL on NVIDIA's
# driver, then measures on the GPU and, as the anchor in the same run, on PoCL over the machine's own CPU cores:
#   - the traversal benchmark (OpenCL against Embree on the same rays), Sponza;
#   - timed renders (1024x768, a = 0.3 and 0.5) of the Cornell box, Sponza and Sibenik, RUNS each for medians, with a
#     bit comparison of repeated runs and the GPU image's error against PoCL's;
#   - benchmarks/equal_error.py on the GPU against GPU-rendered references (Cornell box and Sponza).
# Writes $OUT/results.tar (summaries as JSON, the log).
# Usage: RUNS=3 PARTS="bench renders equal_error" CPU_DEVICE=cpu bash benchmarks/gpu/device_run.sh
# Other parts: frames (`bench` at 1920x1080 on every device), issue13 (Sponza 1920x1080 defaults on the GPU from a cold
# start and warm, the record trace's shapes, and PoCL as the anchor), host (the host's work between passes, against an
# older build in .gpu/rcsplat_old, and NVIDIA's register report), regs (register budgets for NVIDIA's compiler), layers
# (the image layers gathered on the device, against .gpu/rcsplat_old), cold (Sponza 1080p from scratch, then warm),
# wavefront (the record trace fused, split and as a wavefront, against .gpu/rcsplat_old), split_sibenik (Sibenik's
# record trace in each of those shapes), defaults (this build's defaults against .gpu/rcsplat_old, Sponza and Sibenik at 1080p),
# budget (Sponza's frame at the defaults and at cheaper settings), issue41 (Sponza and textured Sibenik on the GPU
# against PoCL, and repeated; textured Sibenik before items 1 and 2, glossy paths without a caustic map), heap (freed host memory reused, against
# .gpu/rcsplat_old), pieces (image layers downloaded in pieces, against .gpu/rcsplat_old).
# issue43 (the colour-only frame against a full one, cold builds by file, the walk's steady-state frame at 1920x1080
# for issue 42, all on the GPU, against .gpu/rcsplat_old where it has one).
# (CPU_DEVICE: a substring of PoCL's device name, as `rcsplat devices` lists it).
set -u
G=$PWD/.gpu
OUT=${OUT:-/tmp/out}
runs=${RUNS:-3}
parts=${PARTS:-bench renders equal_error}
cpu=${CPU_DEVICE:-cpu}
work=/tmp/rcsplat-gpu && rm -rf $work && mkdir -p $work/ocl $work/res $OUT
for d in $G/*.deb; do dpkg -x "$d" $work/ocl; done
tar -xJf $G/lib.tar.xz -C $work
# NVIDIA's OpenCL library ships with the driver; the ICD loader finds it through this file.
nv=$(find /usr/local/nvidia /usr/lib /usr/lib64 /lib -name 'libnvidia-opencl.so.1' 2>/dev/null | head -1)
mkdir -p /etc/OpenCL/vendors && echo "$nv" > /etc/OpenCL/vendors/nvidia.icd
export LD_LIBRARY_PATH=$work/ocl/usr/lib/x86_64-linux-gnu:$work/lib:${LD_LIBRARY_PATH:-}
export RCSPLAT_CACHE_DIR=$work/kernel-cache
R=$work/res
exec > >(tee -a $R/log.txt) 2>&1
trap 'tar -C $work -cf $OUT/results.tar res' EXIT
echo "NVIDIA OpenCL library: ${nv:-none found}"
nvidia-smi -L; lscpu | grep -E 'Model name|^CPU\(s\)'
$work/ocl/usr/bin/clinfo -l
rc=$G/rcsplat
$rc devices
S=$G/scenes/sponza_dabrovic/sponza.gltf
B=$G/scenes/sibenik/sibenik_textured.gltf
[[ $parts == *bench* ]] && for dev in NVIDIA $cpu; do $rc -q bench --traversal $S --device $dev --repeats 5 --json $R/bench_sponza_$dev.json; done
[[ $parts == *frames* ]] && $rc -q bench $S --devices all --width 1920 --height 1080 --repeats 3 --json $R/bench_frames_sponza_1080p.json

# Issue 13, part 2: Sponza 1920x1080 with render defaults on the GPU; the record trace's shape (samples a work-item
# takes: 1 is the GPU's default, 100000 a whole record, as the one-kernel pass had) with the same bits expected; then
# PoCL on the host's cores as the anchor.
if [[ $parts == *issue13* ]]; then
  hd="--width 1920 --height 1080"
  RCSPLAT_CACHE_DIR=$work/cold-cache timeout 60 $rc render $S --device NVIDIA $hd -o $work/cold.exr --json $R/i13_cold_render.json \
    || echo "FAILED: cold render"
  for spi in 1 100000 8; do
    for i in 1 2; do
      RCSPLAT_RECORD_SAMPLES_PER_ITEM=$spi timeout 60 $rc -q render $S --device NVIDIA $hd -o $work/spi$spi.$i.exr \
        --json $R/i13_spi${spi}_run$i.json >/dev/null || echo "FAILED: spi $spi run $i"
    done
    cmp -s $work/spi$spi.1.exr $work/spi$spi.2.exr && echo "spi $spi: runs identical" || echo "spi $spi: runs DIFFER"
    cmp -s $work/spi1.1.exr $work/spi$spi.1.exr && echo "spi $spi: same bits as spi 1" || echo "spi $spi: DIFFERS from spi 1"
    rm -f $work/spi$spi.2.exr
  done
  timeout 90 $rc -q bench $S --device NVIDIA $hd --repeats 5 --json $R/i13_bench_gpu_1080p.json
  for spi in 1 100000; do  # the settings of the first GPU run's table, records time against its 0.287 s
    RCSPLAT_RECORD_SAMPLES_PER_ITEM=$spi timeout 60 $rc -q render $S --device NVIDIA --width 1024 --height 768 --bounces 1 \
      --pixel-samples 1 --accuracy 0.5 -o $work/old_settings.exr --json $R/i13_old_settings_spi$spi.json >/dev/null
  done
  timeout 40 $rc -q bench --traversal $S --device NVIDIA --repeats 5 --json $R/i13_traversal_gpu.json
  timeout 240 $rc -q render $S --device $cpu $hd -o $work/pocl.exr --json $R/i13_pocl_render.json >/dev/null \
    && $rc compare $work/spi1.1.exr $work/pocl.exr --json $R/i13_gpu_vs_pocl.json
  timeout 200 $rc -q bench $S --device $cpu $hd --repeats 1 --json $R/i13_bench_pocl_1080p.json
  rm -f $work/*.exr
fi

# Sponza 1920x1080 defaults on the GPU, $G/rcsplat_old (a build before this one, copied in by hand) and this build
# alternating, twice, medians of 3 frames: $R/<tag>_<binary>_sponza_run<i>.json.
alternate_sponza_1080p() {
  for i in 1 2; do
    for b in rcsplat_old rcsplat; do
      timeout 90 $G/$b -q bench $S --device NVIDIA --width 1920 --height 1080 --repeats 3 \
        --json $R/$1_${b}_sponza_run$i.json | grep -v "^cold_s"
    done
  done
}

# Sponza 1920x1080 defaults on the GPU from scratch (empty kernel caches, rcsplat's and, on a fresh machine, NVIDIA's),
# then warm: the frame a first-time user waits for, pass by pass, in the render summaries.
if [[ $parts == *cold* ]]; then
  for run in cold warm; do
    RCSPLAT_CACHE_DIR=$work/scratch-cache timeout 90 $rc render $S --device NVIDIA --width 1920 --height 1080 \
      -o $work/scratch.exr --json $R/scratch_${run}_render.json | grep -E "^(time|total|photon map|records) "
  done
  rm -f $work/*.exr
fi

# Issues 42 and 43 on the GPU: Sponza 1920x1080 defaults written as a PNG (a colour-only frame: only the colour comes
# back) and as an EXR (every layer), alternating, twice, and the PNGs' bits compared; `bench` with the cold kernel
# builds by file, and again with the builds one at a time (RCSPLAT_BUILD_AHEAD=0); then issue 42's walk (benchmarks/walkthrough/sponza_walk.txt) at 1920x1080 with records kept, 24
# frames, PNG frames: the steady-state time a frame and per pass, in the CSV (goal 33 ms on an H100-class GPU).
if [[ $parts == *issue43* ]]; then
  hd="--width 1920 --height 1080"
  for i in 1 2; do
    for o in png exr; do
      timeout 60 $rc -q render $S --device NVIDIA $hd -o $work/i43_$i.$o --json $R/i43_render_${o}_$i.json | grep -E "^total"
    done
  done
  cmp -s $work/i43_1.png $work/i43_2.png && echo "issue43: colour-only runs identical" || echo "issue43: colour-only runs DIFFER"
  # Third session: textured Sibenik's colour-only frame, whose glossy pass reads the records through a grid built on
  # the device, as are the photon map's estimate order and surface patches (JSON: specular.record_grid_seconds,
  # cache.later_bounces.seconds_by_part); twice, and the PNGs' bits compared.
  for i in 1 2; do
    timeout 90 $rc -q render $B --device NVIDIA $hd -o $work/i43_sib_$i.png --json $R/i43_sibenik_png_$i.json | grep -E "^total"
  done
  cmp -s $work/i43_sib_1.png $work/i43_sib_2.png && echo "issue43: Sibenik colour-only runs identical" ||
    echo "issue43: Sibenik colour-only runs DIFFER"
  timeout 120 $rc -q bench $S --device NVIDIA $hd --repeats 3 --json $R/i43_bench_gpu_1080p.json
  # Programs built ahead (default) against one at a time: cold_s is the frame's wait for builds, cold_fr the frame.
  RCSPLAT_BUILD_AHEAD=0 timeout 120 $rc -q bench $S --device NVIDIA $hd --repeats 1 --json $R/i43_bench_one_at_a_time.json
  mkdir -p $work/walk
  timeout 240 $rc -q animate $S --keyframes benchmarks/walkthrough/sponza_walk.txt --device NVIDIA $hd --last-frame 23 \
    -o $work/walk/%04d.png --stats $R/i43_walk_1080p.csv --json $R/i43_walk_1080p.json | tail -3
  rm -rf $work/walk $work/*.png $work/*.exr
fi

# Host work between passes (probe, layers, other): this binary against $G/rcsplat_old (a build before it, copied in by
# hand), alternating, Sponza and Sibenik at 1920x1080 on the GPU and Sponza on PoCL; then NVIDIA's compiler report
# (registers, spills) for every kernel a default frame builds.
if [[ $parts == *host* ]]; then
  hd="--width 1920 --height 1080"
  alternate_sponza_1080p host
  timeout 90 $rc -q bench $B --device NVIDIA $hd --repeats 3 --json $R/host_sibenik_gpu.json | grep -v "^cold_s"
  RCSPLAT_CACHE_DIR=$work/verbose-cache RCSPLAT_BUILD_OPTIONS=-cl-nv-verbose timeout 60 $rc render $S --device NVIDIA \
    --width 64 --height 48 -o $work/v.exr > $R/nv_verbose.txt 2>&1
  grep -E "build log of|ptxas info|Used|spill" $R/nv_verbose.txt | head -80
  for b in rcsplat_old rcsplat; do
    timeout 150 $G/$b -q bench $S --device $cpu $hd --repeats 1 --json $R/host_${b}_pocl.json | grep -v "^cold_s"
  done
fi

# Image layers gathered on the device (passes/layer_pass.h) against $G/rcsplat_old (the build before, which filled and
# averaged sub-pixel layers on the host): Sponza and Sibenik at 1920x1080 defaults on the GPU, alternating, then the
# two binaries' images compared, the new one's determinism, and PoCL's frame at 1024x768 as the anchor.
if [[ $parts == *layers* ]]; then
  hd="--width 1920 --height 1080"
  alternate_sponza_1080p layers
  for b in rcsplat_old rcsplat; do
    timeout 90 $G/$b -q bench $B --device NVIDIA $hd --repeats 3 --json $R/layers_${b}_sibenik.json | grep -v "^cold_s"
    timeout 60 $G/$b -q render $S --device NVIDIA $hd -o $work/$b.exr --json $R/layers_${b}_render.json > /dev/null
  done
  timeout 60 $rc -q render $S --device NVIDIA $hd -o $work/again.exr > /dev/null
  cmp -s $work/rcsplat.exr $work/again.exr && echo "layers: new runs identical" || echo "layers: new runs DIFFER"
  $rc compare $work/rcsplat.exr $work/rcsplat_old.exr --json $R/layers_new_vs_old.json | sed "s/^/new vs old: /"
  for b in rcsplat_old rcsplat; do
    timeout 120 $G/$b -q bench $S --device $cpu --width 1024 --height 768 --repeats 1 --json $R/layers_${b}_pocl.json \
      | grep -v "^cold_s"
  done
  rm -f $work/*.exr
fi

# Register budgets for NVIDIA's compiler (trace_record_rays uses 255 registers and spills at its default): the GPU frame
# of Sponza 1920x1080 (and Sibenik at the first budget that helps) under -cl-nv-maxrregcount=N, with a bit comparison
# of a render against the default's.
if [[ $parts == *regs* ]]; then
  hd="--width 1920 --height 1080"
  for n in default ${REGS:-64 96 128 168}; do
    opt=$([ $n = default ] || echo "-cl-nv-maxrregcount=$n")
    RCSPLAT_BUILD_OPTIONS="$opt" timeout 90 $rc -q bench $S --device NVIDIA $hd --repeats 3 --json $R/regs_sponza_$n.json \
      | grep -v "^cold_s"
    RCSPLAT_BUILD_OPTIONS="$opt" RCSPLAT_CACHE_DIR=$work/cache_$n timeout 60 $rc -q render $S --device NVIDIA \
      --width 1024 --height 768 -o $work/regs_$n.exr > /dev/null 2>&1
    cmp -s $work/regs_default.exr $work/regs_$n.exr && echo "regs $n: same bits as default" || echo "regs $n: bits DIFFER"
  done
  for n in default ${REGS_SIBENIK:-128}; do
    opt=$([ $n = default ] || echo "-cl-nv-maxrregcount=$n")
    RCSPLAT_BUILD_OPTIONS="$opt" timeout 90 $rc -q bench $B --device NVIDIA $hd --repeats 3 --json $R/regs_sibenik_$n.json \
      | grep -v "^cold_s"
  done
  rm -f $work/*.exr
fi

# The record trace's three shapes (RCSPLAT_RECORD_TRACE=fused|split|wavefront; a GPU's default is the wavefront:
# tracing, the first hits' shading, a kernel a later bounce over the queued paths) against $G/rcsplat_old: NVIDIA's
# register report of the record kernels; Sponza 1920x1080 defaults alternating old and the three shapes, twice (bench:
# warm medians of 3 and the cold frame); the images' bits (the same whatever the shape); PoCL at 1024x768 as the anchor.
if [[ $parts == *wavefront* ]]; then
  hd="--width 1920 --height 1080"
  RCSPLAT_CACHE_DIR=$work/verbose-cache RCSPLAT_BUILD_OPTIONS=-cl-nv-verbose timeout 60 $rc render $S --device NVIDIA \
    --width 64 --height 48 -o $work/v.exr > $R/nv_verbose.txt 2>&1
  grep -E "ptxas info|stack frame" $R/nv_verbose.txt | grep -A3 -E \
    "entry function '(trace_record_rays|trace_record_hits|shade_record_hits|shade_record_first_hits|step_record_paths|reduce_records)'" |
    head -60
  for i in 1 2; do
    timeout 90 $G/rcsplat_old -q bench $S --device NVIDIA $hd --repeats 3 --json $R/wave_old_run$i.json
    for shape in fused split wavefront; do
      RCSPLAT_RECORD_TRACE=$shape timeout 90 $rc -q bench $S --device NVIDIA $hd --repeats 3 \
        --json $R/wave_${shape}_run$i.json
    done
  done
  timeout 60 $G/rcsplat_old -q render $S --device NVIDIA $hd -o $work/old.exr > /dev/null
  for shape in fused split wavefront; do
    RCSPLAT_RECORD_TRACE=$shape timeout 60 $rc -q render $S --device NVIDIA $hd -o $work/$shape.exr \
      --json $R/wave_render_$shape.json > /dev/null
  done
  for shape in split wavefront; do
    cmp -s $work/fused.exr $work/$shape.exr && echo "$shape: same bits as fused" || echo "$shape: bits DIFFER from fused"
  done
  cmp -s $work/fused.exr $work/old.exr && echo "new: same bits as old" || echo "new: bits DIFFER from old"
  $rc compare $work/wavefront.exr $work/old.exr --json $R/wave_vs_old.json | sed "s/^/wavefront vs old: /"
  timeout 100 $G/rcsplat_old -q bench $S --device $cpu --width 1024 --height 768 --repeats 1 --json $R/wave_old_pocl.json
  timeout 100 $rc -q bench $S --device $cpu --width 1024 --height 768 --repeats 1 --json $R/wave_pocl.json
  rm -f $work/*.exr
fi

# Sibenik 1920x1080 defaults with each shape of the record trace (RCSPLAT_RECORD_TRACE), and their images' bits. (At
# 7a3f2e2 this part, then named prefetch, also timed cold frames with a frame's programs built on threads of their own:
# no faster on NVIDIA, so that was taken out; benchmarks/RESULTS.md.)
if [[ $parts == *split_sibenik* ]]; then
  hd="--width 1920 --height 1080"
  for shape in fused split wavefront; do
    RCSPLAT_RECORD_TRACE=$shape timeout 90 $rc -q bench $B --device NVIDIA $hd --repeats 3 \
      --json $R/sibenik_$shape.json | grep NVIDIA | sed "s/^/sibenik $shape: /"
    RCSPLAT_RECORD_TRACE=$shape timeout 60 $rc -q render $B --device NVIDIA $hd -o $work/sibenik_$shape.exr \
      > /dev/null
  done
  for shape in split wavefront; do
    cmp -s $work/sibenik_fused.exr $work/sibenik_$shape.exr && echo "sibenik $shape: same bits" ||
      echo "sibenik $shape: bits DIFFER"
  done
  rm -f $work/*.exr
fi

# This build with its defaults (on a GPU the record trace a wavefront) against $G/rcsplat_old: Sponza 1920x1080 alternating
# twice, then Sibenik 1920x1080 once each.
if [[ $parts == *defaults* ]]; then
  alternate_sponza_1080p defaults
  for b in rcsplat_old rcsplat; do
    timeout 90 $G/$b -q bench $B --device NVIDIA --width 1920 --height 1080 --repeats 3 \
      --json $R/defaults_${b}_sibenik.json | grep NVIDIA | sed "s/^/sibenik $b: /"
  done
fi

# Issue 41 (the dielectric's diffuse weight as one less its lobe's albedo, read from a __constant table in every kernel;
# record rays continue their path where photons are scarce): Sponza and textured Sibenik at 1024x768 with the defaults
# on the GPU, twice (the same bits expected), and on PoCL over the host's cores; the GPU's images against PoCL's.
if [[ $parts == *issue41* ]]; then
  for sc in $S $B; do
    n=$(basename $sc .gltf)
    for i in 1 2; do
      timeout 90 $rc -q render $sc --device NVIDIA --width 1024 --height 768 -o $work/${n}_gpu$i.exr \
        --json $R/i41_${n}_gpu$i.json > /dev/null || echo "FAILED: $n GPU run $i"
    done
    cmp -s $work/${n}_gpu1.exr $work/${n}_gpu2.exr && echo "$n: GPU runs identical" || echo "$n: GPU runs DIFFER"
    timeout 150 $rc -q render $sc --device $cpu --width 1024 --height 768 -o $work/${n}_pocl.exr \
      --json $R/i41_${n}_pocl.json > /dev/null || echo "FAILED: $n PoCL"
    $rc compare $work/${n}_gpu1.exr $work/${n}_pocl.exr --json $R/i41_${n}_gpu_vs_pocl.json | sed "s/^/$n GPU vs PoCL: /"
  done
  # Items 1 and 2 on the GPU: textured Sibenik as before them (glossy paths, no caustic map) against the defaults.
  n=$(basename $B .gltf)
  timeout 90 $rc -q render $B --device NVIDIA --width 1024 --height 768 --glossy-paths --caustic-photons 0 \
    -o $work/${n}_gpu_before.exr --json $R/i41_${n}_gpu_before.json > /dev/null || echo "FAILED: $n GPU before"
  $rc compare $work/${n}_gpu_before.exr $work/${n}_gpu1.exr --json $R/i41_${n}_before_vs_now.json |
    sed "s/^/$n before items 1-2 vs now: /"
  rm -f $work/*.exr
fi

# The cheapest frame of the budget part below, where the host's work is most of it.
cheapest="--hemisphere 4x8 --guide-rays 0 --pixel-samples 1 --accuracy 0.5 --bounces 1"

# What accuracy costs in time on the GPU (issue 13 part 2's 33 ms goal): Sponza render summaries (warm kernel cache,
# 3 runs of each setting, then the next setting) at 1920x1080 with the defaults and cheaper settings, and at 1024x768
# with the defaults and part 1's --hemisphere 8x16; then the traversal kernel's rate, the ceiling of the record rays.
# $R/budget_<i>_run<r>.json, the settings in $R/budget_settings.txt (the errors are PoCL's, same images: RESULTS.md).
if [[ $parts == *budget* ]]; then
  i=0
  while read -r opts; do
    i=$((i+1)); echo "$i $opts" | tee -a $R/budget_settings.txt
    for run in 0 1 2 3; do  # run 0 builds the setting's programs, untimed
      timeout 60 $rc -q render $S --device NVIDIA $opts -o $work/b.exr --json $R/budget_${i}_run$run.json >/dev/null \
        || echo "FAILED: $opts"
    done
    rm -f $R/budget_${i}_run0.json $work/b.exr
  done <<SETTINGS
--width 1920 --height 1080
--width 1920 --height 1080 --fine-hemisphere 8x16
--width 1920 --height 1080 --hemisphere 8x16
--width 1920 --height 1080 --pixel-samples 1
--width 1920 --height 1080 --hemisphere 8x16 --pixel-samples 1
--width 1920 --height 1080 --hemisphere 8x16 --pixel-samples 1 --accuracy 0.5
--width 1920 --height 1080 --hemisphere 8x16 --pixel-samples 1 --accuracy 0.5 --bounces 1
--width 1920 --height 1080 $cheapest
--width 1024 --height 768
--width 1024 --height 768 --hemisphere 8x16
SETTINGS
  timeout 60 $rc -q bench --traversal $S --device NVIDIA --repeats 5 --json $R/budget_traversal_gpu.json
fi

# $G/rcsplat_old (the build before) and this build, alternating three times, one frame a process as `render` makes it
# (no earlier frame's memory to reuse): Sponza 1920x1080 with the defaults and the cheapest frame,
# $R/<tag>_{render,floor}_<binary>_run<i>.json; then whether the two binaries' images are the same bits.
alternate_one_frame_renders() {
  for i in 1 2 3; do
    for b in rcsplat_old rcsplat; do
      timeout 60 $G/$b -q render $S --device NVIDIA --width 1920 --height 1080 -o $work/$b.exr \
        --json $R/$1_render_${b}_run$i.json >/dev/null
      timeout 60 $G/$b -q render $S --device NVIDIA --width 1920 --height 1080 $cheapest -o $work/floor.exr \
        --json $R/$1_floor_${b}_run$i.json >/dev/null
    done
  done
  cmp -s $work/rcsplat.exr $work/rcsplat_old.exr && echo "$1: same bits as old" || echo "$1: bits DIFFER from old"
  rm -f $work/*.exr
}

# Freed host memory kept for reuse (host/util/host_heap.h) against $G/rcsplat_old: Sponza 1920x1080 defaults in
# `bench` (frames after the first in a process) alternating twice, one-frame renders, and Sibenik in `bench`.
if [[ $parts == *heap* ]]; then
  alternate_sponza_1080p heap
  alternate_one_frame_renders heap
  for b in rcsplat_old rcsplat; do
    timeout 90 $G/$b -q bench $B --device NVIDIA --width 1920 --height 1080 --repeats 3 \
      --json $R/heap_${b}_sibenik.json | grep NVIDIA | sed "s/^/sibenik $b: /"
  done
fi

# Image layers downloaded in pieces (passes/layer_pass.h) against $G/rcsplat_old: one-frame renders.
[[ $parts == *pieces* ]] && alternate_one_frame_renders pieces

render() {  # device, tag, then rcsplat render arguments; RUNS runs, the first image kept
  local dev=$1 tag=$2; shift 2
  for i in $(seq 1 $runs); do
    $rc -q render "$@" --device $dev --width 1024 --height 768 --bounces 1 --pixel-samples 1 -o $work/$tag.run$i.exr --json $R/$tag.run$i.json \
      >/dev/null || echo "FAILED: $tag $*"
  done
  for i in $(seq 2 $runs); do  # same input, same device: same bits
    [ -f $work/$tag.run$i.exr ] || continue
    cmp -s $work/$tag.run1.exr $work/$tag.run$i.exr && echo "$tag run $i: identical" || echo "$tag run $i: DIFFERS"
    rm -f $work/$tag.run$i.exr
  done
}
[[ $parts == *renders* ]] && for a in 0.3 0.5; do
  for scene in cornell:"" sponza:$S sibenik:$B; do
    tag=${scene%%:*}_a$a; file=${scene#*:}
    render NVIDIA gpu_$tag $file --accuracy $a
    render $cpu pocl_$tag $file --accuracy $a
    $rc compare $work/gpu_$tag.run1.exr $work/pocl_$tag.run1.exr --json $R/gpu_vs_pocl_$tag.json | sed "s/^/$tag GPU vs PoCL: /"
  done
done
rm -f $work/*.exr
[[ $parts == *equal_error* ]] || exit 0

# Equal error on the GPU (benchmarks/RESULTS.md has the same on PoCL): references first.
timeout 120 $rc -q reference $S --device NVIDIA --width 1024 --height 768 --bounces 1 --pixel-samples 1 --spp 8192 --light-samples 64 -o $work/spref.exr \
  --json $R/sponza_reference.json
timeout 60 $rc -q reference --device NVIDIA --width 1024 --height 768 --bounces 1 --pixel-samples 1 --spp 16384 --light-samples 1024 -o $work/cbref.exr \
  --json $R/cornell_reference.json
timeout 150 python3 benchmarks/equal_error.py $S --rcsplat $rc --device NVIDIA --reference $work/spref.exr --accuracy 0.5 0.3 \
  --start-spp 256 --max-spp 8192 --json $R/equal_error_sponza_gpu.json
timeout 90 python3 benchmarks/equal_error.py --rcsplat $rc --device NVIDIA --reference $work/cbref.exr --accuracy 0.3 0.5 \
  --start-spp 256 --max-spp 16384 --json $R/equal_error_cornell_gpu.json
