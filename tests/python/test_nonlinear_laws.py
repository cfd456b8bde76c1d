"""Nonlinear laws from Python (docs/reference/laws.md, "Nonlinear laws"): power-law
(Norton) creep linear in time, the tangent linearization, and damage-burgers
stepped to failure with its damage carried by advance()."""
import numpy as np
import pytest

import rheodda

NORTON = {"E1": 26.87, "A": 0.2 / 34807.72, "tau_ref": 0.2, "n": 4.0}
DAMAGE = dict(NORTON, E2=192.43, eta2=2141.23, t_r=234.0, r=3.0)


def test_power_law_is_nonlinear_and_creeps_linearly_in_time():
    law = rheodda.law("power-law", NORTON)
    assert law.linearity == "nonlinear" and not law.is_linear
    assert rheodda.law("burgers", {"E1": 1, "E2": 1, "eta1": 1, "eta2": 1}).linearity == "affine"
    t = np.array([0.0, 50.0, 100.0])
    rate = NORTON["A"] * (0.3 / NORTON["tau_ref"]) ** NORTON["n"]
    np.testing.assert_allclose(law.creep_closed_form(0.3, t), rate * t, rtol=1e-14)
    assert law.failure_time(0.3) == np.inf


def test_the_tangent_goes_through_the_increment():
    law = rheodda.law("power-law", NORTON)
    k = law.step_constants(5.0, "implicit")
    q = [0.0] * 4
    h, c = law.linearize(k, q, 0.1, 0.3)
    dd, _ = law.advance(k, q, 0.1, 0.3)
    assert abs(h + c * 0.3 - dd) <= 1e-15 * abs(dd)
    assert abs(c - 5.0 * NORTON["A"] * 4 * 0.3 ** 3 / 0.2 ** 4) <= 1e-12 * c


def test_damage_burgers_fails_at_kachanovs_time_when_its_damage_is_carried():
    law = rheodda.law("damage-burgers", DAMAGE)
    tf = 234.0 * (0.2 / 0.232) ** 3
    assert abs(law.failure_time(0.232) - tf) <= 1e-12 * tf
    k = law.step_constants(1.0, "implicit")
    q, damage, t = [0.0] * 4, 0.0, 0.0
    while damage < 1.0:
        dd, q, damage = law.advance(k, q, 0.232, 0.232, damage=damage)
        t += 1.0
    assert tf <= t < tf + 1.0  # fails in the step that holds t_f


def test_a_curve_with_a_tolerance_is_accurate_and_without_one_never_returns_nan():
    # power-law, n = 20, held at twice tau_ref (issue 43): one lagged step per 10 h
    # goes to NaN, which is an error now; with a tolerance the curve follows the
    # closed-form relaxation (exact) to within ten tolerances of the initial force.
    law = rheodda.law("power-law", {"E1": 20.0, "tau_ref": 0.2, "A": 1e-3, "n": 20.0})
    with pytest.raises(rheodda.RunError, match="not a finite number"):
        rheodda.relaxation_curve(law, 0.02, t_end=100.0, dt=10.0, scheme="lagged")
    for scheme in ("lagged", "implicit", "exponential-linear"):
        c = rheodda.relaxation_curve(law, 0.02, t_end=100.0, dt=10.0, scheme=scheme, tolerance=1e-6)
        assert np.all(np.isfinite(c["force"]))
        assert np.max(np.abs(c["force"] - c["exact"])) <= 10 * 1e-6 * c["force"][0]
    with pytest.raises(rheodda.LawError, match="tolerance"):
        rheodda.creep_curve(law, 0.1, t_end=1.0, dt=1.0, tolerance=0.5)


def test_the_shipped_slope_steps_onto_its_failure_within_dt_max(root):
    # examples/creeping-slope-failure.yaml: adaptive creep steps of at most dt_max, the
    # one that reaches the failure too (docs/reference/rheology-in-dda.md, "Failure"; issue 43: it
    # was 0.731 d against a dt_max of 0.1 d).
    steps = []  # (dt, end time) of every accepted step [d]
    sim = rheodda.Simulation(str(root / "examples" / "creeping-slope-failure.yaml"),
                             callback=lambda s, r: steps.append((r.dt, r.time)))
    dt_max = sim.settings["dt_max"]
    assert dt_max == 0.1
    sim.run()
    assert len(steps) > 100 and max(dt for dt, _ in steps) <= dt_max * (1 + 1e-12)
