#!/usr/bin/python3
"""The pictures of the tunnel and reservoir examples (docs/guide/tunnels-and-slopes.md):

  examples/rockmass/tunnel-stages.yaml   -> docs/img/tunnel-stages-convergence.png (crown settlement and
                                            wall convergence over time, the stages marked),
                                            docs/img/tunnel-stages-bolts.png (bolt forces over time),
                                            docs/img/tunnel-stages-blocks.png (the blocks at 100 d)
  examples/rockmass/reservoir-slope.yaml -> docs/img/reservoir-slope.png (toe displacement over time,
                                            the water level at the toe on a second axis),
                                            docs/img/reservoir-slope-blocks.png (the blocks at the end)

Usage: scripts/engineering-examples.py [--only tunnel|reservoir] [--from-tunnel OUT] [--from-reservoir OUT]
(RHEODDA_BUILD_DIR: the build, default build/). Without --from-* it runs the examples into out/engineering/
first (a few minutes), prints the figures the docs quote and, without --only, writes them into the table of
docs/guide/tunnels-and-slopes.md between its engineering-figures markers.
"""
import argparse
import csv
import json
import os
import pathlib
import shutil
import subprocess
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[1]
IMG = ROOT / "docs" / "img"
BUILD = pathlib.Path(os.environ.get("RHEODDA_BUILD_DIR", ROOT / "build"))
RHEODDA = BUILD / "apps" / "rheodda"
TUNNEL = ROOT / "examples" / "rockmass" / "tunnel-stages.yaml"
RESERVOIR = ROOT / "examples" / "rockmass" / "reservoir-slope.yaml"
TOE_X = -4.5  # the reservoir slope's measurement point `toe` [m]


def run(scene, out):
    """Runs `scene` into `out` (anew) and draws its plots (rheodda plot); returns out."""
    if out.exists():
        shutil.rmtree(out)
    subprocess.run([str(RHEODDA), "run", str(scene), "-o", str(out)], check=True, stdout=subprocess.DEVNULL)
    return out


def last_blocks_picture(out, png):
    """The blocks of the run's last frame (rheodda plot) copied to `png`."""
    subprocess.run([str(RHEODDA), "plot", str(out)], check=True, stdout=subprocess.DEVNULL)
    shutil.copy(sorted((out / "plots").glob("blocks_*.png"))[-1], png)


def history(out):
    """history.csv as {column: numpy array} (the `stage` column as strings)."""
    with open(out / "history.csv") as f:
        rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    cols = {}
    for key in rows[0]:
        values = [r[key] for r in rows]
        try:
            cols[key] = np.array([float(v) for v in values])
        except ValueError:
            cols[key] = np.array(values)
    return cols


def mark_stages(ax, out):
    """A dotted line at each stage's time (summary.json's `stages`), named; stages less than a
    hundredth of the run apart share a line ("heading + bolt_heading")."""
    stages = json.loads((out / "summary.json").read_text()).get("stages", [])
    span = max(s["time"] for s in stages) if stages else 1.0
    groups = []
    for stage in stages:
        if groups and stage["time"] - groups[-1][0] < 0.01 * span:
            groups[-1][1].append(stage["name"])
        else:
            groups.append((stage["time"], [stage["name"]]))
    for time, names in groups:
        ax.axvline(time, color="grey", linestyle=":", linewidth=1)
        ax.text(time, 0.98, " " + " + ".join(names), transform=ax.get_xaxis_transform(), rotation=90, va="top",
                ha="left", fontsize=8, color="grey")


def half_time(t, series, after, level):
    """The first time after `after` at which `series` reaches `level`."""
    later = t > after
    return t[later][np.argmax(series[later] >= level)]


