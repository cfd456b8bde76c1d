"""Scenes from Python: a dict scene equals the YAML one, the per-step callback
changes loads, law parameters and step settings, the state as numpy arrays,
run() equals `rheodda run`, errors carry the command's messages, Ctrl-C."""
import copy
import json
import math
import os
import signal
import subprocess

import numpy as np
import pytest

import rheodda
from conftest import TABLE1

# examples/shear-creep-test.yaml as a dict (the seed's Table 1 row 1 shear creep test).
SHEAR_TEST = {
    "title": "Shear creep test, Table 1 row 1 (sigma = 1.408 MPa, tau = 0.232 MPa)",
    "units": {"length": "mm", "force": "N", "time": "h"},
    "analysis": {"type": "static", "duration": 200, "dt": 1, "output_interval": 2, "scheme": "implicit",
                 "gravity": [0, 0]},
    "materials": {"rock": {"density": 2.08e-16, "young_modulus": 20000, "poisson_ratio": 0.25}},
    "joint_sets": {"plane": {"friction_angle": 40, "law": dict(name="burgers", **TABLE1), "record": True}},
    "blocks": [
        {"name": "B", "rectangle": {"x": 0, "y": 0, "width": 100, "height": 50}, "fixed": True},
        {"name": "A", "rectangle": {"x": 20, "y": 50, "width": 60, "height": 30}},
    ],
    "loads": [
        {"point": [50, 80], "block": "A", "force": [0, -84.48]},
        {"point": [20, 65], "block": "A", "force": [13.92, 0]},
    ],
    "measurement_points": [{"name": "A_joint", "point": [50, 50], "block": "A"}],
}


def same(a, b):
    """Equal to the last digit, NaN where the other has NaN (rows without a closed contact)."""
    return set(a) == set(b) and all(np.array_equal(a[k], b[k], equal_nan=True) for k in a)


@pytest.fixture
def yaml_scene(root):
    return rheodda.load_scene(str(root / "examples" / "shear-creep-test.yaml"))


def test_dict_scene_gives_the_yaml_scene_history_to_the_last_digit(yaml_scene):
    from_yaml = rheodda.Simulation(yaml_scene).run().history()
    from_dict = rheodda.Simulation(SHEAR_TEST).run().history()
    assert len(from_yaml["time"]) == 201 and from_yaml["time"][-1] == 200.0
    assert same(from_yaml, from_dict)
    # the seed's result: the joint follows the Burgers closed form (docs/reference/outputs.md: 1.1e-5 relative)
    law = rheodda.law("burgers", TABLE1)
    d = -from_dict["plane.shear_displacement"][1:]
    exact = law.displacement_closed_form(0.232, from_dict["time"][1:])
    assert np.max(np.abs(d - exact) / exact) < 2e-5


def test_a_dict_scene_with_units_is_the_scene_in_bare_numbers(yaml_scene):
    # Values with units (docs/reference/scene-format.md, "Values with units") in a dict scene:
    # converted into its mm, N, h by factors exact in binary, the same run to the last digit.
    with_units = copy.deepcopy(SHEAR_TEST)
    with_units["analysis"]["duration"] = "12000 min"
    with_units["materials"]["rock"]["young_modulus"] = "20 GPa"
    with_units["loads"][0]["force"] = [0, "-84.48 N/mm"]
    with_units["blocks"][1]["rectangle"]["width"] = "6 cm"
    scene = rheodda.scene_from_dict(with_units)
    assert scene.duration == 200.0 and scene.materials["rock"]["young_modulus"] == 20000.0
    assert same(rheodda.Simulation(yaml_scene).run().history(), rheodda.Simulation(scene).run().history())
    wrong = copy.deepcopy(SHEAR_TEST)
    wrong["materials"]["rock"]["young_modulus"] = "20 GPa*s"
    with pytest.raises(rheodda.SceneError, match="has the wrong dimension") as e:
        rheodda.scene_from_dict(wrong)
    assert e.value.key == "materials.rock.young_modulus"


