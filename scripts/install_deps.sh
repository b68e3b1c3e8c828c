#!/usr/bin/env bash
# Installs everything Sabo needs to build, test and plot on Debian 12 (run as root).
set -euo pipefail
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq --no-install-recommends \
  cmake ninja-build g++ \
  libtomlplusplus-dev libcli11-dev libfmt-dev libspdlog-dev nlohmann-json3-dev zlib1g-dev \
  libgtest-dev libgmock-dev libbenchmark-dev \
  clang-format python3 python3-numpy python3-matplotlib \
  clang libclang-rt-14-dev libomp-dev \
  libopenmpi-dev openmpi-bin \
  ocl-icd-opencl-dev opencl-c-headers opencl-clhpp-headers pocl-opencl-icd clinfo \
  python3-vtk9 python3-pil xvfb xauth libgl1-mesa-dri >/dev/null
# views (python/view.py): VTK's Python module renders the run folders off screen on Xvfb's display;
# fuzz test: libFuzzer is clang's; MPI: sweeps over ranks; OpenCL: the lattice on a GPU, POCL runs it on the
# CPU in the tests
