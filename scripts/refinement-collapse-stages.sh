#!/usr/bin/env bash
# The seed's slope with its Burgers creep (bench/scenes/goodman-toppling-seed-steps.yaml: base
# 50 deg, planes 25 deg, static) run for 100 d with collapse stages
# (analysis.settle with type dynamic and collapse_dt; docs/reference/engine.md, "Collapse
# stages"): the columns settle in a 20 s dynamic stage (plastic impacts, damped
# blocks, dt 1 ms), and every later collapse is located to within collapse_dt
# and taken dynamically. `rheodda check --refine=9` with the stages' dynamic
# steps held at 1 ms (--hold settle.dt,settle.max_displacement_ratio: their own
# refinement converges to 0.05 %, docs/notes/contact-solves.md "The same slope settled
# dynamically") and the static controls halved level by level from dt 1/16 d,
# g2 0.0005, collapse_dt 5e-5 d down to dt 1/4096 d. Puts a table (block 10 at
# 1, 5, 10, 20, 50 and 100 d, the level-to-level changes, the stages, steps,
# wall time) and check's verdict into docs/reference/engine.md between the
# refinement-collapse-stages markers, and into docs/notes/step-controls.md ("The seed's
# slope itself, refined"). About 10 min on 2 cores.
# Usage: scripts/refinement-collapse-stages.sh   (uses $RHEODDA_BUILD_DIR or build/)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${RHEODDA_BUILD_DIR:-$root/build}"
work="$(mktemp -d)"
scene="$root/bench/scenes/.collapse-stages.yaml"  # beside the original (its relative paths)
trap 'rm -rf "$work" "$scene"' EXIT
/usr/bin/python3 - "$root/bench/scenes/goodman-toppling-seed-steps.yaml" "$scene" <<'PY'
import re, sys
s = open(sys.argv[1]).read()
def sub(pattern, repl):
    global s
    s, n = re.subn(pattern, repl, s, count=1, flags=re.M)
    assert n == 1, pattern
sub(r"^  duration: .*$", "  duration: 100          # d")
sub(r"^  dt: .*$", "  dt: 0.0625             # d\n"
    "  max_displacement_ratio: 0.0005\n"
    "  settle: {type: dynamic, until: 2.3148148e-4, dt: 1.1574074e-8, max_displacement_ratio: 0.00025, "
    "collapse_dt: 5.0e-5}   # 20 s at 1 ms")
sub(r"^(    poisson_ratio: .*)$", r"\1\n    damping_ratio: 1")
for joint in ("base", "anti_toppling"):
    sub(rf"^(  {joint}:.*\n    friction_angle: .*)$", r"\1\n    restitution: 0")
open(sys.argv[2], "w").write(s)
PY
"$build/apps/rheodda" check "$scene" --refine=9 --hold settle.dt,settle.max_displacement_ratio \
  -j "$(nproc)" -o "$work/out" >"$work/log" 2>&1 || true
/usr/bin/python3 - "$work/out" >"$work/table.md" <<'PY'
import csv, json, math, os, sys
out = sys.argv[1]
ref = json.load(open(os.path.join(out, "refinement.json")))
days = [1, 5, 10, 20, 50, 100]
rows = []
for lev in ref["levels"]:
    case = os.path.join(out, "cases", lev["name"])
    f = open(os.path.join(case, "history.csv")); f.readline()
    hist = [(float(r["time"]), math.hypot(float(r["block10_top.u"]), float(r["block10_top.v"]))) for r in csv.DictReader(f)]
    def at(t):
        return min(hist, key=lambda h: abs(h[0] - t))[1]
    summ = json.load(open(os.path.join(case, "summary.json")))
    stages = summ["static_mechanism"]["collapse_stages"]
    rows.append((lev, [at(t) for t in days], stages, summ["steps"], lev.get("wall_seconds")))
print("| level | dt [d] | collapse_dt [d] | " + " | ".join(f"block 10 at {t} d [m]" for t in days) +
      " | collapse stages | steps | wall [s] |")
print("|---|---:|---:|" + "---:|" * len(days) + "---:|---:|---:|")
prev = None
for lev, vals, stages, steps, wall in rows:
    controls = dict(c.split(" ", 1) for c in lev["controls"].split(", "))
    dt = controls.get("dt", "").split()[0]
    cdt = controls.get("collapse_dt", "").split()[0]
    cells = []
    for k, v in enumerate(vals):
        change = "" if prev is None else f" ({100 * (v - prev[k]) / v:+.1f} %)"
        cells.append(f"{v:.3f}{change}")
    wall_text = f"{wall:.0f}" if wall is not None else "–"
    print(f"| {lev['name']} | {dt} | {cdt} | " + " | ".join(cells) + f" | {len(stages)} | {steps} | {wall_text} |")
    prev = vals
print()
print(f"`rheodda check --refine=9 --hold settle.dt,settle.max_displacement_ratio` verdict: {ref['verdict']}"
      + (f" ({ref['message']})" if ref.get("message") else "") + ".")
PY
cat "$work/table.md"
"$root/scripts/splice-doc.sh" "$root/docs/notes/dynamic-stages.md" refinement-collapse-stages "$work/table.md"
"$root/scripts/splice-doc.sh" "$root/docs/notes/step-controls.md" refinement-collapse-stages "$work/table.md"
