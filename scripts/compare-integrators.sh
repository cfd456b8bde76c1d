#!/usr/bin/env bash
# The shipped examples with dynamic steps run by each integrator (issue 51 item 5): as
# shipped (the implicit step) and with `integrator: explicit` added to their `analysis:`
# map (docs/reference/explicit-step.md), one thread each, and a Markdown table of their CPU
# seconds (user + system, /usr/bin/time), steps, each measurement point's displacement
# magnitude √(u² + v²) at the end by each integrator, the relative difference
# |d_explicit − d_implicit| / d_implicit, and the example's refinement tolerance (5 %:
# `rheodda check --refine`'s default, at which each example's row of the refinement table of
# docs/guide/choosing-step-controls.md is judged) with whether the difference is within it.
# Where it is not, the explicit run is repeated with `explicit_safety: 0.4` (half the default
# cycle) and its difference shown: whether the explicit answer is converged in its cycle.
# An example whose full run costs too long is run shortened (analysis keys replaced in a
# copy, both integrators on the same copy; the table says so); a run is stopped after
# 300 s of CPU.
# Puts the table into docs/notes/integrator-comparison.md between the
# integrator-comparison markers. About 10 min of CPU on one core (measured 2026-11-29).
# Usage: scripts/compare-integrators.sh   (uses $RHEODDA_BUILD_DIR or build/)
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"  # strict mode; root, build, work (removed at exit)
ensure_built rheodda
# example | analysis keys replaced in a shortened copy ("" = as shipped) | refinement tolerance [%]
examples=(
  "examples/sliding-block.yaml||5"
  "examples/excavation-stages.yaml||5"
  "examples/goodman-toppling.yaml||5"
  "examples/rockmass/tunnel.yaml||5"
  "examples/rockmass/jointed-slope.yaml||5"
)
cpu_limit=300  # s of CPU: a run that needs more is stopped (SIGXCPU) and the table says so
run() {  # run SCENE OUT: one thread, CPU seconds into OUT.cpu
  ( ulimit -t "$cpu_limit"
    OMP_NUM_THREADS=1 /usr/bin/time -f "%U %S" -o "$2.cpu" "$build/apps/rheodda" run "$1" -o "$2" \
      >"$2.log" 2>&1 ) || true
}
i=0
for e in "${examples[@]}"; do
  IFS='|' read -r scene duration tolerance <<<"$e"
  i=$((i + 1))
  grep -qx 'analysis:' "$root/$scene" || { echo "$scene: no block-style 'analysis:' line" >&2; exit 1; }
  base="$work/$i.yaml"
  cp "$root/$scene" "$base"
  IFS=',' read -r -a keys <<<"$duration"
  for kv in "${keys[@]}"; do  # KEY=VALUE: `  KEY:` of analysis, settle.KEY in the settle map
    k="${kv%%=*}" v="${kv#*=}"
    if [[ "$k" == settle.* ]]; then
      sed -i "/^  settle:/,/}/s/\([{ ]\)${k#settle.}: [0-9.e+-]*/\1${k#settle.}: $v/" "$base"
    else
      sed -i "s/^  $k: [0-9.e+-]*/  $k: $v/" "$base"
    fi
  done
  sed "s/^analysis:/analysis:\n  integrator: explicit/" "$base" >"$work/$i-explicit.yaml"
  sed "s/^analysis:/analysis:\n  integrator: explicit\n  explicit_safety: 0.4/" "$base" >"$work/$i-explicit-0.4.yaml"
  run "$base" "$work/$i-implicit"
  run "$work/$i-explicit.yaml" "$work/$i-explicit"
  echo "$scene|$duration|$tolerance|$work/$i" >>"$work/list"
  echo "$scene: CPU implicit $(cat "$work/$i-implicit.cpu") s, explicit $(cat "$work/$i-explicit.cpu") s (user, system)" >&2
