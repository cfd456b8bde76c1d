#!/usr/bin/env bash
# `rheodda check --refine` on every shipped example: each scene at its own step
# controls (L0) and with every step control halved, level by level, and the
# verdict (fine / coarse / not converged) with L0's error, the last two levels'
# difference, the largest static inertia share and, where a joint fails, the
# failure time of each level. Puts the shipped examples' table into
# docs/guide/choosing-step-controls.md between the refinement-examples markers, and the
# bench scenes' and the examples' variants' into docs/notes/step-controls.md between the
# refinement-bench-scenes markers. About 25 min on 2 cores.
# Usage: scripts/refinement-examples.sh   (uses $RHEODDA_BUILD_DIR or build/)
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"  # strict mode; root, build, work (removed at exit)
# example | refine options (levels, --until: before a joint fails, where that is the headline)
# (paths from the repository's root: the shipped examples, then the bench scenes
# of issue "Steps that converge": the brick wall, the incline drop undamped and
# damped, the stepped slope)
examples=(
  "examples/shear-creep-test.yaml|--refine"
  "examples/power-law-creep-test.yaml|--refine"
  "examples/damage-creep-test.yaml|--refine --until 140"
  "examples/damage-creep-test.yaml|--refine"
  "examples/creeping-slope-failure.yaml|--refine --until 20"
  "examples/creeping-slope-failure.yaml|--refine"
  "examples/sliding-block.yaml|--refine"
  "examples/goodman-toppling-creep.yaml|--refine=6"
  "examples/goodman-toppling-creep.yaml|--refine=6|open_close_limit: 30"
  "examples/goodman-toppling.yaml|--refine=3 --hold settle.dt,settle.max_displacement_ratio"
  "examples/rockmass/tunnel.yaml|--refine"
  "examples/rockmass/jointed-slope.yaml|--refine=3 --hold settle.dt,settle.max_displacement_ratio"
  "bench/scenes/goodman-toppling-seed-steps.yaml|--refine"
  "bench/scenes/brick-wall.yaml|--refine=5"
  "bench/scenes/brick-wall.yaml|--refine=5|restitution: 0, damping_ratio: 1"
  "bench/scenes/brick-wall.yaml|--refine=6|restitution: 0, damping_ratio: 1, dt 3.125e-05, g2 1.25e-05"
  "bench/scenes/incline-drop.yaml|--refine=5"
  "bench/scenes/incline-drop-damped.yaml|--refine=5"
  "bench/scenes/stepped-toppling.yaml|--refine=5 --until 2"
  "bench/scenes/stepped-toppling.yaml|--refine=5 --until 2|restitution: 0, damping_ratio: 1"
)
i=0
for e in "${examples[@]}"; do
  IFS='|' read -r scene opts extra <<<"$e"
  i=$((i + 1))
  file="$root/$scene"
  if [[ -n "$extra" ]]; then  # a variant, in a copy beside the original
    file="$(dirname "$root/$scene")/.refine-variant-$i.yaml"
    if [[ "$extra" == "restitution: 0, damping_ratio: 1"* ]]; then
      # plastic impacts on every joint set, critically damped blocks (docs/reference/contacts.md, "Contact damping");
      # optionally with the scene's dt and g2 replaced (", dt DT, g2 G2": finer levels)
      dt_g2=()
      if [[ "$extra" =~ dt\ ([0-9.e-]+),\ g2\ ([0-9.e-]+) ]]; then
        dt_g2=(-e "s/^  dt: [0-9.e-]*/  dt: ${BASH_REMATCH[1]}/"
               -e "s/^  max_displacement_ratio: [0-9.e-]*/  max_displacement_ratio: ${BASH_REMATCH[2]}/")
      fi
      sed -e "s/^\(  [a-z_]*: {friction_angle: [0-9.]*\)/\1, restitution: 0/" \
          -e "s/^\(  [a-z_]*: {density: .*poisson_ratio: [0-9.]*\)/\1, damping_ratio: 1/" "${dt_g2[@]}" \
          "$root/$scene" >"$file"
    else  # one more analysis key
      sed "s/^analysis:/analysis:\n  $extra/" "$root/$scene" >"$file"
    fi
  fi
  # shellcheck disable=SC2086  # opts is a list of options
  "$build/apps/rheodda" check "$file" $opts -j "$(nproc)" -o "$work/$i" >/dev/null 2>&1 || true
  [[ -n "$extra" ]] && rm -f "$file"
  echo "$scene${extra:+ with $extra}|$opts|$work/$i" >>"$work/list"
done
table() {  # table LIST shipped|other: the rows of the shipped examples as they ship, or the others
/usr/bin/python3 - "$@" <<'PY'
import json, sys, os
print("| scene | `check` options | levels | verdict | L0 error | largest of the last two differences | largest inertia share | steps L0 … last | failure time per level |")
print("|---|---|---:|---|---:|---:|---:|---|---|")
for line in open(sys.argv[1]):
    scene, opts, out = line.rstrip("\n").split("|")
    if (scene.startswith("examples/") and " with " not in scene) != (sys.argv[2] == "shipped"):
        continue
    j = json.load(open(os.path.join(out, "refinement.json")))
    judged = [q for q in j["quantities"] if q["judged"]]
    last = max((d for q in judged for d in q["differences"][-2:]), default=0.0)
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
}
table "$work/list" shipped >"$work/table.md"
table "$work/list" other >"$work/bench.md"
cat "$work/table.md" "$work/bench.md"
"$root/scripts/splice-doc.sh" "$root/docs/guide/choosing-step-controls.md" refinement-examples "$work/table.md"
"$root/scripts/splice-doc.sh" "$root/docs/notes/step-controls.md" refinement-bench-scenes "$work/bench.md"
# The toppling example's levels in full (its refinement.txt, as `check` prints it).
n=$(grep -n '^examples/goodman-toppling-creep.yaml|' "$work/list" | head -n 1 | cut -d: -f1)
{ echo '```'; cat "$work/$n/refinement.txt"; echo '```'; } >"$work/toppling.md"
"$root/scripts/splice-doc.sh" "$root/docs/notes/step-controls.md" refinement-toppling-creep-levels "$work/toppling.md"
# The damped wall refined past its contact period, its levels in full.
n=$(grep -n '^bench/scenes/brick-wall.yaml with restitution: 0, damping_ratio: 1, dt ' "$work/list" | head -n 1 | cut -d: -f1)
{ echo '```'; cat "$work/$n/refinement.txt"; echo '```'; } >"$work/wall.md"
"$root/scripts/splice-doc.sh" "$root/docs/notes/step-controls.md" refinement-damped-wall-levels "$work/wall.md"
