#!/usr/bin/env bash
# The force resolution taken from an absurd iterate (docs/notes/rock-mass-steps.md, "A resolution
# taken from an absurd iterate"): writes the benchmark's 744-block slope (rockmass_bench --creep
# 1000) with the bedding's friction angle at 30.02 deg (one of the neighbouring cases of
# scripts/notes-slope-convergence.sh) and runs it by `rheodda run`, one thread, for SECONDS of
# wall time (default 600): its CPU time, the time it reached and its dynamic stages (events.csv:
# kind, start, steps, at rest, blocks involved, largest displacement [m], kinetic energy peak
# [N*m/m]).
#
# With BEFORE=1 first the same with bench/prototypes/resolution-last-iterate.patch (the open-close
# decisions judged at the force resolution of the last iterate, uncapped, as before
# ContactSystem::force_resolution capped it, contact/src/contact_check.cpp), then the steps from its
# last checkpoint (25 d) traced by scene_trace --restore: each attempt's iterates, the spring
# energy contacts start each step with beyond what they stored (by cause, with the largest
# contact), and the two contacts of the toe block on the foundation (#6: its corner on the
# ground, #7: its base on the bed; the ids of that run).
#
#   scripts/notes-absurd-iterate.sh [SECONDS]
#   BEFORE=1 scripts/notes-absurd-iterate.sh [SECONDS]
#
# SECONDS plus a minute; BEFORE=1 adds a build of the copy and SECONDS more.
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
seconds="${1:-600}"
ensure_built rockmass_bench rheodda scene_trace
bench_slope
scene="$work/slope-30.02.yaml"
scene_variant "$slope_scene" "$scene" $'creeping bedding planes\n    friction_angle: 30=>creeping bedding planes\n    friction_angle: 30.02'
# run_for BUILD: the scene by `rheodda run` of BUILD for $seconds of wall time, into $work/run.
run_for() {
  rm -rf "$work/run"
  /usr/bin/time -f "%U" -o "$work/cpu" timeout -s INT "$seconds" "$1/apps/rheodda" run "$scene" -o "$work/run" \
    --threads 1 --quiet >/dev/null 2>&1 || true
  echo "CPU $(tail -n 1 "$work/cpu") s, reached t = $(awk -F, 'NR > 2 { t = $1 } END { print t }' "$work/run/history.csv") d"
  cut -d, -f1,2,5,6,7,8,9 "$work/run/events.csv"
}
if [[ -n "${BEFORE:-}" ]]; then
  prototype_build "$root/bench/prototypes/resolution-last-iterate.patch" rheodda scene_trace
  echo "# with bench/prototypes/resolution-last-iterate.patch, rheodda run for $seconds s:"
  run_for "$proto_build"
  echo "# its steps from the checkpoint (scene_trace --restore):"
  "$proto_build/bench/scene_trace" "$scene" --restore "$work/run/checkpoint-0.state" --steps 5 --contacts |
    grep -E '^step|#6 |#7 ' | cut -c1-400
fi
echo "# rheodda run for $seconds s:"
run_for "$build"
