"""A law written in Python: the Burgers model, for prototyping a law before writing it in C++.

Sample run (from the repository root, after `bash scripts/build.sh`):
    PYTHONPATH=build/python /usr/bin/python3 examples/python/burgers_in_python.py

It runs the two-block shear creep test (examples/shear-creep-test.yaml) with the
joint set `plane` given this Python law instead of the built-in `burgers`, and
prints the largest difference between the two joint shear displacements (they
agree to round-off) and the wall time of each run.

The law (per unit joint area; docs/reference/laws.md): a spring E1 and a dashpot eta1 in
series with a Kelvin element E2 || eta2. Creep under constant force F (the seed's
eqs. 20-21): d(t) = F/E1 + F/E2 (1 - exp(-E2 t/eta2)) + F t/eta1. The DDA host
asks for the creep increment of a step in the affine form Delta d_c = h + c F_e
(laws/contact_rheology.hpp, eq. 1) and then advances the state. State q:
q[0] = Kelvin displacement, q[1] = dashpot displacement [length].
"""
import math
import os
import sys
import time
from typing import Sequence

import numpy as np

import rheodda


class PythonBurgers(rheodda.PythonLaw):
    """Burgers in Python, the same recurrences as the built-in one (laws/src/series_law.cpp)."""

    def __init__(self, E1: float, E2: float, eta1: float, eta2: float) -> None:
        rheodda.PythonLaw.__init__(self, "python-burgers", {"E1": E1, "E2": E2, "eta1": eta1, "eta2": eta2},
                                   internal_count=2, instantaneous_stiffness=E1, linear=True)
        self.E1, self.E2, self.eta1, self.eta2 = E1, E2, eta1, eta2
        self._units: dict[tuple[float, str], tuple[rheodda.UnitStepConstants, rheodda.UnitStepConstants]] = {}

    def step_constants(self, dt: float, scheme: str) -> rheodda.StepConstants:
        """Once per step: the per-element coefficients of eq. (2) of contact_rheology.hpp,
        Delta q = per_q q + per_start F_s + per_end F_e.
        Kelvin, exact for the scheme's force: b = 1 - exp(-dt E2/eta2), phi = 1 - b/r
        (r = dt E2/eta2); dashpot: dt/eta1 (rectangle rule, trapezoid for exponential-linear)."""
        k = rheodda.StepConstants(dt, scheme)
        kelvin, dashpot = rheodda.UnitStepConstants(), rheodda.UnitStepConstants()
        r = dt * self.E2 / self.eta2
        kelvin.b = -math.expm1(-r)
        kelvin.phi = 1.0 - kelvin.b / r
        kelvin.per_q = -kelvin.b
        dashpot.dt_over_eta = dt / self.eta1
        if scheme == "lagged":
            kelvin.per_start, dashpot.per_start = kelvin.b / self.E2, dashpot.dt_over_eta
        elif scheme == "implicit":
            kelvin.per_end, dashpot.per_end = kelvin.b / self.E2, dashpot.dt_over_eta
        else:  # exponential-linear
            kelvin.per_start, kelvin.per_end = (kelvin.b - kelvin.phi) / self.E2, kelvin.phi / self.E2
            dashpot.per_start = dashpot.per_end = 0.5 * dashpot.dt_over_eta
        k.unit = [kelvin, dashpot]
        # The host asks for constants of more than one scheme per step (the step's own and
        # implicit for contacts starting from rest); the per-contact calls below look theirs
        # up by (dt, scheme) instead of reading k.unit, which copies.
        if len(self._units) > 64:
            self._units.clear()
        self._units[(dt, scheme)] = (kelvin, dashpot)
        return k

    def linearize(self, k: rheodda.StepConstants, q: Sequence[float], force_start: float,
                  force_end_guess: float) -> tuple[float, float]:
        """Delta d_c = h + c F_e: h from the old state and F_s, c the step's creep compliance."""
        kel, dash = self._units[(k.dt, k.scheme)]
        h = kel.per_q * q[0] + kel.per_start * force_start + dash.per_start * force_start
        c = kel.per_end + dash.per_end
        return h, c

    def advance(self, k: rheodda.StepConstants, q: Sequence[float], force_start: float,
                force_end: float) -> tuple[float, tuple[float, float]]:
        """The step's increments of each element; returns (Delta d_c, new q)."""
        kel, dash = self._units[(k.dt, k.scheme)]
        dq0 = kel.per_q * q[0] + kel.per_start * force_start + kel.per_end * force_end
        dq1 = dash.per_start * force_start + dash.per_end * force_end
        return dq0 + dq1, (q[0] + dq0, q[1] + dq1)

    def creep_closed_form(self, force: float, t: float) -> float:
        return force / self.E2 * -math.expm1(-self.E2 * t / self.eta2) + force * t / self.eta1


def main() -> int:
    root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
    scene = rheodda.load_scene(os.path.join(root, "examples", "shear-creep-test.yaml"))
    p = {"E1": 26.87, "E2": 192.43, "eta1": 34807.72, "eta2": 2141.23}  # Table 1 row 1, as in the scene

    start = time.perf_counter()
    builtin = rheodda.Simulation(scene).run()
    t_builtin = time.perf_counter() - start
    start = time.perf_counter()
    python = rheodda.Simulation(scene, laws={"plane": PythonBurgers(**p)}).run()
    t_python = time.perf_counter() - start

    # (NaN in the row of t = 0: no contact is closed yet)
    a = builtin.history()["plane.shear_displacement"]
    b = python.history()["plane.shear_displacement"]
    assert (np.isnan(a) == np.isnan(b)).all()
    diff = np.nanmax(np.abs(a - b))
    print("plane.shear_displacement at {:g} h: built-in {:.10g} mm, Python law {:.10g} mm".format(
        builtin.time, a[-1], b[-1]))
    print("largest difference over {} steps: {:.3g} mm (relative {:.3g})".format(
        builtin.step_count, diff, diff / abs(a[-1])))
    print("wall time: built-in {:.3f} s, Python law {:.3f} s".format(t_builtin, t_python))
    return 0 if diff <= 1e-10 * abs(a[-1]) else 1


if __name__ == "__main__":
    sys.exit(main())
