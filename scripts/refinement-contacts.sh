#!/usr/bin/env bash
# Step-size studies of the open-close iteration, spliced into docs/notes/contact-rules.md (incline-drop)
# and docs/notes/contact-solves.md (walls; "Why the iteration does not settle"):
#   - incline-drop: bench/scenes/incline-drop.yaml (a block dropped 2 mm on a
#     30 deg incline, friction 40 deg) and incline-drop-damped.yaml (the same
#     with restitution 0 and damping_ratio 1) at dt = 1 ms ... 6.25 us: the
#     slip along the slope after 0.5 s (rigid-plastic answer 1.155 mm);
#   - walls: running-bond walls of N x N bricks (0.2 m x 0.1 m, the geometry of
#     bench/contact_bench) written as scenes, penalty 50 E, nu 0.25, 50 steps
#     of 1 ms: solves per step, cuts and simulated time, with Shi's rule and
#     with analysis.stick_keeps_force.
# About 3 min on 2 cores. Usage: scripts/refinement-contacts.sh (uses
# $RHEODDA_BUILD_DIR or build/; needs bench/scene_trace).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${RHEODDA_BUILD_DIR:-$root/build}"
trace="$build/bench/scene_trace"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

# The drop: slip = -(u cos 30 + v sin 30) of the measurement point `centre`,
# undamped (Shi's contact) and with plastic impacts and damped blocks.
drop_dts="0.001 0.0005 0.00025 0.0001 0.00005 0.000025 0.0000125 0.00000625"
{
  printf "| Δt [ms] |"
  for dt in $drop_dts; do printf " %s |" "$(awk -v d="$dt" 'BEGIN { printf "%g", d * 1e3 }')"; done
  echo
  printf "|---|"
  for dt in $drop_dts; do printf -- "---:|"; done
  echo
  for scene in incline-drop incline-drop-damped; do
    case $scene in
      incline-drop) printf "| slip [mm], Shi's contact (incline-drop.yaml) |" ;;
      *) printf "| slip [mm], restitution 0, damping_ratio 1 (incline-drop-damped.yaml) |" ;;
    esac
    for dt in $drop_dts; do
      "$trace" "$root/bench/scenes/$scene.yaml" --dt "$dt" --duration 0.5 --summary |
        awk '/measurement 0: displacement/ { gsub(/[(),]/, " "); u = $5; v = $6;
               printf " %.3f |", -(u * cos(atan2(1, 1) * 4 / 6) + v * sin(atan2(1, 1) * 4 / 6)) * 1e3 }'
    done
    echo
  done
} >"$work/drop.md"
# Pictures: every level of `check --refine=5` of both scenes (the centre's
# displacement against time), docs/img/incline-drop-refinement-{undamped,damped}.png.
for scene in incline-drop incline-drop-damped; do
  "$build/apps/rheodda" check "$root/bench/scenes/$scene.yaml" --refine=5 -j "$(nproc)" -o "$work/check-$scene" \
    >/dev/null 2>&1 || true  # exit 3 (not converged) is a result here
  picture=undamped
  [[ $scene == incline-drop-damped ]] && picture=damped
  cp "$work/check-$scene/study.png" "$root/docs/img/incline-drop-refinement-$picture.png"
done

# A running-bond wall of n x n bricks as a scene (stick = true/false).
wall() {
  local n=$1 stick=$2
  awk -v n="$n" -v stick="$stick" 'BEGIN {
    W = 0.2; H = 0.1; width = n * W
    w0 = 0.5 * ((width + 1.0) > (n * H + 0.5) ? (width + 1.0) : (n * H + 0.5))
    print "title: running-bond wall " n " x " n
    print "units: {length: m, force: N, time: s}"
    print "analysis:"
    print "  type: dynamic"
    print "  duration: 0.05"
    print "  dt: 0.001"
    printf "  max_displacement_ratio: %.9g\n", 1e-3 / w0
    print "  penalty: 2.5e11"
    print "  stick_keeps_force: " stick
    print "  gravity: [0, -9.81]"
    print "materials:"
    print "  rock: {density: 2600, young_modulus: 5.0e9, poisson_ratio: 0.25}"
    print "joint_sets:"
    print "  mortar: {friction_angle: 30}"
    print "blocks:"
    printf "  - {name: base, polygon: [[-0.5, -0.5], [%g, -0.5], [%g, 0], [-0.5, 0]], fixed: true}\n", width + 0.5, width + 0.5
    for (j = 0; j < n; ++j) {
      y0 = j * H; y1 = y0 + H
      if (j % 2 == 0) { for (i = 0; i < n; ++i) rect(i * W, y0, (i + 1) * W, y1) }
      else {
        rect(0, y0, 0.5 * W, y1)
        for (i = 0; i + 1 < n; ++i) rect((i + 0.5) * W, y0, (i + 1.5) * W, y1)
        rect(width - 0.5 * W, y0, width, y1)
      }
    }
  }
  function rect(x0, y0, x1, y1) {
    printf "  - {polygon: [[%.6g, %.6g], [%.6g, %.6g], [%.6g, %.6g], [%.6g, %.6g]]}\n", x0, y0, x1, y0, x1, y1, x0, y1
  }'
}
{
  echo "| wall | rule | solves per step | cuts | simulated [ms] |"
  echo "|---|---|---:|---:|---:|"
  for n in 10 14 20; do
    for stick in false true; do
      wall "$n" "$stick" >"$work/wall.yaml"
      rule=$([[ $stick == true ]] && echo '`stick_keeps_force`' || echo "Shi's")
      "$trace" "$work/wall.yaml" --steps 50 --summary |
        awk -v n="$n" -v rule="$rule" '/steps to t =/ {
          for (i = 1; i <= NF; ++i) { if ($i == "=") t = $(i + 1); if ($i == "cuts,") c = $(i - 1); if ($i == "solves") s = $(i - 1) }
          sub(/,$/, "", t)
          printf "| %d × %d | %s | %s | %s | %.1f |\n", n, n, rule, s, c, 1e3 * t }'
    done
  done
} >"$work/walls.md"

splice() { "$root/scripts/splice-doc.sh" "$root/$1" "$2" "$3"; }
splice docs/notes/contact-rules.md incline-drop "$work/drop.md"
splice docs/notes/contact-solves.md walls "$work/walls.md"
cat "$work/drop.md" "$work/walls.md"
