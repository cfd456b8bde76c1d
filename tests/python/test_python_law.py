"""A law written in Python, used for a joint set of a scene."""
import importlib.util

import numpy as np
import pytest

import rheodda
from conftest import TABLE1


@pytest.fixture
def python_burgers(root):
    """The Python Burgers of examples/python/burgers_in_python.py (the example users read)."""
    spec = importlib.util.spec_from_file_location("burgers_in_python",
                                                  root / "examples" / "python" / "burgers_in_python.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module.PythonBurgers


@pytest.fixture
def scene(root):
    return rheodda.load_scene(str(root / "examples" / "shear-creep-test.yaml"))


class PythonMaxwell(rheodda.PythonLaw):
    """The smallest Python law: spring E1 and dashpot eta1, implicit (backward Euler,
    exact for a dashpot under the end force): Delta d_c = dt F_e / eta1, so h = 0, c = dt/eta1.
    It keeps the default step_constants (k.dt, k.scheme only)."""

    def __init__(self, E1, eta1):
        super().__init__("python-maxwell", {"E1": E1, "eta1": eta1}, internal_count=1,
                         instantaneous_stiffness=E1)
        self.eta1 = eta1

    def linearize(self, k, q, force_start, force_end_guess):
        return 0.0, k.dt / self.eta1

    def advance(self, k, q, force_start, force_end):
        dd = k.dt * force_end / self.eta1
        return dd, (q[0] + dd,)


def test_python_burgers_matches_the_builtin_burgers_on_the_shear_creep_test(scene, python_burgers):
    law = python_burgers(**TABLE1)
    assert law.parameters == TABLE1 and law.instantaneous_stiffness == TABLE1["E1"]
    builtin = rheodda.Simulation(scene).run().history()
    python = rheodda.Simulation(scene, laws={"plane": law}).run().history()
    for k in ("plane.shear_displacement", "plane.shear_force", "A_joint.u", "A_joint.v", "dissipation_creep"):
        a, b = builtin[k][1:], python[k][1:]
        assert np.max(np.abs(a - b)) <= 1e-10 * np.max(np.abs(a)), k
    # the law alone: its closed form and its steps against the built-in law's
    ref = rheodda.law("burgers", TABLE1)
    t = np.linspace(0.0, 200.0, 11)
    np.testing.assert_allclose([law.creep_closed_form(0.232, x) for x in t], ref.creep_closed_form(0.232, t),
                               rtol=1e-14)
    for scheme in ("lagged", "implicit", "exponential-linear"):
        a = rheodda.creep_curve(law, "0:0.232,100:0.424", t_end=200.0, dt=2.0, scheme=scheme)
        b = rheodda.creep_curve(ref, "0:0.232,100:0.424", t_end=200.0, dt=2.0, scheme=scheme)
        np.testing.assert_allclose(a["displacement"], b["displacement"], rtol=1e-14, err_msg=scheme)


def test_a_minimal_python_maxwell_matches_the_builtin_maxwell(scene):
    p = {"E1": 26.87, "eta1": 34807.72}
    builtin = rheodda.Simulation(scene, laws={"plane": rheodda.law("maxwell", p)}).run().history()
    python = rheodda.Simulation(scene, laws={"plane": PythonMaxwell(**p)}).run().history()
    a, b = builtin["plane.shear_displacement"][1:], python["plane.shear_displacement"][1:]
    assert np.max(np.abs(a - b)) <= 1e-10 * np.max(np.abs(a))
    # Maxwell under constant stress: F/E1 + F t/eta1, to the contact layer's 1e-5 (docs/reference/outputs.md)
    t = builtin["time"][1:]
    np.testing.assert_allclose(-b, 0.232 / p["E1"] + 0.232 * t / p["eta1"], rtol=2e-5)


def test_a_python_law_that_raises_stops_the_run(scene):
    class Broken(PythonMaxwell):
        def advance(self, k, q, force_start, force_end):
            raise ArithmeticError("broken law")

    sim = rheodda.Simulation(scene, laws={"plane": Broken(26.87, 34807.72)})
    with pytest.raises(ArithmeticError, match="broken law"):
        sim.run()
    assert sim.failed
    with pytest.raises(rheodda.RunError, match="the simulation failed earlier"):
        sim.run()


def test_a_python_law_with_e1_and_a_shear_stiffness_is_refused_as_in_a_scene(scene):
    text = scene.text.replace("law: {name: burgers, E1: 26.87, E2: 192.43, eta1: 34807.72, eta2: 2141.23}",
                              "shear_stiffness: 30")
    plain = rheodda.parse_scene(text, "no-law.yaml")
    with pytest.raises(rheodda.SceneError, match="shear_stiffness and the E1 of law 'python-maxwell'"):
        rheodda.Simulation(plain, laws={"plane": PythonMaxwell(26.87, 34807.72)})
