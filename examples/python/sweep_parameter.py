"""Sweep a law parameter of a scene in a loop and plot the result.

Sample run (from the repository root, after `bash scripts/build.sh`):
    PYTHONPATH=build/python /usr/bin/python3 examples/python/sweep_parameter.py [OUT.png]

Runs the two-block shear creep test (examples/shear-creep-test.yaml, the seed's
Table 1 row 1) for seven values of the Maxwell viscosity eta1 of the joint's
Burgers law, in process (rheodda.Simulation), and draws into OUT.png (default
docs/img/python-sweep.png): the joint's shear displacement over 200 h for each
eta1, and the displacement at 200 h against eta1 with the Burgers closed form
F/E1 + F/E2 (1 - exp(-E2 t/eta2)) + F t/eta1 (the seed's eqs. 20-21) beside it.
"""
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import rheodda  # noqa: E402

root = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(root, "docs", "img", "python-sweep.png")
scene = rheodda.load_scene(os.path.join(root, "examples", "shear-creep-test.yaml"))
seed = rheodda.Simulation(scene).law_parameters("plane")   # E1, E2, eta1, eta2 of the scene
tau = 0.232                                                # MPa: F2 / 60 mm

eta1_values = seed["eta1"] * np.array([0.25, 0.5, 1.0, 2.0, 4.0, 8.0, 16.0])
final, exact = [], []
fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.5))
for eta1 in eta1_values:
    sim = rheodda.Simulation(scene)
    sim.set_law_parameters("plane", eta1=eta1)   # before the first step: as if written in the scene
    h = sim.run().history()
    d = -h["plane.shear_displacement"]           # the joint's shear, positive along the load
    law = rheodda.law("burgers", dict(seed, eta1=eta1))
    final.append(d[-1])
    exact.append(law.displacement_closed_form(tau, sim.time))
    left.plot(h["time"], d, label="eta1 = {:.3g}".format(eta1))
    print("eta1 {:10.5g} MPa h/mm: d(200 h) = {:.6g} mm, closed form {:.6g} mm (relative {:.1e})".format(
        eta1, final[-1], exact[-1], abs(final[-1] - exact[-1]) / exact[-1]))
left.set_xlabel("time [h]")
left.set_ylabel("joint shear displacement [mm]")
left.set_title("Shear creep test, sweep of eta1 (Burgers)", fontsize=10)
left.legend(fontsize=7)
right.semilogx(eta1_values, final, "o", label="rheodda (DDA, two blocks)")
fine = np.geomspace(eta1_values[0], eta1_values[-1], 200)
right.semilogx(fine, [rheodda.law("burgers", dict(seed, eta1=e)).displacement_closed_form(tau, 200.0)
                      for e in fine], "-", label="closed form, seed eqs. 20-21")
right.set_xlabel("eta1 [MPa h/mm]")
right.set_ylabel("shear displacement at 200 h [mm]")
right.legend(fontsize=8)
fig.tight_layout()
fig.savefig(out, dpi=110)
print("wrote " + os.path.relpath(out, root))
