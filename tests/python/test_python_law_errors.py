"""A law written in Python that returns a bad value raises rheodda.PythonLawError naming the law,
the method, the value and what was expected, at the first step it happens (python/src/python_law.cpp)."""
import math
import re

import numpy as np
import pytest

import rheodda


class Maxwell(rheodda.PythonLaw):
    """Spring E1 and dashpot eta1, implicit: h = 0, c = dt/eta1 (as test_python_law.py); `bad`
    replaces one method's return value from the moment it is set."""

    def __init__(self, E1=26.87, eta1=34807.72):
        super().__init__("test-maxwell", {"E1": E1, "eta1": eta1}, internal_count=1, instantaneous_stiffness=E1)
        self.eta1 = eta1
        self.bad = {}

    def linearize(self, k, q, force_start, force_end_guess):
        return self.bad.get("linearize", (0.0, k.dt / self.eta1))

    def advance(self, k, q, force_start, force_end):
        dd = k.dt * force_end / self.eta1
        return self.bad.get("advance", (dd, (q[0] + dd,)))


@pytest.fixture
def scene(root):
    return rheodda.load_scene(str(root / "examples" / "shear-creep-test.yaml"))


LINEARIZE = "a tuple (h, c) of two finite numbers: h [length], c [length/force]"
ADVANCE = ("a tuple (delta_creep, q_new): a finite number [length] and a sequence of internal_count = 1 "
           "finite numbers [length]")


@pytest.mark.parametrize("method, value, shown, expected", [
    ("linearize", (0.0, math.inf), "(0.0, inf)", LINEARIZE),            # an infinite compliance
    ("linearize", (math.nan, 1e-3), "(nan, 0.001)", LINEARIZE),          # NaN
    ("linearize", (0.0, 1e-3, 2.0), "(0.0, 0.001, 2.0)", LINEARIZE),     # wrong shape
    ("linearize", 1e-3, "0.001", LINEARIZE),                             # wrong type: not a tuple
    ("linearize", (0.0, "1e-3"), "(0.0, '1e-3')", LINEARIZE),            # wrong type inside
    ("advance", (math.inf, (0.0,)), "(inf, (0.0,))", ADVANCE),
    ("advance", (0.0, (0.0, 0.0)), "(0.0, (0.0, 0.0))", ADVANCE),        # q_new of the wrong length
    ("advance", (0.0, (math.nan,)), "(0.0, (nan,))", ADVANCE),
    ("advance", (0.0, None), "(0.0, None)", ADVANCE),
])
def test_a_bad_value_raises_at_the_first_step_it_happens(scene, method, value, shown, expected):
    law = Maxwell()
    sim = rheodda.Simulation(scene, laws={"plane": law})
    sim.step(3)  # good steps first

    def go_bad(s, report):
        if s.step_count == 5:
            law.bad[method] = value
    sim.callback = go_bad
    with pytest.raises(rheodda.PythonLawError) as e:
        sim.run()
    assert sim.step_count == 5 and sim.failed  # the step after the change, not later
    err = e.value
    assert (err.law, err.method, err.value, err.expected) == ("test-maxwell", method, shown, expected)
    assert str(err).startswith("PythonLaw 'test-maxwell': {} returned {}; expected {}, at contact ".format(
        method, shown, expected))
    assert str(err).endswith(", in step 6 (from t = 5 h)") and (err.step, err.time) == (6, 5.0)
    assert isinstance(err, rheodda.Error)


def test_the_other_methods_are_checked_too():
    # Through the library (a curve calls the methods from C++), not the Python methods directly.
    class Closed(Maxwell):
        def creep_closed_form(self, force, t):
            return math.inf if t > 1 else force * t / self.eta1

    class Relaxation(Maxwell):
        def relaxation_modulus(self, t):
            return "26.87"

    class Constants(Maxwell):
        def step_constants(self, dt, scheme):
            return (dt, scheme)

    with pytest.raises(rheodda.PythonLawError, match=r"creep_closed_form returned inf; expected a finite number "
                                                     r"\[length\]"):
        rheodda.creep_curve(Closed(), 0.2, t_end=2.0, dt=1.0)
    with pytest.raises(rheodda.PythonLawError, match=r"relaxation_modulus returned '26.87'; expected a finite "
                                                     r"number \[force/length\] or None"):
        rheodda.relaxation_curve(Relaxation(), 0.01, t_end=2.0, dt=1.0)
    with pytest.raises(rheodda.PythonLawError, match=r"step_constants returned \(1.0, 'implicit'\); expected a "
                                                     r"rheodda.StepConstants"):
        rheodda.creep_curve(Constants(), 0.2, t_end=2.0, dt=1.0)


def test_numpy_numbers_and_lists_are_accepted(scene):
    import numpy as np

    class NumpyMaxwell(Maxwell):
        def linearize(self, k, q, force_start, force_end_guess):
            return np.array([0.0, k.dt / self.eta1])

        def advance(self, k, q, force_start, force_end):
            dd = np.float64(k.dt * force_end / self.eta1)
            return [dd, [q[0] + dd]]

    a = rheodda.Simulation(scene, laws={"plane": Maxwell()}).run().history()["plane.shear_displacement"]
    b = rheodda.Simulation(scene, laws={"plane": NumpyMaxwell()}).run().history()["plane.shear_displacement"]
    np.testing.assert_array_equal(a, b)


@pytest.mark.parametrize("method, value", [
    ("advance", (0.0, np.array([[0.0]]))),      # q_new of shape (1, 1)
    ("advance", (np.array([1e-9]), (0.0,))),    # delta_creep of shape (1,)
    ("linearize", np.array([[0.0], [1e-3]])),   # (h, c) of shape (2, 1)
])
def test_numpy_arrays_of_the_wrong_shape_are_refused_as_lists_of_that_shape_are(scene, method, value):
    law = Maxwell()
    sim = rheodda.Simulation(scene, laws={"plane": law})
    sim.step(2)
    law.bad[method] = value
    with pytest.raises(rheodda.PythonLawError) as e:
        sim.step()
    shown = re.sub(r"\n\s*", " ", repr(value))
    assert e.value.value == shown and e.value.method == method
    nested = (0.0, [[0.0]]) if method == "advance" and isinstance(value[1], np.ndarray) else None
    if nested is not None:  # the nested list of the same shape: refused the same way
        law2 = Maxwell()
        law2.bad["advance"] = nested
        with pytest.raises(rheodda.PythonLawError):
            rheodda.Simulation(scene, laws={"plane": law2}).step(1)


def test_an_error_inside_a_run_names_the_step_the_time_and_the_contact(scene):
    law = Maxwell()
    sim = rheodda.Simulation(scene, laws={"plane": law})
    sim.step(4)
    ids = set(sim.contacts()["id"].tolist())
    law.bad["advance"] = (math.nan, (0.0,))
    with pytest.raises(rheodda.PythonLawError) as e:
        sim.step()
    err = e.value
    assert (err.step, err.time) == (5, sim.time) and err.contact in ids
    assert str(err).endswith(", in step 5 (from t = {:g} h)".format(sim.time))
    assert ", at contact {} (vertex ".format(err.contact) in str(err)
    with pytest.raises(rheodda.PythonLawError) as outside:  # a curve: no contact, no step
        class Closed(Maxwell):
            def creep_closed_form(self, force, t):
                return math.inf
        rheodda.creep_curve(Closed(), 0.2, t_end=2.0, dt=1.0)
    assert (outside.value.contact, outside.value.step, outside.value.time) == (None, None, None)
