#!/usr/bin/env bash
# The benchmark environment (never a runtime need of rcsplat): a virtual environment at benchmarks/.venv with
# matplotlib (sweep plots), flip-evaluator (checks rcsplat's FLIP), pyoidn (path tracing + denoising), mitsuba (the
# Mitsuba 3 peer), OpenEXR and numpy. Mitsuba 3.9's llvm variant needs a newer LLVM than Debian 12's default:
# libllvm19 from Debian's bookworm updates; benchmarks/mitsuba_peer.py finds it through DRJIT_LIBLLVM_PATH.
#   bash benchmarks/setup_python.sh
set -euo pipefail
cd "$(dirname "$0")"
sudo_if_needed() { if [ "$(id -u)" -eq 0 ]; then "$@"; else sudo "$@"; fi; }
missing=()
python3 -c "import venv, ensurepip" 2> /dev/null || missing+=(python3-venv)
dpkg -s libllvm19 > /dev/null 2>&1 || missing+=(libllvm19)
if [ ${#missing[@]} -gt 0 ]; then
  sudo_if_needed apt-get update -q
  sudo_if_needed env DEBIAN_FRONTEND=noninteractive apt-get install -y -q "${missing[@]}"
fi
[ -x .venv/bin/python ] || python3 -m venv .venv
.venv/bin/pip install -q --upgrade pip
.venv/bin/pip install -q matplotlib numpy OpenEXR flip-evaluator pyoidn mitsuba
.venv/bin/python -c "import matplotlib, numpy, OpenEXR, flip_evaluator, pyoidn, mitsuba; print('benchmark environment ready:', '$PWD/.venv')"
