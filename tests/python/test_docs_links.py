"""Every link and every docs/ path resolves (issue 44, docs in four kinds), so that a
page moved later cannot leave a dangling reference behind:

- every relative Markdown link ([text](target), ![alt](img/...)) in README.md,
  docs/** and the other Markdown files of the tree names an existing file, and its
  #anchor, if any, a heading of that file;
- every `docs/....md` path named in README.md, docs/** or a source, build, script or
  example file names an existing file (from the root of the tree);
- every section a docs/ path names after it (`docs/X.md, "Section"`, also over a
  comment's line break) is a heading or a bold paragraph label of that page;
- every generated block a report script splices (scripts/splice-doc.sh DOC NAME, and
  the Python writers' DOC and MARK) exists in the page it is spliced into.

Needs no build. After moving a page: python3 scripts/docs-paths.py (with the page in
its map) rewrites the references.
"""
import pathlib
import re

ROOT = pathlib.Path(__file__).resolve().parents[2]
SCOPE = ["README.md", "docs", "core", "contact", "laws", "units", "rockmass", "scene", "study",
         "forecast", "apps", "python", "bench", "tests", "scripts", "examples", "CMakeLists.txt",
         ".ci", "cmake"]
TEXT = {".md", ".cpp", ".hpp", ".h", ".c", ".py", ".sh", ".txt", ".cmake", ".in", ".yaml",
        ".yml", ".toml", ".cfg", ".json", ".pyi"}
SKIP_DIRS = {"build", ".git", "__pycache__", "prototypes"}
# they name old and example paths on purpose
OLD_PATHS_ON_PURPOSE = {"scripts/docs-paths.py", "tests/python/test_docs_links.py"}

LINK = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)\)")
DOC_PATH = re.compile(r"(?<![A-Za-z0-9_.-])docs/[A-Za-z0-9_./-]*[A-Za-z0-9_-]\.md\b")
FENCE = re.compile(r"^(```|~~~)")


def files():
    out = []
    for s in SCOPE:
        p = ROOT / s
        if p.is_file():
            out.append(p)
        elif p.is_dir():
            out += [f for f in p.rglob("*") if f.is_file() and f.suffix in TEXT
                    and not SKIP_DIRS & set(f.relative_to(ROOT).parts)]
    return sorted(out)


def markdown_files():
    return [f for f in files() if f.suffix == ".md"]


def outside_code(text):
    """The lines of a Markdown text outside fenced code blocks, with their numbers."""
    fenced = False
    for n, line in enumerate(text.split("\n"), 1):
        if FENCE.match(line.strip()):
            fenced = not fenced
            continue
        if not fenced:
            yield n, line


def slug(title):
    """GitHub's anchor of a heading."""
    title = re.sub(r"`", "", title.strip().lower())
    return re.sub(r"[^\w\- ]", "", title).replace(" ", "-")


def anchors(path):
    out = set()
    for _, line in outside_code(path.read_text()):
        m = re.match(r"^#{1,6}\s+(.*?)\s*#*\s*$", line)
        if m:
            out.add(slug(m.group(1)))
    return out


def test_relative_links_resolve():
    bad = []
    for f in markdown_files():
        for n, line in outside_code(f.read_text()):
            for target in LINK.findall(line):
                if re.match(r"^[a-z][a-z0-9+.-]*:", target) or target.startswith("<"):
                    continue
                file, _, anchor = target.partition("#")
                dest = (f.parent / file) if file else f
                where = f"{f.relative_to(ROOT)}:{n}: ({target})"
                if not dest.exists():
                    bad.append(f"{where}: no file {dest.resolve().relative_to(ROOT) if dest.resolve().is_relative_to(ROOT) else dest}")
                elif anchor and dest.suffix == ".md" and anchor not in anchors(dest):
                    bad.append(f"{where}: no heading #{anchor} in {dest.resolve().relative_to(ROOT)}")
    assert not bad, "dangling Markdown links:\n" + "\n".join(bad)


