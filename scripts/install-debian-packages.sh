#!/usr/bin/env bash
# Installs the Debian packages rcsplat needs to build, run and test. Run as root (or with sudo).
set -euo pipefail
packages=(
  build-essential cmake pkg-config
  pocl-opencl-icd ocl-icd-opencl-dev opencl-headers opencl-clhpp-headers clinfo
  libembree-dev libopenimageio-dev libtinygltf-dev libstb-dev libglm-dev libcli11-dev nlohmann-json3-dev
  libwebp-dev  # EXT_texture_webp images
  libgtest-dev libgmock-dev libbenchmark-dev
  clang libclang-rt-dev  # scripts/fuzz.sh: libFuzzer
  ffmpeg  # rcsplat animate --mp4: the walkthrough's preview
  slurm-wlm munge  # tests/slurm/run_test.sh: the render-farm scripts (deploy/slurm/) on a one-node Slurm cluster
  python3-pip unzip  # scripts/install-oidn.sh: Open Image Denoise's libraries from PyPI's pyoidn wheel
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  sudo_cmd=""
  [ "$(id -u)" -eq 0 ] || sudo_cmd="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $sudo_cmd apt-get update -qq
  $sudo_cmd apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
