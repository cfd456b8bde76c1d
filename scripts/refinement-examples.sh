#!/usr/bin/env bash
# `rheodda check --refine` on every shipped example: each scene at its own step
# controls (L0) and with every step control halved, level by level, and the
# verdict (fine / coarse / not converged) with L0's error, the last two levels'
# difference, the largest static inertia share and, where a joint fails, the
# failure time of each level. Puts the table into docs/speed-accuracy.md between
# the refinement-examples markers. About 6 min on 2 cores (the Goodman slope's
# level L2 takes 600 000 steps, the rock-mass slope 1 min per level).
# Usage: scripts/refinement-examples.sh   (uses $RHEODDA_BUILD_DIR or build/)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${RHEODDA_BUILD_DIR:-$root/build}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
# example | refine options (levels, --until: before a joint fails, where that is the headline)
examples=(
  "shear-creep-test.yaml|--refine"
  "power-law-creep-test.yaml|--refine"
  "damage-creep-test.yaml|--refine --until 140"
  "damage-creep-test.yaml|--refine"
  "creeping-slope-failure.yaml|--refine --until 20"
  "creeping-slope-failure.yaml|--refine"
  "sliding-block.yaml|--refine"
  "goodman-toppling-creep.yaml|--refine=6"
  "goodman-toppling.yaml|--refine"
  "rockmass/tunnel.yaml|--refine"
  "rockmass/jointed-slope.yaml|--refine=3 --until 20"
)
i=0
for e in "${examples[@]}"; do
  scene="${e%%|*}" opts="${e#*|}"
  i=$((i + 1))
  # shellcheck disable=SC2086  # opts is a list of options
  "$build/apps/rheodda" check "$root/examples/$scene" $opts -j "$(nproc)" -o "$work/$i" >/dev/null 2>&1 || true
  echo "$scene|$opts|$work/$i" >>"$work/list"
done
/usr/bin/python3 - "$work/list" >"$work/table.md" <<'PY'
import json, sys, os
print("| example | `check` options | levels | verdict | L0 error | last two levels | largest inertia share | steps L0 … last | failure time per level |")
print("|---|---|---:|---|---:|---:|---:|---|---|")
for line in open(sys.argv[1]):
    scene, opts, out = line.rstrip("\n").split("|")
    j = json.load(open(os.path.join(out, "refinement.json")))
    judged = [q for q in j["quantities"] if q["judged"]]
    last = max((q["differences"][-1] for q in judged), default=0.0)
    steps = " … ".join(str(l["steps"]) for l in (j["levels"][0], j["levels"][-1]))
    failures = []
    for l in j["levels"]:
        s = json.load(open(os.path.join(out, "cases", l["name"], "summary.json")))
        times = [c["first_failure_time"] for c in s.get("creep", {}).values() if c.get("first_failure_time") is not None]
        if times:
            failures.append(f"{min(times):.4f}")
    share = j["largest_inertia_share"]
    print(f"| {scene} | `{opts}` | {len(j['levels'])} | {j['verdict']} | {100 * j['largest_error']:.2g} % | "
          f"{100 * last:.2g} % | {share:.2g} | {steps} | {', '.join(failures) if failures else '–'} |")
PY
cat "$work/table.md"
"$root/scripts/splice-doc.sh" "$root/docs/speed-accuracy.md" refinement-examples "$work/table.md"
