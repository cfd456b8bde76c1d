"""The scripting API of rheodda.Simulation (docs/guide/python.md, "Scripting"): blocks as
objects and read-only arrays, blocks fixed, freed, removed and loaded between steps, joint
sets changed between steps (a block on an incline against the closed form of its
acceleration), callbacks with a period, save/restore bit for bit, pickling and a
multiprocessing sweep, and rheodda.run of a dict or a path."""
import copy
import math
import multiprocessing
import pickle

import numpy as np
import pytest

import rheodda
from conftest import TABLE1
from test_python_law import PythonMaxwell
from test_scene import SHEAR_TEST, same

G = 9.81  # m/s^2, the scene's gravity

# examples/sliding-block.yaml: a 1 m x 0.5 m block on a fixed 30 deg incline (dynamic, dt 1 ms).
INCLINE = {
    "title": "Block on a 30 deg incline",
    "units": {"length": "m", "force": "N", "time": "s"},
    "analysis": {"type": "dynamic", "duration": 1, "dt": 0.001, "output_interval": 0.02, "gravity": [0, -G]},
    "materials": {"rock": {"density": 2600, "young_modulus": 5.0e9, "poisson_ratio": 0.25}},
    "joint_sets": {"slope": {"friction_angle": 40, "record": True}},
    "blocks": [
        {"name": "base", "polygon": [[0, 0], [10, 0], [10, 5.773502692]], "fixed": True},
        {"name": "block", "rectangle": {"x": 5.196152423, "y": 3.0, "width": 1, "height": 0.5, "angle": 30}},
    ],
    "measurement_points": [{"name": "centre", "point": [5.504165125, 3.466506351], "block": "block"}],
}
DOWN_SLOPE = np.array([-math.cos(math.radians(30)), -math.sin(math.radians(30))])


def incline(friction=40.0):
    scene = copy.deepcopy(INCLINE)
    scene["joint_sets"]["slope"]["friction_angle"] = friction
    return scene


def slid(sim):
    """The block's centre displacement down the slope since t = 0 [m]."""
    return float(sim.blocks["block"].point_displacement(5.504165125, 3.466506351) @ DOWN_SLOPE)


def acceleration(friction_deg):
    """a = g (sin 30 - cos 30 tan phi): a block sliding on a 30 deg incline (Goodman 1976, Methods of
    Geological Engineering, ch. 3; the check of examples/sliding-block.yaml) [m/s^2]."""
    a = math.radians(30)
    return G * (math.sin(a) - math.cos(a) * math.tan(math.radians(friction_deg)))


def shoelace(v):
    """Area of a polygon from its vertices (the shoelace formula) [length^2]."""
    x, y = v[:, 0], v[:, 1]
    return 0.5 * abs(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))


def affine_map(before, after):
    """The affine map x = F x0 + b taking `before` vertices to `after` ones (least squares)."""
    a = np.hstack([before, np.ones((len(before), 1))])
    m, *_ = np.linalg.lstsq(a, after, rcond=None)
    return m[:2].T


# --- blocks -----------------------------------------------------------------------

