#!/usr/bin/python3
"""The shipped examples with the two contact solves (docs/reference/contacts.md, "Contact
solves"): runs every example as shipped (analysis.contact_solver open-close,
the default) and with `contact_solver: newton`, and prints each headline
result of scripts/example_results.py (the final displacement of each
measurement point, the first damage failure) with the relative difference.
With --write the table is spliced into docs/notes/contact-solves.md between
<!-- examples-solves:begin/end -->.

Usage: /usr/bin/python3 scripts/contact-solver-examples.py [--write]   (build: $RHEODDA_BUILD_DIR or build/)
"""
import os
import pathlib
import re
import subprocess
import sys
import tempfile

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import example_results as er  # noqa: E402

NOTE = er.ROOT / "docs" / "notes" / "contact-solves.md"
MARK = "examples-solves"


def newton_variant(example):
    """A hidden copy of the example beside it (its relative paths still resolve)
    with `contact_solver: newton` as the analysis's first key."""
    text = example.read_text()
    m = re.search(r"^analysis:[ \t]*\n", text, flags=re.M)
    if m is None:
        raise SystemExit(f"{example}: no block-style `analysis:` section to add contact_solver to")
    text = text[:m.end()] + "  contact_solver: newton\n" + text[m.end():]
    variant = example.with_name(f".contact-solver-newton-{example.name}")
    variant.write_text(text)
    return variant


def table():
    scenes = er.examples()
    variants = [newton_variant(e) for e in scenes]
    try:
        with tempfile.TemporaryDirectory() as tmp:
            ref = er.headlines(scenes, pathlib.Path(tmp) / "open-close")
            new = er.headlines(variants, pathlib.Path(tmp) / "newton")
    finally:
        for v in variants:
            v.unlink()
    lines = ["| example | quantity | open-close | newton | relative difference |", "|---|---|---:|---:|---:|"]
    for e, v in zip(scenes, variants):
        a, b = ref[e], new[v]
        if isinstance(a, Exception) or isinstance(b, Exception):
            lines.append(f"| {er.label(e)} | run failed | {a if isinstance(a, Exception) else ''} | "
                         f"{b if isinstance(b, Exception) else ''} | |")
            continue
        for (q, x, u), (_, y, _) in zip(a, b):
            d = abs(y - x) / abs(x) if x != 0 else abs(y)
            lines.append(f"| {er.label(e)} | {q} [{u}] | {x:.6g} | {y:.6g} | {d:.2g} |")
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    t = table()
    if "--write" in sys.argv:
        with tempfile.NamedTemporaryFile("w", suffix=".md", delete=False) as f:
            f.write(t)
        subprocess.run(["bash", str(er.ROOT / "scripts" / "splice-doc.sh"), str(NOTE), MARK, f.name], check=True)
        os.unlink(f.name)
    print(t, end="")
