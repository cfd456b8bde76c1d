#!/usr/bin/env bash
# Step refinement of examples/goodman-toppling-creep.yaml as shipped (with its
# settling stage, analysis.settle) and without the stage: blocks 1 and 10 at
# 100 d for dt = 1/2 ... 1/128 d, with each run's steps and static inertia
# share (docs/reference/engine.md, "Mechanisms in static analysis"). Puts the table into
# docs/notes/step-controls.md between the refinement-toppling-creep markers. About
# 10 s on 2 cores.
# Usage: scripts/refinement-toppling-creep.sh   (uses $RHEODDA_BUILD_DIR or build/)
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"  # strict mode; root, build, work (removed at exit)
dts=(0.5 0.25 0.125 0.0625 0.03125 0.015625 0.0078125)
{
  echo "scene: $root/examples/goodman-toppling-creep.yaml"
  echo "outputs: [block1_top.displacement, block10_top.displacement]"
  echo "times: [100]"
  echo "cases:"
  for dt in "${dts[@]}"; do
    echo "  - {name: settled_$dt, set: {analysis.dt: $dt}}"
    echo "  - {name: unsettled_$dt, set: {analysis.dt: $dt, analysis.settle: ~}}"
  done
} >"$work/study.yaml"
"$build/apps/rheodda" study "$work/study.yaml" -o "$work/out" -j "$(nproc)" --no-plot >/dev/null 2>&1
/usr/bin/python3 - "$work/out/study.csv" "${dts[@]}" >"$work/table.md" <<'PY'
import csv, sys
from fractions import Fraction
rows = {r["case"]: r for r in csv.DictReader(open(sys.argv[1]))}
dts = sys.argv[2:]
print("| dt [d] | block 1, settled [m] | block 10, settled [m] | steps | inertia share | block 10, no settling stage [m] | inertia share |")
print("|---|---:|---:|---:|---:|---:|---:|")
for dt in dts:
    s, u = rows[f"settled_{dt}"], rows[f"unsettled_{dt}"]
    print(f"| {Fraction(float(dt)).limit_denominator()} | {float(s['block1_top.displacement@100']):.5f} | "
          f"{float(s['block10_top.displacement@100']):.5f} | {s['steps']} | {float(s['inertia_share']):.2g} | "
          f"{float(u['block10_top.displacement@100']):.3f} | {float(u['inertia_share']):.2g} |")
PY
cat "$work/table.md"
"$root/scripts/splice-doc.sh" "$root/docs/notes/step-controls.md" refinement-toppling-creep "$work/table.md"
