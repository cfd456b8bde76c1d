#!/usr/bin/env bash
# The 744-block cohesionless slope's mechanism stage that never rests (docs/notes/rock-mass-steps.md,
# "A mechanism stage that never rests"): writes the benchmark's slope (rockmass_bench --creep
# 1000), steps it through the Python API to the static steps that find its mechanism and prints,
# step by step, the energies and the contacts committed locked outside their Mohr-Coulomb
# envelope (bench/stage_glue.py). With PROTOTYPE=opens it also builds a copy of the tree with
# bench/prototypes/anti-chattering-opens.patch and prints the slope's stages with it
# (bench/stage_motion.py, 6 000 steps), then runs the slope with `rheodda run` for 480 s of wall
# time (its last lines and events.csv). With RUN=1, the slope by `rheodda run` of the tree as
# it is, for 600 s of wall time (the commit projecting glued contacts onto their envelope,
# docs/reference/contacts.md).
#
#   scripts/notes-mechanism-glue.sh [FROM TO]     # steps, default 3312 3320
#   PROTOTYPE=opens scripts/notes-mechanism-glue.sh
#   RUN=1 scripts/notes-mechanism-glue.sh
#
# About 3 minutes (the slope's first 3 300 steps); a prototype adds a build and 8-10 minutes,
# RUN=1 10 minutes.
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
from="${1:-3312}"
to="${2:-3320}"
ensure_built rockmass_bench
bench_slope
scene="$slope_scene"
RHEODDA_BUILD_DIR="$build" /usr/bin/python3 "$root/bench/stage_glue.py" "$scene" "$from" "$to" 3
# run_for ENV_VAR BUILD SECONDS: the slope by `rheodda run` of BUILD for SECONDS of wall time
# (ENV_VAR set to 1 unless empty).
run_for() {
  env ${1:+"$1=1"} /usr/bin/time -f "# CPU: %U s user, %S s system" timeout -s INT "$3" "$2/apps/rheodda" run \
    "$scene" -o "$work/run" --threads 1 >"$work/run.log" 2>&1 || true
  grep '^rheodda run:' "$work/run.log" | tail -n 1
  grep -v '^rheodda run:' "$work/run.log" | tail -n 9
  cat "$work/run/events.csv"
}
case "${PROTOTYPE:-}" in
  opens)
    prototype_build "$root/bench/prototypes/anti-chattering-opens.patch" _rheodda rheodda
    echo "# with bench/prototypes/anti-chattering-opens.patch:"
    RHEODDA_ANTI_CHATTERING_OPENS=1 RHEODDA_BUILD_DIR="$proto_build" \
      /usr/bin/python3 "$root/bench/stage_motion.py" "$scene" 6000 100
    run_for RHEODDA_ANTI_CHATTERING_OPENS "$proto_build" 480
    ;;
  "") ;;
  *) echo "PROTOTYPE: opens" >&2; exit 2 ;;
esac
if [[ -n "${RUN:-}" ]]; then
  ensure_built rheodda
  echo "# rheodda run for 600 s:"
  run_for "" "$build" 600
fi
