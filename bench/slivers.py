#!/usr/bin/env python3
"""Small blocks in generated rock masses (docs/notes/slivers.md): the spread of the blocks'
explicit cycles, what merging the blocks below rock_mass.sliver_area does to it and to the
settled state, and what density scaling (analysis.stage_cycles) does to the state at rest.

For each scene (the cohesionless slope, bench/scenes/jointed-slope-cohesionless.yaml, and the
tunnel, examples/rockmass/tunnel.yaml, both scaled to about 1e3 blocks by rockmass_bench
--write-scenes --creep 1000):
  1. for each sliver_area: the blocks, how many were merged (the blocks at sliver_area 0 less
     these), each block's cycle on the initial state (Simulation.block_cycles, seconds) as a
     histogram by half-decades, its smallest, 1st percentile and median, the blocks that set
     the smallest (area, 2A/P: about the width of a thin block), and the scene's cycle;
  2. for each sliver_area, the settling stage as the scene takes it (implicit) until it ends at
     rest: its simulated time, steps, cuts, CPU seconds, each measurement point's displacement
     and the largest block displacement at rest [mm], against sliver_area 0; then the scene's
     own sliver_area at half the stage's dt (the step control's share in the differences);
  3. (--scaling) the settling stage in explicit cycles on a coarse tunnel (--scaling-scene,
     --scaling-blocks: about 1e2 blocks), with density scaling at each --stage-cycles (and
     unscaled with --unscaled), with the scene's sliver_area and with 0: steps, the most cycles
     of a step, CPU seconds, the state at the stage's end against the implicit stage's.
Prints markdown tables; asserts nothing. One thread (OMP_NUM_THREADS=1 unless set: the
cycles' threads spin at each cycle, and on a machine shared with other jobs two of them took 20
times the CPU of one).

    RHEODDA_BUILD_DIR=build bench/slivers.py [--scenes slope,tunnel] [--no-settle] [--scaling]
    RHEODDA_BUILD_DIR=build bench/slivers.py --scenes slope --slope-areas 0,0.053,0.25
"""
import argparse
import math
import os
import re
import subprocess
import sys
import tempfile
import time

os.environ.setdefault("OMP_NUM_THREADS", "1")
import numpy as np  # noqa: E402

root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
build = os.environ.get("RHEODDA_BUILD_DIR", os.path.join(root, "build"))
sys.path.insert(0, os.path.join(build, "python"))
import rheodda  # noqa: E402

SECONDS = {"s": 1.0, "min": 60.0, "h": 3600.0, "d": 86400.0}
# rockmass_bench's arguments that write each scene scaled to about N blocks.
SCENES = {
    "slope": ["--scene", os.path.join(root, "bench/scenes/jointed-slope-cohesionless.yaml")],
    "tunnel": ["--example", "tunnel", "--rest-tolerance", "1e-5"],
}


def write_scene(name, blocks, out):
    """The scene `name` scaled to about `blocks` blocks, as rockmass_bench writes it; its text."""
    d = os.path.join(out, f"{name}-{blocks}")
    subprocess.run([os.path.join(build, "bench", "rockmass_bench"), "--no-generation", *SCENES[name],
                    "--write-scenes", d, "--creep", str(blocks), "--max-wall", "0"],
                   check=True, stdout=subprocess.DEVNULL)
    (f,) = [f for f in os.listdir(d) if f.endswith(".yaml")]
    with open(os.path.join(d, f)) as fh:
        return fh.read()


def with_sliver_area(text, area):
    return re.sub(r"sliver_area: [0-9.eE+-]+", f"sliver_area: {area:g}", text, count=1)


def with_analysis(text, keys, settle_keys=None):
    """The scene text with `keys` added to its analysis (and `settle_keys` to its settle map)."""
    lines = "".join(f"  {k}: {v}\n" for k, v in keys.items())
    text = text.replace("\nanalysis:\n", "\nanalysis:\n" + lines, 1)
    if settle_keys:
        text = text.replace("settle: {", "settle: {" + ", ".join(f"{k}: {v}" for k, v in settle_keys.items()) + ", ", 1)
    return text


def simulation(text, out, tag, callback=None):
    path = os.path.join(out, f"{tag}.yaml")
    with open(path, "w") as fh:
        fh.write(text)
    return rheodda.Simulation(path, callback=callback)


def cycles(sim):
    """Per moving block: cycle [s], area [m^2], 2A/P [m]; the scene's cycle [s] and block."""
    to_s = SECONDS[sim.units["time"]]
    h = sim.block_cycles() * to_s
    k = np.flatnonzero(np.isfinite(h))
    area = np.asarray(sim.blocks.area)
    width = []
    for b in k:
        v = np.asarray(sim.block_vertices(int(b)))
        perimeter = np.sum(np.hypot(*(np.roll(v, -1, axis=0) - v).T))
        width.append(2.0 * area[b] / perimeter)
    c, block = sim.stable_cycle()
    return k, h[k], area[k], np.asarray(width), c * to_s, block


