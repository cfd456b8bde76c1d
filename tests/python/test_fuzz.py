"""Fuzzing the Python inputs: deterministic, seeded mutations of scene dicts (the shear
creep test and a rock mass: values replaced by other types, NaN, infinities, huge and
tiny numbers; keys deleted, misspelt or added; list items dropped or repeated) and of law
parameters and staged forces. Every mutant either loads (and then steps with finite
block positions and contact forces) or is refused with rheodda.Error (a ValueError)
naming the key path, or a RunError (a RuntimeError) for a run that cannot go on; nothing
else escapes, nothing crashes."""
import copy
import random

import numpy as np
import pytest

import rheodda
from conftest import TABLE1
from test_scene import SHEAR_TEST

# A rock mass with a hole, a generated persistent set, a set of traces with gaps and an
# explicit trace (the scene the C++ fuzz test mutates, tests/scene/fuzz_test.cpp).
ROCK_MASS = {
    "units": {"length": "m", "force": "N", "time": "d"},
    "analysis": {"type": "static", "duration": 1, "dt": 0.5, "gravity": [0, -7.32313e10]},
    "materials": {"rock": {"density": 3.41384e-7, "young_modulus": 1.0e10, "poisson_ratio": 0.25}},
    "joint_sets": {"bedding": {"friction_angle": 30}, "joints": {"friction_angle": 35},
                   "frame": {"friction_angle": 40}},
    "blocks": [{"name": "base", "rectangle": {"x": -1, "y": -1, "width": 22, "height": 1},
                "joint_set": "frame", "fixed": True}],
    "rock_mass": {
        "name": "rm", "material": "rock",
        "region": [[0, 0], [20, 0], [20, 8], [12, 12], [0, 12]],
        "holes": [[[8, 4], [11, 4], [11, 6], [8, 6]]],
        "boundary_joint_set": "frame", "seed": 5, "sliver_area": 0.05,
        "joint_sets": [
            {"joint_set": "bedding", "dip": 12, "dip_direction": "left", "spacing": 1.5, "origin": [0, 0.5]},
            {"joint_set": "joints", "dip": 80, "spacing": 2, "spacing_distribution": "normal",
             "spacing_deviation": 0.3, "trace_length": 5, "gap": 1, "dip_spread": 4},
        ],
        "traces": [{"joint_set": "joints", "from": [-1, 9], "to": [21, 2]}],
    },
}

VALUES = [None, "x", "", [], {}, [1, 2, 3], {"a": 1}, True, 0, -1, -0.0, 0.5, 7, 1e-320, 1e308, -1e308,
          2 ** 63, float("nan"), float("inf"), -float("inf"), np.float64(3.0), np.array([1.0, 2.0])]


def paths(value, prefix=()):
    """Every path into a dict/list tree, the root excluded."""
    if isinstance(value, dict):
        items = value.items()
    elif isinstance(value, list):
        items = enumerate(value)
    else:
        return
    for k, v in items:
        yield prefix + (k,)
        yield from paths(v, prefix + (k,))


def mutate(scene, rng):
    """A mutant of `scene` (deep copy) and the paths it changed."""
    d = copy.deepcopy(scene)
    changed = []
    for _ in range(rng.randint(1, 3)):
        ps = list(paths(d))
        if not ps:
            break
        p = rng.choice(ps)
        parent = d
        for k in p[:-1]:
            parent = parent[k]
        kind = rng.randrange(5)
        if kind <= 1:  # a value replaced
            parent[p[-1]] = copy.deepcopy(rng.choice(VALUES))
        elif kind == 2:  # a key or list item deleted
            del parent[p[-1]]
        elif kind == 3 and isinstance(parent, dict):  # a key misspelt
            parent[str(p[-1]) + "x"] = parent.pop(p[-1])
        elif isinstance(parent, list):  # a list item repeated
            parent.append(copy.deepcopy(parent[p[-1]]))
        else:  # a number scaled by a power of ten
            v = parent[p[-1]]
            if isinstance(v, (int, float)) and not isinstance(v, bool):
                parent[p[-1]] = v * 10.0 ** rng.choice([-12, -6, -3, 3, 6, 12])
        changed.append(p)
    return d, changed


