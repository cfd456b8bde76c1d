#!/usr/bin/env bash
# Step-control refinement of the seed's Goodman slope without creep (no laws,
# joint shear stiffness 1e8 Pa/m): block 10's displacement at base friction 35,
# 45 and 60 deg, with max_displacement_ratio (g2) and dt halved together level
# by level. Prints a Markdown table (displacement [m] and steps per level) and
# puts it into docs/notes/contact-solves.md ("Why the iteration does not settle").
# Usage: scripts/refinement-goodman.sh [--stick-keeps-force | --dynamic]   (uses $RHEODDA_BUILD_DIR or build/)
#   (default)            static, 2 d, g2 / dt from 0.001 / 0.5 d over seven levels,
#                        refinement-goodman markers; about 5 s;
#   --stick-keeps-force  the same with analysis.stick_keeps_force: true,
#                        refinement-goodman-stick markers;
#   --dynamic            settled dynamically with plastic impacts and damped blocks
#                        (joint sets restitution 0, material damping_ratio 1;
#                        docs/reference/contacts.md, "Contact damping"): gravity on at t = 0,
#                        20 s of motion (2.315e-4 d), g2 / dt from 0.001 / 2 ms over
#                        five levels, refinement-goodman-dynamic markers; about 1 min.
set -euo pipefail
marker=refinement-goodman
levels=7
end=2            # d
dt0=0.5          # d
dt_unit=d        # the table's dt column: days, or ms (--dynamic)
dt_scale=1
extra=()
case "${1:-}" in
  --stick-keeps-force)
    marker=refinement-goodman-stick
    extra=("  analysis.stick_keeps_force: true") ;;
  --dynamic)
    marker=refinement-goodman-dynamic
    levels=5
    end=2.315e-4        # d (20 s)
    dt0=2.3148148e-8    # d (2 ms)
    dt_unit=ms
    dt_scale=86400000   # ms per d
    extra=("  joint_sets.base.restitution: 0" "  joint_sets.anti_toppling.restitution: 0"
           "  materials.rock.damping_ratio: 1" "  analysis.type: dynamic" "  analysis.scheme: ~"
           "  analysis.output_interval: $end") ;;
  "") ;;
  *) echo "usage: $0 [--stick-keeps-force | --dynamic]" >&2; exit 2 ;;
esac
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${RHEODDA_BUILD_DIR:-$root/build}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
phis=(35 45 60)
{
  echo "scene: $root/bench/scenes/goodman-toppling-seed-steps.yaml"
  echo "set:"
  echo "  joint_sets.base.law: ~"
  echo "  joint_sets.base.shear_stiffness: 1.0e8"
  echo "  joint_sets.anti_toppling.law: ~"
  echo "  joint_sets.anti_toppling.shear_stiffness: 1.0e8"
  echo "  analysis.duration: $end"
  for line in "${extra[@]}"; do echo "$line"; done
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
awk -F, -v levels=$levels -v dt0=$dt0 -v unit=$dt_unit -v scale=$dt_scale '
  NR == 1 { for (i = 1; i <= NF; ++i) { col[$i] = i; if ($i ~ /^block10_top\.displacement@/) disp = i }; next }
  { split($1, a, "_L"); phi = substr(a[1], 4); l = a[2];
    d[phi, l] = $disp; s[phi, l] = $(col["steps"]);
    if (!(phi in seen)) { seen[phi] = 1; order[++n] = phi } }
  END {
    printf "| base φ | quantity |"; for (l = 0; l < levels; ++l) printf " L%d |", l; print ""
    printf "|---|---|"; for (l = 0; l < levels; ++l) printf "---:|"; print ""
    printf "| | g2 / Δt [%s] |", unit; for (l = 0; l < levels; ++l) printf " %.3g / %.3g |", 0.001 / 2^l, dt0 * scale / 2^l; print ""
    for (k = 1; k <= n; ++k) {
      phi = order[k]
      printf "| %s° | block 10 [m] |", phi; for (l = 0; l < levels; ++l) printf " %.3f |", d[phi, l]; print ""
      printf "| | steps |"; for (l = 0; l < levels; ++l) printf " %d |", s[phi, l]; print ""
    }
  }' "$work/out/study.csv" >"$work/table.md"
cat "$work/table.md"
"$root/scripts/splice-doc.sh" "$root/docs/notes/contact-solves.md" "$marker" "$work/table.md"
