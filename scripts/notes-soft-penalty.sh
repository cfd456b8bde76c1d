#!/usr/bin/env bash
# A softer penalty (docs/notes/explicit-step.md, "A softer penalty"): the
# benchmark's 744-block cohesionless slope (rockmass_bench --creep 1000) run for its 100 d by
# `rheodda run`, one thread each, with the contacts' penalty `analysis.penalty` at 1 E, 10 E,
# 40 E (the scene's default) and 160 E (E = 1e10 Pa), the settling and mechanism stages implicit as
# shipped; then at 1 E, 10 E and 40 E with `integrator: explicit` (`stage_cycles: 200`,
# `stage_local_damping: 0.8`, rest by `settle.force_ratio: 1e-5`). Prints per run its CPU
# seconds, steps, the settling stage's steps, the mechanism stages, and the toe's displacement
# at 100 d (total and since the settling stage ended) [m].
#
#   scripts/notes-soft-penalty.sh            # about 40 CPU minutes
#   LARGE=1 scripts/notes-soft-penalty.sh    # and the slope at 7 307 blocks (--creep 10000),
#                                            # explicit at 1 E, for up to SECONDS_LARGE (default 3 600) s of wall time
# (uses $RHEODDA_BUILD_DIR or build/)
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
ensure_built rockmass_bench rheodda
bench_slope
explicit=("rest_tolerance: 1.0e-5,=>rest_tolerance: 1.0e-5, force_ratio: 1.0e-5,"
          $'  gravity:=>  integrator: explicit\n  stage_cycles: 200\n  stage_local_damping: 0.8\n  gravity:')
# penalty P: the replacement that gives the scene analysis.penalty P [Pa]
penalty() { printf '  gravity:=>  penalty: %s\n  gravity:' "$1"; }
# run NAME SCENE [OLD=>NEW...]: the scene (with the replacements) run for its 100 d, or
# for $seconds of wall time; one line of figures.
run() {
  local name="$1" base="$2"
  shift 2
  scene_variant "$base" "$work/$name.yaml" "$@"
  /usr/bin/time -f "%U" -o "$work/$name.cpu" timeout -s INT "${seconds:-100000}" \
    "$build/apps/rheodda" run "$work/$name.yaml" -o "$work/$name" --threads 1 --quiet >/dev/null 2>&1 || true
  /usr/bin/python3 - "$name" "$work/$name" "$work/$name.cpu" <<'PY'
import csv, json, math, sys
name, out, cpu = sys.argv[1], sys.argv[2], float(open(sys.argv[3]).read().split()[-1])
rows = [r for r in csv.reader(open(out + "/history.csv")) if not r[0].startswith("#")]
head, last = rows[0], rows[-1]
col = {k: i for i, k in enumerate(head)}
num = lambda k: float(last[col[k]] or "nan")  # empty before the settling stage ends
toe = math.hypot(num("toe.u"), num("toe.v"))
after = math.hypot(num("toe.u_after_settling"), num("toe.v_after_settling"))
ev = list(csv.DictReader(open(out + "/events.csv")))
settle = [e for e in ev if e["kind"] == "settling"]
mech = [e for e in ev if e["kind"] == "mechanism"]
rest = all(e["at_rest"] == "1" for e in ev)
s = settle[0]["steps"] + (" steps (at rest)" if settle[0]["at_rest"] == "1" else " steps (not at rest)") if settle else "not ended"
summary = json.load(open(out + "/summary.json"))  # written at the end, or at an interruption
print(f"{name}: t = {summary['time']:g} d, {summary['steps']} steps, CPU {cpu:.1f} s; settling {s}; "
      f"{len(mech)} mechanism stages{'' if rest else ' (not all at rest)'}; toe {toe:.5f} m, since settling {after:.5f} m")
PY
}
run implicit-1E "$slope_scene" "$(penalty 1.0e10)"
run implicit-10E "$slope_scene" "$(penalty 1.0e11)"
run implicit-40E "$slope_scene"
run implicit-160E "$slope_scene" "$(penalty 1.6e12)"
run explicit-1E "$slope_scene" "${explicit[@]}" "$(penalty 1.0e10)"
run explicit-10E "$slope_scene" "${explicit[@]}" "$(penalty 1.0e11)"
run explicit-40E "$slope_scene" "${explicit[@]}"
if [[ -n "${LARGE:-}" ]]; then
  "$build/bench/rockmass_bench" --no-generation --scene "$root/bench/scenes/jointed-slope-cohesionless.yaml" \
    --write-scenes "$work" --creep 10000 --max-wall 0 >/dev/null
  seconds="${SECONDS_LARGE:-3600}" run large-explicit-1E "$work/jointed-slope-cohesionless-10000.yaml" "${explicit[@]}" \
    "$(penalty 1.0e10)"
fi
