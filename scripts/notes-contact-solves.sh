#!/usr/bin/env bash
# Regenerates the 2026-11 figures of docs/notes/contact-solves.md ("Contact solves
# measured on the brick wall"): the running-bond wall of bench/contact_bench.cpp,
# penalty 50 E, nu = 0.25, dynamic, for a fixed 50 ms, with the open-close and
# the newton contact solves (Settings::contact_solver) at three residual
# tolerances. Prints a Markdown table and splices it between the wall-solves
# markers of that note; about 3 min on 2 cores.
#
#   scripts/notes-contact-solves.sh [SIZES]            # default 40 (1 620 blocks)
#   scripts/notes-contact-solves.sh --prototypes       # the solves tried and not adopted
#
# --prototypes builds commit 67c7022 with docs/notes/prototypes/contact-solves-67c7022.patch
# applied (environment switches RHEODDA_NSGS=<sweeps> (the dual nonlinear Gauss-Seidel
# against the accepted step), RHEODDA_LS (a line search on the residual norm),
# RHEODDA_PREDICT (a dynamic step starting from the states at the Newmark predictor),
# RHEODDA_DUMP_K=<solve> (writes the system of that solve to /tmp/K.mtx)) in a
# scratch worktree, and times CHOLMOD's update/downdate on the dumped system with
# docs/notes/prototypes/cholmod-updown.cpp. About 10 min on 2 cores.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
if [ "${1:-}" = "--prototypes" ]; then
  work="$(mktemp -d)"
  trap 'git -C "$root" worktree remove --force "$work/src" >/dev/null 2>&1 || true; rm -rf "$work"' EXIT
  git -C "$root" worktree add --detach "$work/src" 67c7022 >/dev/null
  git -C "$work/src" apply "$root/docs/notes/prototypes/contact-solves-67c7022.patch"
  cmake -S "$work/src" -B "$work/build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
  cmake --build "$work/build" -j "$(nproc)" --target contact_bench >/dev/null
  bench="$work/build/bench/contact_bench"
  echo "## the 10 x 10 wall, 200 steps: from the last step's states, from the predictor's"
  "$bench" --sizes 10 --steps 200 --solver cholmod | tail -3
  RHEODDA_PREDICT=1 "$bench" --sizes 10 --steps 200 --solver cholmod | tail -3
  echo "## line search on the residual norm, the 20 x 20 wall, 50 steps"
  RHEODDA_LS=1 "$bench" --sizes 20 --steps 50 --penalty 50 --poisson 0.25 --solver cholmod 2>/dev/null | tail -3
  echo "## dual NSGS, 100 sweeps, against each accepted step (relative displacement error per sweep)"
  RHEODDA_NSGS=100 "$bench" --sizes 40 --steps 3 --penalty 50 --poisson 0.25 --solver cholmod 2>&1 >/dev/null | tail -3
  echo "## CHOLMOD factorize, solve, update/downdate of rank k on the 1 620-block wall's system"
  RHEODDA_DUMP_K=5 "$bench" --sizes 40 --steps 2 --penalty 50 --poisson 0.25 --solver cholmod >/dev/null
  g++ -O2 -std=c++20 -I/usr/include/suitesparse "$root/docs/notes/prototypes/cholmod-updown.cpp" \
    -lcholmod -o "$work/updown"
  "$work/updown" /tmp/K.mtx
  exit 0
fi
sizes="${1:-40}"
"$root/scripts/build.sh" >/dev/null
bench="$root/build/bench/contact_bench"
table="$(mktemp)"
trap 'rm -f "$table"' EXIT
{
echo "| wall | solve | residual tolerance | solves per step | cuts | CPU s per simulated ms | largest displacement [m] |"
echo "|---|---|---|---|---|---|---|"
row() {
  local label="$1" tol="$2"; shift 2
  "$bench" --sizes "$sizes" --duration 0.05 --penalty 50 --poisson 0.25 "$@" |
    awk -v s="$label" -v t="$tol" '
      /^ *[0-9]+ +[0-9]+ +[0-9]+/ { blocks = $1; cuts = $12; disp = $NF }
      /CPU s per simulated ms/ { for (i = 1; i <= NF; ++i) { if ($i == "CPU" && $(i+1) == "s" && $(i+2) == "per") cpu = $(i-1);
                                                            if ($i == "solves") sps = $(i-1) } }
      END { printf "| %s blocks | %s | %s | %s | %s | %s | %s |\n", blocks, s, t, sps, cuts, cpu, disp }'
}
row open-close - --contact-solver open-close
for tol in 1e-2 1e-3 1e-4; do row newton "$tol" --contact-solver newton --residual-tol "$tol"; done
} | tee "$table"
"$root/scripts/splice-doc.sh" "$root/docs/notes/contact-solves.md" wall-solves "$table"
