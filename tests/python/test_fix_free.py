"""Blocks fixed and freed in a dynamic run, velocities set between steps and blocks held in
chosen directions only (docs/guide/python.md, "Blocks"; docs/reference/engine.md, "Fixing and
freeing a moving block"): a fixed block stops and its kinetic energy is booked, a freed one
slides from rest a t^2/2, a set velocity carries a block v t, a block held in y only is pushed
F t^2/(2m) and one held in x only falls g t^2/2."""
import copy

import numpy as np
import pytest

import rheodda
from test_scripting import acceleration, incline, slid

G = 9.81  # m/s^2

STORED = ["energy_kinetic", "energy_strain", "energy_fixed", "energy_contact_normal", "energy_contact_shear"]
DISSIPATED = ["dissipation_friction", "dissipation_creep", "dissipation_integration", "dissipation_contact_damping",
              "dissipation_block_damping", "dissipation_contact_closing", "dissipation_contact_release",
              "dissipation_edits"]


def unbooked(h):
    """Change of the stored energy since t = 0 minus the net input and the summed residual, per row:
    zero to round-off when every change of the stored energy is booked (docs/reference/engine.md,
    "Energy balance") [J/m]."""
    stored = sum(h[c] for c in STORED)
    net = h["work_gravity"] + h["work_loads"] + h["work_contact_restart"] - sum(h[c] for c in DISSIPATED)
    return (stored - stored[0]) - net - h["energy_residual"]


def test_fixing_a_sliding_block_stops_it_and_books_its_kinetic_energy():
    sim = rheodda.Simulation(incline(20))
    block = sim.blocks["block"]
    sim.run(0.4)
    v = block.velocity
    kinetic = 0.5 * block.mass * (v[0] ** 2 + v[1] ** 2)  # it slides without turning
    assert kinetic > 100.0
    block.fix()
    assert np.array_equal(block.velocity, np.zeros(6))  # held at every vertex: no velocity admitted
    sim.run(0.6)
    h = sim.history()
    assert h["dissipation_edits"][-1] == pytest.approx(kinetic, rel=1e-9)
    assert h["energy_kinetic"][-1] < 1e-6 * kinetic  # the penalty springs' vibration only
    assert np.abs(unbooked(h)).max() < 1e-9 * kinetic


@pytest.mark.parametrize("held_steps", [100, 101])
def test_a_freed_block_slides_from_rest_whether_held_an_even_or_odd_number_of_steps(held_steps):
    sim = rheodda.Simulation(incline(20))
    block = sim.blocks["block"]
    sim.run(0.4)
    block.fix()
    sim.step(held_steps)
    block.free()
    assert np.array_equal(block.velocity, np.zeros(6))
    t_free, d_free = sim.time, slid(sim)
    sim.run(t_free + 0.4)
    assert slid(sim) - d_free == pytest.approx(acceleration(20) * 0.4 ** 2 / 2, rel=1e-6)
    assert np.abs(unbooked(sim.history())).max() < 1e-9 * block.mass * G


def plane(**blocks_fixed):
    """A 0.5 m x 0.25 m block resting on a fixed frictionless horizontal base (dynamic, dt 1 ms)."""
    return {
        "title": "Block on a frictionless plane",
        "units": {"length": "m", "force": "N", "time": "s"},
        "analysis": {"type": "dynamic", "duration": 1, "dt": 0.001, "output_interval": 0.1, "gravity": [0, -G]},
        "materials": {"rock": {"density": 2600, "young_modulus": 5.0e9, "poisson_ratio": 0.25}},
        "joint_sets": {"plane": {"friction_angle": 0}},
        "blocks": [
            {"name": "base", "rectangle": {"x": 0, "y": 0, "width": 10, "height": 1}, "fixed": True},
            {"name": "block", "rectangle": {"x": 4, "y": 1, "width": 0.5, "height": 0.25}},
        ],
    }


def test_a_velocity_set_carries_the_block_and_its_kinetic_energy_is_booked():
    sim = rheodda.Simulation(plane())
    block = sim.blocks["block"]
    sim.run(0.05)  # settled on the base
    x0 = block.position[0]
    block.velocity = (0.8, 0.0, 0.0)  # [m/s, m/s, rad/s]
    assert block.velocity[0] == 0.8 and block.velocity[2] == 0.0
    t0 = sim.time
    sim.run(t0 + 0.5)
    assert block.position[0] - x0 == pytest.approx(0.8 * 0.5, rel=1e-8)  # x = v t: no friction
    h = sim.history()
    assert h["dissipation_edits"][-1] == pytest.approx(-0.5 * block.mass * 0.8 ** 2, rel=1e-8)
    assert np.abs(unbooked(h)).max() < 1e-9 * block.mass * G
    with pytest.raises(rheodda.Error, match=r"expected \(vx, vy, omega\)"):
        block.velocity = (1.0, 0.0)
    block.fix(dofs=["y"])
    with pytest.raises(rheodda.ModelError, match=r"set_velocities\[0\]\.velocity: Block.velocity of block "
                                                 r"'block' \(1\): moves block 1 where its fixed points hold it"):
        block.velocity = (0.0, 1.0, 0.0)
    static = plane()
    static["analysis"]["type"] = "static"
    with pytest.raises(rheodda.ModelError, match="a static analysis carries no velocity"):
        rheodda.Simulation(static).blocks["block"].velocity = (1.0, 0.0, 0.0)