def test_docs_paths_named_anywhere_exist():
    bad = []
    for f in files():
        if str(f.relative_to(ROOT)) in OLD_PATHS_ON_PURPOSE:
            continue
        try:
            text = f.read_text()
        except UnicodeDecodeError:
            continue
        for m in DOC_PATH.finditer(text):
            if not (ROOT / m.group(0)).is_file():
                n = text.count("\n", 0, m.start()) + 1
                bad.append(f"{f.relative_to(ROOT)}:{n}: {m.group(0)}")
    assert not bad, ("paths to pages that do not exist (moved? add the page to "
                     "scripts/docs-paths.py's map and run it):\n" + "\n".join(bad))


SECTION_REF = re.compile(r'(?<![A-Za-z0-9_.-])(docs/[A-Za-z0-9_./-]*[A-Za-z0-9_-]\.md),?\s*'
                         r'(?:section\s+)?\(?\\?"([A-Za-z`][^"();{}]{0,160}?)\\?"')


def norm(title):
    """A title as referred to: broken over comment lines joined, punctuation and case ignored."""
    title = re.sub(r"\n\s*(?:///|//|#|\*)?", " ", title)
    return re.sub(r"[^a-z0-9]+", " ", title.lower()).strip()


def test_sections_named_after_a_docs_path_exist():
    bad = []
    for f in files():
        if str(f.relative_to(ROOT)) in OLD_PATHS_ON_PURPOSE:
            continue
        try:
            text = f.read_text()
        except UnicodeDecodeError:
            continue
        for m in SECTION_REF.finditer(text):
            page = ROOT / m.group(1)
            title = norm(m.group(2))
            if not page.is_file() or not title:
                continue
            body = page.read_text()
            labels = [norm(h) for h in re.findall(r"^#{1,6}\s+(.*)$", body, re.M)]
            labels += [norm(b) for b in re.findall(r"\*\*([^*]+)\*\*", body)]
            if not any(x and (x.startswith(title) or title.startswith(x)) for x in labels):
                n = text.count("\n", 0, m.start()) + 1
                bad.append(f'{f.relative_to(ROOT)}:{n}: {m.group(1)}, "{m.group(2)}"')
    assert not bad, ("sections named that are not headings (or bold labels) of their page "
                     "(moved? add it to SECTIONS of scripts/docs-paths.py and run it):\n" + "\n".join(bad))


def spliced_blocks():
    """[(script, doc path relative to the root, block name)] of every splice the report
    scripts make with literal names."""
    out = []
    for f in sorted((ROOT / "scripts").iterdir()):
        if f.name == "splice-doc.sh" or f.suffix not in {".sh", ".py"}:
            continue
        text = f.read_text()
        if f.suffix == ".sh":
            # splice() { ... "$root/docs/X.md" "$1" "$2"; } then: splice NAME FILE
            fixed = re.search(r'^splice\(\)\s*\{[^}]*?(docs/[\w./-]+\.md)"?\s+"\$1"', text, re.M)
            for line in text.split("\n"):
                if "splice" not in line or line.lstrip().startswith("#"):
                    continue
                m = re.search(r'(docs/[\w./-]+\.md)"?\s+"?([a-z][a-z0-9-]*)\b', line)
                if m:
                    out.append((f.name, m.group(1), m.group(2)))
                    continue
                m = re.match(r'\s*splice\s+([a-z][a-z0-9-]*)\s', line)
                if m and fixed:
                    out.append((f.name, fixed.group(1), m.group(1)))
        else:
            mark = re.search(r'^MARK\s*=\s*"([^"]+)"', text, re.M)
            doc = re.search(r'^(?:DOC|NOTE)\s*=\s*(?:\w+\.)?ROOT((?:\s*/\s*"[^"]+")+)', text, re.M)
            if mark and doc:
                path = "/".join(re.findall(r'"([^"]+)"', doc.group(1)))
                out.append((f.name, path, mark.group(1)))
    return out


def test_spliced_blocks_exist_where_they_are_spliced():
    blocks = spliced_blocks()
    assert len(blocks) >= 20, blocks   # the parser still finds the report scripts' splices
    bad = []
    for script, doc, name in blocks:
        page = ROOT / doc
        if not page.is_file():
            bad.append(f"scripts/{script}: {doc} does not exist")
            continue
        lines = page.read_text().split("\n")
        if f"<!-- {name}:begin -->" not in lines or f"<!-- {name}:end -->" not in lines:
            bad.append(f"scripts/{script}: no <!-- {name}:begin/end --> in {doc}")
    assert not bad, "\n".join(bad)
