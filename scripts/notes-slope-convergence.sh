#!/usr/bin/env bash
# The 744-block cohesionless slope's convergence in its static step controls
# (docs/notes/rock-mass-steps.md, "Where the refined slope parts ways"): writes the benchmark's
# slope (rockmass_bench --creep 1000), then runs it by `rheodda run` (one thread) as written
# (L0), with every static step control halved (L1) and quartered (L2) as `rheodda check
# --refine --hold settle.dt,settle.max_displacement_ratio` sets them, with each of those
# controls halved alone, and with the bedding's friction angle or Maxwell viscosity moved by
# a thousandth (a perturbation far below what a laboratory could resolve). Prints, per run:
# its CPU time, its mechanism stages (events.csv: start time, blocks involved, largest
# displacement [m], kinetic energy peak and work [N*m/m]) and the toe's displacement at 20,
# 50 and 100 d [m].
#
#   scripts/notes-slope-convergence.sh [SECONDS]
#
# SECONDS: the wall-time limit per run (default 900; a run stopped there prints what it
# reached). 12 runs of 1-10 minutes of CPU each, JOBS (default 2) at a time.
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
seconds="${1:-900}"
ensure_built rockmass_bench rheodda
bench_slope
base="$slope_scene"

# variant NAME OLD=>NEW...: the base scene with each OLD text replaced by NEW (once), as $work/NAME.yaml.
variant() {
  local name="$1"
  shift
  scene_variant "$base" "$work/$name.yaml" "$@"
}
dt="dt: 0.03125            # d, the first step"
g2="max_displacement_ratio: 0.000625"
ct="creep_tolerance: 6.25e-6"
cd="collapse_dt: 1.0e-5"
dm="dt_max: 0.625"
phi=$'creeping bedding planes\n    friction_angle: 30'
eta=$'eta1: 2.0e10, eta2: 6.2e9}\n    record'
variant L0
variant L1 "$dt=>dt: 0.015625" "$g2=>max_displacement_ratio: 0.0003125" "$ct=>creep_tolerance: 3.125e-6" \
  "$cd=>collapse_dt: 5.0e-6" "$dm=>dt_max: 0.3125"
variant L2 "$dt=>dt: 0.0078125" "$g2=>max_displacement_ratio: 0.00015625" "$ct=>creep_tolerance: 1.5625e-6" \
  "$cd=>collapse_dt: 2.5e-6" "$dm=>dt_max: 0.15625"
variant dt-halved "$dt=>dt: 0.015625"
variant g2-halved "$g2=>max_displacement_ratio: 0.0003125"
variant creep_tolerance-halved "$ct=>creep_tolerance: 3.125e-6"
variant collapse_dt-halved "$cd=>collapse_dt: 5.0e-6"
variant dt_max-halved "$dm=>dt_max: 0.3125"
variant friction-29.98 "$phi=>creeping bedding planes"$'\n'"    friction_angle: 29.98"
variant friction-30.02 "$phi=>creeping bedding planes"$'\n'"    friction_angle: 30.02"
variant eta1-0.999 "$eta=>eta1: 1.998e10, eta2: 6.2e9}"$'\n'"    record"
variant eta1-1.001 "$eta=>eta1: 2.002e10, eta2: 6.2e9}"$'\n'"    record"

# run NAME: the variant by `rheodda run` (one thread, $seconds of wall time at most), its report
# written to $work/NAME.txt.
run() {
  local name="$1" out="$work/out-$1" cpu reached
  /usr/bin/time -f "%U" -o "$work/$name.cpu" timeout -s INT "$seconds" "$build/apps/rheodda" run "$work/$name.yaml" \
    -o "$out" --threads 1 --quiet >/dev/null 2>&1 || true
  cpu=$(tail -n 1 "$work/$name.cpu")
  reached=$(awk -F, 'NR > 2 { t = $1 } END { print t }' "$out/history.csv")
  {
    echo "## $name: $cpu s CPU, reached t = $reached d"
    echo "mechanism stages (start d, blocks involved, largest displacement m, kinetic energy peak, work N*m/m):"
    awk -F, '$1 == "mechanism" { printf "  %.4f %d %.3g %.3g %.3g\n", $2, $7, $8, $9, $11 }' "$out/events.csv"
    awk -F, 'NR == 2 { for (i = 1; i <= NF; i++) if ($i == "toe.u") u = i; else if ($i == "toe.v") v = i }
             NR > 2 && ($1 == 20 || $1 == 50 || $1 == 100) { printf "toe at %g d: (%.5g, %.5g) m\n", $1, $u, $v }' \
      "$out/history.csv"
  } >"$work/$name.txt"
}
export -f run
export work build seconds
names=(L0 L1 L2 dt-halved g2-halved creep_tolerance-halved collapse_dt-halved dt_max-halved
  friction-29.98 friction-30.02 eta1-0.999 eta1-1.001)
printf '%s\n' "${names[@]}" | xargs -P "${JOBS:-2}" -I{} bash -c 'run {}'
for name in "${names[@]}"; do cat "$work/$name.txt"; done
