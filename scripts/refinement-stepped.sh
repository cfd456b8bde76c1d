#!/usr/bin/env bash
# Step-size study of stick and slip on a slope that stands (docs/notes/contact-solves.md,
# "Stick and slip"): bench/scenes/stepped-toppling.yaml - the Goodman & Bray
# toppling slope at friction 5 deg above its limit-equilibrium angle, dynamic,
# 8 s - at dt = 5, 2, 1, 0.5, 0.25, 0.1 and 0.05 ms, with Shi's rule
# (analysis.stick_keeps_force: false, the static default) and with elastic-plastic
# joints (stick_keeps_force: true, the dynamic default), and the latter with
# plastic impacts and damped blocks (joint set restitution 0, material
# damping_ratio 1; docs/reference/contacts.md, "Contact damping"). Prints a Markdown table of the largest
# displacement of the 16 block tops at 8 s [mm], with the run's cuts of dt and
# its energy-balance residual, and puts it between the refinement-stepped
# markers of docs/notes/contact-solves.md. About 3 min on 2 cores.
# Usage: scripts/refinement-stepped.sh   (uses $RHEODDA_BUILD_DIR or build/)
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"  # strict mode; root, build, work (removed at exit)
dts=(0.005 0.002 0.001 0.0005 0.00025 0.0001 0.00005)
{
  echo "scene: $root/bench/scenes/stepped-toppling.yaml"
  printf "outputs: ["
  for b in $(seq 1 16); do printf "b%d_top.displacement%s" "$b" "$([[ $b -lt 16 ]] && echo ", ")"; done
  echo "]"
  echo "times: [8]"
  echo "cases:"
  for stick in false true; do
    for dt in "${dts[@]}"; do
      echo "  - {name: ${stick}_$dt, set: {analysis.dt: $dt, analysis.stick_keeps_force: $stick}}"
    done
  done
  for dt in "${dts[@]}"; do  # the dynamic default with plastic impacts and damped blocks
    echo "  - {name: damped_$dt, set: {analysis.dt: $dt, joint_sets.joint.restitution: 0, materials.rock.damping_ratio: 1}}"
  done
} >"$work/study.yaml"
"$build/apps/rheodda" study "$work/study.yaml" -o "$work/out" -j "$(nproc)" --no-plot >/dev/null 2>&1 || true
for stick in false true damped; do
  for dt in "${dts[@]}"; do
    summary="$work/out/cases/${stick}_$dt/summary.json"
    /usr/bin/python3 - "$summary" "$stick" "$dt" >>"$work/rows.txt" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
print(sys.argv[2], sys.argv[3], s["status"], s["cuts"], s["energy"]["max_relative_residual"])
PY
  done
done
awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i ~ /_top.displacement@8$/) top[i] = 1; next }
  { m = 0; for (i in top) if ($i != "" && $i + 0 > m) m = $i + 0; split($1, a, "_"); d[a[1], a[2]] = m; st[a[1], a[2]] = $2 }
  END { for (k in d) { split(k, p, SUBSEP); print p[1], p[2], d[k], st[k] } }' "$work/out/study.csv" >"$work/disp.txt"
/usr/bin/python3 - "$work/rows.txt" "$work/disp.txt" "${dts[@]}" >"$work/table.md" <<'PY'
import sys
rows = {}
for line in open(sys.argv[1]):
    stick, dt, status, cuts, res = line.split()
    rows[stick, dt] = (status, int(cuts), float(res))
disp = {}
for line in open(sys.argv[2]):
    stick, dt, d, status = line.split()
    disp[stick, dt] = float(d)
dts = sys.argv[3:]
print("| joint rule | quantity | " + " | ".join(f"{float(d) * 1e3:g} ms" for d in dts) + " |")
print("|---|---|" + "---:|" * len(dts))
for stick, name in (("false", "Shi's (`stick_keeps_force: false`)"), ("true", "`stick_keeps_force: true` (dynamic default)"),
                    ("damped", "dynamic default, `restitution: 0`, `damping_ratio: 1`")):
    cells = []
    for d in dts:
        status = rows[stick, d][0]
        # A run that stops early (the travel guard: a block moved 10 x the model
        # size) has no value at 8 s: say so.
        cells.append(f"{disp[stick, d] * 1e3:.1f}" if status == "completed" else status)
    print(f"| {name} | largest displacement at 8 s [mm] | " + " | ".join(cells) + " |")
    print("| | cuts of Δt | " + " | ".join(str(rows[stick, d][1]) for d in dts) + " |")
    print("| | largest energy residual / work | " + " | ".join(f"{rows[stick, d][2]:.1e}" for d in dts) + " |")
PY
cat "$work/table.md"
"$root/scripts/splice-doc.sh" "$root/docs/notes/contact-solves.md" refinement-stepped "$work/table.md"