def test_scene_analysis_holds_every_declared_key_as_summary_json_does(yaml_scene, rheodda_binary, tmp_path):
    # The keys are declared once (scene/src/keys.cpp): `rheodda keys` lists them,
    # Scene.analysis and summary.json's inputs hold each with the same value.
    listed = subprocess.run([rheodda_binary, "keys"], capture_output=True, text=True, check=True).stdout
    declared = [line.split(" ", 1)[0] for line in listed.splitlines()]
    analysis = yaml_scene.analysis
    assert [k for k in declared if k.startswith("analysis.") and k.count(".") == 1] == [
        "analysis." + k for k in analysis
    ]
    assert analysis["dt"] == yaml_scene.dt and analysis["duration"] == yaml_scene.duration
    assert analysis["type"] == "static" and analysis["settle"] is None
    assert analysis["gravity"] == (0.0, 0.0)
    few_frames = copy.deepcopy(SHEAR_TEST)
    few_frames["analysis"]["output_interval"] = 100
    few_frames["analysis"]["settle"] = {"until": 1.0, "dt": 0.1}
    scene = rheodda.scene_from_dict(few_frames)
    path = tmp_path / "scene.yaml"
    path.write_text(scene.text)
    subprocess.run([rheodda_binary, "run", str(path), "-o", str(tmp_path / "out")], capture_output=True, check=True)
    inputs = json.loads((tmp_path / "out" / "summary.json").read_text())["inputs"]["analysis"]
    expected = {k: list(v) if isinstance(v, tuple) else v for k, v in scene.analysis.items()}
    assert inputs == expected
    assert scene.analysis["settle"]["until"] == 1.0 and scene.analysis["settle"]["type"] == "static"


def test_scene_materials_hold_every_declared_key(yaml_scene, rheodda_binary):
    # The materials' keys are declared once (scene/src/keys_joints.cpp): `rheodda keys
    # materials` lists them, Scene.materials holds each with its value, defaults filled in.
    listed = subprocess.run([rheodda_binary, "keys", "materials"], capture_output=True, text=True, check=True).stdout
    declared = [line.split(" ", 1)[0].removeprefix("materials.") for line in listed.splitlines()]
    rock = yaml_scene.materials["rock"]
    assert list(rock) == declared
    assert rock["young_modulus"] == 20000 and rock["poisson_ratio"] == 0.25
    assert rock["plane"] == "strain" and rock["damping_ratio"] is None


# The sections of summary.json's inputs (docs/reference/outputs.md, "summary.json") and how
# Scene exposes each: as written, or a list of named entries as a dict by name.
SECTIONS = ["joint_sets", "fixed_points", "loads", "bolts", "stages", "rock_mass", "water"]
NAMED = ["blocks", "measurement_points"]


def by_name(entries):
    return {e["name"]: e for e in entries}


@pytest.mark.parametrize("example", ["shear-creep-test.yaml", "bolted-block.yaml"])
def test_scene_sections_are_the_inputs_summary_json_writes(root, tmp_path, example):
    # Scene and summary.json take their inputs from one function (scene::scene_json_text):
    # every section with every key and value is the same in both.
    scene = rheodda.load_scene(str(root / "examples" / example))
    rheodda.run(scene, str(tmp_path / "out"))
    inputs = json.loads((tmp_path / "out" / "summary.json").read_text())["inputs"]
    assert scene.inputs == inputs
    for key in SECTIONS:
        assert getattr(scene, key) == inputs.get(key, {} if key == "joint_sets" else
                                                 None if key in ("rock_mass", "water") else []), key
    for key in NAMED:
        assert getattr(scene, key) == by_name(inputs[key]) and len(getattr(scene, key)) == len(inputs[key]), key
    assert set(scene.joint_sets) == set(inputs["joint_sets"]) and len(scene.joint_sets) > 0
    # each read is a fresh copy: changing one changes neither the scene nor the next read
    scene.inputs["title"] = "changed"
    scene.blocks[next(iter(scene.blocks))]["fixed"] = "changed"
    assert scene.inputs == inputs


