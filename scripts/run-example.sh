#!/usr/bin/env bash
# The main job: installs what is missing, builds, and runs the shipped example
# examples/shear-creep-test.yaml (the seed's two-block shear creep test, Table 1
# row 1, Burgers joint, 200 h), then draws its pictures.
# Outputs: out/shear-creep/ (history.csv, contacts.csv, blocks.pvd, summary.json, plots/*.png).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/build.sh"
build="${RHEODDA_BUILD_DIR:-$root/build}"
out="$root/out/shear-creep"
"$build/apps/rheodda" run "$root/examples/shear-creep-test.yaml" -o "$out"
"$build/apps/rheodda" plot "$out"
echo "joint shear displacement at the end (mm), DDA vs the Burgers closed form 0.01117:"
awk -F, '/^#/ {next} !h {for (i = 1; i <= NF; i++) if ($i == "plane.shear_displacement") c = i; h = 1; next}
  {v = $c} END {print "  plane.shear_displacement =", (v < 0 ? -v : v)}' "$out/history.csv"
