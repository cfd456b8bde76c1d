#!/usr/bin/env bash
# The main job: installs what the example needs, builds the rheodda command alone, and runs
# the shipped example examples/shear-creep-test.yaml (the seed's two-block shear creep
# test, Table 1 row 1, Burgers joint, 200 h), then draws its pictures.
# Only the command and the libraries it links are built (not the tests, benchmarks or
# Python module, nor their packages: scripts/test.sh installs and builds those, in the
# same build folder, configured the same way). Timing: README.md, "Quick start".
# Outputs: out/shear-creep/ (history.csv, contacts.csv, blocks.pvd, summary.json, plots/*.png).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/install-deps.sh" --command
build="${RHEODDA_BUILD_DIR:-$root/build}"
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE="${CMAKE_BUILD_TYPE:-Release}" >/dev/null
cmake --build "$build" -j "$(nproc)" --target rheodda
out="$root/out/shear-creep"
"$build/apps/rheodda" run "$root/examples/shear-creep-test.yaml" -o "$out"
"$build/apps/rheodda" plot "$out"
echo "joint shear displacement at the end (mm), DDA vs the Burgers closed form 0.01117:"
awk -F, '/^#/ {next} !h {for (i = 1; i <= NF; i++) if ($i == "plane.shear_displacement") c = i; h = 1; next}
  {v = $c} END {print "  plane.shear_displacement =", (v < 0 ? -v : v)}' "$out/history.csv"
