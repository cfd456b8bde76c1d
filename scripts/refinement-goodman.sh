#!/usr/bin/env bash
# Step-control refinement of the seed's Goodman slope without creep (static):
# block 10's displacement after 2 d at base friction 35, 45 and 60 deg, with
# max_displacement_ratio (g2) and dt halved together from 0.001 / 0.5 d over
# seven levels. Prints a Markdown table (displacement [m] and steps per level)
# and puts it into docs/contacts.md ("Why the iteration does not settle",
# between the refinement-goodman markers). About 5 s.
# Usage: scripts/refinement-goodman.sh [--stick-keeps-force]   (uses $RHEODDA_BUILD_DIR or build/)
#   --stick-keeps-force: the same with analysis.stick_keeps_force: true, into the
#   refinement-goodman-stick markers.
set -euo pipefail
marker=refinement-goodman
extra=""
if [[ "${1:-}" == "--stick-keeps-force" ]]; then
  marker=refinement-goodman-stick
  extra="  analysis.stick_keeps_force: true"
fi
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${RHEODDA_BUILD_DIR:-$root/build}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
levels=7
phis=(35 45 60)
{
  echo "scene: $root/examples/goodman-toppling.yaml"
  echo "set:"
  echo "  joint_sets.base.law: ~"
  echo "  joint_sets.base.shear_stiffness: 1.0e8"
  echo "  joint_sets.anti_toppling.law: ~"
  echo "  joint_sets.anti_toppling.shear_stiffness: 1.0e8"
  echo "  analysis.duration: 2"
  [[ -n "$extra" ]] && echo "$extra"
  echo "outputs: [block10_top.displacement]"
  echo "times: [2]"
  echo "cases:"
  for phi in "${phis[@]}"; do
    for ((l = 0; l < levels; ++l)); do
      g2=$(awk -v l=$l 'BEGIN { printf "%.9g", 0.001 / 2^l }')
      dt=$(awk -v l=$l 'BEGIN { printf "%.9g", 0.5 / 2^l }')
      echo "  - {name: phi${phi}_L$l, set: {joint_sets.base.friction_angle: $phi, analysis.max_displacement_ratio: $g2, analysis.dt: $dt}}"
    done
  done
} >"$work/study.yaml"
"$build/apps/rheodda" study "$work/study.yaml" -o "$work/out" -j "$(nproc)" --no-plot >/dev/null 2>&1
awk -F, -v levels=$levels '
  NR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i; next }
  { split($1, a, "_L"); phi = substr(a[1], 4); l = a[2];
    d[phi, l] = $(col["block10_top.displacement@2"]); s[phi, l] = $(col["steps"]);
    if (!(phi in seen)) { seen[phi] = 1; order[++n] = phi } }
  END {
    printf "| base φ | quantity |"; for (l = 0; l < levels; ++l) printf " L%d |", l; print ""
    printf "|---|---|"; for (l = 0; l < levels; ++l) printf "---:|"; print ""
    printf "| | g2 / Δt [d] |"; for (l = 0; l < levels; ++l) printf " %.3g / %.3g |", 0.001 / 2^l, 0.5 / 2^l; print ""
    for (k = 1; k <= n; ++k) {
      phi = order[k]
      printf "| %s° | block 10 [m] |", phi; for (l = 0; l < levels; ++l) printf " %.3f |", d[phi, l]; print ""
      printf "| | steps |"; for (l = 0; l < levels; ++l) printf " %d |", s[phi, l]; print ""
    }
  }' "$work/out/study.csv" >"$work/table.md"
cat "$work/table.md"
"$root/scripts/splice-doc.sh" "$root/docs/contacts.md" "$marker" "$work/table.md"
