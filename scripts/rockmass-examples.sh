#!/usr/bin/env bash
# Runs the rock-mass examples (docs/guide/rockmass.md) and draws their pictures into docs/img/:
#   rockmass-<name>-cut.png      the generated blocks, edges coloured by joint set (rheodda generate --plot)
#   rockmass-<name>-blocks.png   the blocks after 100 days (rheodda plot of the run, last frame)
#   rockmass-<name>-history.png  the history curves of the run
# and prints each run's summary line. Outputs in out/rockmass/.
# Usage: bash scripts/rockmass-examples.sh   (RHEODDA_BUILD_DIR: the build to use, default build/)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${RHEODDA_BUILD_DIR:-$root/build}"
[ -x "$build/apps/rheodda" ] || RHEODDA_BUILD_DIR="$build" bash "$root/scripts/build.sh"
rheodda="$build/apps/rheodda"
out="$root/out/rockmass"
mkdir -p "$out" "$root/docs/img"
for name in jointed-slope tunnel; do
  scene="$root/examples/rockmass/$name.yaml"
  echo "== $name"
  "$rheodda" check "$scene" | sed -n '/^rock mass/,/^fixed points/p'
  "$rheodda" generate "$scene" -o "$out/$name-explicit.yaml" --plot
  cp "$out/$name-explicit-blocks.png" "$root/docs/img/rockmass-$name-cut.png"
  rm -rf "$out/$name"
  "$rheodda" run "$scene" -o "$out/$name" | tail -n 4
  "$rheodda" plot "$out/$name" --times 100 >/dev/null
  last="$(ls "$out/$name/plots"/blocks_*.png | tail -n 1)"
  cp "$last" "$root/docs/img/rockmass-$name-blocks.png"
  cp "$out/$name/plots/history.png" "$root/docs/img/rockmass-$name-history.png"
done
echo "pictures: docs/img/rockmass-*.png"
