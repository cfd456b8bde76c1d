#!/usr/bin/env bash
# Where `solver: automatic` should switch from CHOLMOD to amg: the running-bond
# brick wall of bench/contact_bench (penalty 50 E, nu 0.25, dynamic, dt 1 ms)
# over its first 10 ms with each solver, one core. Prints a Markdown table and
# splices it into docs/notes/performance.md ("Which solver, from how many blocks").
# About 2 min on 2 cores. Usage: scripts/solver-switch.sh [--no-splice]
# (uses $RHEODDA_BUILD_DIR or build/).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${RHEODDA_BUILD_DIR:-$root/build}"
bench="$build/bench/contact_bench"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

# One run: prints "blocks ms_per_step solves_per_step".
run() {
  "$bench" --sizes "$1" --duration 0.01 --penalty 50 --poisson 0.25 --solver "$2" |
    awk '/^ +[0-9]/ { blocks = $1 }
         /CPU s per simulated ms/ { for (i = 1; i <= NF; ++i) {
             if ($(i + 1) == "solves") solves = $i }
           # 10 steps of 1 ms: CPU s per simulated ms is also s per step
           split($0, a, ": "); split(a[2], b, " "); per_ms = b[1] }
         END { printf "%s %.1f %s\n", blocks, per_ms * 1e3, solves }'
}

{
  echo "| blocks | cholmod: CPU ms per step | solves per step | amg: CPU ms per step | solves per step | amg / cholmod |"
  echo "|---:|---:|---:|---:|---:|---:|"
  for n in 10 20 28 34 40 46 50 64; do
    read -r blocks c_ms c_solves < <(run "$n" cholmod)
    read -r _ a_ms a_solves < <(run "$n" amg)
    awk -v b="$blocks" -v cm="$c_ms" -v cs="$c_solves" -v am="$a_ms" -v as="$a_solves" \
      'BEGIN { printf "| %d | %.1f | %.2f | %.1f | %.2f | %.2f |\n", b, cm, cs, am, as, am / cm }'
  done
} >"$work/table.md"
cat "$work/table.md"
[ "${1:-}" = "--no-splice" ] || "$root/scripts/splice-doc.sh" "$root/docs/notes/performance.md" solver-switch "$work/table.md"