def test_scene_sections_keep_the_names_they_listed(yaml_scene):
    # joint_sets, blocks and measurement_points were lists of names: iterating, `in` and len()
    # still give the names, in scene order.
    assert list(yaml_scene.blocks) == ["B", "A"] and "A" in yaml_scene.blocks and len(yaml_scene.blocks) == 2
    assert list(yaml_scene.joint_sets) == ["plane"]
    assert list(yaml_scene.measurement_points) == ["A_joint"]
    assert yaml_scene.blocks["A"]["material"] == "rock" and yaml_scene.blocks["B"]["fixed"] is True
    assert yaml_scene.measurement_points["A_joint"]["point"] == [50, 50]
    assert yaml_scene.joint_sets["plane"]["friction_angle"] == 40
    assert yaml_scene.loads[1]["block"] == "A" and len(yaml_scene.loads) == yaml_scene.load_count
    # a scene without water, bolts, stages or a rock mass
    assert yaml_scene.water is None and yaml_scene.rock_mass is None
    assert yaml_scene.bolts == [] and yaml_scene.stages == [] and yaml_scene.fixed_points == []


def test_scene_exposes_water_bolts_and_stages(root):
    # loaded only (not run): the sections hold what the scene files give
    tunnel = rheodda.load_scene(str(root / "examples" / "rockmass" / "tunnel-stages.yaml"))
    assert [s["name"] for s in tunnel.stages][:2] == ["heading", "bolt_heading"]
    assert len(tunnel.stages[1]["add_bolts"]) == 5  # the five bolts round the heading
    assert tunnel.water is None and tunnel.bolts == []
    bolted = rheodda.load_scene(str(root / "examples" / "bolted-block.yaml"))
    assert len(bolted.bolts) == 1 and bolted.stages == []
    reservoir = rheodda.load_scene(str(root / "examples" / "rockmass" / "reservoir-slope.yaml"))
    assert reservoir.water is not None and reservoir.water == reservoir.inputs["water"]
    assert reservoir.stages == [] and reservoir.bolts == []


def test_scene_exposes_its_rock_mass(root):
    # the rock mass's keys as the file gives them, names resolved, defaults filled in
    tunnel = rheodda.load_scene(str(root / "examples" / "rockmass" / "tunnel-stages.yaml"))
    r = tunnel.rock_mass
    assert r is not None and r == tunnel.inputs["rock_mass"]
    assert r["name"] == "rock" and r["material"] in tunnel.materials
    assert r["seed"] == 7 and r["sliver_area"] == 0.05 and r["boundary_joint_set"] == "frame"
    assert [g["joint_set"] for g in r["joint_sets"]] == ["bedding", "joints"]
    assert r["joint_sets"][0]["trace_length"] is None and r["joint_sets"][0]["origin"] == [0, 0]  # persistent
    assert r["joint_sets"][1]["trace_length"] == 5 and r["joint_sets"][1]["spacing_distribution"] == "normal"
    assert r["traces"][0] == {"joint_set": "excavation", "from": [15, 9], "to": [16.14805, 9.228361]}