def test_blocks_are_objects_and_read_only_arrays_of_the_state():
    sim = rheodda.Simulation(incline(20))
    blocks = sim.blocks
    assert len(blocks) == 2 and blocks.names == ["base", "block"]
    assert [b.name for b in blocks] == ["base", "block"] and blocks[1] == blocks["block"] == blocks[-1]
    base, block = blocks
    assert base.fixed and not block.fixed and not block.removed
    assert list(blocks.fixed) == [True, False] and list(blocks.removed) == [False, False]
    # area by the shoelace formula of the vertices, mass = density x area (per unit thickness)
    assert block.area == pytest.approx(0.5, rel=1e-9) and base.area == pytest.approx(10 * 5.773502692 / 2, rel=1e-9)
    np.testing.assert_allclose(blocks.area, [shoelace(b.vertices) for b in blocks], rtol=1e-12)
    np.testing.assert_allclose(blocks.mass, 2600 * blocks.area, rtol=1e-15)
    np.testing.assert_allclose(blocks.position[1], block.vertices.mean(axis=0), rtol=1e-12)  # a rectangle
    assert "block" in repr(block) and "fixed" in repr(base) and "2 blocks" in repr(blocks)
    for name in ("position", "centroid", "rotation", "velocity", "strain", "stress", "area", "mass", "fixed",
                 "removed"):
        view = getattr(blocks, name)
        assert view.shape[0] == 2 and not view.flags.writeable, name
        with pytest.raises(ValueError):
            view[0] = 0
    assert blocks.velocity.shape == (2, 6) and blocks.stress.shape == (2, 3) and blocks.strain.shape == (2, 3)
    with pytest.raises(IndexError):
        blocks[2]
    with pytest.raises(rheodda.Error, match="block 'blok' is not in the scene"):
        blocks["blok"]
    # the old names still read the same arrays
    assert np.array_equal(sim.block_positions, blocks.position)
    start = block.vertices
    sim.run(0.3)
    # rotation and strain against the affine map fitted to the vertices (an independent route)
    f = affine_map(start, block.vertices)
    assert block.rotation == pytest.approx(math.atan2(f[1, 0] - f[0, 1], f[0, 0] + f[1, 1]), abs=1e-12)
    e = 0.5 * (f.T @ f - np.eye(2))
    np.testing.assert_allclose(block.strain, [e[0, 0], e[1, 1], 2 * e[0, 1]], atol=1e-12)
    # the block slides: its centroid velocity along the slope is a t
    v = block.velocity[:2] @ DOWN_SLOPE
    assert v == pytest.approx(acceleration(20) * 0.3, rel=1e-4)
    assert np.array_equal(blocks.velocity[1], block.velocity)


def test_a_spinning_block_rotates_by_omega_t_without_strain():
    scene = {
        "title": "A free block spinning", "units": {"length": "m", "force": "N", "time": "s"},
        "analysis": {"type": "dynamic", "duration": 1, "dt": 0.001, "gravity": [0, 0]},
        "materials": {"rock": {"density": 2600, "young_modulus": 5.0e9, "poisson_ratio": 0.25}},
        "joint_sets": {"j": {"friction_angle": 30}},
        "blocks": [{"name": "spin", "rectangle": {"x": 0, "y": 0, "width": 1, "height": 1},
                    "initial_velocity": [0, 0, 0.5]}],
    }
    sim = rheodda.Simulation(scene).run(0.5)
    b = sim.blocks["spin"]
    f = affine_map(np.array([[0, 0], [1, 0], [1, 1], [0, 1]], float), b.vertices)
    assert b.rotation == pytest.approx(math.atan2(f[1, 0] - f[0, 1], f[0, 0] + f[1, 1]), abs=1e-12)
    assert b.rotation == pytest.approx(0.5 * 0.5, rel=1e-12)  # omega t [rad]
    assert np.all(np.abs(b.strain) < 1e-12)


def test_the_explicit_cycle_of_each_block_has_the_scenes_at_its_minimum():
    scene = incline()
    scene["analysis"]["integrator"] = "explicit"
    sim = rheodda.Simulation(scene)
    cycle, block = sim.stable_cycle()
    h = sim.block_cycles()
    assert h.shape == (2,)
    assert math.isinf(h[0])  # the fixed base has no cycle
    assert block == 1 and h[1] == cycle
    assert 0.0 < cycle < 1e-3  # s: the scene's 1 ms steps take several cycles
    assert not sim.in_stage  # a dynamic analysis has no stages