def test_a_block_held_in_y_only_is_pushed_along_the_plane_as_a_free_mass():
    sim = rheodda.Simulation(plane())
    block = sim.blocks["block"]
    sim.run(0.05)
    block.fix(dofs=["y"])  # one fixed point at the centroid, held in y: x and the rotation free
    m, force = block.mass, 200.0  # [kg/m], [N/m]
    x0, y0 = block.position
    block.add_load(block.position, force=(force, 0.0))
    t0 = sim.time
    sim.run(t0 + 0.4)
    assert block.position[0] - x0 == pytest.approx(force * 0.4 ** 2 / (2 * m), rel=1e-7)  # F t^2 / (2 m)
    assert abs(block.position[1] - y0) < 1e-9


def falling(hold):
    """A block in the air, no contacts, held in one direction by a scene's fixed point at its centre."""
    return {
        "title": "A falling block",
        "units": {"length": "m", "force": "N", "time": "s"},
        "analysis": {"type": "dynamic", "duration": 0.3, "dt": 0.001, "output_interval": 0.1, "gravity": [0, -G]},
        "materials": {"rock": {"density": 2600, "young_modulus": 5.0e9, "poisson_ratio": 0.25}},
        "joint_sets": {"joint": {"friction_angle": 30}},
        "blocks": [{"name": "rock", "rectangle": {"x": 0, "y": 10, "width": 1, "height": 0.5}}],
        "fixed_points": [{"point": [0.5, 10.25], "block": "rock", "hold": hold}],
    }


def test_a_block_held_in_x_only_falls_freely():
    sim = rheodda.Simulation(falling("x")).run()
    d = sim.blocks["rock"].point_displacement(0.5, 10.25)
    assert d[1] == pytest.approx(-G * 0.3 ** 2 / 2, rel=1e-9)  # g t^2 / 2
    assert abs(d[0]) < 1e-12
    # The same from Python: fix() of a free block in x only.
    scene = falling("x")
    del scene["fixed_points"]
    sim = rheodda.Simulation(scene)
    sim.blocks["rock"].fix(dofs="x")
    sim.run()
    assert sim.blocks["rock"].point_displacement(0.5, 10.25)[1] == pytest.approx(-G * 0.3 ** 2 / 2, rel=1e-9)
    held = rheodda.Simulation(falling("both")).run()
    assert np.abs(held.blocks["rock"].point_displacement(0.5, 10.25)).max() < 1e-6  # held: no fall


def test_hold_is_read_and_checked_as_the_loader_reads_other_keys():
    scene = rheodda.scene_from_dict(falling("y"))
    assert scene.fixed_points[0]["hold"] == "y"
    assert rheodda.scene_from_dict(copy.deepcopy(plane())).fixed_points == []
    with pytest.raises(rheodda.SceneError) as e:
        rheodda.scene_from_dict(falling("z"))
    assert e.value.key == "fixed_points[0].hold" and e.value.line > 0 and e.value.column > 0
    assert "'z'" in e.value.message and "both" in e.value.message
    sim = rheodda.Simulation(plane())
    with pytest.raises(rheodda.Error, match="rotation alone cannot be held"):
        sim.blocks["block"].fix(dofs=["rotation"])
    with pytest.raises(rheodda.Error, match="unknown 'z'"):
        sim.blocks["block"].fix(dofs=["z"])


def test_a_stage_holding_a_falling_block_in_y_stops_its_fall_and_leaves_it_sliding_in_x(tmp_path):
    # The block falls (g t^2/2) moving at 0.5 m/s in x; at t1 = 0.1 s a stage holds its centre in y
    # only: the fall stops, its kinetic energy in y, m (g t1)^2 / 2, is booked, and it goes on in x at
    # 0.5 m/s (x = 0.5 t throughout). A scene with stages runs with rheodda.run.
    t1, vx = 0.1, 0.5
    scene = falling("x")
    del scene["fixed_points"]
    scene["blocks"][0]["initial_velocity"] = [vx, 0.0, 0.0]
    scene["measurement_points"] = [{"name": "centre", "point": [0.5, 10.25], "block": "rock"}]
    y1 = 10.25 - G * t1 ** 2 / 2
    scene["stages"] = [{"name": "hold", "at": t1,
                        "add_fixed_points": [{"point": [0.5 + vx * t1, y1], "block": "rock", "hold": "y"}]}]
    assert rheodda.run(scene, str(tmp_path / "out"))["status"] == "completed"
    rows = [line.split(",") for line in (tmp_path / "out" / "history.csv").read_text().splitlines()
            if not line.startswith("#")]
    h = {name: np.array([float(r[k]) for r in rows[1:]]) for k, name in enumerate(rows[0]) if name != "stage"}
    assert h["centre.u"][-1] == pytest.approx(vx * 0.3, rel=1e-9)
    # held from t1 on, by a penalty spring: its deflection m g / p = 2.5e-8 m is 5e-7 of the fall
    assert h["centre.v"][-1] == pytest.approx(-G * t1 ** 2 / 2, rel=1e-6)
    mass = 2600 * 1.0 * 0.5  # density x area [kg/m]
    assert h["dissipation_edits"][-1] == pytest.approx(mass * (G * t1) ** 2 / 2, rel=1e-9)
    assert np.abs(unbooked(h)).max() < 1e-9 * mass * G  # history.csv's 10 digits