def tunnel(out):
    h = history(out)
    t = h["time"]
    crown = -1000.0 * h["crown.v"]  # settlement [mm], down positive
    floor = 1000.0 * h["floor.v"]  # vertical displacement [mm], up positive
    walls = 1000.0 * (h["left_wall.u"] - h["right_wall.u"])  # convergence [mm], closing positive
    stage_times = {s["name"]: s["time"] for s in json.loads((out / "summary.json").read_text())["stages"]}
    bolted = stage_times["bolt_walls"]  # the end of the bench's settling
    fig, (ax, zoom) = plt.subplots(2, 1, figsize=(8, 7), sharex=True, height_ratios=[3, 2])
    curves = [(crown, "crown settlement"), (walls, "wall convergence (left_wall.u - right_wall.u)"),
              (floor, "floor displacement (up +)")]
    for series, label in curves:
        ax.plot(t, series, label=label)
    ax.set_ylabel("[mm]")
    mark_stages(ax, out)
    ax.legend(loc="center right", fontsize=9)
    ax.set_title("Tunnel in two stages, bolted: convergence with Burgers creep of the joints")
    after = t >= bolted
    i0 = np.argmax(after)
    for series, label in curves:
        zoom.plot(t[after], 1000.0 * (series[after] - series[i0]), label=label)
    zoom.set_xlabel("time [d]")
    zoom.set_ylabel("change since the bench\nsettled [um]")
    mark_stages(zoom, out)
    fig.tight_layout()
    fig.savefig(IMG / "tunnel-stages-convergence.png", dpi=110)
    plt.close(fig)

    with open(out / "bolts.csv") as f:
        rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    bolts = {}
    for r in rows:
        bolts.setdefault(r["bolt"], []).append((float(r["time"]), float(r["force"]) / 1000.0))
    fig, ax = plt.subplots(figsize=(8, 4.5))
    for name, series in bolts.items():
        ts, fs = zip(*series)
        ax.plot(ts, fs, label=name)
    ax.set_xlabel("time [d]")
    ax.set_ylabel("axial force [kN per m of tunnel]")
    mark_stages(ax, out)
    ax.legend(fontsize=8, ncol=2)
    ax.set_title("Tunnel: bolt forces (installed at the stages, creep loads them)")
    fig.tight_layout()
    fig.savefig(IMG / "tunnel-stages-bolts.png", dpi=110)
    plt.close(fig)
    last_blocks_picture(out, IMG / "tunnel-stages-blocks.png")
    stages = {s["name"]: s["time"] for s in json.loads((out / "summary.json").read_text())["stages"]}

    def at(series, time):
        """The value of the last history row at or before `time` [d]."""
        return series[np.searchsorted(t, time + 1e-9, side="right") - 1]

    bolted = stages["bolt_walls"]  # the end of the bench's settling
    creep = at(walls, 100.0) - at(walls, bolted)
    strongest = max(bolts, key=lambda name: abs(bolts[name][-1][1]))
    rows = [
        ("tunnel", "crown settlement after the heading settled", f"{at(crown, stages['bolt_heading']):.3f} mm"),
        ("tunnel", "wall convergence after the heading settled (negative: apart)",
         f"{at(walls, stages['bolt_heading']):.3f} mm"),
        ("tunnel", "wall convergence after the bench settled", f"{at(walls, bolted):.3f} mm"),
        ("tunnel", "wall convergence at 100 d", f"{at(walls, 100.0):.3f} mm"),
        ("tunnel", "of which creep after the bench (10 -> 100 d)",
         f"{creep:.4f} mm ({100.0 * creep / at(walls, bolted):.0f} %), half of it by "
         f"{half_time(t, walls, bolted, at(walls, bolted) + creep / 2) - bolted:.1f} d after the bench"),
        ("tunnel", "crown settlement at 100 d", f"{at(crown, 100.0):.3f} mm"),
        ("tunnel", f"largest bolt force at 100 d ({strongest})", f"{bolts[strongest][-1][1]:.2f} kN/m"),
    ]
    for _, what, value in rows:
        print(f"tunnel-stages: {what}: {value}")
    return rows


def surface_height(surface, x):
    """The height [m] of a polyline surface [[x, y], ...] at x, held beyond its ends."""
    xs, ys = zip(*surface)
    return float(np.interp(x, xs, ys))


