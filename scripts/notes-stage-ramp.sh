#!/usr/bin/env bash
# The figures of docs/notes/explicit-step.md, "Settling by static steps on the 744-block
# slope" (its second table): the 744-block cohesionless slope's settling stage taken by the
# explicit step (integrator: explicit, stage_cycles 50, stage_local_damping 0.8, the rest test
# by the unbalanced force, settle.force_ratio 1e-5), the stage 5 s long, with the scene's
# gravity ramp of 1 s and with one of 0.1 s. Prints, per ramp, the settling stage's row of
# events.csv (steps, at rest, blocks involved, largest displacement, kinetic energy's peak
# and end, work, dissipated) and the CPU seconds of the run (one thread).
#   scripts/notes-stage-ramp.sh          # about 3 CPU minutes
# (uses $RHEODDA_BUILD_DIR or build/)
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"  # strict mode; root, build, work (removed at exit)
ensure_built rockmass_bench rheodda
"$build/bench/rockmass_bench" --no-generation --scene "$root/bench/scenes/jointed-slope-cohesionless.yaml" \
  --creep 1000 --write-scenes "$work" --max-wall 0 >/dev/null
python3 - "$work/jointed-slope-cohesionless-1000.yaml" "$work" <<'PY'
import re, sys
src = open(sys.argv[1]).read()
settle = """  settle: {type: dynamic, dt: 1.1574074e-8, max_displacement_ratio: 0.00025, gravity_ramp: 1.1574074e-5,
           rest_tolerance: 1.0e-5, collapse_dt: 1.0e-5}"""
assert settle in src, "the scaled scene's settle line changed: update scripts/notes-stage-ramp.sh"
for name, ramp in (("ramp-1s", "1.1574074e-5"), ("ramp-0.1s", "1.1574074e-6")):
    v = src.replace(settle, f"""  settle: {{type: dynamic, dt: 1.1574074e-8, max_displacement_ratio: 0.00025, gravity_ramp: {ramp},
           rest_tolerance: 1.0e-5, force_ratio: 1.0e-5, until: 5.787037e-5}}
  integrator: explicit
  stage_cycles: 50
  stage_local_damping: 0.8""")
    v = re.sub(r"\n  duration: [^\n]*", "\n  duration: 6.0e-5", v)          # the stage, then a step
    v = re.sub(r"\n  output_interval: [^\n]*", "\n  output_interval: 6.0e-5", v)
    v = re.sub(r"\n  dt: 0.03125[^\n]*", "\n  dt: 3.0e-6", v)
    open(f"{sys.argv[2]}/{name}.yaml", "w").write(v)
PY
for name in ramp-1s ramp-0.1s; do
  /usr/bin/time -f "%U" -o "$work/$name.cpu" env OMP_NUM_THREADS=1 \
    "$build/apps/rheodda" run "$work/$name.yaml" -o "$work/out-$name" >/dev/null 2>&1
  echo "$name: CPU $(tail -n 1 "$work/$name.cpu") s"
  grep "^settling," "$work/out-$name/events.csv" | sed 's/^/  /'
done
echo "(events.csv columns: $(head -n 1 "$work/out-ramp-1s/events.csv"))"
