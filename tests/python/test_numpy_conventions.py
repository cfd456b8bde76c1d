"""numpy conventions (docs/guide/python.md, "numpy conventions"): closed forms broadcast over forces and
times; state read from a simulation or a data set is a read-only array (a write raises instead of
being dropped); every array-like result is a numpy array; a Python law's parameters follow its
attributes."""
import math

import numpy as np
import pytest

import rheodda
from conftest import TABLE1


def burgers_creep(F, t):
    """The seed's eq. 2 without the spring: F/E2 (1 - exp(-E2 t/eta2)) + F t/eta1 [mm]."""
    p = TABLE1
    return F / p["E2"] * -np.expm1(-p["E2"] * t / p["eta2"]) + F * t / p["eta1"]


def test_closed_forms_broadcast_over_forces_and_times():
    law = rheodda.law("burgers", TABLE1)
    F = np.array([[0.232], [0.424], [0.512]])  # (3, 1) [MPa]
    t = np.linspace(0.0, 400.0, 5)             # (5,) [h]
    c = law.creep_closed_form(F, t)
    assert isinstance(c, np.ndarray) and c.shape == (3, 5)
    np.testing.assert_allclose(c, burgers_creep(F, t), rtol=1e-13, atol=0)
    d = law.displacement_closed_form(F, t)
    np.testing.assert_allclose(d, F / TABLE1["E1"] + burgers_creep(F, t), rtol=1e-13)
    # each element is the scalar call
    assert d[1, 3] == law.displacement_closed_form(0.424, 300.0)
    assert isinstance(law.displacement_closed_form(0.424, 300.0), float)
    # forces alone as an array, time a number; lists are array-likes too
    np.testing.assert_allclose(law.creep_closed_form([0.232, 0.424], 100.0), burgers_creep(np.array([0.232, 0.424]),
                                                                                           100.0), rtol=1e-13)
    with pytest.raises(ValueError, match="broadcast"):
        law.creep_closed_form(np.ones(3), np.ones(4))
    # failure times over an array of forces: t_f = t_r (tau_ref/|F|)^r (docs/reference/laws.md)
    dmg = rheodda.law("damage-burgers", dict(E1=26.87, E2=192.43, eta2=2141.23, A=1e-4, tau_ref=0.3, n=3.0,
                                             t_r=100.0, r=5.0))
    tf = dmg.failure_time(np.array([0.3, 0.6]))
    np.testing.assert_allclose(tf, 100.0 * (0.3 / np.array([0.3, 0.6])) ** 5.0, rtol=1e-14)
    assert math.isinf(law.failure_time(0.3))


def test_simulation_state_is_read_only(root):
    sim = rheodda.Simulation(str(root / "examples" / "shear-creep-test.yaml"))
    sim.step(3)
    for name, a in [("block_positions", sim.block_positions), ("block_velocities", sim.block_velocities),
                    ("block_stresses", sim.block_stresses), ("block_vertices", sim.block_vertices(0)),
                    ("point_displacement", sim.point_displacement(0, 0.0, 0.0)),
                    ("history time", sim.history()["time"]), ("contacts x", sim.contacts()["x"]),
                    ("loads", sim.loads[0])]:
        assert isinstance(a, np.ndarray) and not a.flags.writeable, name
        with pytest.raises(ValueError, match="read-only"):
            a[...] = 0.0
    assert sim.loads[0].shape[1] == 3  # rows (t, fx, fy)
    c = sim.contacts()
    for key in ("state", "kind"):
        assert isinstance(c[key], np.ndarray) and c[key].dtype.kind == "U" and len(c[key]) == len(c["id"]), key
    assert (c["state"] == "locked").all()


def test_creep_data_arrays(root):
    d = rheodda.read_creep_csv(str(root / "examples" / "creep-data" / "steps-unloading.csv"), stress_column="tau")
    assert d.stress.shape == (len(d.stress), 2) and not d.stress.flags.writeable
    assert not d.t.flags.writeable and not d.displacement.flags.writeable
    assert d.sigma is None
    # the stages array feeds exact_displacement as the pairs did
    law = rheodda.law("burgers", TABLE1)
    np.testing.assert_allclose(rheodda.exact_displacement(law, d.stress, d.t),
                               rheodda.exact_displacement(law, [tuple(r) for r in d.stress], d.t), rtol=0)


def test_python_law_parameters_follow_its_attributes():
    class Maxwell(rheodda.PythonLaw):
        def __init__(self, E1, eta1):
            super().__init__("m", {"E1": E1, "eta1": eta1}, instantaneous_stiffness=E1)
            self.eta1 = eta1

    law = Maxwell(26.87, 34807.72)
    assert law.parameters == {"E1": 26.87, "eta1": 34807.72}
    law.eta1 = 1000.0
    assert law.parameters == {"E1": 26.87, "eta1": 1000.0}  # E1 is no attribute: as given
