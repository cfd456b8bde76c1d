#!/usr/bin/python3
"""The reservoir bank slope's picture (docs/notes/prototypes/reservoir-slope.yaml, a draft;
docs/reference/water.md): the toe's displacement over time with the water level
at the toe on a second axis, drawn to docs/img/reservoir-slope.png.

Usage: docs/notes/prototypes/reservoir-slope.py [--from OUT]     (RHEODDA_BUILD_DIR: the build, default build/)
Without --from it runs the example into a temporary folder first (a few minutes).
The level at the toe is the phreatic surface's height at the toe's x, read from
summary.json's inputs (the scene's `water:`) and interpolated as the engine does:
linearly in x along each surface, linearly in time between surfaces.
"""
import argparse
import csv
import json
import os
import pathlib
import subprocess
import sys
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[3]
SCENE = ROOT / "docs" / "notes" / "prototypes" / "reservoir-slope.yaml"
TOE_X = -4.5  # the measurement point `toe` [m]


def surface_height(surface, x):
    """The height [m] of a polyline surface [[x, y], ...] at x, held beyond its ends."""
    xs, ys = zip(*surface)
    return float(np.interp(x, xs, ys))


def level_at(water, x, times):
    """The phreatic surface's height at x [m] at each time [d]."""
    if "level" in water:
        return np.full(len(times), water["level"])
    if "surface" in water:
        return np.full(len(times), surface_height(water["surface"], x))
    if "level_history" in water:
        t, h = zip(*water["level_history"])
        return np.interp(times, t, h)
    t = [s["time"] for s in water["surface_history"]]
    h = [surface_height(s["surface"], x) for s in water["surface_history"]]
    return np.interp(times, t, h)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--from", dest="out", help="a finished run of the example (rheodda run ... -o OUT)")
    ap.add_argument("--png", default=str(ROOT / "docs" / "img" / "reservoir-slope.png"))
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        out = pathlib.Path(args.out) if args.out else pathlib.Path(tmp) / "run"
        if not args.out:
            build = pathlib.Path(os.environ.get("RHEODDA_BUILD_DIR", ROOT / "build"))
            subprocess.run([str(build / "apps" / "rheodda"), "run", str(SCENE), "-o", str(out)], check=True,
                           stdout=subprocess.DEVNULL)
        rows = list(csv.DictReader(open(out / "history.csv")))
        water = json.loads((out / "summary.json").read_text())["inputs"]["water"]
    t = np.array([float(r["time"]) for r in rows])
    u = np.array([float(r["toe.u"]) for r in rows])
    v = np.array([float(r["toe.v"]) for r in rows])
    displacement = 1000.0 * np.hypot(u, v)  # [mm]
    fig, ax = plt.subplots(figsize=(8, 4.5))
    ax.plot(t, displacement, color="tab:brown", label="toe displacement")
    ax.set_xlabel("time [d]")
    ax.set_ylabel("toe displacement [mm]", color="tab:brown")
    ax2 = ax.twinx()
    ax2.plot(t, level_at(water, TOE_X, t), color="tab:blue", linestyle="--", label="water level at the toe")
    ax2.set_ylabel("water level at the toe [m]", color="tab:blue")
    ax.set_title("Reservoir bank slope: Burgers creep of the bedding under a yearly drawdown")
    fig.tight_layout()
    fig.savefig(args.png, dpi=110)
    print(f"reservoir-slope: {args.png}; toe {displacement[-1]:.2f} mm at {t[-1]:g} d")
    return 0


if __name__ == "__main__":
    sys.exit(main())
