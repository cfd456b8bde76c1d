#!/usr/bin/python3
"""Headline results of the shipped examples (docs/reference/outputs.md, "Shipped examples:
headline results"): runs `rheodda run` on every examples/*.yaml and
examples/rockmass/*.yaml and reports, per
example, the final displacement magnitude |(u, v)| of each measurement point
[length] and, for a joint set whose damage law failed, the time of the first
failure [time] (summary.json). With --write the table is spliced into
docs/reference/outputs.md between <!-- example-results:begin/end -->; the test
tests/python/test_example_results.py reruns the examples and fails when a
value drifts from the documented one by more than its tolerance.

The same runs give the sizes of the examples' output folders (docs/reference/outputs.md,
"Shipped examples: output sizes", between <!-- example-output-sizes:begin/end -->):
history.csv's rows and bytes, contacts.csv, the frames, the whole folder, and a bound
on the folder that the test holds each run to.

Usage: /usr/bin/python3 scripts/example_results.py [--write]   (build: $RHEODDA_BUILD_DIR or build/)
"""
import concurrent.futures
import csv
import json
import math
import os
import pathlib
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parent.parent
DOC = ROOT / "docs" / "reference" / "outputs.md"
MARK = "example-results"
# Relative tolerance of a documented value: the runs are deterministic on one
# machine; 1e-4 leaves room for another BLAS kernel's rounding, not for a change
# of behaviour.
TOLERANCE = 1e-4


def binary():
    build = pathlib.Path(os.environ.get("RHEODDA_BUILD_DIR", ROOT / "build"))
    return build / "apps" / "rheodda"


def examples():
    """Every shipped example scene: examples/*.yaml and examples/rockmass/*.yaml, not the
    hidden variants the report scripts write beside them (.refine-variant-*.yaml)."""
    found = sorted((ROOT / "examples").glob("*.yaml")) + sorted((ROOT / "examples" / "rockmass").glob("*.yaml"))
    return [p for p in found if not p.name.startswith(".")]


def label(example):
    """An example's name in the table: its path under examples/ (rockmass/tunnel.yaml)."""
    return example.relative_to(ROOT / "examples").as_posix()


def run(example, out_dir):
    """`rheodda run` of one example into out_dir."""
    subprocess.run([str(binary()), "run", str(example), "-o", str(out_dir)], check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)


def headline_of(out_dir):
    """[(quantity, value, unit)] of a run's outputs in out_dir."""
    out_dir = pathlib.Path(out_dir)
    with open(out_dir / "history.csv") as f:
        units_line = f.readline()
        rows = list(csv.DictReader(f))
    units = dict(kv.split("=") for kv in units_line.lstrip("# units:").split())
    last = rows[-1]
    points = [c[:-2] for c in rows[0] if c.endswith(".u") and c[:-2] + ".v" in rows[0]]
    out = [(f"displacement of {p} at t = {float(last['time']):g} {units['time']}",
            math.hypot(float(last[p + ".u"]), float(last[p + ".v"])), units["length"]) for p in points]
    summary = json.loads((out_dir / "summary.json").read_text())
    for joint, c in summary.get("creep", {}).items():
        if c.get("failures", 0) > 0:
            out.append((f"first failure on {joint}", float(c["first_failure_time"]), units["time"]))
    return out


def headline(example, out_dir):
    """[(quantity, value, unit)] of one example after `rheodda run` into out_dir."""
    run(example, out_dir)
    return headline_of(out_dir)


def runs(scenes, work_dir):
    """{example: its output folder under work_dir, or the exception its run raised}, the
    runs side by side on every core (each `rheodda run` is one process on one core)."""
    def one(e):
        out = pathlib.Path(work_dir) / label(e).replace("/", "_")
        try:
            run(e, out)
            return out
        except Exception as error:  # reported by the caller, per example
            return error
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, os.cpu_count() or 1)) as pool:
        return dict(zip(scenes, pool.map(one, scenes)))


def headlines(scenes, work_dir):
    """{example: headline(example) or the exception its run raised}."""
    out = {}
    for e, r in runs(scenes, work_dir).items():
        try:
            out[e] = r if isinstance(r, Exception) else headline_of(r)
        except Exception as error:
            out[e] = error
    return out


