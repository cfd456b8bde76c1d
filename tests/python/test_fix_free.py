"""Blocks fixed and freed in a dynamic run, velocities set between steps and blocks held in
chosen directions only (docs/guide/python.md, "Blocks"; docs/reference/engine.md, "Fixing and
freeing a moving block", "Holding a block's rotation"): a fixed block stops and its kinetic
energy is booked, a freed one slides from rest a t^2/2, a set velocity carries a block v t, a
block held in y only is pushed F t^2/(2m), one held in x only falls g t^2/2, one held in rotation
only is pushed off centre F t^2/(2m) turning by the torque over p J/S only, and a spinning block
held in rotation stops turning with I omega^2/2 booked."""
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
    with pytest.raises(rheodda.Error, match=r"Block.fix of block 'block' \(1\): dofs: an empty list holds nothing"):
        sim.blocks["block"].fix(dofs=[])
    with pytest.raises(rheodda.Error, match="unknown 'z'; give some of 'x', 'y', 'rotation'"):
        sim.blocks["block"].fix(dofs=["z"])
    with pytest.raises(rheodda.Error, match="'rotation' given twice"):
        sim.blocks["block"].fix(dofs=["rotation", "rotation"])


def test_a_misspelt_hold_is_refused_with_its_file_line_and_column(tmp_path):
    path = tmp_path / "spin.yaml"
    path.write_text(SPIN_YAML.replace("hold: rotation", "hold: rotate"))
    with pytest.raises(rheodda.SceneError) as e:
        rheodda.Simulation(str(path))
    assert e.value.key == "fixed_points[0].hold" and e.value.line == 12 and e.value.column == 46
    assert "'rotate'" in e.value.message and "rotation" in e.value.message
    assert f"{path}:12:46" in str(e.value)  # the value's line and column
    scene = rheodda.scene_from_dict(air(hold="rotation"))
    assert scene.fixed_points[0]["hold"] == "rotation"
    # a stage's add_fixed_points takes the same words
    staged = air()
    staged["stages"] = [{"name": "hold", "at": 0.1, "add_fixed_points": [{"point": [0.5, 10.25], "block": "rock",
                                                                          "hold": "turn"}]}]
    with pytest.raises(rheodda.SceneError) as e:
        rheodda.scene_from_dict(staged)
    assert e.value.key == "stages[0].add_fixed_points[0].hold" and "rotation" in e.value.message


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


RHO, W, H = 2600.0, 1.0, 0.5  # [kg/m^3], block [m]
P = 100 * 5.0e9  # the automatic fixed-point spring 100 E [N/m per m]


def air(hold=None, omega=0.0):
    """The block of falling() without gravity, spinning at omega [rad/s], held by `hold` at its centre."""
    scene = falling("x")
    scene["analysis"]["gravity"] = [0, 0]
    scene["blocks"][0]["initial_velocity"] = [0.0, 0.0, omega]
    if hold is None:
        del scene["fixed_points"]
    else:
        scene["fixed_points"][0]["hold"] = hold
    return scene


SPIN_YAML = """title: A spinning block
units: {length: m, force: N, time: s}
analysis: {type: dynamic, duration: 0.3, dt: 0.001, output_interval: 0.1, gravity: [0, 0]}
materials:
  rock: {density: 2600, young_modulus: 5.0e9, poisson_ratio: 0.25}
joint_sets:
  joint: {friction_angle: 30}
blocks:
  - name: rock
    rectangle: {x: 0, y: 10, width: 1, height: 0.5}
fixed_points:
  - {point: [0.5, 10.25], block: rock, hold: rotation}
"""


def test_a_block_held_in_rotation_only_is_pushed_off_centre_without_turning():
    # F in x on the middle of the top edge, h = 0.25 m above the centre: the torque -h F. The block
    # moves F t^2/(2m) as a free mass; its rotation is -h F / k_r, k_r = p J/S = p (W^2 + H^2)/12
    # [N m/rad per m] (without the hold it turns by about -h F t^2/(2 I) = -0.83 rad by 0.3 s).
    force, h, t = 1.0e4, 0.25, 0.3
    m, k_r = RHO * W * H, P * (W ** 2 + H ** 2) / 12
    for dofs in (None, ["rotation"], ["y", "rotation"]):  # a scene's hold: rotation, then from Python
        sim = rheodda.Simulation(air(hold="rotation") if dofs is None else air())
        rock = sim.blocks["rock"]
        if dofs is not None:
            rock.fix(dofs=dofs)
        rock.add_load((0.5, 10.5), force=(force, 0.0))
        sim.run(t)
        assert rock.position[0] - 0.5 == pytest.approx(force * t ** 2 / (2 * m), rel=1e-9)
        assert abs(rock.position[1] - 10.25) < 1e-9
        # The spring holds the block's mean rotation (docs/reference/engine.md, "Holding a block's
        # rotation") at -h F / k_r = -4.8e-8 rad, storing (h F)^2 / (2 k_r) (to 4e-5); Block.rotation,
        # the polar angle, has besides it the shear the off-centre load strains the block by, of the
        # order h F / (G S) = 2.5e-6 (-6.5e-7 rad in all).
        assert abs(rock.rotation) < 1e-5
        assert sim.history()["energy_fixed"][-1] == pytest.approx((h * force) ** 2 / (2 * k_r), rel=1e-3)
        assert np.abs(unbooked(sim.history())).max() < 1e-9 * sim.history()["work_loads"][-1]


