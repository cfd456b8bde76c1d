#!/usr/bin/env bash
# The 744-block cohesionless slope's dynamic stages ending at rest (docs/notes/rock-mass-steps.md,
# "Stages at rest, and a corner's far neighbour"): writes the benchmark's slope (rockmass_bench
# --creep 1000) and runs it by `rheodda run`, one thread, for SECONDS of wall time (default 900):
# its last progress line, its closing lines and events.csv. With BEFORE=1 the same with
# bench/prototypes/detection-inadmissible-pair.patch (a vertex-vertex pair whose candidates the
# angle rule all refuses taking its best-scored one, as before contact/src/detection.cpp refused
# it), then the state at the end of its first stage after 52.15 d saved through the Python API
# (bench/save_state.py) and its next
# step traced (scene_trace --restore --diagnose: the spring energy new contacts start with).
#
# With NEAREST=1, examples/rockmass/tunnel-stages.yaml with
# bench/prototypes/detection-nearest-vertex.patch (the first fix tried: a vertex paired only with
# the nearest vertex of the other block): its events.csv after 120 s.
#
#   scripts/notes-stage-rest.sh [SECONDS]
#   BEFORE=1 scripts/notes-stage-rest.sh
#   NEAREST=1 scripts/notes-stage-rest.sh
#
# SECONDS plus a minute; BEFORE=1 adds a build of the copy, its run and about 6 minutes.
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
seconds="${1:-900}"
ensure_built rockmass_bench rheodda scene_trace
bench_slope
scene="$slope_scene"
# run_for BUILD: the slope by `rheodda run` of BUILD for $seconds of wall time.
run_for() {
  rm -rf "$work/run"
  /usr/bin/time -f "# CPU: %U s user, %S s system" timeout -s INT "$seconds" "$1/apps/rheodda" run \
    "$scene" -o "$work/run" --threads 1 >"$work/run.log" 2>&1 || true
  grep '^rheodda run:' "$work/run.log" | tail -n 1
  grep -v '^rheodda run:' "$work/run.log" | tail -n 6
  cut -d, -f1,2,5,6,7,8,9,11,12 "$work/run/events.csv"
}
if [[ -n "${BEFORE:-}" ]]; then
  prototype_build "$root/bench/prototypes/detection-inadmissible-pair.patch" rheodda _rheodda scene_trace
  echo "# with bench/prototypes/detection-inadmissible-pair.patch, rheodda run for $seconds s:"
  run_for "$proto_build"
  RHEODDA_BUILD_DIR="$proto_build" /usr/bin/python3 "$root/bench/save_state.py" "$scene" 52.15 "$work/s52.state" 5
  "$proto_build/bench/scene_trace" "$scene" --restore "$work/s52.state" --steps 1 --diagnose | grep 'spring energy'
fi
if [[ -n "${NEAREST:-}" ]]; then
  prototype_build "$root/bench/prototypes/detection-nearest-vertex.patch" rheodda
  echo "# examples/rockmass/tunnel-stages.yaml with bench/prototypes/detection-nearest-vertex.patch, 120 s:"
  timeout -s INT 120 "$proto_build/apps/rheodda" run "$root/examples/rockmass/tunnel-stages.yaml" -o "$work/tunnel" \
    >/dev/null 2>&1 || true
  cut -d, -f1,2,5,6,9,11,12 "$work/tunnel/events.csv"
fi
echo "# rheodda run for $seconds s:"
run_for "$build"