def test_blocks_are_fixed_freed_removed_and_loaded_between_steps():
    sim = rheodda.Simulation(incline(20))
    base, block = sim.blocks
    sim.run(0.1)
    block.fix()
    assert block.fixed and sim.blocks.fixed.all()
    held = slid(sim)
    sim.run(0.3)
    assert abs(slid(sim) - held) < 1e-6  # held by its fixed points (it slid 9 mm by t = 0.1 s)
    block.free()
    assert not block.fixed
    sim.run(0.4)
    assert slid(sim) > held + 1e-3
    with pytest.raises(rheodda.Error, match="Block.free of block 'block' \\(1\\): the block has no fixed point"):
        block.free()
    with pytest.raises(rheodda.ModelError, match="would leave no fixed point"):
        base.free()
    with pytest.raises(rheodda.ModelError, match=r"add_loads\[0\].point: .*lies outside block 1 where it stands now"):
        block.add_load((100, 100), force=(0, -1))
    with pytest.raises(rheodda.Error, match="give force=.* or history="):
        block.add_load(block.position)

    # a load F down the slope adds F / m to the acceleration (Newton's second law)
    sim = rheodda.Simulation(incline(20))
    block = sim.blocks["block"]
    m = block.mass
    force = 0.5 * m * acceleration(20) * DOWN_SLOPE
    load = block.add_load(block.position, force=force)
    assert load.index == 0 and len(sim.loads) == 1 and not load.removed
    sim.run(0.4)
    assert slid(sim) == pytest.approx(1.5 * acceleration(20) * 0.4 ** 2 / 2, rel=1e-4)
    load.remove()
    assert load.removed and load.index is None and sim.loads == []
    with pytest.raises(rheodda.Error, match="not in the model any more"):
        load.remove()

    block.remove()
    assert block.removed and list(sim.blocks.removed) == [False, True]
    assert len(sim.contacts) == 0
    with pytest.raises(rheodda.ModelError, match="would remove every block of the model"):
        sim.blocks["base"].remove()
    with pytest.raises(rheodda.ModelError, match="was removed before"):
        block.remove()
    # a removed block stays removed when a step setting builds a new engine, frozen where it was
    where = block.vertices
    sim.set_settings(dt=0.002)
    sim.run(0.5)
    assert block.removed and np.array_equal(block.vertices, where) and not block.velocity.any()
    assert "removed" in repr(block)


def test_every_step_setting_is_set_and_read_back_by_its_scene_name():
    # Simulation.set_settings and Simulation.settings read one list of the core's settings,
    # each by its scene name (python/src/simulation.cpp, step_settings and step_choices): every one set reads back
    # exactly, of its own type; an unknown name is refused with the valid ones.
    sim = rheodda.Simulation(SHEAR_TEST)
    before = sim.settings
    wanted = {}
    for name, value in before.items():
        if isinstance(value, str):  # a choice (`solver`, `contact_solver`): another of its words
            with pytest.raises(rheodda.Error, match="is not one of: ") as refused:
                sim.set_settings(**{name: "nonesuch"})
            words = str(refused.value).split("is not one of: ")[1].split(", ")
            wanted[name] = next(w for w in words if w != value)
        elif isinstance(value, bool):
            wanted[name] = value  # a flag: set as it is (its partner settings are not changed)
        elif isinstance(value, int):
            wanted[name] = value + 1
        else:
            wanted[name] = value * 2 if value else value
    sim.set_settings(**wanted)
    after = sim.settings
    assert after == wanted
    assert all(type(after[k]) is type(before[k]) for k in before)
    assert all(after[k] != before[k] for k in before if before[k] and not isinstance(before[k], bool))
    with pytest.raises(rheodda.Error, match="unknown setting 'max_displacment_ratio'; valid: dt, "):
        sim.set_settings(max_displacment_ratio=0.01)


def test_loads_of_the_scene_are_removed_by_their_handles_and_the_indices_follow():
    sim = rheodda.Simulation(SHEAR_TEST)
    assert len(sim.loads) == 2
    sim.load(0).remove()
    assert len(sim.loads) == 1 and sim.loads[0][0, 1] == 13.92  # the second load is index 0 now
    with pytest.raises(rheodda.Error, match="load 1 does not exist"):
        sim.load(1)


