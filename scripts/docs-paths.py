#!/usr/bin/python3
"""Docs in four kinds (issue 44): moves the pages of docs/ into docs/guide/,
docs/reference/, docs/design/ and docs/notes/ and rewrites every reference to an
old path, so that a branch written against the old layout can be merged and this
script re-run.

What it does, each step idempotent (a second run changes nothing):

1. PAGES maps an old page docs/X.md to its new place. A page still at its old
   path is moved there with `git mv` (a page added by a branch that did not know
   the layout, e.g. docs/bolts.md). When both the old and the new path exist
   (a branch edited a page that was split or moved here) nothing is moved: the
   script names the page, to be merged by hand.
2. Every mention of an old path in README.md, docs/**, examples/**/README.md and
   the source and build files (core/ contact/ laws/ units/ rockmass/ scene/
   study/ forecast/ apps/ python/ bench/ tests/ scripts/ examples/ CMakeLists.txt
   .ci) is rewritten:
   - `docs/X.md, "Section"` (also `docs/X.md "Section"`, `docs/X.md ("Section"`,
     `docs/X.md, section "Section"`): to the page the section went to (SECTIONS,
     matched on the start of the title), else to PAGES[X];
   - `docs/X.md" MARKER` and `docs/X.md MARKER` (the splice calls of the report
     scripts, scripts/splice-doc.sh): to the page that holds the generated
     block <!-- MARKER:begin --> now (MARKERS);
   - any other `docs/X.md`, and `"docs" / "X.md"` (pathlib): to PAGES[X].
3. Relative Markdown links ([text](target), ![alt](img/...)) in Markdown files
   that no longer resolve are resolved again: from the page's old place in docs/
   (a moved page's `img/x.png` becomes `../img/x.png`) and through PAGES (and
   SECTIONS for an anchor).

Usage: python3 scripts/docs-paths.py [--dry-run]       (from anywhere in the tree)
"""
import os
import pathlib
import re
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent

# Old page (under docs/) -> new page (under docs/). Pages split by hand give the
# page that took the most of them; SECTIONS and MARKERS say where the rest went.
PAGES = {
    # the guide: how to do things
    "fitting.md": "guide/fitting.md",
    "forecast.md": "guide/forecast.md",
    "studies.md": "guide/studies.md",
    "python.md": "guide/python.md",
    "library.md": "guide/library.md",
    "rockmass.md": "guide/rockmass.md",
    "toppling-study.md": "guide/toppling-study.md",
    "speed-accuracy.md": "guide/choosing-step-controls.md",   # split: SECTIONS, MARKERS
    # the reference: keys, outputs, commands, equations, parameter tables
    "scene-format.md": "reference/scene-format.md",
    "outputs.md": "reference/outputs.md",
    "laws.md": "reference/laws.md",                          # split: SECTIONS
    "engine.md": "reference/engine.md",                      # split: SECTIONS, MARKERS
    "contacts.md": "reference/contacts.md",
    "rheology-in-dda.md": "reference/rheology-in-dda.md",
    # pages other branches are adding (issue 44's lead merges them after this one)
    "bolts.md": "reference/bolts.md",
    "water.md": "reference/water.md",
    "stages.md": "reference/stages.md",
    # dated measurements
    "performance.md": "notes/performance.md",
}

# (old page, section title) -> new page, for sections that left their page's
# main destination. A reference's title matches when one title starts with the
# other (punctuation and case ignored), so '"Stability"' finds "Stability map".
SECTIONS = {
    ("speed-accuracy.md", "Adaptive creep stepping"): "reference/step-controls.md",
    ("speed-accuracy.md", "Step doubling"): "reference/step-controls.md",
    ("speed-accuracy.md", "What is not done"): "reference/step-controls.md",
    ("speed-accuracy.md", "Measurements"): "notes/step-controls.md",
    ("speed-accuracy.md", "Against the targets"): "notes/step-controls.md",
    ("speed-accuracy.md", "The toppling model"): "notes/step-controls.md",
    ("speed-accuracy.md", "The shipped toppling example, with and without its settling stage"): "notes/step-controls.md",
    ("speed-accuracy.md", "The seed's slope itself, refined"): "notes/step-controls.md",
    ("speed-accuracy.md", "Stability map"): "notes/step-controls.md",
    ("speed-accuracy.md", "Nonlinear laws: the Norton map"): "notes/step-controls.md",
    ("speed-accuracy.md", "DDA spot-check"): "notes/step-controls.md",
    ("speed-accuracy.md", "Adaptive stepping tests"): "notes/step-controls.md",
    ("laws.md", "From the seed's hereditary sum to a state per contact"): "design/law-interface.md",
    ("laws.md", "Using a law from C++"): "design/law-interface.md",
    ("laws.md", "Adding a law"): "design/law-interface.md",
    ("laws.md", "Adding a nonlinear law"): "design/law-interface.md",
    ("engine.md", "Why `amg`, and how it works"): "design/linear-solvers.md",
    ("studies.md", "Measured scaling"): "notes/performance.md",
    # contacts.md's diary, moved to notes/contact-solves.md before this layout
    ("contacts.md", "Why the iteration does not settle"): "notes/contact-solves.md",
    ("contacts.md", "The same slope settled dynamically"): "notes/contact-solves.md",
    ("contacts.md", "Friction that pushed"): "notes/contact-solves.md",
    ("contacts.md", "Springs of a joint on point contacts"): "notes/contact-solves.md",
    ("contacts.md", "Contacts that stop"): "notes/contact-solves.md",
    ("contacts.md", "Stick and slip"): "notes/contact-solves.md",
    ("contacts.md", "A consistent elastic-plastic joint"): "notes/contact-solves.md",
    ("contacts.md", "The wall converges when the iteration is not cut"): "notes/contact-solves.md",
    ("contacts.md", "Inexact iterates"): "notes/contact-solves.md",
    ("contacts.md", "The iteration limit in static analysis"): "notes/contact-solves.md",
    ("contacts.md", "A semismooth Newton iteration"): "notes/contact-solves.md",
    ("contacts.md", "Relaxation to equilibrium in static analysis"): "notes/contact-solves.md",
    ("engine.md", "The seed's slope with collapse stages, refined over 100 days"): "notes/dynamic-stages.md",
}

