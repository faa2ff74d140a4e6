#!/usr/bin/env bash
# The project's one install step: every Debian package fricon needs, installed only when missing.
# Idempotent and non-interactive; runs `apt-get update` at most once, and only if something is missing.
set -euo pipefail

packages=(
  # toolchain
  build-essential cmake ninja-build pkg-config clang-format
  # numerics: dense/sparse algebra, sparse Cholesky with an optimised BLAS
  libeigen3-dev libsuitesparse-dev libopenblas-dev
  # input/output and command line
  libtomlplusplus-dev libcli11-dev nlohmann-json3-dev libfmt-dev
  # the problems of other codes: FCLIB (HDF5)
  libfclib-dev
  # meshes of other tools: the Gmsh API (its C API, opened at run time) (MSH files, .geo meshed on the fly)
  libgmsh-dev
  # friction laws written as formulas in problem files (law = "expression")
  libmuparser-dev
  # the Python module (fricon for /usr/bin/python3) and its tests
  pybind11-dev python3-dev python3-pytest
  # runs on many MPI ranks: PETSc 3.18 with OpenMPI, MUMPS, hypre, PT-Scotch
  petsc-dev
  # graph partitions of the bodies into subdomains (backend "tfeti")
  libmetis-dev
  # tests and benchmarks
  libgtest-dev libgmock-dev libbenchmark-dev
  # reading results back (tests) and plots: Debian's Python packages for /usr/bin/python3
  python3 python3-numpy python3-meshio python3-matplotlib
  # peer comparison in bench/ (optional for the library)
  libsiconos-numerics-dev
  # fuzzing (make fuzz): clang with libFuzzer and the sanitizer runtimes
  clang libclang-rt-14-dev
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
