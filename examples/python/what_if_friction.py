"""What if the joint weakens? Branches from one settled state, over two processes.

Sample run (from the repository root, after `bash scripts/build.sh`):
    PYTHONPATH=build/python /usr/bin/python3 examples/python/what_if_friction.py [OUT.png]

The block of examples/sliding-block.yaml rests on its 30 deg incline with the joint's
friction angle raised to 40 deg (tan 40 > tan 30: friction holds it). The simulation
runs 0.2 s to settle and is saved (Simulation.save). Each branch restores that state
(Simulation.restore, in a worker of a multiprocessing pool: the state pickles), lowers
the friction angle to one of 35 ... 15 deg (sim.joint_sets["slope"].friction_angle)
and runs 0.6 s more, sampling the block's slide every 0.02 s (a callback with a period).
A block that slides moves d = a t^2 / 2 down the slope with a = g (sin 30 - cos 30 tan phi)
(Goodman 1976, Methods of Geological Engineering, ch. 3); the script prints each
branch's slide at 0.6 s against it and draws the slides over time into OUT.png
(default docs/img/python-what-if.png). Exits 1 when a sliding branch is more than 1 %
off the closed form or a holding branch moves more than 10 micrometres.
"""
import math
import multiprocessing
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import rheodda  # noqa: E402

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
G = 9.81                                                   # m/s^2, the scene's gravity
SLOPE = math.radians(30)                                   # the incline
DOWN = np.array([-math.cos(SLOPE), -math.sin(SLOPE)])      # unit vector down the slope
CENTRE = (5.504165125, 3.466506351)                        # m, the block's centre at t = 0
SETTLE, BRANCH = 0.2, 0.6                                  # s


def slid(sim: rheodda.Simulation) -> float:
    """The block centre's displacement down the slope since t = 0 [m]."""
    return float(sim.blocks["block"].point_displacement(*CENTRE) @ DOWN)


def branch(args: tuple[rheodda.SimulationState, float]) -> tuple[float, list[float], list[float]]:
    """Restores the settled state, sets the friction angle [deg], runs BRANCH s more; returns
    the friction angle and the slide [m] sampled every 0.02 s [s]."""
    state, friction = args
    sim = rheodda.Simulation.restore(state)
    start_time, start = sim.time, slid(sim)
    sim.joint_sets["slope"].friction_angle = friction
    times, slides = [0.0], [0.0]

    def sample(s: rheodda.Simulation, report: rheodda.StepReport) -> None:
        times.append(s.time - start_time)
        slides.append(slid(s) - start)

    sim.add_callback(sample, time=0.02)
    sim.run(start_time + BRANCH)
    return friction, times, slides


def main() -> int:
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "docs", "img", "python-what-if.png")
    sim = rheodda.Simulation(os.path.join(ROOT, "examples", "sliding-block.yaml"))
    sim.joint_sets["slope"].friction_angle = 40.0    # before the first step: as if written in the scene
    sim.run(SETTLE)
    settled = sim.save()
    print("settled at t = {:g} s after {} steps, slide {:.2e} m; state {} bytes".format(
        sim.time, sim.step_count, slid(sim), len(settled.data)))

    frictions = [35.0, 32.0, 25.0, 20.0, 15.0]   # deg; 30 would be the limit itself (a = 0)
    with multiprocessing.get_context("fork").Pool(2) as pool:
        results = pool.map(branch, [(settled, phi) for phi in frictions])

    failed = False
    fig, ax = plt.subplots(figsize=(7, 4.5))
    print("friction [deg]  slide at {:g} s [m]  closed form [m]".format(BRANCH))
    for friction, times, slides in results:
        a = G * (math.sin(SLOPE) - math.cos(SLOPE) * math.tan(math.radians(friction)))
        if a > 0:
            exact = a * BRANCH ** 2 / 2
            failed |= abs(slides[-1] - exact) > 0.01 * exact
            print("{:14g}  {:18.6f}  {:15.6f}".format(friction, slides[-1], exact))
            t = np.linspace(0, BRANCH, 50)
            ax.plot(t, a * t ** 2 / 2, "k:", lw=1)
        else:
            failed |= abs(slides[-1]) > 1e-5
            print("{:14g}  {:18.2e}  {:>15}".format(friction, slides[-1], "held"))
        ax.plot(times, slides, "o-", ms=3, label="{:g} deg".format(friction))
    ax.set_xlabel("time after the friction change [s]")
    ax.set_ylabel("slide down the slope [m]")
    ax.set_title("Branches from one settled state (dotted: a t^2/2)")
    ax.legend(title="friction angle")
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    print("wrote", out)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