# --- contacts ------------------------------------------------------------------------

def test_contacts_are_an_object_of_read_only_columns_and_stay_callable():
    sim = rheodda.Simulation(SHEAR_TEST).step(3)
    c = sim.contacts
    assert len(c) == 2 and "2 contacts" in repr(c)
    assert isinstance(c.state, np.ndarray) and list(c.state) == ["locked", "locked"]
    assert isinstance(c["kind"], np.ndarray) and c.kind.dtype.kind == "U"
    assert np.array_equal(c.normal_force, c["normal_force"]) and not c.normal_force.flags.writeable
    old = sim.contacts()  # the dict it was
    assert isinstance(old, dict) and set(old) == set(c.columns) and np.array_equal(old["x"], c.x)
    assert sim.joint_sets[c.joint_set[0]].name == "plane"
    # the normal forces carry the vertical load: 84.48 N over the two contacts
    assert c.normal_force.sum() == pytest.approx(84.48, rel=1e-6)
    with pytest.raises(AttributeError, match="no column 'nromal_force'"):
        c.nromal_force
    assert len(sim.bolts) == 0


def test_bolts_are_read_only_columns_and_the_bolt_carries_what_friction_cannot(root):
    sim = rheodda.Simulation(root / "examples" / "bolted-block.yaml").run()
    bolts = sim.bolts
    assert len(bolts) == 1 and list(bolts.name) == ["anchor"] and list(bolts.state) == ["elastic"]
    assert not bolts.force.flags.writeable and "1 bolts" in repr(bolts)
    # N = W (sin 30 - cos 30 tan 20) with W = m g (docs/reference/bolts.md, "Closed forms"),
    # the elongation N / k with k = 1e7 N/m (the scene's axial_stiffness)
    n = sim.blocks["block"].mass * G * (math.sin(math.radians(30)) - math.cos(math.radians(30))
                                        * math.tan(math.radians(20)))
    assert bolts.force[0] == pytest.approx(n, rel=1e-6)
    assert bolts.elongation[0] == pytest.approx(n / 1.0e7, rel=1e-6)
    assert bolts.rupture_time[0] == -1


# --- joint sets ------------------------------------------------------------------------

def test_lowering_the_friction_between_steps_lets_the_block_slide_with_the_closed_form_acceleration():
    sim = rheodda.Simulation(incline(40))  # tan 40 > tan 30: held
    slope = sim.joint_sets["slope"]
    assert slope.friction_angle == 40 and slope.cohesion == 0 and slope.law is None and slope.index == 0
    sim.run(0.15)
    assert abs(slid(sim)) < 1e-5
    changed = []

    def weaken(sim, report):
        sim.joint_sets["slope"].friction_angle = 20  # from a callback: between two steps
        changed.append((report.time, slid(sim)))
        probe.remove()

    probe = sim.add_callback(weaken, time=0.05)  # after the first step reaching t = 0.2 s
    sim.run(1.0)
    assert sim.joint_sets[0].friction_angle == 20 and len(changed) == 1
    t0, start = changed[0]
    assert t0 == pytest.approx(0.2, abs=1e-9)
    d = slid(sim) - start
    assert d == pytest.approx(acceleration(20) * (1.0 - t0) ** 2 / 2, rel=1e-4)
    assert "friction_angle 20 deg" in repr(sim.joint_sets["slope"])


@pytest.mark.parametrize("key,value", [("friction_angle", 95.0), ("friction_angle", -1.0), ("cohesion", -2.0),
                                       ("tensile_strength", float("nan")), ("friction_angle", True)])
