#!/usr/bin/env bash
# The benchmarks of docs/notes/performance.md, "Rock masses that run": the generated
# slope with every joint set cohesionless and one set oblique
# (bench/scenes/jointed-slope-cohesionless.yaml) scaled to about 1e3 blocks and
# the generated tunnel (examples/rockmass/tunnel.yaml, its settling stage ended
# at rest by rest_tolerance 1e-5) at about 1e3 blocks,
# 100 days of creep each, stopped after the issue's budget of CPU time (slope
# 600 s, tunnel 300 s); then the slope's convergence check: the first CHECK_DAYS
# days (default 100, the whole run, whose run as shipped is then the first one) with
# every static step control halved, the toe's displacement compared. One core each (bench/rockmass_bench.cpp, CPU
# time, so that a loaded machine gives the same figures). Prints the figures
# and splices a Markdown table between the rock-masses-run markers of
# docs/notes/performance.md.
#
#   scripts/bench-rock-masses.sh                  # about 1e3 blocks; about 15 CPU minutes
#   CHECK_DAYS=5 scripts/bench-rock-masses.sh     # the convergence check over the first 5 days
#   BUDGET=3 scripts/bench-rock-masses.sh         # budgets x 3 (how far the runs get beyond them)
#   LARGE=1 scripts/bench-rock-masses.sh          # and the slope at about 1e4 blocks (1 CPU hour)
# (uses $RHEODDA_BUILD_DIR or build/)
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"  # strict mode; root, build, work (removed at exit)
ensure_built rockmass_bench
bench="$build/bench/rockmass_bench"
budget="${BUDGET:-1}"
days="${CHECK_DAYS:-100}"
cpu() { python3 -c "print(int($1 * $budget))"; }
slope="$root/bench/scenes/jointed-slope-cohesionless.yaml"
log="$work/log"
table="$work/table"
run() { "$bench" --no-generation "$@" | tee -a "$log"; }
run --scene "$slope" --creep 1000 --max-cpu "$(cpu 600)"
run --example tunnel --creep 1000 --rest-tolerance 1e-5 --max-cpu "$(cpu 300)"
if [ -n "${LARGE:-}" ]; then run --scene "$slope" --creep 10000 --max-cpu "$(cpu 3600)"; fi
if [ "$days" != 100 ]; then run --scene "$slope" --creep 1000 --duration "$days" --max-cpu 36000; fi
run --scene "$slope" --creep 1000 --duration "$days" --max-cpu 36000 --halve
python3 - "$log" >"$table" <<'PY'
import re, sys
row = re.compile(r"^creep: (?P<scene>.*?), lengths x [0-9.]+: (?P<blocks>\d+) blocks.*?(completed|stopped) at "
                 r"t = (?P<t>\S+) of (?P<end>\S+) d: (?P<steps>\d+) steps, (?P<cuts>\d+) cuts.*?CPU (?P<cpu>[0-9.]+) s"
                 r".*dynamic stages: (?P<stages>[^;]*); first measurement point displaced (?P<disp>\S+)$")
print("| scene | blocks | reached [d] | steps | cuts | CPU [s] | dynamic stages | first measurement point [m] | target |")
print("|---|---:|---:|---:|---:|---:|---|---:|---|")
rows = [m for m in (row.match(line.strip()) for line in open(sys.argv[1])) if m]
for m in rows:
    blocks = int(m["blocks"])
    if "halved" in m["scene"]:
        # the same slope and days at the scene's own controls: the row it is checked against
        ref = next(r for r in rows if int(r["blocks"]) == blocks and r["end"] == m["end"] and "halved" not in r["scene"])
        apart = abs(float(m["disp"]) / float(ref["disp"]) - 1) * 100
        target = f"convergence check: toe within 5 % with the static controls halved ({apart:.2g} % apart at {m['end']} d)"
    elif float(m["end"]) < 100:
        target = "the convergence check's run at the scene's controls"
    elif "tunnel" in m["scene"]:
        target = "100 d in <= 300 s"
    else:
        target = "100 d in <= 3600 s" if blocks > 5000 else "100 d in <= 600 s"
    print(f"| {m['scene']} | {blocks} | {float(m['t']):.4g} of {m['end']} | {m['steps']} | {m['cuts']} | "
          f"{m['cpu']} | {m['stages']} | {float(m['disp']):.4g} | {target} |")
PY
cat "$table"
"$root/scripts/splice-doc.sh" "$root/docs/notes/performance.md" rock-masses-run "$table"
