#!/usr/bin/env bash
# Regenerates the figures of docs/notes/rock-mass-steps.md: where the steps of
# the generated rock masses go.
#   1. how the 55-block cohesionless slope (bench/scenes/jointed-slope-cohesionless.yaml)
#      settles: its dynamic stage ended at rest by rest_tolerance 1e-3, 1e-4,
#      1e-5, or run to its full 20 s; and with settle dt 1, 5, 10 ms (100 d each:
#      settling steps, all steps, CPU, toe displacement at 100 d);
#   2. the cut attempts of the slope at about 1e3 blocks and of the tunnel at
#      about 1e3 blocks, by class (bench/scene_trace.cpp --diagnose) over the
#      first DIAG_STEPS steps (default 600).
# Prints Markdown and splices it between the measured markers of that note;
# about 15 min on 2 cores.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/build.sh" >/dev/null
bin="$root/build"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
slope="$root/bench/scenes/jointed-slope-cohesionless.yaml"

# A variant of the slope's settle line: rest_tolerance and dt replaced.
variant() {  # $1 = out file, $2 = rest_tolerance ("full": none, the stage 20 s long), $3 = settle dt [d]
  python3 - "$slope" "$1" "$2" "$3" <<'PY'
import re, sys
src, dst, rest, dt = sys.argv[1:]
t = open(src).read()
t = re.sub(r"(settle: \{type: dynamic, dt: )[0-9.eE+-]+", r"\g<1>" + dt, t)
if rest == "full":
    t = t.replace("rest_tolerance: 1.0e-5,", "until: 2.3148148e-4,")
else:
    t = t.replace("rest_tolerance: 1.0e-5,", "rest_tolerance: " + rest + ",")
open(dst, "w").write(t)
PY
}
# One run: prints "settling steps | steps | CPU s | toe [mm]".
measure() {  # $1 = scene file
  local out="$work/out-$(basename "$1" .yaml)"
  /usr/bin/time -f "%U %S" -o "$work/time" "$bin/apps/rheodda" run "$1" -o "$out" >/dev/null 2>&1
  python3 - "$out" "$work/time" <<'PY'
import csv, math, sys
out, tf = sys.argv[1:]
rows = [r for r in csv.reader(l for l in open(out + "/history.csv") if not l.startswith("#"))]
h, last = rows[0], rows[-1]
u, v = float(last[h.index("toe.u")]), float(last[h.index("toe.v")])
ev = list(csv.DictReader(open(out + "/events.csv")))
settle = sum(int(e["steps"]) for e in ev if e["kind"] == "settling")
mech = sum(1 for e in ev if e["kind"] != "settling")
cpu = sum(float(x) for x in open(tf).read().split())
print(f"{settle} | {mech} | {last[h.index('step')]} | {cpu:.1f} | {1e3 * math.hypot(u, v):.2f} |")
PY
}

{
echo "### The 55-block slope: when its stage ends"
echo
echo "| settling stage | settle dt [ms] | settling steps | mechanism stages | steps | CPU [s] | toe at 100 d [mm] |"
echo "|---|---:|---:|---:|---:|---:|---:|"
for rest in 1e-3 1e-4 1e-5 full; do
  variant "$work/rest-$rest.yaml" "$rest" 1.1574074e-8
  label="at rest, rest_tolerance $rest"; [ "$rest" = full ] && label="full 20 s"
  echo "| $label | 1 | $(measure "$work/rest-$rest.yaml")"
done
for ms in 5 10; do
  dt=$(python3 -c "print(f'{$ms * 1e-3 / 86400:.8g}')")
  variant "$work/dt-$ms.yaml" 1e-5 "$dt"
  echo "| at rest, rest_tolerance 1e-5 | $ms | $(measure "$work/dt-$ms.yaml")"
done
echo
echo "### Cut attempts by class (scene_trace --diagnose, first ${DIAG_STEPS:-600} steps)"
"$bin/bench/rockmass_bench" --no-generation --scene "$slope" --creep 1000 --write-scenes "$work" --max-wall 0 >/dev/null
"$bin/bench/rockmass_bench" --no-generation --example tunnel --creep 1000 --write-scenes "$work" --max-wall 0 >/dev/null
for scene in "$slope" "$work/jointed-slope-cohesionless-1000.yaml" "$work/tunnel-1000.yaml"; do
  echo
  echo "$(basename "$scene"):"
  echo '```'
  "$bin/bench/scene_trace" "$scene" --steps "${DIAG_STEPS:-600}" --diagnose | grep '^#'
  echo '```'
done
} | tee "$work/measured.md"
"$root/scripts/splice-doc.sh" "$root/docs/notes/rock-mass-steps.md" measured "$work/measured.md"
