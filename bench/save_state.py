#!/usr/bin/env python3
"""Saves a scene's state where a run goes wrong, for `scene_trace --restore` (bench/scene_trace.cpp):
steps SCENE through the Python API as `rheodda run` does (stopping at its output times, so that
its steps fall where the run's do), past TIME [the scene's time unit], then to the end of the
dynamic stage in progress if any, and writes the state to OUT (rheodda.Simulation.save). Prints
the time and step reached. A diagnostic tool: it asserts nothing.

    bench/save_state.py SCENE TIME OUT OUTPUT_INTERVAL
    RHEODDA_BUILD_DIR=build bench/save_state.py /tmp/slope-1000.yaml 52.15 /tmp/s52.state 5

OUTPUT_INTERVAL: the scene's analysis.output_interval.
"""
import os
import sys

root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(os.environ.get("RHEODDA_BUILD_DIR", os.path.join(root, "build")), "python"))
import rheodda  # noqa: E402


def main():
    scene, until, out, every = sys.argv[1], float(sys.argv[2]), sys.argv[3], float(sys.argv[4])
    sim = rheodda.Simulation(scene)
    t = every
    while t < until:
        sim.run(until=t)
        t += every
    while sim.time < until:
        sim.step(1)
    while sim.in_stage:
        sim.step(1)
    sim.save(out)
    print(f"saved {out}: t = {sim.time:.12g}, step {sim.step_count}")


if __name__ == "__main__":
    main()