def test_history_equals_rheodda_run(tmp_path):
    few_frames = copy.deepcopy(SHEAR_TEST)
    few_frames["analysis"]["output_interval"] = 50  # each frame is written and synced: keep the test fast
    few_frames["analysis"]["history"] = "steps"  # a row per step, as Simulation.history() keeps
    yaml_scene = rheodda.scene_from_dict(few_frames)
    result = rheodda.run(yaml_scene, str(tmp_path / "out"))
    assert result["status"] == "completed" and result["steps"] == 200
    # a static creep test that stands: summary.json's static_mechanism, no mechanism step
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert result["static_mechanism"] == summary["static_mechanism"]
    assert result["static_mechanism"]["steps"] == 0 and result["static_mechanism"]["inertia_share"] < 0.01
    assert result["static_mechanism"]["collapse_stages"] == []  # no settle.collapse_dt, no stage
    lines = [l for l in (tmp_path / "out" / "history.csv").read_text().splitlines() if not l.startswith("#")]
    header = lines[0].split(",")
    rows = [l.split(",") for l in lines[1:]]
    h = rheodda.Simulation(yaml_scene).run().history()
    assert list(h) == header and len(rows) == len(h["time"])
    for name in ("time", "A_joint.u", "A_joint.v", "plane.shear_displacement", "plane.shear_force",
                 "work_loads", "dissipation_creep"):
        column = np.array([float(r[header.index(name)] or "nan") for r in rows])
        # history.csv prints 10 significant digits
        np.testing.assert_allclose(h[name][1:], column[1:], rtol=1e-9, atol=0, err_msg=name)
    # By default history.csv has the rows of the output times (t = 0, 50, ..., 200 h): those same rows.
    del few_frames["analysis"]["history"]
    rheodda.run(rheodda.scene_from_dict(few_frames), str(tmp_path / "outputs"))
    lines = [l for l in (tmp_path / "outputs" / "history.csv").read_text().splitlines() if not l.startswith("#")]
    assert [l.split(",")[0] for l in lines[1:]] == ["0", "50", "100", "150", "200"]
    assert lines[1:] == [l for l in (tmp_path / "out" / "history.csv").read_text().splitlines()
                         if l.split(",")[0] in ("0", "50", "100", "150", "200")]


def test_callback_changing_a_load_mid_run_equals_the_load_history_from_the_start(yaml_scene):
    # F2 = 0.232 MPa x 60 mm until 100 h, then 0.424 MPa x 60 mm.
    def raise_load(sim, report):
        if report.time == 100.0:
            sim.set_load(1, (0.424 * 60, 0.0))

    changed = rheodda.Simulation(yaml_scene, callback=raise_load).run().history()
    staged = copy.deepcopy(SHEAR_TEST)
    # The engine takes a load's value at the end of each step: the step 100 -> 101 h gets the new one.
    staged["loads"][1] = {"point": [20, 65], "block": "A",
                          "history": [[0, 13.92, 0], [100, 13.92, 0], [101, 0.424 * 60, 0]]}
    reference = rheodda.Simulation(staged).run().history()
    for k in ("A_joint.u", "A_joint.v", "plane.shear_displacement", "plane.shear_force", "work_loads"):
        np.testing.assert_allclose(changed[k], reference[k], rtol=1e-12, atol=0, err_msg=k)
    # and the joint follows the staged closed form (Boltzmann superposition) as the constant load does
    # (but at t = 100 h itself, where the closed form has jumped and the engine applies the
    # new load over the step that ends at 101 h)
    law = rheodda.law("burgers", TABLE1)
    t = changed["time"][1:]
    exact = rheodda.exact_displacement(law, "0:0.232,100:0.424", t)
    d = -changed["plane.shear_displacement"][1:]
    assert np.max(np.abs(d - exact)[t != 100.0] / exact[t != 100.0]) < 2e-5
    assert d[-1] > 1.5 * law.displacement_closed_form(0.232, 200.0)  # the load did change


def test_callback_changing_law_parameters_and_dt(yaml_scene):
    slower = copy.deepcopy(SHEAR_TEST)
    slower["joint_sets"]["plane"]["law"]["eta1"] = 2 * TABLE1["eta1"]
    reference = rheodda.Simulation(slower).run().history()
    # before any step: the same as the scene with the parameter in it, to the last digit
    sim = rheodda.Simulation(yaml_scene)
    sim.set_law_parameters("plane", eta1=2 * TABLE1["eta1"])
    assert sim.law_parameters("plane")["eta1"] == 2 * TABLE1["eta1"]
    assert same(sim.run().history(), reference)

    # mid-run: the Maxwell dashpot creeps at tau/eta1, so doubling eta1 at 100 h takes
    # tau 100 h / (2 eta1) = 3.33e-4 mm off the displacement at 200 h
    def slow_down(sim, report):
        if report.time == 100.0:
            sim.set_law_parameters("plane", {"eta1": 2 * TABLE1["eta1"]})
            sim.set_settings(dt=0.5)

    base = rheodda.Simulation(yaml_scene).run().history()
    h = rheodda.Simulation(yaml_scene, callback=slow_down).run().history()
    assert np.array_equal(h["plane.shear_displacement"][:101], base["plane.shear_displacement"][:101],
                          equal_nan=True)
    assert np.all(h["dt"][1:101] == 1.0) and np.all(h["dt"][101:] == 0.5) and h["time"][-1] == 200.0
    change = base["plane.shear_displacement"][-1] - h["plane.shear_displacement"][-1]
    assert -change == pytest.approx(0.232 * 100 / (2 * TABLE1["eta1"]), rel=1e-3)