def test_a_joint_set_setter_refuses_a_value_with_the_loaders_key_and_message(key, value):
    bad = incline(40)
    bad["joint_sets"]["slope"][key] = value
    with pytest.raises(rheodda.SceneError) as loader:
        rheodda.scene_from_dict(bad)
    sim = rheodda.Simulation(incline(40))
    with pytest.raises(rheodda.ModelError) as setter:
        setattr(sim.joint_sets["slope"], key, value)
    assert setter.value.key == loader.value.key == "joint_sets.slope." + key
    assert str(setter.value) == "{}: {}".format(loader.value.key, loader.value.message)
    assert sim.joint_sets["slope"].friction_angle == 40  # unchanged


def test_joint_set_values_change_together_and_laws_keep_their_checks():
    sim = rheodda.Simulation(SHEAR_TEST)
    plane = sim.joint_sets["plane"]
    plane.set(cohesion=0.1, tensile_strength=0.05, residual_cohesion=0.02)
    assert (plane.cohesion, plane.tensile_strength, plane.residual_cohesion) == (0.1, 0.05, 0.02)
    with pytest.raises(rheodda.ModelError) as setter:
        plane.residual_friction_angle = 45.0  # above the peak friction angle 40
    # the loader's message for the same value in a scene file: key, shortest numbers
    scene = copy.deepcopy(SHEAR_TEST)
    scene["joint_sets"]["plane"]["residual_friction_angle"] = 45.0
    with pytest.raises(rheodda.SceneError) as loader:
        rheodda.scene_from_dict(scene)
    assert str(setter.value) == "{}: {}".format(loader.value.key, loader.value.message) == (
        "joint_sets.plane.residual_friction_angle: 45 deg is above the peak friction_angle 40 deg: a residual "
        "strength is at most the peak")
    with pytest.raises(rheodda.ModelError, match="joint_sets.plane.frction_angle"):
        plane.set(frction_angle=20)
    assert plane.law == "burgers" and plane.law_parameters == TABLE1
    plane.law_parameters = {"eta1": 2 * TABLE1["eta1"]}
    assert sim.law_parameters("plane")["eta1"] == 2 * TABLE1["eta1"] and plane.law_parameters["E1"] == TABLE1["E1"]
    with pytest.raises(rheodda.LawError, match="eta1"):
        plane.law_parameters = {"eta1": -1.0}
    with pytest.raises(AttributeError):
        plane.law = "maxwell"
    assert len(sim.joint_sets) == 1 and sim.joint_sets.names == ["plane"]


# --- callbacks ---------------------------------------------------------------------------

def test_callbacks_run_every_n_steps_or_after_each_period_of_simulated_time():
    calls = {"main": [], "three": [], "time": []}
    sim = rheodda.Simulation(SHEAR_TEST, callback=lambda s, r: calls["main"].append(r.step), every_steps=4)
    sim.add_callback(lambda s, r: calls["three"].append(s.step_count), steps=3)
    c = sim.add_callback(lambda s, r: calls["time"].append(r.time), time=2.5)
    sim.run(20.0)  # dt = 1 h
    assert calls["main"] == [3, 7, 11, 15, 19]
    assert calls["three"] == [3, 6, 9, 12, 15, 18]
    # the first step reaching each multiple of 2.5 h (the steps are not shortened to land on them)
    times = np.arange(1.0, 21.0)
    expected = [t for t in times if math.floor(t / 2.5) > math.floor((t - 1) / 2.5)]
    assert calls["time"] == expected == [3.0, 5.0, 8.0, 10.0, 13.0, 15.0, 18.0, 20.0]
    c.remove()
    sim.step(5)
    assert len(calls["time"]) == 8 and calls["three"][-1] == 24
    # periods counted from when the callback was added; history unchanged by callbacks
    late = []
    sim.add_callback(lambda s, r: late.append(r.time), time=10)
    sim.run(50)
    assert late == [35.0, 45.0]
    assert same(sim.history(), rheodda.Simulation(SHEAR_TEST).run(50).history())
    with pytest.raises(rheodda.Error, match="not both"):
        sim.add_callback(print, steps=2, time=1.0)
    with pytest.raises(rheodda.Error, match="steps=0"):
        sim.add_callback(print, steps=0)
    with pytest.raises(rheodda.Error, match="positive finite period"):
        sim.add_callback(print, time=-1)
    with pytest.raises(rheodda.Error, match="callback=, which is missing"):
        rheodda.Simulation(SHEAR_TEST, every_steps=2)