def key_text(path):
    """A dict path as the loader names keys: a.b[2].c."""
    s = ""
    for k in path:
        s += "[{}]".format(k) if isinstance(k, int) else ("." if s else "") + str(k)
    return s


def all_finite(sim):
    c = sim.contacts()
    return (np.isfinite(sim.block_positions).all() and np.isfinite(sim.block_stresses).all() and
            all(np.isfinite(c[k]).all() for k in ("normal_force", "shear_force", "shear_displacement",
                                                 "creep_displacement")))


@pytest.mark.parametrize("name, scene, count, steps", [("shear", SHEAR_TEST, 250, 3),
                                                       ("rock_mass", ROCK_MASS, 120, 0)])
def test_mutated_scene_dicts_load_and_step_or_raise_an_error_naming_the_key(name, scene, count, steps):
    rng = random.Random(0x5ce + len(name))
    loaded = refused = 0
    for i in range(count):
        d, changed = mutate(scene, rng)
        what = "{} mutant {}: {}".format(name, i, [key_text(p) for p in changed])
        try:
            sim = rheodda.Simulation(d)
        except rheodda.SceneError as e:
            refused += 1
            # the key path, and the line and column of the dict's text (Scene.text)
            assert e.key and e.key in str(e) and e.line > 0 and e.column > 0, what + ": " + str(e)
            assert str(e).startswith("<dict>:{}:{}: ".format(e.line, e.column)), what + ": " + str(e)
            continue
        except rheodda.Error as e:  # a model the engine refuses (ModelError): names its key
            refused += 1
            assert isinstance(e, ValueError) and getattr(e, "key", None), what + ": " + str(e)
            continue
        loaded += 1
        if steps:
            try:
                sim.step(steps)
            except rheodda.RunError:
                continue
            assert all_finite(sim), what
    assert refused > 0 and loaded > 0


def test_mutated_law_parameters_and_forces_give_a_law_or_an_error_naming_the_key():
    rng = random.Random(0x1a3)
    made = refused = 0
    for entry in rheodda.laws():
        good = {p["name"]: p["default"] if p["default"] is not None else TABLE1.get(p["name"], 1.0)
                for p in entry["parameters"]}
        for i in range(25):
            params = dict(good)
            name = rng.choice(list(params) + ["nonsense"])
            if rng.randrange(4) == 0:
                params.pop(name, None)
            else:
                params[name] = rng.choice(VALUES)
            try:
                law = rheodda.law(entry["name"], params)
            except rheodda.LawError as e:
                refused += 1
                assert e.key and e.key in str(e), "{} {}: {}".format(entry["name"], params, e)
                continue
            except (TypeError, rheodda.Error):  # a value that is no number at all: pybind11's conversion
                refused += 1
                continue
            made += 1
            force = rng.choice([0.1, -0.1, 0.0, "0:0.1,1:0.2", [(0.0, 0.05), (2.0, 0.0)], "x", "1:", float("nan")])
            try:
                c = rheodda.creep_curve(law, force, t_end=4.0, dt=1.0, tolerance=1e-6)
            except (rheodda.Error, rheodda.RunError) as e:
                assert str(e), entry["name"]
                continue
            assert np.isfinite(c["displacement"]).all(), "{} {} {}".format(entry["name"], params, force)
    assert made > 0 and refused > 0


def test_a_non_finite_python_number_is_refused_with_its_key():
    for path, value in [(("analysis", "dt"), float("inf")), (("joint_sets", "plane", "friction_angle"), float("nan")),
                        (("loads", 1, "force", 0), -float("inf"))]:
        d = copy.deepcopy(SHEAR_TEST)
        target = d
        for k in path[:-1]:
            target = target[k]
        target[path[-1]] = value
        with pytest.raises(rheodda.SceneError) as e:
            rheodda.scene_from_dict(d)
        assert e.value.key.startswith(key_text(path[:-1]) if isinstance(path[-1], int) else key_text(path)), str(e.value)
