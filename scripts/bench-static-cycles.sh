#!/usr/bin/env bash
# Static steps by cycles against the implicit static step (docs/notes/explicit-step.md,
# "Static steps by cycles"): the same creep scenes run with their static steps implicit and
# taken by explicit cycles at several unbalanced-force ratios (analysis.static_force_ratio,
# docs/reference/explicit-step.md), one thread each. Prints a Markdown table: CPU seconds
# (user + system of `rheodda run`), steps, cycles per static step, and the measurement
# points' displacement at the end with its difference from the implicit answer, into
# docs/notes/explicit-step.md between the static-cycles-table markers.
#
#   scripts/bench-static-cycles.sh                 # the Goodman creep slope (16 blocks), 5 minutes
#   TUNNEL=1 scripts/bench-static-cycles.sh        # and the 945-block tunnel's first DAYS days
#   DAYS=5 TUNNEL=1 scripts/bench-static-cycles.sh
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
ensure_built rheodda rockmass_bench
rheodda="$build/apps/rheodda"
ratios="${RATIOS:-1e-4 1e-5 1e-6}"
days="${DAYS:-10}"

# variant SCENE OUT KEYS...: SCENE with KEYS (lines of YAML) added to its analysis map.
variant() {
  local scene="$1" out="$2"
  shift 2
  awk -v keys="$(printf '%s\n' "$@")" '{print} /^analysis:/ {n = split(keys, k, "\n"); for (i = 1; i <= n; ++i) if (k[i] != "") print "  " k[i]}' \
    "$scene" >"$out"
}

# measure NAME SCENE: one run; prints its table row.
implicit_disp=""
measure() {
  local name="$1" scene="$2"
  shift 2
  local out="$work/out-$name"
  local start end
  /usr/bin/time -f '%U %S' -o "$work/time.txt" env OMP_NUM_THREADS=1 "$rheodda" run "$scene" -o "$out" --quiet "$@" \
    >/dev/null 2>"$work/err.txt" || { echo "| $name | failed: $(tail -n 1 "$work/err.txt") |"; return; }
  local cpu
  cpu=$(awk '{printf "%.1f", $1 + $2}' "$work/time.txt")
  /usr/bin/python3 - "$out" "$name" "$cpu" "$implicit_disp" <<'PY'
import csv, json, sys
out, name, cpu, ref = sys.argv[1:5]
summary = json.load(open(f"{out}/summary.json"))
rows = list(csv.DictReader(line for line in open(f"{out}/history.csv") if not line.startswith("#")))
last = rows[-1]
points = summary.get("measurement_points") or []
disp = [((float(last[f"{p}.u"]) ** 2 + float(last[f"{p}.v"]) ** 2) ** 0.5) for p in points]
steps = summary["steps"]
# history.csv's iterations: a static step by cycles gives its cycles there (the rows at the output times)
its = sorted(int(r["iterations"]) for r in rows if int(r["step"]) > 0)
cycles = its[len(its) // 2] if its else None
shown = " / ".join(f"{d:.6g}" for d in disp)
diff = "–"
if ref:
    r = [float(x) for x in ref.split(",")]
    diff = " / ".join(f"{abs(d - q) / q:.2e}" for d, q in zip(disp, r))
print(f"| {name} | {float(last['time']):g} | {steps} | {cpu} | {cycles if cycles is not None else '–'} | {shown} | {diff} |")
open(f"{out}/disp.txt", "w").write(",".join(repr(d) for d in disp))
PY
  [[ "$name" == *implicit* ]] && implicit_disp=$(cat "$out/disp.txt")
  return 0
}

header() {
  printf '| run | reached | steps | CPU [s] | iterations or cycles per step (median at the output times) | measurement points'"'"' displacement [m] | relative difference from implicit |\n'
  printf '|---|---:|---:|---:|---:|---|---|\n'
}

{
echo "Goodman toppling slope with Burgers creep (examples/goodman-toppling-creep.yaml), 100 d:"
echo
header
slope="$root/examples/goodman-toppling-creep.yaml"
implicit_disp=""
measure "slope implicit" "$slope"
for r in $ratios; do
  variant "$slope" "$work/slope-$r.yaml" "integrator: explicit" "static_force_ratio: $r"
  measure "slope cycles $r" "$work/slope-$r.yaml"
done

if [[ -n "${TUNNEL:-}" ]]; then
  echo
  echo "Generated tunnel (examples/rockmass/tunnel.yaml, rockmass_bench --creep 1000), first $days d:"
  echo
  header
  "$build/bench/rockmass_bench" --example tunnel --creep 1000 --rest-tolerance 1e-5 --write-scenes "$work/tunnel" \
    --duration 0 >/dev/null 2>&1 || true
  tunnel="$work/tunnel-$days.yaml"
  sed "s/^  duration: .*/  duration: $days/" "$(ls "$work"/tunnel/*.yaml | head -n 1)" >"$tunnel"
  implicit_disp=""
  measure "tunnel implicit" "$tunnel"
  variant "$tunnel" "$work/tunnel-explicit.yaml" "integrator: explicit"
  measure "tunnel explicit stages, implicit static steps" "$work/tunnel-explicit.yaml"
  for r in $ratios; do
    variant "$tunnel" "$work/tunnel-$r.yaml" "integrator: explicit" "static_force_ratio: $r"
    measure "tunnel cycles $r" "$work/tunnel-$r.yaml"
  done
fi
} | tee "$work/table.md"
"$root/scripts/splice-doc.sh" "$root/docs/notes/explicit-step.md" static-cycles-table "$work/table.md"
