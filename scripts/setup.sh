#!/usr/bin/env bash
# Installs the Debian packages asperity needs (run as root on Debian 12; python3 runs the layer
# check of every build, scripts/check_layers.py; the python3-* packages serve the Python module,
# its tests and examples/, Sphinx with MyST the reference docs' build, docs/conf.py; slurm-wlm
# and munge the SLURM test, scripts/slurm/test_slurm.sh; clang-format the layout check,
# tests/shell/check_format.sh) and builds it.
#   scripts/setup.sh [--deps-only]
set -euo pipefail
cd "$(dirname "$0")/.."
pkgs=(cmake g++ ninja-build libboost-dev libeigen3-dev libtbb-dev libnlopt-cxx-dev
      libyaml-cpp-dev catch2 libcli11-dev gnuplot-nox python3 clang-format
      python3-dev pybind11-dev python3-pybind11 python3-numpy python3-pandas python3-matplotlib
      python3-pytest python3-sphinx python3-myst-parser python3-tqdm python3-nbclient python3-nbformat python3-ipykernel python3-pip python3-setuptools python3-wheel python3-venv slurm-wlm munge libopenblas-openmp-dev
      libsqlite3-dev libssl-dev libfftw3-dev pkg-config
)
missing=()
for p in "${pkgs[@]}"; do dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p"); done
if [ ${#missing[@]} -gt 0 ]; then
  apt-get update -qq
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "${missing[@]}"
fi
[ "${1:-}" = "--deps-only" ] && exit 0
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
ninja -C build -j "$(nproc)"
