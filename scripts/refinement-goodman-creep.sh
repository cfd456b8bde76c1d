#!/usr/bin/env bash
# Step-control refinement of the seed's Goodman slope with its Burgers creep
# (bench/scenes/goodman-toppling-seed-steps.yaml, base 50 deg, static): blocks 1 and 10 at 1,
# 2, 5, 10 and 20 d with max_displacement_ratio (g2) and dt halved together from
# 0.0005 / 0.25 d (level L1 of scripts/refinement-goodman.sh) to 6.25e-5 /
# 1/32 d (L4), with each level's steps and the share of the work the static
# inertia term took (docs/reference/engine.md, "Mechanisms in static analysis"). Level L0
# (0.001 / 0.5 d) is left out: its steps fall into the static g2 trap (2.3
# million steps, 8 minutes for 20 d; docs/reference/contacts.md). Puts the table into
# docs/notes/step-controls.md between the refinement-goodman-creep markers. About
# 40 s on 2 cores.
# Usage: scripts/refinement-goodman-creep.sh   (uses $RHEODDA_BUILD_DIR or build/)
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"  # strict mode; root, build, work (removed at exit)
times=(1 2 5 10 20)
{
  echo "scene: $root/bench/scenes/goodman-toppling-seed-steps.yaml"
  echo "set: {analysis.duration: 20, analysis.output_interval: 1}"
  echo "outputs: [block1_top.displacement, block10_top.displacement]"
  echo "times: [$(IFS=,; echo "${times[*]}")]"
  echo "cases:"
  for l in 1 2 3 4; do
    g2=$(awk -v l=$l 'BEGIN { printf "%.9g", 0.001 / 2^l }')
    dt=$(awk -v l=$l 'BEGIN { printf "%.9g", 0.5 / 2^l }')
    echo "  - {name: L$l, set: {analysis.max_displacement_ratio: $g2, analysis.dt: $dt}}"
  done
} >"$work/study.yaml"
"$build/apps/rheodda" study "$work/study.yaml" -o "$work/out" -j "$(nproc)" --no-plot >/dev/null 2>&1
/usr/bin/python3 - "$work/out/study.csv" "${times[@]}" >"$work/table.md" <<'PY'
import csv, sys
rows = {r["case"]: r for r in csv.DictReader(open(sys.argv[1]))}
times = sys.argv[2:]
levels = ["L1", "L2", "L3", "L4"]
print("| block | t [d] | " + " | ".join(f"{l} [m]" for l in levels) + " | L3 vs L4 |")
print("|---|---:|" + "---:|" * len(levels) + "---:|")
for b in ("block1", "block10"):
    for t in times:
        v = [float(rows[l][f"{b}_top.displacement@{t}"]) for l in levels]
        print(f"| {b} | {t} | " + " | ".join(f"{x:.3f}" for x in v) + f" | {100 * abs(v[2] - v[3]) / v[3]:.1f} % |")
print("| | g2 / Δt [d] | " + " | ".join(f"{0.001 / 2**k:.3g} / {0.5 / 2**k:.3g}" for k in range(1, 5)) + " | |")
print("| | steps | " + " | ".join(rows[l]["steps"] for l in levels) + " | |")
print("| | inertia share | " + " | ".join(f"{float(rows[l]['inertia_share']):.3f}" for l in levels) + " | |")
PY
cat "$work/table.md"
"$root/scripts/splice-doc.sh" "$root/docs/notes/step-controls.md" refinement-goodman-creep "$work/table.md"