def distribution(name, texts, out):
    print(f"\n### {name}: the blocks' cycles on the initial state (explicit_safety 0.8 included)\n")
    rows, hists, shortest = [], [], []
    base_blocks = None
    for area, text in texts:
        sim = simulation(text, out, f"{name}-sliver{area:g}")
        k, h, a, w, c, block = cycles(sim)
        n = int(np.count_nonzero(~np.asarray(sim.blocks.fixed, dtype=bool)))  # the rock mass's blocks
        base_blocks = n if base_blocks is None else base_blocks
        q = np.sort(h)
        p1 = q[int(math.floor(0.01 * (len(q) - 1)))]
        rows.append(f"| {area:g} | {n} | {base_blocks - n} | {q[0]:.3g} | {p1:.3g} | {np.median(q):.3g} | "
                    f"{1e-3 / c:.0f} | {np.median(a):.3g} |")
        hists.append((area, h))
        order = np.argsort(h)[:5]
        shortest.append(f"| {area:g} | " + "; ".join(f"{h[i]:.2g} s: {a[i]:.3g} m², 2A/P {w[i]:.3g} m"
                                                    for i in order) + " |")
    print("| sliver_area [m²] | blocks | merged | smallest [s] | 1st percentile [s] | median [s] | "
          "cycles per 1 ms step | median area [m²] |")
    print("|---:|---:|---:|---:|---:|---:|---:|---:|")
    print("\n".join(rows))
    lo = math.floor(2 * math.log10(min(h.min() for _, h in hists))) / 2
    hi = math.ceil(2 * math.log10(max(h.max() for _, h in hists))) / 2
    edges = 10.0 ** np.arange(lo, hi + 0.25, 0.5)
    print("\nBlocks per half-decade of cycle [s]:\n")
    print("| cycle [s] | " + " | ".join(f"sliver_area {a:g}" for a, _ in hists) + " |")
    print("|---|" + "---:|" * len(hists))
    counts = [np.histogram(h, edges)[0] for _, h in hists]
    for i in range(len(edges) - 1):
        print(f"| {edges[i]:.2g}–{edges[i + 1]:.2g} | " + " | ".join(str(c[i]) for c in counts) + " |")
    print("\nThe five shortest cycles and their blocks:\n")
    print("| sliver_area [m²] | cycle: area, 2A/P |")
    print("|---:|---|")
    print("\n".join(shortest))


def settle(text, out, tag, max_steps=20000):
    """Steps the scene's settling stage until it ends; the state then."""
    most = [0]

    def count(_sim, report):
        most[0] = max(most[0], report.cycles)

    sim = simulation(text, out, tag, count)
    x0 = np.asarray(sim.blocks.position).copy()
    t0 = time.process_time()
    steps = 0
    while steps < max_steps:
        sim.step(1)
        steps += 1
        if steps % 20 == 0:
            print(f"  {tag}: step {steps}, t {sim.time:.4g}, most cycles {most[0]}, CPU "
                  f"{time.process_time() - t0:.0f} s", file=sys.stderr, flush=True)
        if not sim.in_stage:
            break
    cpu = time.process_time() - t0
    h = sim.history()
    to_s = SECONDS[sim.units["time"]]
    points = {c[:-2]: math.hypot(h[c][-1], h[c[:-2] + ".v"][-1]) for c in h if c.endswith(".u")}
    d = np.hypot(*(np.asarray(sim.blocks.position) - x0).T)
    return {"t": h["time"][-1] * to_s, "steps": steps, "cpu": cpu, "at_rest": not sim.in_stage,
            "points": points, "largest": d.max(), "mean": d.mean(), "most_cycles": most[0],
            "cuts": int(np.sum(h["cuts"]))}


def with_settle_dt_halved(text):
    """The scene text with its settling stage's dt halved (its other step controls held)."""
    m = re.search(r"(settle: \{[^}]*\bdt: )([0-9.eE+-]+)", text)
    return text[:m.start(2)] + f"{float(m.group(2)) / 2:.8g}" + text[m.end(2):]


def settle_table(name, texts, out, max_steps, control):
    print(f"\n### {name}: the settling stage (implicit, as the scene gives it) for each sliver_area\n")
    print("| sliver_area [m²] | stage end [s] | steps | cuts | CPU [s] | points [mm] (against sliver_area 0) | "
          "largest block displacement [mm] | mean [mm] |")
    print("|---:|---:|---:|---:|---:|---|---:|---:|")
    ref = None
    runs = [(f"{area:g}", area, text) for area, text in texts]
    if control:  # the step control's share in the differences: the scene's sliver_area at half the dt
        runs.append((f"{texts[1][0]:g}, settle.dt halved", texts[1][0], with_settle_dt_halved(texts[1][1])))
    for label, area, text in runs:
        r = settle(text, out, f"{name}-settle{label.replace(', ', '-').replace('.', '_')}", max_steps)
        ref = ref or r
        pts = "; ".join(f"{p} {1e3 * v:.3g} ({100 * (v / ref['points'][p] - 1):+.0f} %)"
                        for p, v in r["points"].items())
        print(f"| {label} | {r['t']:.3g}{'' if r['at_rest'] else ' (not at rest)'} | {r['steps']} | "
              f"{r['cuts']} | {r['cpu']:.0f} | {pts} | {1e3 * r['largest']:.3g} | {1e3 * r['mean']:.3g} |", flush=True)


