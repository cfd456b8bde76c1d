#!/usr/bin/env python3
"""Contacts held outside their Mohr-Coulomb envelope, step by step: steps a scene through the
Python API to step FROM, then prints for each step up to TO the simulated time, the step, the
kinetic energy, the contacts' shear spring energy, the work of gravity and the spring energy
contacts started the step with beyond what their records stored (work_contact_restart, all
cumulative), and the contacts committed *locked* the farthest outside the envelope: in tension
beyond their tensile strength (N < -T l) or with |S| above their strength N tan(phi) + c l
(contacts.csv's shear_strength). Such a contact is a glue the open-close iteration's
anti-chattering rule left in place (docs/reference/contacts.md, "States and the open-close
iteration"). Prints figures; asserts nothing.

    bench/stage_glue.py SCENE FROM TO [SHOWN]
    RHEODDA_BUILD_DIR=build bench/stage_glue.py /tmp/slope-1000.yaml 3312 3320 4

(docs/notes/rock-mass-steps.md, "A mechanism stage that never rests".)
"""
import os
import sys

import numpy as np

root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(os.environ.get("RHEODDA_BUILD_DIR", os.path.join(root, "build")), "python"))
import rheodda  # noqa: E402


def main():
    scene, first, last = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
    shown = int(sys.argv[4]) if len(sys.argv) > 4 else 3
    sim = rheodda.Simulation(scene)
    sim.step(first)
    print("step,time,dt,energy_kinetic,energy_contact_shear,work_gravity,work_contact_restart,"
          "locked_outside,largest_excess")
    while int(sim.history()["step"][-1]) < last:
        sim.step(1)
        h = sim.history()
        c = sim.contacts
        locked = np.asarray(c["state"]) == "locked"
        n = np.asarray(c["normal_force"])
        s = np.abs(np.asarray(c["shear_force"]))
        strength = np.asarray(c["shear_strength"])
        # How far outside [force/length]: the shear beyond the strength, or the pull.
        excess = np.where(locked, np.maximum(s - strength, np.maximum(-n, 0.0)), 0.0)
        outside = excess > 1e-6 * max(np.abs(n).max(initial=0.0), 1.0)
        print(f"{int(h['step'][-1])},{h['time'][-1]:.10g},{h['dt'][-1]:.4g},{h['energy_kinetic'][-1]:.4g},"
              f"{h['energy_contact_shear'][-1]:.4g},{h['work_gravity'][-1]:.6g},{h['work_contact_restart'][-1]:.4g},"
              f"{int(outside.sum())},{excess.max(initial=0.0):.4g}", flush=True)
        for i in np.argsort(-excess)[:shown]:
            if not outside[i]:
                break
            print(f"#   contact {c['id'][i]} ({c['kind'][i]}, vertex {c['vertex_block'][i]}.{c['vertex'][i]} on edge "
                  f"{c['edge_block'][i]}.{c['edge'][i]}, joint set {c['joint_set'][i]}) at ({c['x'][i]:.3f}, "
                  f"{c['y'][i]:.3f}): N {n[i]:.4g}, |S| {s[i]:.4g}, strength {strength[i]:.4g}, "
                  f"penetration {c['penetration'][i]:.3g}", flush=True)


if __name__ == "__main__":
    main()