# (old page, generated block) -> new page: where <!-- MARKER:begin --> is now.
MARKERS = {
    ("speed-accuracy.md", "refinement-examples"): "guide/choosing-step-controls.md",
    ("speed-accuracy.md", "accuracy-table"): "notes/step-controls.md",
    ("speed-accuracy.md", "refinement-damped-wall-levels"): "notes/step-controls.md",
    ("speed-accuracy.md", "toppling-table"): "notes/step-controls.md",
    ("speed-accuracy.md", "refinement-toppling-creep"): "notes/step-controls.md",
    ("speed-accuracy.md", "refinement-toppling-creep-levels"): "notes/step-controls.md",
    ("speed-accuracy.md", "refinement-goodman-creep"): "notes/step-controls.md",
    ("speed-accuracy.md", "refinement-collapse-stages"): "notes/step-controls.md",
    ("speed-accuracy.md", "stability-table"): "notes/step-controls.md",
    ("speed-accuracy.md", "stability-power"): "notes/step-controls.md",
    ("speed-accuracy.md", "stability-dda"): "notes/step-controls.md",
    ("contacts.md", "incline-drop"): "notes/contact-rules.md",
    ("engine.md", "gravity-ramp"): "notes/dynamic-stages.md",
    ("engine.md", "refinement-collapse-stages"): "notes/dynamic-stages.md",
    ("engine.md", "static-mechanisms"): "notes/dynamic-stages.md",
}

# Where references are rewritten (relative to the root); files and folders.
SCOPE = ["README.md", "docs", "core", "contact", "laws", "units", "rockmass", "scene", "study",
         "forecast", "apps", "python", "bench", "tests", "scripts", "examples", "CMakeLists.txt",
         ".ci", "cmake"]
TEXT = {".md", ".cpp", ".hpp", ".h", ".c", ".py", ".sh", ".txt", ".cmake", ".in", ".yaml",
        ".yml", ".toml", ".cfg", ".json", ".patch", ".pyi"}
SELF = {"scripts/docs-paths.py"}     # holds the map itself

OLD = "|".join(re.escape(p[:-3]) for p in sorted(PAGES, key=len, reverse=True))
PATH = re.compile(r"(?<![A-Za-z0-9_.-])docs/(" + OLD + r")\.md(?![A-Za-z0-9_-])")
TITLE = re.compile(r'(,?\s*(?:section\s+)?\(?\\?)"([^"]{1,160}?)\\?"')
NEW = re.compile(r"(?<![A-Za-z0-9_.-])docs/((?:guide|reference|design|notes)/[a-z0-9-]+\.md)(?![A-Za-z0-9_-])")
MARKER = re.compile(r'("?\s+"?)([a-z0-9][a-z0-9-]*)\b')
# Python's pathlib spelling: ROOT / "docs" / "outputs.md"
PYPATH = re.compile(r'(["\'])docs\1(\s*/\s*)(["\'])(' + OLD + r')\.md\3')
LINK = re.compile(r"(!?\[[^\]]*\]\()([^)\s]+)(\))")


def norm(title):
    """A section title as referred to: a title broken over comment lines
    ('"Step\n  // doubling"') joined, punctuation and case ignored."""
    title = re.sub(r"\n\s*(?:///|//|#|\*)?", " ", title)
    return re.sub(r"[^a-z0-9]+", " ", title.lower()).strip()


