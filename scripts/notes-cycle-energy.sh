#!/usr/bin/env bash
# The figures of docs/notes/explicit-step.md, "The cycles' energy at impacts": the energy
# balance of the explicit step's cycles on examples/sliding-block.yaml's incline (1 m x 0.5 m
# block, E = 5 GPa, 30 deg), taken with `integrator: explicit`:
#   sliding   the example as shipped (friction 20 deg: the block slides from rest);
#   pushed    a 20 deg incline that holds it (friction 30 deg), the block pushed down at 1 m/s:
#             it slows and stops within a step;
#   dropped   the 30 deg incline with friction 35 deg, the block released 1 cm above it: it
#             strikes the penalty springs, slides and stops.
# Prints, at the end of each run, friction's work against the closed form where there is one,
# the contacts' terms and the balance's residual (history.csv).
#   scripts/notes-cycle-energy.sh        # a few seconds
# (uses $RHEODDA_BUILD_DIR or build/)
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"  # strict mode; root, build, work (removed at exit)
ensure_built rheodda
python3 - "$root/examples/sliding-block.yaml" "$work" <<'PY'
import math, sys
src = open(sys.argv[1]).read()
src = src.replace("  gravity: [0, -9.81]    # m/s^2", "  gravity: [0, -9.81]    # m/s^2\n  integrator: explicit")
assert "integrator: explicit" in src
open(sys.argv[2] + "/sliding.yaml", "w").write(src)
# A 20 deg slope (its top face from the origin) and the block on it, pushed down at 1 m/s.
a = math.radians(20.0)
top = 10 * math.tan(a)
x, y = 6 * math.cos(a), 6 * math.sin(a)
pushed = src.replace("[[0, 0], [10, 0], [10, 5.773502692]]", f"[[0, 0], [10, 0], [10, {top:.9f}]]")
pushed = pushed.replace("friction_angle: 20", "friction_angle: 30").replace("duration: 1 ", "duration: 0.7 ")
pushed = pushed.replace("{x: 5.196152423, y: 3.0, width: 1, height: 0.5, angle: 30}",
                        f"{{x: {x:.9f}, y: {y:.9f}, width: 1, height: 0.5, angle: 20}}, "
                        f"initial_velocity: [{-math.cos(a):.9f}, {-math.sin(a):.9f}, 0]")
pushed = pushed.replace("point: [5.504165125, 3.466506351]", f"point: [{x + 0.5 * math.cos(a) - 0.25 * math.sin(a):.9f}, "
                        f"{y + 0.5 * math.sin(a) + 0.25 * math.cos(a):.9f}]")
open(sys.argv[2] + "/pushed.yaml", "w").write(pushed)
b = math.radians(30.0)
dropped = src.replace("friction_angle: 20", "friction_angle: 35").replace("duration: 1 ", "duration: 0.5 ")
dropped = dropped.replace("{x: 5.196152423, y: 3.0,", f"{{x: {5.196152423 - 0.01 * math.sin(b):.9f}, y: {3.0 + 0.01 * math.cos(b):.9f},")
open(sys.argv[2] + "/dropped.yaml", "w").write(dropped)
PY
for case in sliding pushed dropped; do
  "$build/apps/rheodda" run -q "$work/$case.yaml" -o "$work/$case" >/dev/null
done
python3 - "$work" <<'PY'
import csv, math, sys
def last(case):
    rows = [r for r in csv.reader(open(f"{sys.argv[1]}/{case}/history.csv")) if r and not r[0].startswith("#")]
    return dict(zip(rows[0], rows[-1]))
g, m = 9.81, 2600 * 0.5
for case, slope, phi in (("sliding", 30, 20), ("pushed", 20, 30), ("dropped", 30, 35)):
    r = last(case)
    f = lambda k: float(r[k])
    travel = math.hypot(f("centre.u"), f("centre.v"))
    closed = m * g * math.cos(math.radians(slope)) * math.tan(math.radians(phi)) * travel
    line = (f"{case}: t = {f('time'):g} s, travel {travel:.5g} m, friction {f('dissipation_friction'):.6g} J "
            f"(N tan(phi) x travel {closed:.6g} J)" if case != "dropped" else
            f"{case}: t = {f('time'):g} s, travel {travel:.5g} m, friction {f('dissipation_friction'):.6g} J")
    print(line + f", work of gravity {f('work_gravity'):.6g} J, kinetic {f('energy_kinetic'):.3g} J, "
          f"contact damping {f('dissipation_contact_damping'):.4g}, block damping {f('dissipation_block_damping'):.4g}, "
          f"closing {f('dissipation_contact_closing'):.4g}, release {f('dissipation_contact_release'):.4g}, "
          f"integration {f('dissipation_integration'):.3g} J; residual {f('energy_residual'):.4g} J "
          f"(relative {f('energy_residual_relative'):.3g})")
PY