# --- save and restore ---------------------------------------------------------------------

def changed_incline():
    """The incline with changes of every kind logged: friction, a load, a block fixed and freed,
    a step setting."""
    sim = rheodda.Simulation(incline(40))
    sim.run(0.05)
    sim.joint_sets["slope"].friction_angle = 25
    block = sim.blocks["block"]
    load = block.add_load(block.position, history=[(0, 0, 0), (0.1, -50, -20)])
    sim.run(0.1)
    block.fix()
    sim.run(0.12)
    block.free()
    sim.set_settings(dt=0.0005)
    sim.run(0.15)
    load.remove()
    return sim


def final_state(sim):
    return {"history": sim.history(), "position": sim.blocks.position, "velocity": sim.blocks.velocity,
            "stress": sim.blocks.stress, "contacts": sim.contacts(), "time": sim.time, "steps": sim.step_count}


def same_columns(a, b):
    """Equal columns to the last digit (NaN where the other has NaN, for numbers)."""
    return set(a) == set(b) and all(np.array_equal(a[k], b[k], equal_nan=a[k].dtype.kind == "f") for k in a)


def equal_states(a, b):
    assert a["time"] == b["time"] and a["steps"] == b["steps"]
    assert same(a["history"], b["history"]) and same_columns(a["contacts"], b["contacts"])
    for k in ("position", "velocity", "stress"):
        assert np.array_equal(a[k], b[k]), k


def test_a_restored_simulation_continues_bit_for_bit(tmp_path):
    sim = changed_incline()
    state = sim.save()
    assert state.step_count == sim.step_count and state.time == sim.time and "bytes" in repr(state)
    sim.run(0.3)
    straight = final_state(sim)
    again = rheodda.Simulation.restore(state)
    assert again.time == state.time and same(again.history(), {k: v[: state.step_count + 1]
                                                                 for k, v in straight["history"].items()})
    equal_states(final_state(again.run(0.3)), straight)
    # through a file, and through the bytes
    path = tmp_path / "incline.state"
    changed_incline().save(path)
    equal_states(final_state(rheodda.Simulation.restore(path).run(0.3)), straight)
    equal_states(final_state(rheodda.Simulation.restore(state.data).run(0.3)), straight)
    # the laws given at construction come back with the state
    laws = {"plane": rheodda.law("burgers", dict(TABLE1, eta2=2 * TABLE1["eta2"]))}
    a = rheodda.Simulation(SHEAR_TEST, laws=laws).run(50)
    b = rheodda.Simulation.restore(a.save())
    assert b.law_parameters("plane")["eta2"] == 2 * TABLE1["eta2"]
    assert same(a.run(100).history(), b.run(100).history())
    with pytest.raises(rheodda.Error, match="not a saved simulation"):
        rheodda.Simulation.restore(b"not a state")


def test_a_state_with_a_law_written_in_python_keeps_it_in_memory_not_in_a_file(tmp_path):
    law = PythonMaxwell(TABLE1["E1"], TABLE1["eta1"])
    a = rheodda.Simulation(SHEAR_TEST, laws={"plane": law}).run(50)
    state = a.save()
    assert state.laws == {"plane": law}
    b = rheodda.Simulation.restore(state)
    assert same(a.run(100).history(), b.run(100).history())
    with pytest.raises(rheodda.Error, match="laws written in Python .*plane.*which a file cannot hold"):
        a.save(tmp_path / "x.state")
    with pytest.raises(rheodda.Error, match="joint set 'plane' had a law written in Python"):
        rheodda.Simulation.restore(state.data)
    c = rheodda.Simulation.restore(state.data, laws={"plane": law})
    assert same(c.run(100).history(), b.history())


