#!/usr/bin/env bash
# The benchmarks of docs/performance.md, "Rock masses that run": the generated
# slope with every joint set cohesionless and one set oblique
# (bench/scenes/jointed-slope-cohesionless.yaml) scaled to about 1e3 blocks, as
# shipped and with every static step control halved (its convergence check:
# the toe's displacement), the generated tunnel (examples/rockmass/tunnel.yaml)
# at about 1e3 blocks, each 100 days of creep on one core
# (bench/rockmass_bench.cpp). Prints the figures and splices a Markdown table
# between the rock-masses-run markers of docs/performance.md.
#
#   scripts/bench-rock-masses.sh                  # about 1e3 blocks; up to 3 x MAX_WALL
#   MAX_WALL=1800 scripts/bench-rock-masses.sh    # each run stops after this many seconds (default 1200)
#   LARGE=1 scripts/bench-rock-masses.sh          # and the slope at about 1e4 blocks (up to 2 h)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/build.sh" >/dev/null
bench="$root/build/bench/rockmass_bench"
max="${MAX_WALL:-1200}"
slope="$root/bench/scenes/jointed-slope-cohesionless.yaml"
log="$(mktemp)"
table="$(mktemp)"
trap 'rm -f "$log" "$table"' EXIT
run() { "$bench" --no-generation "$@" | tee -a "$log"; }
run --scene "$slope" --creep 1000 --max-wall "$max"
run --scene "$slope" --creep 1000 --max-wall "$max" --halve
run --example tunnel --creep 1000 --max-wall "$max"
if [ -n "${LARGE:-}" ]; then run --scene "$slope" --creep 10000 --max-wall 7200; fi
python3 - "$log" >"$table" <<'PY'
import re, sys
row = re.compile(r"^creep: (?P<scene>[^,]*), lengths x [0-9.]+: (?P<blocks>\d+) blocks.*?(completed|stopped) at "
                 r"t = (?P<t>\S+) of (?P<end>\S+) d: (?P<steps>\d+) steps, (?P<cuts>\d+) cuts.*?CPU (?P<cpu>[0-9.]+) s"
                 r".*dynamic stages: (?P<stages>[^;]*); first measurement point displaced (?P<disp>\S+)$")
print("| scene | blocks | reached [d] | steps | cuts | CPU [s] | dynamic stages | first measurement point [m] | target |")
print("|---|---:|---:|---:|---:|---:|---|---:|---|")
for line in open(sys.argv[1]):
    m = row.match(line.strip())
    if not m:
        continue
    blocks = int(m["blocks"])
    if "halved" in m["scene"]:
        target = "toe within 5 % of the shipped controls"
    elif "tunnel" in m["scene"]:
        target = "100 d in <= 300 s"
    else:
        target = "100 d in <= 7200 s" if blocks > 5000 else "100 d in <= 600 s"
    print(f"| {m['scene']} | {blocks} | {float(m['t']):.4g} of {m['end']} | {m['steps']} | {m['cuts']} | "
          f"{m['cpu']} | {m['stages']} | {float(m['disp']):.4g} | {target} |")
PY
cat "$table"
"$root/scripts/splice-doc.sh" "$root/docs/performance.md" rock-masses-run "$table"
