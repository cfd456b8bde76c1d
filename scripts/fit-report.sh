#!/usr/bin/env bash
# Regenerates the measured tables of docs/guide/fitting.md: runs bench/fit_bench (the
# speed of a Burgers fit on 1e3, 1e5 and 1e6 points) and
# `fit_bench --global --draws 300 --reference-starts 100` (the default fit
# against a 100-start reference over 300 seeded noise draws per law and
# history) and puts their output between the <!-- fit-speed:begin/end --> and
# <!-- fit-global:begin/end --> markers. Takes about 10 min of one core.
# Usage: scripts/fit-report.sh   (uses $RHEODDA_BUILD_DIR or build/; builds fit_bench if missing)
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"  # strict mode; root, build, work (removed at exit)
ensure_built fit_bench
{
  echo '```'
  "$build/bench/fit_bench"
  echo '```'
} >"$work/speed.md"
"$build/bench/fit_bench" --global --draws 300 --reference-starts 100 >"$work/global.md"
"$root/scripts/splice-doc.sh" "$root/docs/guide/fitting.md" fit-speed "$work/speed.md"
"$root/scripts/splice-doc.sh" "$root/docs/guide/fitting.md" fit-global "$work/global.md"