def test_what_if_branches_from_one_settled_state():
    settled = rheodda.Simulation(incline(40)).run(0.2)
    state = settled.save()
    ends = {}
    for friction in (40, 25, 20):
        branch = rheodda.Simulation.restore(state)
        start = slid(branch)
        branch.joint_sets["slope"].friction_angle = friction
        ends[friction] = slid(branch.run(0.6)) - start
    assert abs(ends[40]) < 1e-5
    assert ends[20] == pytest.approx(acceleration(20) * 0.4 ** 2 / 2, rel=1e-4)
    assert ends[25] == pytest.approx(acceleration(25) * 0.4 ** 2 / 2, rel=1e-4)
    # the settled simulation itself is untouched by its branches
    assert settled.time == 0.2 and settled.joint_sets["slope"].friction_angle == 40


def test_laws_scenes_and_simulations_pickle_and_copy():
    law = rheodda.law("burgers", TABLE1)
    back = pickle.loads(pickle.dumps(law))
    assert back.name == "burgers" and back.parameters == law.parameters
    assert copy.deepcopy(law).parameters == TABLE1
    scene = rheodda.scene_from_dict(SHEAR_TEST)
    s2 = pickle.loads(pickle.dumps(scene))
    assert s2.text == scene.text and s2.file == scene.file and s2.blocks == scene.blocks

    class Mine(rheodda.PythonLaw):
        pass

    with pytest.raises(TypeError, match="cannot pickle the law written in Python"):
        pickle.dumps(Mine("mine", {"eta": 1.0}))

    sim = changed_incline()
    twin = pickle.loads(pickle.dumps(sim))
    clone = copy.deepcopy(sim)
    straight = final_state(sim.run(0.3))
    equal_states(final_state(twin.run(0.3)), straight)
    equal_states(final_state(clone.run(0.3)), straight)


def slide_with_friction(args):
    state, friction = args
    sim = rheodda.Simulation.restore(state)
    start = slid(sim)
    sim.joint_sets["slope"].friction_angle = friction
    return slid(sim.run(0.5)) - start


def test_a_friction_sweep_over_two_processes_equals_the_serial_one():
    state = rheodda.Simulation(incline(40)).run(0.2).save()
    cases = [(state, phi) for phi in (35, 25, 20, 15)]
    with multiprocessing.get_context("fork").Pool(2) as pool:
        parallel = pool.map(slide_with_friction, cases)
    assert parallel == [slide_with_friction(c) for c in cases]
    assert parallel[0] < 1e-5 < parallel[1] < parallel[2] < parallel[3]


# --- run --------------------------------------------------------------------------------------

def test_run_accepts_what_simulation_accepts(tmp_path, root):
    from_dict = rheodda.run(SHEAR_TEST, tmp_path / "dict")
    from_path = rheodda.run(root / "examples" / "shear-creep-test.yaml", str(tmp_path / "path"))
    from_scene = rheodda.run(rheodda.scene_from_dict(SHEAR_TEST), tmp_path / "scene")
    assert from_dict["status"] == from_path["status"] == from_scene["status"] == "completed"
    assert from_dict["steps"] == from_path["steps"] == from_scene["steps"] == 200
    assert (tmp_path / "dict" / "history.csv").read_text() == (tmp_path / "scene" / "history.csv").read_text()
    with pytest.raises(TypeError, match="a scene is a rheodda.Scene, a path or a dict"):
        rheodda.run(42, tmp_path / "x")


def test_a_scene_with_stages_is_refused_not_run_without_them(root):
    with pytest.raises(ValueError, match="a scene with stages runs with `rheodda run`; Simulation does not apply"):
        rheodda.Simulation(root / "examples" / "excavation-stages.yaml")
