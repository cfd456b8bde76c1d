#!/usr/bin/env python3
"""Where a dynamic stage's motion is: steps a scene through the Python API and prints, every
EVERY steps, the simulated time, the kinetic energy, the gravity's work and the block moving
fastest (its speed and centroid). Tells a stage that approaches rest (speeds falling) from a
part that does not hold (one block's speed growing). Prints figures; asserts nothing.

    bench/stage_motion.py SCENE [STEPS] [EVERY]
    RHEODDA_BUILD_DIR=build bench/stage_motion.py /tmp/slope-1000.yaml 1500 100

(docs/notes/explicit-step.md, "The cohesionless slope's settling stage".)
"""
import os
import sys
import time

import numpy as np

root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(os.environ.get("RHEODDA_BUILD_DIR", os.path.join(root, "build")), "python"))
import rheodda  # noqa: E402


def main():
    scene = sys.argv[1]
    steps = int(sys.argv[2]) if len(sys.argv) > 2 else 1000
    every = int(sys.argv[3]) if len(sys.argv) > 3 else 100
    sim = rheodda.Simulation(scene)
    t0 = time.process_time()
    print("step,time,energy_kinetic,work_gravity,fastest_block,speed,x,y,cpu_s")
    for _ in range(steps // every):
        sim.step(every)
        h = sim.history()
        v = np.asarray(sim.blocks.velocity)
        p = np.asarray(sim.blocks.position)
        speed = np.hypot(v[:, 0], v[:, 1])
        k = int(np.argmax(speed))
        print(f"{int(h['step'][-1])},{h['time'][-1]:.9g},{h['energy_kinetic'][-1]:.4g},"
              f"{h['work_gravity'][-1]:.4g},{k},{speed[k]:.4g},{p[k, 0]:.2f},{p[k, 1]:.2f},"
              f"{time.process_time() - t0:.1f}", flush=True)


if __name__ == "__main__":
    main()