def scaling_table(name, text, out, stage_cycles, scaling_steps, unscaled):
    """The settling stage in explicit cycles (local damping 0.8; at rest by the scene's own
    kinetic-energy test, as the implicit stage) at each stage_cycles (and unscaled), with the
    scene's sliver_area and with 0, against the implicit stage of the same scene (the state at
    rest of the true masses)."""
    print(f"\n### Density scaling: the coarse {name}'s settling stage in explicit cycles\n")
    area = float(re.search(r"sliver_area: ([0-9.eE+-]+)", text).group(1))
    for a, t in [(area, text), (0.0, with_sliver_area(text, 0.0))]:
        sim = simulation(t, out, f"scaling-probe{a:g}")
        k, h, _, _, c, _ = cycles(sim)
        n = int(np.count_nonzero(~np.asarray(sim.blocks.fixed, dtype=bool)))
        print(f"sliver_area {a:g} m²: {n} blocks; cycles [s]: smallest {h.min():.3g}, 1st percentile "
              f"{np.sort(h)[int(0.01 * (len(h) - 1))]:.3g}, median {np.median(h):.3g}; unscaled "
              f"{1e-3 / c:.0f} cycles per 1 ms step on the initial state\n")
    print("| sliver_area [m²] | run | stage end [s] | steps | most cycles in a step | CPU [s] | "
          "points [mm] (against implicit) | largest block displacement [mm] |")
    print("|---:|---|---:|---:|---:|---:|---|---:|")
    for a, t in [(area, text), (0.0, with_sliver_area(text, 0.0))]:
        runs = [("implicit", t)]
        for n in ([0] if unscaled else []) + stage_cycles:
            keys = {"integrator": "explicit", "stage_local_damping": 0.8}
            if n:
                keys["stage_cycles"] = n
            runs.append((f"explicit, stage_cycles {n}" if n else "explicit, unscaled", with_analysis(t, keys)))
        ref = None
        for label, tt in runs:
            r = settle(tt, out, f"scaling{a:g}-" + re.sub(r"\W+", "-", label), scaling_steps)
            ref = ref or r
            pts = "; ".join(f"{p} {1e3 * v:.4g}" + ("" if r is ref else f" ({100 * (v / ref['points'][p] - 1):+.2g} %)")
                            for p, v in r["points"].items())
            print(f"| {a:g} | {label} | {r['t']:.3g}{'' if r['at_rest'] else ' (not at rest)'} | {r['steps']} | "
                  f"{r['most_cycles']} | {r['cpu']:.0f} | {pts} | {1e3 * r['largest']:.4g} |", flush=True)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--scenes", default="slope,tunnel", help="slope, tunnel or both")
    ap.add_argument("--blocks", type=int, default=1000, help="rockmass_bench --creep: about this many blocks")
    ap.add_argument("--slope-areas", default="0,0.053,0.12,0.25", help="sliver_area values of the slope [m^2]")
    ap.add_argument("--tunnel-areas", default="0,0.0207,0.07,0.15", help="sliver_area values of the tunnel [m^2]")
    ap.add_argument("--no-settle", action="store_true", help="the cycles only, no settling stage")
    ap.add_argument("--no-control", action="store_true",
                    help="no settling stage at half the dt (the step control's share in the differences)")
    ap.add_argument("--max-steps", type=int, default=5000, help="most steps of a settling stage")
    ap.add_argument("--scaling", action="store_true", help="also density scaling on the coarse slope")
    ap.add_argument("--scaling-scene", default="tunnel", help="the scene of --scaling, slope or tunnel")
    ap.add_argument("--scaling-blocks", type=int, default=100, help="--scaling's scene at about this many blocks")
    ap.add_argument("--unscaled", action="store_true",
                    help="--scaling: also the explicit stage unscaled (some of its steps take 1e5 cycles)")
    ap.add_argument("--scaling-steps", type=int, default=3000, help="most steps of a --scaling stage")
    ap.add_argument("--stage-cycles", default="1000,50", help="stage_cycles values of --scaling")
    ap.add_argument("--out", help="scratch directory for the scenes (default: a temporary one)")
    a = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        out = a.out or tmp
        os.makedirs(out, exist_ok=True)
        for name in filter(None, a.scenes.split(",")):
            text = write_scene(name, a.blocks, out)
            areas = [float(x) for x in getattr(a, f"{name}_areas").split(",")]
            texts = [(area, with_sliver_area(text, area)) for area in areas]
            distribution(name, texts, out)
            if not a.no_settle:
                settle_table(name, texts, out, a.max_steps, not a.no_control)
        if a.scaling:
            text = write_scene(a.scaling_scene, a.scaling_blocks, out)
            scaling_table(a.scaling_scene, text, out, [int(x) for x in a.stage_cycles.split(",")], a.scaling_steps,
                          a.unscaled)


if __name__ == "__main__":
    main()