done
# The table; where an example's difference is beyond its tolerance, the explicit run at
# explicit_safety 0.4 (run from here, then the table made again with it).
table() {
/usr/bin/python3 - "$work/list" "$work/beyond" "$cpu_limit" <<'PY'
import json, math, os, sys

def result(out):
    """status, steps, CPU s, {point: |d| at the end}, time at the end, length and time units, dynamic stages"""
    cpu = sum(float(x) for x in open(out + ".cpu").read().split()[-2:]) if os.path.exists(out + ".cpu") else math.nan
    stopped = os.path.exists(out + ".cpu") and "signal" in open(out + ".cpu").read()
    try:
        s = json.load(open(os.path.join(out, "summary.json")))
    except OSError:
        s = {"status": "failed"}
    if stopped or s["status"] != "completed":
        return ("stopped at the CPU limit" if stopped else s["status"]), 0, cpu, {}, math.nan, "", "", 0
    lines = [l for l in open(os.path.join(out, "history.csv")) if not l.startswith("#")]
    head = lines[0].rstrip("\n").split(",")
    last = dict(zip(head, lines[-1].rstrip("\n").split(",")))
    d = {p: math.hypot(float(last[p + ".u"]), float(last[p + ".v"])) for p in s["measurement_points"]}
    ev = os.path.join(out, "events.csv")  # the dynamic stages, one row each
    stages = sum(1 for l in open(ev) if l.strip()) - 1 if os.path.exists(ev) else 0
    return s["status"], s["steps"], cpu, d, s["time"], s["units"]["length"], s["units"]["time"], stages

beyond = set()
print("| example | run to | CPU implicit / explicit [s] | steps implicit / explicit | dynamic stages implicit / explicit | point | displacement implicit | "
      "displacement explicit | difference | tolerance | within | difference at explicit_safety 0.4 |")
print("|---|---|---:|---:|---:|---|---:|---:|---:|---:|---|---:|")
for line in open(sys.argv[1]):
    scene, duration, tol, out = line.rstrip("\n").split("|")
    imp, exp = result(out + "-implicit"), result(out + "-explicit")
    half = result(out + "-explicit-0.4") if os.path.exists(out + "-explicit-0.4.cpu") else None
    if imp[0] != "completed" or exp[0] != "completed":
        status = lambda r: r[0] + (f" ({sys.argv[3]} s)" if r[0].startswith("stopped") else "")
        print(f"| {scene} | {'(shortened)' if duration else ''} | {imp[2]:.1f} / {exp[2]:.1f} | – | – | – | {status(imp)} | "
              f"{status(exp)} | – | – | {tol} % | – | – |")
        continue
    unit, tunit = imp[5], imp[6]
    runto = f"{imp[4]:.6g} {tunit}" + (" (shortened)" if duration else "")
    for k, p in enumerate(imp[3]):
        di, de = imp[3][p], exp[3][p]
        diff = abs(de - di) / di if di > 0 else math.inf
        within = "yes" if diff <= float(tol) / 100 else "**no**"
        if within != "yes":
            beyond.add(out)
        h = "–"
        if half is not None and half[0] == "completed":
            h = f"{100 * abs(half[3][p] - di) / di:.2g} % ({half[2]:.0f} s CPU)"
        elif half is not None:
            h = half[0]
        first = k == 0
        print(f"| {scene if first else ''} | {runto if first else ''} | "
              f"{f'{imp[2]:.1f} / {exp[2]:.1f}' if first else ''} | {f'{imp[1]} / {exp[1]}' if first else ''} | "
              f"{f'{imp[7]} / {exp[7]}' if first else ''} | "
              f"{p} | {di:.6g} {unit} | {de:.6g} {unit} | {100 * diff:.2g} % | {tol} % | {within} | {h} |")
open(sys.argv[2], "w").write("".join(b + "\n" for b in sorted(beyond)))
PY
}
table >"$work/table.md"
# Reruns at explicit_safety 0.4 for the examples with a row beyond tolerance.
while read -r out; do
  run "$out-explicit-0.4.yaml" "$out-explicit-0.4"
  echo "$out: explicit_safety 0.4, CPU $(cat "$out-explicit-0.4.cpu") s" >&2
done <"$work/beyond"
table >"$work/table.md"
cat "$work/table.md"
"$root/scripts/splice-doc.sh" "$root/docs/notes/integrator-comparison.md" integrator-comparison "$work/table.md"