def level_at(water, x, times):
    """The phreatic surface's height at x [m] at each time [d], as the engine interpolates it:
    linearly in x along each surface, linearly in time between surfaces (docs/reference/water.md)."""
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


def reservoir(out):
    h = history(out)
    water = json.loads((out / "summary.json").read_text())["inputs"]["water"]
    t = h["time"]
    displacement = 1000.0 * np.hypot(h["toe.u"], h["toe.v"])  # [mm]
    fig, ax = plt.subplots(figsize=(8, 4.5))
    ax.plot(t, displacement, color="tab:brown")
    ax.set_xlabel("time [d]")
    ax.set_ylabel("toe displacement [mm]", color="tab:brown")
    ax2 = ax.twinx()
    ax2.plot(t, level_at(water, TOE_X, t), color="tab:blue", linestyle="--")
    ax2.set_ylabel("water level at the toe [m]", color="tab:blue")
    ax.set_title("Reservoir bank slope: Burgers creep of the bedding under a yearly drawdown")
    fig.tight_layout()
    fig.savefig(IMG / "reservoir-slope.png", dpi=110)
    plt.close(fig)
    last_blocks_picture(out, IMG / "reservoir-slope-blocks.png")

    def at(time):
        """The toe's displacement [mm] at the last history row at or before `time` [d]."""
        return displacement[np.searchsorted(t, time + 1e-9, side="right") - 1]

    rows = [("reservoir", "toe displacement after the settling", f"{at(1e-3):.2f} mm")]
    for year, start in ((1, 120.0), (2, 485.0)):
        before = (at(start) - at(start - 30.0)) / 30.0
        during = (at(start + 30.0) - at(start)) / 30.0
        rows.append(("reservoir", f"toe creep rate, year {year}: the 30 d before the drawdown, during it",
                     f"{1000 * before:.1f} um/d, {1000 * during:.1f} um/d ({during / before:.1f} x)"))
    rows.append(("reservoir", "toe displacement at 730 d", f"{at(730.0):.2f} mm"))
    for _, what, value in rows:
        print(f"reservoir-slope: {what}: {value}")
    return rows


def write_figures(rows):
    """The figures table of docs/guide/tunnels-and-slopes.md, between its engineering-figures markers."""
    table = ["| example | figure | value |", "|---|---|---|"]
    table += [f"| {example} | {what} | {value} |" for example, what, value in rows]
    text = (ROOT / "docs" / "guide" / "tunnels-and-slopes.md").read_text()
    begin, end = "<!-- engineering-figures:begin -->\n", "<!-- engineering-figures:end -->"
    head, rest = text.split(begin)
    tail = rest[rest.index(end):]
    (ROOT / "docs" / "guide" / "tunnels-and-slopes.md").write_text(head + begin + "\n".join(table) + "\n" + tail)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--only", choices=["tunnel", "reservoir"])
    ap.add_argument("--from-tunnel", help="a finished run of examples/rockmass/tunnel-stages.yaml")
    ap.add_argument("--from-reservoir", help="a finished run of examples/rockmass/reservoir-slope.yaml")
    args = ap.parse_args()
    if not RHEODDA.exists():
        subprocess.run(["bash", str(ROOT / "scripts" / "build.sh")], check=True)
    work = ROOT / "out" / "engineering"
    work.mkdir(parents=True, exist_ok=True)
    IMG.mkdir(exist_ok=True)
    rows = []
    if args.only in (None, "tunnel"):
        rows += tunnel(pathlib.Path(args.from_tunnel) if args.from_tunnel else run(TUNNEL, work / "tunnel-stages"))
    if args.only in (None, "reservoir"):
        rows += reservoir(pathlib.Path(args.from_reservoir) if args.from_reservoir
                          else run(RESERVOIR, work / "reservoir-slope"))
    if args.only is None:
        write_figures(rows)
    return 0


if __name__ == "__main__":
    sys.exit(main())
