#!/usr/bin/env bash
# The seed's Goodman slope without creep (the scene of scripts/refinement-goodman.sh:
# no laws, joint shear stiffness 1e8 Pa/m) settled in a *dynamic* analysis with
# plastic impacts and damped blocks (joint sets restitution 0, material
# damping_ratio 1; docs/contacts.md, "Contact damping"): gravity on at t = 0,
# 20 s of motion (2.315e-4 d), block 10's displacement at the end at base
# friction 35, 45 and 60 deg, with dt halved over five levels from 2 ms
# (max_displacement_ratio halved with it from 0.001). Prints a Markdown table
# and puts it into docs/contacts.md (between the refinement-goodman-dynamic
# markers). About 5 min on 2 cores.
# Usage: scripts/refinement-goodman-dynamic.sh   (uses $RHEODDA_BUILD_DIR or build/)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${RHEODDA_BUILD_DIR:-$root/build}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
levels=5
phis=(35 45 60)
end=2.315e-4                   # d (20 s)
dt0=2.3148148e-8               # d (2 ms)
{
  echo "scene: $root/examples/goodman-toppling.yaml"
  echo "set:"
  echo "  joint_sets.base.law: ~"
  echo "  joint_sets.base.shear_stiffness: 1.0e8"
  echo "  joint_sets.base.restitution: 0"
  echo "  joint_sets.anti_toppling.law: ~"
  echo "  joint_sets.anti_toppling.shear_stiffness: 1.0e8"
  echo "  joint_sets.anti_toppling.restitution: 0"
  echo "  materials.rock.damping_ratio: 1"
  echo "  analysis.type: dynamic"
  echo "  analysis.scheme: ~"
  echo "  analysis.duration: $end"
  echo "  analysis.output_interval: $end"
  echo "outputs: [block10_top.displacement]"
  echo "times: [$end]"
  echo "cases:"
  for phi in "${phis[@]}"; do
    for ((l = 0; l < levels; ++l)); do
      g2=$(awk -v l=$l 'BEGIN { printf "%.9g", 0.001 / 2^l }')
      dt=$(awk -v l=$l -v d=$dt0 'BEGIN { printf "%.9g", d / 2^l }')
      echo "  - {name: phi${phi}_L$l, set: {joint_sets.base.friction_angle: $phi, analysis.max_displacement_ratio: $g2, analysis.dt: $dt}}"
    done
  done
} >"$work/study.yaml"
"$build/apps/rheodda" study "$work/study.yaml" -o "$work/out" -j "$(nproc)" --no-plot >"$work/log" 2>&1 || {
  cat "$work/log" >&2
  exit 1
}
awk -F, -v levels=$levels '
  NR == 1 { for (i = 1; i <= NF; ++i) { col[$i] = i; if ($i ~ /^block10_top\.displacement@/) disp = i }; next }
  { split($1, a, "_L"); phi = substr(a[1], 4); l = a[2];
    d[phi, l] = $disp; s[phi, l] = $(col["steps"]);
    if (!(phi in seen)) { seen[phi] = 1; order[++n] = phi } }
  END {
    printf "| base φ | quantity |"; for (l = 0; l < levels; ++l) printf " L%d |", l; print ""
    printf "|---|---|"; for (l = 0; l < levels; ++l) printf "---:|"; print ""
    printf "| | g2 / Δt [ms] |"; for (l = 0; l < levels; ++l) printf " %.3g / %.3g |", 0.001 / 2^l, 2 / 2^l; print ""
    for (k = 1; k <= n; ++k) {
      phi = order[k]
      printf "| %s° | block 10 at 20 s [m] |", phi; for (l = 0; l < levels; ++l) printf " %.4f |", d[phi, l]; print ""
      printf "| | steps |"; for (l = 0; l < levels; ++l) printf " %d |", s[phi, l]; print ""
    }
  }' "$work/out/study.csv" >"$work/table.md"
cat "$work/table.md"
"$root/scripts/splice-doc.sh" "$root/docs/contacts.md" refinement-goodman-dynamic "$work/table.md"
