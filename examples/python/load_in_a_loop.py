"""Drive a run from Python: raise the shear load step by step in a loop.

Sample run (from the repository root, after `bash scripts/build.sh`):
    PYTHONPATH=build/python /usr/bin/python3 examples/python/load_in_a_loop.py [OUT.png]

The two-block shear creep test (examples/shear-creep-test.yaml) is run 50 h at a
time; after each stretch the loop reads the joint's contacts (numpy arrays) and
raises the shear load F2 (load 1 of the scene) by 0.064 MPa x 60 mm, as a
multi-stage laboratory test would. A per-step callback records the contacts'
mean creep displacement. The joint's shear displacement is drawn into OUT.png
(default docs/img/python-load-loop.png) with the staged Burgers closed form
(Boltzmann superposition, rheodda.exact_displacement) beside it.
"""
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import rheodda  # noqa: E402

root = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(root, "docs", "img", "python-load-loop.png")
scene = rheodda.load_scene(os.path.join(root, "examples", "shear-creep-test.yaml"))
length = 60.0   # mm, the joint: a stress tau [MPa] is the force tau * 60 mm [N/mm]

creep: dict[str, list[float]] = {"t": [], "creep": []}


def record_creep(sim: rheodda.Simulation, report: rheodda.StepReport) -> None:
    c = sim.contacts()
    creep["t"].append(report.time)
    creep["creep"].append(-c["creep_displacement"].mean())


sim = rheodda.Simulation(scene, callback=record_creep)
stages = []            # (start time, tau)
tau = 0.232
for stage in range(4):
    stages.append((sim.time, tau))
    sim.set_load(1, (tau * length, 0.0))          # F2 from the next step on
    sim.run(until=sim.time + 50.0)
    c = sim.contacts()
    print("t = {:5.0f} h: tau {:.3f} MPa, {} contacts {}, joint shear {:.6g} mm".format(
        sim.time, tau, len(c["id"]), "/".join(sorted(set(c["state"]))), -c["shear_displacement"].mean()))
    tau += 0.064

h = sim.history()
t, d = h["time"][1:], -h["plane.shear_displacement"][1:]
law = rheodda.law("burgers", sim.law_parameters("plane"))
exact = rheodda.exact_displacement(law, stages, t)
off_stage = ~np.isin(t, [s for s, _ in stages])     # the closed form jumps at a stage start; the engine a step later
print("largest difference from the staged closed form: {:.2e} (relative)".format(
    np.max(np.abs(d - exact)[off_stage] / exact[off_stage])))

fig, ax = plt.subplots(figsize=(8, 4.5))
ax.plot(t, d, label="rheodda: joint shear displacement")
ax.plot(t, exact, "--", label="staged Burgers closed form")
ax.plot(creep["t"], creep["creep"], label="creep part (contacts' law state)")
for s, v in stages:
    ax.annotate("{:.3f} MPa".format(v), (s, 0), xytext=(s + 2, 0.0005), fontsize=8)
ax.set_xlabel("time [h]")
ax.set_ylabel("displacement [mm]")
ax.set_title("Shear load raised every 50 h from a Python loop", fontsize=10)
ax.legend(fontsize=8)
fig.tight_layout()
fig.savefig(out, dpi=110)
print("wrote " + os.path.relpath(out, root))