def test_a_spinning_block_held_in_rotation_stops_turning_and_its_kinetic_energy_is_booked():
    omega, t1 = 3.0, 0.1  # [rad/s], [s]
    inertia = RHO * (W ** 3 * H + W * H ** 3) / 12  # rho J about the centroid [kg m^2/m]
    sim = rheodda.Simulation(air(omega=omega))
    rock = sim.blocks["rock"]
    sim.run(t1)
    assert rock.rotation == pytest.approx(omega * t1, rel=1e-12)
    rock.fix(dofs=["rotation"])
    assert rock.velocity[2] == pytest.approx(0.0, abs=1e-12 * omega) and np.abs(rock.velocity).max() < 1e-12
    assert rock.fixed
    sim.run(0.3)
    h = sim.history()
    assert h["dissipation_edits"][-1] == pytest.approx(inertia * omega ** 2 / 2, rel=1e-12)  # I omega^2/2
    assert rock.rotation == pytest.approx(omega * t1, abs=1e-12)  # held where it was, not at 0
    assert h["energy_kinetic"][-1] < 1e-12 * inertia * omega ** 2
    assert np.abs(unbooked(h)).max() < 1e-9 * inertia * omega ** 2
    # held in x too (a second fixed point), a push in x and y moves it in y only
    rock.fix(dofs=["x"])
    y0 = rock.position[1]
    rock.add_load(rock.position, force=(100.0, 100.0))
    sim.run(0.4)
    assert rock.position[1] - y0 == pytest.approx(100.0 * 0.1 ** 2 / (2 * RHO * W * H), rel=1e-8)
    assert abs(rock.position[0] - 0.5) < 1e-9 and rock.rotation == pytest.approx(omega * t1, abs=1e-12)


def test_a_rotation_held_from_python_survives_save_and_restore():
    sim = rheodda.Simulation(air(omega=2.0)).run(0.05)
    sim.blocks["rock"].fix(dofs=["rotation"])
    sim.blocks["rock"].add_load((0.5, 10.5), force=(1.0e4, 0.0))
    sim.run(0.1)
    again = rheodda.Simulation.restore(sim.save())
    sim.run(0.2)
    again.run(0.2)
    assert np.array_equal(sim.blocks.position, again.blocks.position)
    assert np.array_equal(sim.blocks.rotation, again.blocks.rotation)
    assert np.array_equal(sim.history()["energy_fixed"], again.history()["energy_fixed"])


def test_a_stage_holding_a_spinning_block_in_rotation_books_half_I_omega_squared(tmp_path):
    omega, t1 = 3.0, 0.1
    scene = air(omega=omega)
    scene["stages"] = [{"name": "hold", "at": t1,
                        "add_fixed_points": [{"point": [0.5, 10.25], "block": "rock", "hold": "rotation"}]}]
    scene["measurement_points"] = [{"name": "corner", "point": [1.0, 10.5], "block": "rock"}]
    assert rheodda.run(scene, str(tmp_path / "out"))["status"] == "completed"
    rows = [line.split(",") for line in (tmp_path / "out" / "history.csv").read_text().splitlines()
            if not line.startswith("#")]
    h = {name: np.array([float(r[k]) for r in rows[1:]]) for k, name in enumerate(rows[0]) if name != "stage"}
    inertia = RHO * (W ** 3 * H + W * H ** 3) / 12
    assert h["dissipation_edits"][-1] == pytest.approx(inertia * omega ** 2 / 2, rel=1e-9)
    # the corner (0.5, 0.25) from the centre, turned by omega t1 and held there
    a = omega * t1
    assert h["corner.u"][-1] == pytest.approx(0.5 * np.cos(a) - 0.25 * np.sin(a) - 0.5, abs=1e-9)
    assert h["corner.v"][-1] == pytest.approx(0.5 * np.sin(a) + 0.25 * np.cos(a) - 0.25, abs=1e-9)