def test_state_as_numpy_arrays(yaml_scene):
    seen = []

    def look(sim, report):
        c = sim.contacts()
        seen.append((report.step, report.time, sim.time, len(c["id"])))

    sim = rheodda.Simulation(yaml_scene, callback=look)
    sim.step(5)
    assert [s[0] for s in seen] == [0, 1, 2, 3, 4] and sim.step_count == 5 and sim.time == 5.0
    assert all(s[1] == s[2] for s in seen)
    assert sim.block_positions.shape == (2, 2) and sim.block_stresses.shape == (2, 3)
    assert sim.block_velocities.shape == (2, 6) and not sim.block_velocities.any()  # static
    assert sim.block_vertices("A").shape == (4, 2)
    c = sim.contacts()
    assert len(c["id"]) == 2 and list(c["state"]) == ["locked", "locked"]
    assert sim.joint_sets[c["joint_set"][0]].name == "plane"
    # the joint's mean shear displacement in the history is the contacts' mean
    assert sim.history()["plane.shear_displacement"][-1] == pytest.approx(c["shear_displacement"].mean(), rel=1e-14)
    # each contact's creep displacement is the sum of its law's internal displacements
    np.testing.assert_allclose(c["creep_displacement"], c["q"].sum(axis=1), rtol=1e-14)
    # the measurement point's displacement, read from the block
    np.testing.assert_allclose(sim.point_displacement("A", 50, 50),
                               [sim.history()["A_joint.u"][-1], sim.history()["A_joint.v"][-1]], rtol=1e-14)
    frame = sim.history_frame()
    assert list(frame.columns) == sim.columns and len(frame) == 6


def test_errors_carry_the_command_line_messages(root, rheodda_binary, tmp_path):
    bad = copy.deepcopy(SHEAR_TEST)
    bad["joint_sets"]["plane"]["friction_angel"] = 40
    with pytest.raises(rheodda.SceneError) as e:
        rheodda.scene_from_dict(bad, file="bad-scene")
    assert e.value.key == "joint_sets.plane.friction_angel"
    assert "did you mean 'friction_angle'" in str(e.value)
    assert isinstance(e.value, rheodda.Error) and isinstance(e.value, ValueError)
    # the same text from a file: the message `rheodda check` prints, exit code 2
    path = tmp_path / "bad.yaml"
    path.write_text(rheodda.scene_from_dict.__globals__["_json"].dumps(bad, indent=1))
    with pytest.raises(rheodda.SceneError) as from_file:
        rheodda.load_scene(str(path))
    cli = subprocess.run([rheodda_binary, "check", str(path)], capture_output=True, text=True)
    assert cli.returncode == 2
    assert cli.stderr.strip() == "rheodda: error: " + str(from_file.value)
    assert str(from_file.value).startswith(str(path) + ":")
    with pytest.raises(rheodda.Error, match="joint set 'plain' is not in the scene \\(did you mean 'plane'\\?\\)"):
        rheodda.Simulation(SHEAR_TEST).set_law_parameters("plain", eta1=1.0)
    with pytest.raises(rheodda.LawError, match="eta1"):
        rheodda.Simulation(SHEAR_TEST).set_law_parameters("plane", eta1=-1.0)
    with pytest.raises(rheodda.ModelError, match="settings.dt"):
        rheodda.Simulation(SHEAR_TEST).set_settings(dt=-1.0)
    with pytest.raises(rheodda.Error, match="unknown setting 'dtt'"):
        rheodda.Simulation(SHEAR_TEST).set_settings(dtt=1.0)
    sim = rheodda.Simulation(SHEAR_TEST)
    assert sim.settings["solver_iterate_tolerance"] == 1e-4
    sim.set_settings(solver_iterate_tolerance=0.0)
    assert sim.settings["solver_iterate_tolerance"] == 0.0
    with pytest.raises(rheodda.ModelError, match="settings.solver_iterate_tolerance"):
        rheodda.Simulation(SHEAR_TEST).set_settings(solver_iterate_tolerance=1.0)
    with pytest.raises(rheodda.Error, match="load 5 does not exist"):
        rheodda.Simulation(SHEAR_TEST).set_load(5, (0.0, 0.0))
    # What the user gave is named, not the history set_load makes of it.
    with pytest.raises(rheodda.Error) as e:
        rheodda.Simulation(SHEAR_TEST).set_load(1, (math.nan, 0.0))
    assert str(e.value) == "set_load: load 1: force (nan, 0) must be finite [N]"
    with pytest.raises(rheodda.Error, match=r"set_load_history: load 1: samples\[1\]: time 0 does not follow 5"):
        rheodda.Simulation(SHEAR_TEST).set_load_history(1, [(5.0, 1.0, 0.0), (0.0, 2.0, 0.0)])