def section_page(page, title):
    t = norm(title)
    if not t:
        return None
    for (p, s), new in SECTIONS.items():
        if p == page and (norm(s).startswith(t) or t.startswith(norm(s))):
            return new
    return None


def headings(path):
    return [m.group(1) for m in re.finditer(r"^#{1,6}\s+(.*?)\s*$", path.read_text(), re.M)]


def slug(title):
    """GitHub's anchor of a heading."""
    return re.sub(r"[^\w\- ]", "", title.strip().lower()).replace(" ", "-")


def rewrite_paths(text):
    def one(m):
        page = m.group(1) + ".md"
        new = PAGES[page]
        rest = text[m.end():m.end() + 200]
        t = TITLE.match(rest)
        if t and section_page(page, t.group(2)):
            new = section_page(page, t.group(2))
        else:
            k = MARKER.match(rest)
            if k and (page, k.group(2)) in MARKERS:
                new = MARKERS[(page, k.group(2))]
        return "docs/" + new
    text = PATH.sub(one, text)

    def moved(m):
        """docs/KIND/X.md, "Section" where the section is not on that page but left
        it for another (SECTIONS): to that page."""
        page = m.group(1)
        t = TITLE.match(text[m.end():m.end() + 200])
        if not t or not (ROOT / "docs" / page).is_file():
            return m.group(0)
        if any(norm(h).startswith(norm(t.group(2))) or norm(t.group(2)).startswith(norm(h))
               for h in headings(ROOT / "docs" / page) if norm(h)):
            return m.group(0)
        for old, new in PAGES.items():
            if new == page and section_page(old, t.group(2)):
                return "docs/" + section_page(old, t.group(2))
        return m.group(0)
    text = NEW.sub(moved, text)

    def py(m):
        q, sep, q2 = m.group(1), m.group(2), m.group(3)
        parts = PAGES[m.group(4) + ".md"].split("/")
        return q + "docs" + q + sep + sep.join(q2 + p + q2 for p in parts)
    return PYPATH.sub(py, text)


def rewrite_links(path, text):
    """Relative links of a Markdown file at `path` (relative to the root)."""
    here = path.parent

    def one(m):
        target = m.group(2)
        if re.match(r"^[a-z]+:", target) or target.startswith(("#", "/", "<")):
            return m.group(0)
        file, _, anchor = target.partition("#")
        if not file or (ROOT / here / file).exists():
            return m.group(0)
        # the old place of a moved page: docs/X.md -> the file from docs/
        tries = [os.path.normpath(here / file)]
        if here.parts[:1] == ("docs",):
            tries.append(os.path.normpath(pathlib.Path("docs") / file))
        for t in tries:
            new = t
            if t.startswith("docs/") and t[5:] in PAGES:
                new = "docs/" + PAGES[t[5:]]
                if anchor:
                    for (p, s), n in SECTIONS.items():
                        if p == t[5:] and slug(s) == anchor:
                            new = "docs/" + n
            if (ROOT / new).exists():
                rel = os.path.relpath(ROOT / new, ROOT / here)
                return m.group(1) + rel + ("#" + anchor if anchor else "") + m.group(3)
        return m.group(0)
    return LINK.sub(one, text)


def files():
    out = []
    for s in SCOPE:
        p = ROOT / s
        if p.is_file():
            out.append(p)
        elif p.is_dir():
            out += [f for f in p.rglob("*") if f.is_file() and f.suffix in TEXT
                    and "img" not in f.relative_to(ROOT).parts[:2]]
    return [f for f in out if str(f.relative_to(ROOT)) not in SELF]


def move_pages(dry):
    conflicts = []
    for old, new in PAGES.items():
        src, dst = ROOT / "docs" / old, ROOT / "docs" / new
        if not src.exists():
            continue
        if dst.exists():
            conflicts.append(f"docs/{old} and docs/{new} both exist: merge docs/{old} into "
                             f"docs/{new} (or the pages its sections went to) by hand, then git rm it")
            continue
        print(f"git mv docs/{old} docs/{new}")
        if not dry:
            dst.parent.mkdir(parents=True, exist_ok=True)
            subprocess.run(["git", "-C", str(ROOT), "mv", f"docs/{old}", f"docs/{new}"], check=True)
    return conflicts


def main():
    dry = "--dry-run" in sys.argv[1:]
    conflicts = move_pages(dry)
    changed = 0
    for f in files():
        rel = f.relative_to(ROOT)
        try:
            text = f.read_text()
        except UnicodeDecodeError:
            continue
        new = rewrite_paths(text)
        if f.suffix == ".md":
            new = rewrite_links(rel, new)
        if new != text:
            changed += 1
            print(f"rewrote {rel}")
            if not dry:
                f.write_text(new)
    print(f"docs-paths: {changed} file(s) rewritten")
    for c in conflicts:
        print("docs-paths: " + c, file=sys.stderr)
    return 1 if conflicts else 0


if __name__ == "__main__":
    sys.exit(main())
