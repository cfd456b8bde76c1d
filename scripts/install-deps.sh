#!/usr/bin/env bash
# Installs the Debian 12 packages rheodda needs to build, test and plot.
# Idempotent: only packages that are missing are installed. Needs root (or sudo).
# Usage: scripts/install-deps.sh             every package (scripts/build.sh, scripts/test.sh)
#        scripts/install-deps.sh --command   only what building the rheodda command and
#                                            drawing its pictures needs (scripts/run-example.sh)
set -euo pipefail

# The rheodda command: build, run, plot.
command_packages=(
  build-essential cmake ninja-build pkg-config
  libeigen3-dev          # dense 6x6 blocks and sparse matrices
  libsuitesparse-dev     # CHOLMOD sparse Cholesky
  libopenblas0-serial    # optimised BLAS for CHOLMOD's supernodal factorisation (1.7x on the brick wall)
  libyaml-cpp-dev        # scene files: the nodes the loader reads
  libyaml-dev            # scene files: the parser (8x faster than yaml-cpp's on large files)
  libgsl-dev             # nonlinear least squares (rheodda fit)
  libboost-test-dev      # unit tests (CMake looks for it while the tests are configured; 0.5 MB beside CGAL's Boost)
  libcli11-dev           # command-line parsing
  libudunits2-dev        # quantities with units in scenes, studies, fits and on the command line
  libfmt-dev             # formatting
  nlohmann-json3-dev     # summary.json, fit reports
  gnuplot-nox            # rheodda plot: PNG/SVG pictures
  libcgal-dev            # exact 2D arrangements: cutting rock masses from joint sets
  ccache                 # compiler cache: a clean clone or work tree compiles only what changed
)

# The tests, the Python module, studies over MPI, the reports.
other_packages=(
  pybind11-dev           # the Python module (python/)
  python3-dev            # Python headers for the module
  python3-numpy          # arrays in and out of the Python module
  python3-pytest         # the Python tests
  python3-pandas         # histories as DataFrames (optional at run time, tested)
  python3-matplotlib     # examples/python pictures
  python3-lmfit          # tests/python/test_fit_lmfit.py: the reference fits of rheodda.fit(params=, sigma=)
  python3-nbclient       # tests/python/test_notebook.py: executes examples/python's notebook headless
  python3-nbformat       # the notebook's file format, read and written by that test
  python3-ipykernel      # the notebook's Python 3 kernel
  python3-mypy           # tests/python/test_typing.py: mypy --strict on the examples against the .pyi stubs
  libopenmpi-dev         # studies across machines (mpirun rheodda study)
  openmpi-bin            # mpirun, used by the MPI study tests
  time                   # /usr/bin/time -v: peak memory in scripts/memory-report.sh
)

case "${1:-}" in
  "") packages=("${command_packages[@]}" "${other_packages[@]}") ;;
  --command) packages=("${command_packages[@]}") ;;
  *) echo "install-deps: unknown option '$1' (usage: scripts/install-deps.sh [--command])" >&2; exit 2 ;;
esac

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