def test_a_run_to_a_time_already_passed_is_refused():
    sim = rheodda.Simulation(SHEAR_TEST)
    sim.run(until=10.0)
    with pytest.raises(rheodda.Error) as e:
        sim.run(until=5.0)
    assert str(e.value) == ("Simulation.run: until = 5 h lies before the simulation's time 10 h: a run goes forward "
                            "only (restore a saved state to go back)")
    with pytest.raises(rheodda.Error, match="until = nan is not a time"):
        sim.run(until=math.nan)
    assert sim.run(until=10.0).step_count == 10  # already there: nothing to do, no error


def test_an_exception_in_the_callback_stops_between_steps_and_the_run_can_go_on(yaml_scene):
    def fail_at_3(sim, report):
        if report.step == 2:
            raise ZeroDivisionError("stop here")

    sim = rheodda.Simulation(yaml_scene, callback=fail_at_3)
    with pytest.raises(ZeroDivisionError, match="stop here"):
        sim.run()
    assert sim.step_count == 3 and not sim.failed
    sim.callback = None
    assert same(sim.run().history(), rheodda.Simulation(yaml_scene).run().history())


@pytest.fixture
def sigint_raises():
    """Ctrl-C raises KeyboardInterrupt here even when the suite was started in the
    background of a non-interactive shell, which starts it with SIGINT ignored."""
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    yield
    signal.signal(signal.SIGINT, previous)


def test_ctrl_c_interrupts_between_steps(yaml_scene, sigint_raises):
    def interrupt_at_10(sim, report):
        if report.step == 9:
            os.kill(os.getpid(), signal.SIGINT)

    sim = rheodda.Simulation(yaml_scene, callback=interrupt_at_10)
    with pytest.raises(KeyboardInterrupt):
        sim.run()
    assert sim.step_count == 10 and sim.time == 10.0
    sim.callback = None
    assert same(sim.run().history(), rheodda.Simulation(yaml_scene).run().history())


def test_run_stops_on_ctrl_c_with_a_checkpoint(tmp_path, sigint_raises):
    import json
    import threading
    # 200 000 steps of the shear test (4.5 s here), interrupted after 0.3 s
    long = copy.deepcopy(SHEAR_TEST)
    long["analysis"].update(dt=0.001, output_interval=20)
    scene = rheodda.scene_from_dict(long)
    timer = threading.Timer(0.3, os.kill, (os.getpid(), signal.SIGINT))
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            rheodda.run(scene, str(tmp_path / "out"))
    finally:
        timer.cancel()
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert summary["status"] == "interrupted" and 0 < summary["steps"] < 200000
    assert (tmp_path / "out" / "checkpoint.json").exists()


