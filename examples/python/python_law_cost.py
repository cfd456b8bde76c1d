"""What a law written in Python costs per contact-step, against the built-in law.

Sample run (from the repository root, after `bash scripts/build.sh`):
    PYTHONPATH=build/python /usr/bin/python3 examples/python/python_law_cost.py [STEPS]

Runs the first STEPS steps (default 300: the whole 100 d) of the creeping Goodman slope
(examples/goodman-toppling-creep.yaml: 16 columns, both joint sets with Burgers
laws) twice: with the built-in `burgers` and with the Python Burgers of
burgers_in_python.py on both joint sets. Prints the wall time of each (best of
3), the contact-steps (contacts with a law, summed over the steps), the calls
into Python per contact-step, the added time per contact-step, and the largest
difference between the two runs' joint shear displacements. docs/guide/python.md
quotes its output.
"""
import os
import sys
import time
from typing import Callable, Sequence

import numpy as np

import rheodda

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from burgers_in_python import PythonBurgers  # noqa: E402


class CountingBurgers(PythonBurgers):
    """Counts the calls the host makes (a separate run: counting costs time)."""

    def __init__(self, **p: float) -> None:
        super().__init__(**p)
        self.calls = {"step_constants": 0, "linearize": 0, "advance": 0}

    def step_constants(self, dt: float, scheme: str) -> rheodda.StepConstants:
        self.calls["step_constants"] += 1
        return super().step_constants(dt, scheme)

    def linearize(self, k: rheodda.StepConstants, q: Sequence[float], force_start: float,
                  force_end_guess: float) -> tuple[float, float]:
        self.calls["linearize"] += 1
        return super().linearize(k, q, force_start, force_end_guess)

    def advance(self, k: rheodda.StepConstants, q: Sequence[float], force_start: float,
                force_end: float) -> tuple[float, tuple[float, float]]:
        self.calls["advance"] += 1
        return super().advance(k, q, force_start, force_end)


def best_time(make: Callable[[], rheodda.Simulation], steps: int,
              repeats: int = 3) -> tuple[float, rheodda.Simulation]:
    best, sim = float("inf"), make()
    for _ in range(repeats):
        sim = make()
        start = time.perf_counter()
        sim.step(steps)
        best = min(best, time.perf_counter() - start)
    return best, sim


def main() -> None:
    steps = int(sys.argv[1]) if len(sys.argv) > 1 else 300
    root = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
    scene = rheodda.load_scene(os.path.join(root, "examples", "goodman-toppling-creep.yaml"))
    probe = rheodda.Simulation(scene)
    params = {js: probe.law_parameters(js) for js in probe.joint_sets.names}

    t_builtin, builtin = best_time(lambda: rheodda.Simulation(scene), steps)
    t_python, python = best_time(
        lambda: rheodda.Simulation(scene, laws={js: PythonBurgers(**p) for js, p in params.items()}), steps)

    # contact-steps: the contacts that carry a law state after each step, summed
    counted = {"contact_steps": 0}

    def count(sim: rheodda.Simulation, report: rheodda.StepReport) -> None:
        counted["contact_steps"] += int(np.count_nonzero(sim.contacts()["length"] > 0))

    counting_laws = {js: CountingBurgers(**p) for js, p in params.items()}
    rheodda.Simulation(scene, laws=counting_laws, callback=count).step(steps)
    calls = {k: sum(l.calls[k] for l in counting_laws.values()) for k in ("step_constants", "linearize", "advance")}
    contact_steps = counted["contact_steps"]

    diffs = []
    for js in probe.joint_sets.names:
        a = builtin.history()[js + ".shear_displacement"]
        b = python.history()[js + ".shear_displacement"]
        diffs.append(np.nanmax(np.abs(a - b)) / np.nanmax(np.abs(a)))
    print("scene: {} ({} steps to t = {:g} {})".format(os.path.relpath(scene.file, root), builtin.step_count,
                                                     builtin.time, builtin.units["time"]))
    print("contact-steps (edge contacts with a law, summed over steps): {}".format(contact_steps))
    print("calls into Python: " + ", ".join("{} {}".format(k, v) for k, v in calls.items())
          + " ({:.2f} per contact-step)".format((calls["linearize"] + calls["advance"]) / contact_steps))
    print("wall time, best of 3: built-in {:.3f} s, Python law {:.3f} s ({:.1f}x)".format(
        t_builtin, t_python, t_python / t_builtin))
    print("per contact-step: built-in run {:.1f} us (whole step), Python law adds {:.1f} us".format(
        1e6 * t_builtin / contact_steps, 1e6 * (t_python - t_builtin) / contact_steps))
    print("largest relative difference of the joint sets' shear displacement: {:.2g}".format(max(diffs)))


if __name__ == "__main__":
    main()
