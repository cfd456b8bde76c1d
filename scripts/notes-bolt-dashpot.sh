#!/usr/bin/env bash
# The figures of docs/notes/explicit-step.md, "The bolts' dashpots by the kick's mean rate":
# the energy balance of a bolt's dashpot in the explicit step's cycles. The model is
# tests/core/bolt_test.cpp's explicit_hanging_model: a 1 m x 1 m block (rho 2600 kg/m^3,
# plane stress) hanging from a vertical bolt at the middle of its top edge, anchored 2 m
# above at a fixed point, 1 ms explicit steps (dynamic_ratio 1), gravity -9.81 m/s^2, the
# cycles' dashpots at explicit_damping zeta. Each case (bolt stiffness k [N/m], Young's
# modulus E [Pa], the block's initial downward speed v0 [m/s], zeta, steps) prints the
# bolt's dissipation (its dashpot: no yield), the blocks' damping and the residual at the
# end [J/m] (history.csv), and the largest relative residual after any step (summary.json).
#   scripts/notes-bolt-dashpot.sh        # a few seconds
# (uses $RHEODDA_BUILD_DIR or build/; run it on a build of an earlier commit for its figures)
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"  # strict mode; root, build, work (removed at exit)
ensure_built rheodda
cases=(
  # k     E      v0  zeta steps
  "1e7   1e12   0   0.5  100"
  "1e7   1e12   1   0.5  100"
  "1e7   1e10   1   0.5  100"
  "1e9   1e12   1   0.5  50"
  "1e11  1e12   1   0.5  20"
  "1e12  1e12   1   0.5  20"
  "1e13  1e12   1   0.5  10"
  "1e14  1e12   1   0.5  5"
  "1e12  1e12   1   1.0  20"
)
for c in "${cases[@]}"; do
  read -r k E v0 zeta steps <<<"$c"
  name="k${k}_E${E}_v${v0}_z${zeta}"
  cat >"$work/$name.yaml" <<EOF
title: Block hanging from a damped bolt, explicit cycles
units: {length: m, force: N, time: s}
analysis:
  type: dynamic
  integrator: explicit
  explicit_damping: $zeta
  duration: $(/usr/bin/python3 -c "print($steps * 1e-3)")   # s
  dt: 0.001              # s
  gravity: [0, -9.81]    # m/s^2
materials:
  rock: {density: 2600, young_modulus: $E, poisson_ratio: 0.25, plane: stress}
joint_sets:
  none: {friction_angle: 30}   # deg; the one block has no contact
blocks:
  - {name: block, polygon: [[0, 0], [1, 0], [1, 1], [0, 1]], initial_velocity: [0, -$v0, 0]}
bolts:
  - name: bolt
    from: {point: [0.5, 1.0], block: block}
    to: {fixed: [0.5, 3.0]}
    axial_stiffness: $k   # N/m per m of thickness
EOF
  "$build/apps/rheodda" run -q --threads 1 "$work/$name.yaml" -o "$work/$name" >/dev/null
  /usr/bin/python3 - "$work/$name/history.csv" "$work/$name/summary.json" "$c" <<'PY'
import csv, json, sys
rows = [r for r in csv.reader(l for l in open(sys.argv[1]) if not l.startswith("#"))]
last = dict(zip(rows[0], rows[-1]))
rel = json.load(open(sys.argv[2]))["energy"]["max_relative_residual"]
k, E, v0, zeta, steps = sys.argv[3].split()
print(f"k {k} N/m, E {E} Pa, v0 {v0} m/s, zeta {zeta}, {steps} steps: "
      f"bolt dissipation {float(last['dissipation_bolt']):.6g} J/m, block damping "
      f"{float(last['dissipation_block_damping']):.6g} J/m, residual {float(last['energy_residual']):.3g} J/m, "
      f"largest relative {rel:.3g}")
PY
done
