#!/usr/bin/env bash
# Mechanism motion of static analyses (docs/reference/engine.md, "Mechanisms in static
# analysis"): runs every shipped static example, the seed's slope on its
# own static steps (bench/scenes/goodman-toppling-seed-steps.yaml), the sliding block in static
# analysis at friction 20 and 40 deg, the Goodman slope without creep (base
# 45 deg, 2 d) at two refinement levels and the toppling model of
# examples/goodman-toppling-creep.yaml at dt 1/8 d and without its settling stage, the stepped
# slope of bench/scenes/stepped-toppling.yaml in static analysis, and prints
# summary.json's `static_mechanism` for each: the share of the work of gravity
# and loads the static steps' inertia terms took, and the steps that moved as a
# mechanism. Puts the table into docs/reference/engine.md between the static-mechanisms
# markers. About 10 s.
# Usage: scripts/static-mechanisms.sh   (uses $RHEODDA_BUILD_DIR or build/)
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"  # strict mode; root, build, work (removed at exit)
ex="$root/examples"
# variant NAME SOURCE SED-SCRIPT: a copy of SOURCE edited by SED-SCRIPT
variant() { sed -e "$3" "$2" >"$work/$1.yaml"; echo "$work/$1.yaml"; }
cases=()
for f in shear-creep-test power-law-creep-test damage-creep-test creeping-slope-failure goodman-toppling goodman-toppling-creep; do
  cases+=("examples/$f.yaml|$ex/$f.yaml")
done
cases+=("bench/scenes/goodman-toppling-seed-steps.yaml (the seed's static steps)|$root/bench/scenes/goodman-toppling-seed-steps.yaml")
for phi in 20 40; do
  cases+=("sliding block, static, dt 0.01 s, friction $phi°|$(variant slide$phi "$ex/sliding-block.yaml" \
    "s/type: dynamic/type: static/; s/dt: 0.001 /dt: 0.01 /; s/friction_angle: 20,/friction_angle: $phi,/")")
done
noc='s/^    law: {name: burgers.*/    shear_stiffness: 1.0e8/; s/friction_angle: 50/friction_angle: 45/; s/duration: 60 /duration: 2 /'
cases+=("Goodman slope without creep, base 45°, 2 d, g2 6.25e-5, dt 1/32 d|$(variant g4 "$root/bench/scenes/goodman-toppling-seed-steps.yaml" \
  "$noc; s/^  dt: .*/  dt: 0.03125/; s/^analysis:/analysis:\n  max_displacement_ratio: 6.25e-5/")")
cases+=("Goodman slope without creep, base 45°, 2 d, g2 1.25e-4, dt 1/16 d|$(variant g3 "$root/bench/scenes/goodman-toppling-seed-steps.yaml" \
  "$noc; s/^  dt: .*/  dt: 0.0625/; s/^analysis:/analysis:\n  max_displacement_ratio: 1.25e-4/")")
for dt in 0.01 0.0001; do
  cases+=("bench/scenes/stepped-toppling.yaml (stands 5° above its limit), static, 2 s, dt $dt s|$(variant st$dt \
    "$root/bench/scenes/stepped-toppling.yaml" "s/type: dynamic/type: static/; s/^  duration: .*/  duration: 2/; s/^  dt: .*/  dt: $dt/")")
done
cases+=("examples/goodman-toppling-creep.yaml at dt 1/8 d|$(variant gc8 "$ex/goodman-toppling-creep.yaml" "s/^  dt: .*/  dt: 0.125/")")
for dt in 0.25 0.0625; do
  cases+=("examples/goodman-toppling-creep.yaml without its settling stage, dt $dt d|$(variant gcu$dt \
    "$ex/goodman-toppling-creep.yaml" "s/^  dt: .*/  dt: $dt/; /^  settle:/d")")
done
{
  echo "| scene | inertia share [%] | mechanism steps / steps | first – last [time] |"
  echo "|---|---:|---:|---|"
  k=0
  for c in "${cases[@]}"; do
    name="${c%%|*}" file="${c#*|}"
    out="$work/out$((k++))"
    "$build/apps/rheodda" run "$file" -o "$out" >/dev/null 2>&1
    /usr/bin/python3 - "$out/summary.json" "$name" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
m = s["static_mechanism"]
when = "–" if m["first_time"] is None else f'{m["first_time"]:.3g} – {m["last_time"]:.3g} {s["units"]["time"]}'
print(f'| {sys.argv[2]} | {100 * m["inertia_share"]:.3g} | {m["steps"]} / {s["steps"]} | {when} |')
PY
  done
} >"$work/table.md"
cat "$work/table.md"
"$root/scripts/splice-doc.sh" "$root/docs/notes/dynamic-stages.md" static-mechanisms "$work/table.md"
