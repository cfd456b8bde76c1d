#!/usr/bin/env bash
# The figures of docs/notes/explicit-step.md, "The slope at 7 307 blocks": the cohesionless
# slope of bench/scenes scaled to about 1e4 blocks (rockmass_bench --creep 10000), its first
# steps timed (one thread, CPU seconds of the whole process, its start included) in three ways
# of taking its settling:
#   implicit   the scene as shipped: a dynamic settling stage of 1 ms implicit steps;
#   explicit   integrator: explicit, with density scaling (stage_cycles 200), local damping
#              0.8 and the rest test by the unbalanced force (settle.force_ratio 1e-5);
#   cycles     integrator: explicit, a static settling stage of 86.4 s steps, each taken by
#              cycles to an unbalanced-force ratio of 1e-5 (static_force_ratio; the scene's
#              velocity-only keys, damping_ratio and restitution, taken out).
# Prints, per way, the steps, the cycles of the last step, the CPU seconds and the CPU
# seconds per step.
#   scripts/notes-large-slope.sh            # about 5 CPU minutes
#   STEPS="3 60 1" scripts/notes-large-slope.sh   # steps of each way (implicit explicit cycles; 0: not run)
#   CREEP=1000 STEPS="0 0 3" scripts/notes-large-slope.sh   # the 744-block slope's settling by cycles
#                                                           # (about 6 CPU minutes; "Settling by static steps")
# With the cycles way, each of its steps is printed too (cycles, cuts, the step's dt).
# (uses $RHEODDA_BUILD_DIR or build/)
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"  # strict mode; root, build, work (removed at exit)
ensure_built rockmass_bench scene_trace
read -r n_implicit n_explicit n_cycles <<<"${STEPS:-3 60 1}"
"$build/bench/rockmass_bench" --no-generation --scene "$root/bench/scenes/jointed-slope-cohesionless.yaml" \
  --creep "${CREEP:-10000}" --write-scenes "$work" --max-wall 0 >/dev/null
scene="$work/jointed-slope-cohesionless-${CREEP:-10000}.yaml"
python3 - "$scene" "$work" <<'PY'
import sys
src = open(sys.argv[1]).read()
settle = """  settle: {type: dynamic, dt: 1.1574074e-8, max_displacement_ratio: 0.00025, gravity_ramp: 1.1574074e-5,
           rest_tolerance: 1.0e-5, collapse_dt: 1.0e-5}"""
assert settle in src, "the scaled scene's settle line changed: update scripts/notes-large-slope.sh"
explicit = src.replace(settle, settle.replace("rest_tolerance: 1.0e-5,", "rest_tolerance: 1.0e-5, force_ratio: 1.0e-5,")
                       + "\n  integrator: explicit\n  stage_cycles: 200\n  stage_local_damping: 0.8")
open(sys.argv[2] + "/explicit.yaml", "w").write(explicit)
cycles = src.replace(settle, "  settle: {until: 0.02, dt: 0.001, max_displacement_ratio: 0.00025}\n"
                             "  integrator: explicit\n  static_force_ratio: 1.0e-5")
cycles = cycles.replace(",\n         damping_ratio: 1}", "}").replace("    restitution: 0 ", "    # ")
cycles = cycles.replace("restitution: 0, ", "").replace(", restitution: 0}", "}")
open(sys.argv[2] + "/cycles.yaml", "w").write(cycles)
PY
"$build/apps/rheodda" check "$scene" | grep -E "^rock mass|block area"
run() {  # NAME SCENE STEPS
  local out
  [ "$3" -gt 0 ] || return 0
  out="$work/$1.log"
  /usr/bin/time -f "%U" -o "$work/$1.cpu" env OMP_NUM_THREADS=1 "$build/bench/scene_trace" "$2" --steps "$3" --cycles >"$out"
  python3 - "$1" "$3" "$out" "$work/$1.cpu" <<'PY'
import re, sys
name, steps, log, cpu = sys.argv[1], int(sys.argv[2]), open(sys.argv[3]).read(), float(open(sys.argv[4]).read().split()[-1])
last = [l for l in log.splitlines() if l.startswith("step ")][-1]
cycles = re.search(r": (\d+) cycles", last)
summary = [l for l in log.splitlines() if l.startswith("# ") and "steps to" in l][0]
print(f"{name}: {summary[2:].split(';')[0]}; last step: {cycles.group(1) + ' cycles' if cycles and int(cycles.group(1)) > 0 else 'implicit'}; "
      f"CPU {cpu:.1f} s, {cpu / steps:.2f} s per step")
PY
}
run implicit "$scene" "$n_implicit"
run explicit "$work/explicit.yaml" "$n_explicit"
run cycles "$work/cycles.yaml" "$n_cycles"
if [ "$n_cycles" -gt 0 ]; then grep "^step " "$work/cycles.log" | sed 's/^/  cycles /'; fi