def table(found):
    """The headline table of {example: output folder} (runs())."""
    lines = ["| example | quantity | value | unit | tolerance |", "|---|---|---:|---|---:|"]
    for e, out in found.items():
        if isinstance(out, Exception):
            raise out
        for q, v, u in headline_of(out):
            lines.append(f"| {label(e)} | {q} | {v:.9g} | {u} | {TOLERANCE:g} |")
    return "\n".join(lines) + "\n"


SIZES = "example-output-sizes"
# A folder's bound: this factor on its documented size, rounded up to two significant
# digits: room for an adaptive path that ends a few steps or rows apart, not for an
# output that grows with the steps again.
SIZE_MARGIN = 1.5


def folder_bytes(path):
    """Bytes of the files under path [byte]."""
    return sum(f.stat().st_size for f in pathlib.Path(path).rglob("*") if f.is_file())


def sizes_of(out_dir):
    """{history_rows, history, contacts, frames, folder}: history.csv's rows [-] and the
    bytes of history.csv, contacts.csv, the frames (frames/ and the .pvd collections) and
    the whole folder [byte] of a run's output folder."""
    out_dir = pathlib.Path(out_dir)
    with open(out_dir / "history.csv") as f:
        rows = sum(1 for line in f if line[:1] not in ("#", "t", ""))
    size = lambda name: (out_dir / name).stat().st_size if (out_dir / name).exists() else 0
    frames = folder_bytes(out_dir / "frames") if (out_dir / "frames").exists() else 0
    frames += sum(size(p) for p in ("blocks.pvd", "contacts.pvd", "bolts.pvd"))
    return {"history_rows": rows, "history": size("history.csv"), "contacts": size("contacts.csv"),
            "frames": frames, "folder": folder_bytes(out_dir)}


def megabytes(b):
    return f"{b / 1e6:.3g}"


def bound_of(folder):
    """The bound of a folder of `folder` bytes [MB]: SIZE_MARGIN x, up to two significant digits."""
    mb = SIZE_MARGIN * folder / 1e6
    step = 10 ** (math.floor(math.log10(mb)) - 1) if mb > 0 else 0.01
    return max(0.01, math.ceil(mb / step) * step)


def sizes_table(found):
    """The output sizes table of {example: output folder} (runs())."""
    lines = ["| example | history.csv rows | history.csv [MB] | contacts.csv [MB] | frames [MB] | folder [MB] | bound [MB] |",
             "|---|---:|---:|---:|---:|---:|---:|"]
    for e, out in found.items():
        if isinstance(out, Exception):
            raise out
        s = sizes_of(out)
        lines.append(f"| {label(e)} | {s['history_rows']} | {megabytes(s['history'])} | {megabytes(s['contacts'])} | "
                     f"{megabytes(s['frames'])} | {megabytes(s['folder'])} | {bound_of(s['folder']):.2g} |")
    return "\n".join(lines) + "\n"


def documented_sizes():
    """{example: bound of its output folder [byte]} from docs/reference/outputs.md."""
    text = DOC.read_text()
    body = text.split(f"<!-- {SIZES}:begin -->")[1].split(f"<!-- {SIZES}:end -->")[0]
    return {cells[0]: float(cells[6]) * 1e6
            for cells in ([c.strip() for c in line.strip().strip("|").split("|")]
                          for line in body.strip().splitlines()[2:])}


def splice(mark, text):
    with tempfile.NamedTemporaryFile("w", suffix=".md", delete=False) as f:
        f.write(text)
    subprocess.run(["bash", str(ROOT / "scripts" / "splice-doc.sh"), str(DOC), mark, f.name], check=True)
    os.unlink(f.name)


def documented():
    """{(example, quantity): (value, tolerance)} from the table in docs/reference/outputs.md."""
    text = DOC.read_text()
    body = text.split(f"<!-- {MARK}:begin -->")[1].split(f"<!-- {MARK}:end -->")[0]
    rows = {}
    for line in body.strip().splitlines()[2:]:
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        rows[(cells[0], cells[1])] = (float(cells[2]), float(cells[4]))
    return rows


if __name__ == "__main__":
    with tempfile.TemporaryDirectory() as tmp:
        found = runs(examples(), tmp)
        t, s = table(found), sizes_table(found)
    if "--write" in sys.argv:
        splice(MARK, t)
        splice(SIZES, s)
    print(t, end="")
    print()
    print(s, end="")
