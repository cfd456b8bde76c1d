#!/usr/bin/env bash
# Peak resident memory and wall time of `rheodda run` on stacked walls of
# N x N blocks (docs/notes/performance.md, "Memory at 1e5 blocks"), beside the
# estimate `rheodda check` prints. Each run is stopped (SIGINT, a clean stop)
# after LIMIT seconds of wall time; the peak is reached in the first step.
# Usage: scripts/memory-report.sh [LIMIT_SECONDS [N ...]]   (default: 120 s, N = 100 316)
# Uses $RHEODDA_BUILD_DIR or build/. Needs /usr/bin/time (Debian package time).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${RHEODDA_BUILD_DIR:-$root/build}"
limit="${1:-120}"
shift || true
sizes=("$@")
[ ${#sizes[@]} -eq 0 ] && sizes=(100 316)
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
echo "| wall | blocks | solver | estimate (check) | peak RSS | steps in ${limit} s |"
echo "|---|---:|---|---:|---:|---:|"
for n in "${sizes[@]}"; do
  for solver in amg cholmod; do
    # cholmod only where its factor stays small enough to measure quickly
    if [ "$solver" = cholmod ] && [ "$n" -gt 100 ]; then continue; fi
    f="$work/grid$n-$solver.yaml"
    cat >"$f" <<YAML
title: stacked wall $n x $n
units: {length: m, force: N, time: s}
analysis: {type: dynamic, duration: 0.05, dt: 0.001, output_interval: 0.01, gravity: [0, -9.81], solver: $solver}
materials: {rock: {density: 2600, young_modulus: 5.0e9, poisson_ratio: 0.25}}
joint_sets: {j: {friction_angle: 35}}
blocks:
  - {name: base, rectangle: {x: -1, y: -1, width: $((n + 2)), height: 1}, fixed: true}
  - {name: w, grid: {x: 0, y: 0, width: 1, height: 0.5, columns: $n, rows: $n}}
YAML
    est="$("$build/apps/rheodda" check "$f" | sed -n 's/^estimated memory of a run: \([^(]*\) (.*/\1/p')"
    /usr/bin/time -v -o "$work/time.txt" timeout -s INT "$limit" "$build/apps/rheodda" run "$f" -o "$work/out-$n-$solver" \
      >"$work/run.txt" 2>&1 || true
    rss_kb="$(sed -n 's/.*Maximum resident set size (kbytes): //p' "$work/time.txt")"
    steps="$(grep -o '[0-9]* steps' "$work/run.txt" | head -1 | cut -d' ' -f1)"
    printf '| %s x %s | %s | %s | %s | %.2f GB | %s |\n' "$n" "$n" "$((n * n + 1))" "$solver" "$est" \
      "$(awk -v k="$rss_kb" 'BEGIN { print k / 1e6 }')" "${steps:-?}"
  done
done
