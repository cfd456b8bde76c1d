#!/usr/bin/env bash
# The main job: installs what is missing, builds, and runs the shipped example.
# Today: the seed's Table 1 row 1 creep curve (Burgers law, tau = 0.232 MPa, 200 h),
# written to out/table1-row1.csv and printed.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/build.sh"
build="${RHEODDA_BUILD_DIR:-$root/build}"
mkdir -p "$root/out"
"$build/apps/rheodda" law curve burgers \
  --param E1=26.87 --param E2=192.43 --param eta1=34807.72 --param eta2=2141.23 \
  --force 0:0.232 --t-end 200 --dt 10 --scheme exponential-linear | tee "$root/out/table1-row1.csv"