def test_long_calls_release_the_gil(yaml_scene, tmp_path):
    import threading
    import time
    # Another Python thread runs while the engine steps (it could not if the GIL were held).
    count = {"n": 0}
    stop = threading.Event()

    def spin():
        while not stop.is_set():
            count["n"] += 1
            time.sleep(0)

    fine = copy.deepcopy(SHEAR_TEST)
    fine["analysis"].update(dt=0.02, output_interval=200)   # 10 000 steps
    sim = rheodda.Simulation(fine)
    thread = threading.Thread(target=spin)
    thread.start()
    try:
        sim.run()
    finally:
        stop.set()
        thread.join()
    assert sim.step_count == 10000
    assert count["n"] > 100


def test_the_callback_cannot_step_the_simulation(yaml_scene):
    def nested(sim, report):
        sim.step()

    sim = rheodda.Simulation(yaml_scene, callback=nested)
    with pytest.raises(rheodda.Error, match="cannot be called from the step callback"):
        sim.step(3)
    assert sim.step_count == 1 and not sim.failed


def test_dict_scene_takes_numpy_values():
    d = copy.deepcopy(SHEAR_TEST)
    d["analysis"]["duration"] = np.float64(20.0)
    d["analysis"]["gravity"] = np.zeros(2)
    d["loads"][1]["force"] = np.array([13.92, 0.0])
    d["materials"]["rock"]["young_modulus"] = np.int64(20000)
    short = copy.deepcopy(SHEAR_TEST)
    short["analysis"]["duration"] = 20
    assert same(rheodda.Simulation(d).run().history(), rheodda.Simulation(short).run().history())
    d["analysis"]["dt"] = float("nan")
    with pytest.raises(rheodda.SceneError) as e:
        rheodda.scene_from_dict(d)
    assert e.value.key == "analysis.dt"


def test_a_failing_run_raises_run_error_with_the_command_line_message(rheodda_binary, tmp_path):
    # max_displacement_ratio w0 ~ 0 and no cuts allowed: the first step cannot be accepted.
    d = copy.deepcopy(SHEAR_TEST)
    d["analysis"].update(max_displacement_ratio=1e-9, max_cuts=0)
    scene = rheodda.scene_from_dict(d)
    sim = rheodda.Simulation(scene)
    with pytest.raises(rheodda.RunError) as from_sim:
        sim.run()
    assert sim.failed and isinstance(from_sim.value, RuntimeError)
    assert str(from_sim.value).startswith("run failed at t = 0 h (step 0): ")
    with pytest.raises(rheodda.RunError) as from_run:
        rheodda.run(scene, str(tmp_path / "py"))
    path = tmp_path / "scene.yaml"
    path.write_text(scene.text)
    cli = subprocess.run([rheodda_binary, "run", str(path), "-o", str(tmp_path / "cli")],
                         capture_output=True, text=True)
    assert cli.returncode == 1
    assert cli.stderr.strip().endswith("rheodda: error: " + str(from_run.value))
    assert str(from_run.value) == str(from_sim.value)


def test_residual_strength_keys_from_a_dict():
    # joint_sets.*.residual_friction_angle / residual_cohesion (docs/reference/scene-format.md): read as
    # from a file, refused above the peak with the key path.
    d = copy.deepcopy(SHEAR_TEST)
    d["joint_sets"]["plane"].update(residual_friction_angle=30, cohesion=0.1, residual_cohesion=0.05)
    assert "residual_friction_angle 30 deg, residual_cohesion 0.05" in rheodda.scene_from_dict(d).describe()
    d["joint_sets"]["plane"]["residual_friction_angle"] = 45
    with pytest.raises(rheodda.SceneError) as e:
        rheodda.scene_from_dict(d)
    assert e.value.key == "joint_sets.plane.residual_friction_angle" and "peak friction_angle 40" in str(e.value)
