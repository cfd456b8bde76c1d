"""The guides, the reference, the design pages and the READMEs say what the program does and
how to use it; the history of how it got there lives in docs/notes/. This test fails on the
three marks of a lab notebook outside docs/notes/:

- issue and pull-request numbers: "issue 51", "issues 44 and 51", "#51", "PR 12", and an
  issue named by its title (`issue "Rock masses that run"`);
- commit hashes: 7 to 40 hexadecimal digits standing alone in the text, with at least one
  digit and one letter a-f (so no plain number, no word such as "defaced"), not part of a
  longer hexadecimal run (a SHA-256 of a data file), a version, a file name, an anchor or a
  colour (#a1b2c3); and "the commit message";
- dates: 2026-11, 2026-11-29, "November 2026", "Nov 29, 2026" (a year alone, as in
  "Shi 1988" or a rock mass's seed 2026, is not a date).

A measurement that a page needs as a rule of thumb is stated in the present tense, with the
script that regenerates it; its dated record goes to the matching note. Needs no build.
"""
import pathlib
import re

ROOT = pathlib.Path(__file__).resolve().parents[2]

ISSUE = re.compile(
    r"\b(?:issues?|PRs?|pull[ -]requests?)\s+#?\d+\b"            # issue 51, PR #12
    r"|\bissues?\s+#?\d+(?:\s*(?:,|and|&)\s*#?\d+)+"             # issues 44, 51 and 53
    r"|(?<![\w&/#.\])`])#\d+\b(?![\w-])"                         # #51 (not an anchor, an entity, a colour)
    r"|\bissues?\s+[\"“]",                                       # issue "Rock masses that run"
    re.I)
HASH = re.compile(
    r"(?<![\w.\-/#+])(?=[0-9a-f]*[a-f])(?=[0-9a-f]*\d)[0-9a-f]{7,40}(?![\w\-])"
    r"|\bcommit messages?\b")
MONTH = (r"(?:Jan(?:uary)?|Feb(?:ruary)?|Mar(?:ch)?|Apr(?:il)?|May|June?|July?|Aug(?:ust)?"
         r"|Sep(?:t(?:ember)?)?|Oct(?:ober)?|Nov(?:ember)?|Dec(?:ember)?)")
DATE = re.compile(
    r"\b20\d\d-(?:0[1-9]|1[0-2])(?:-[0-3]\d)?\b"                 # 2026-11, 2026-11-29
    rf"|\b(?:\d{{1,2}}\s+)?{MONTH}\.?\s+(?:\d{{1,2}},?\s+)?20\d\d\b")  # (29) November (29,) 2026

MARKS = (("an issue number", ISSUE), ("a commit", HASH), ("a date", DATE))


def pages():
    """README.md and every page of docs/ but the notes."""
    out = [ROOT / "README.md"]
    out += [p for p in sorted((ROOT / "docs").rglob("*.md")) if "notes" not in p.relative_to(ROOT / "docs").parts]
    return out


def marks(text):
    """[(line number, kind, the text found)] of every history mark in text."""
    found = []
    for n, line in enumerate(text.split("\n"), 1):
        for kind, rx in MARKS:
            found += [(n, kind, m.group(0)) for m in rx.finditer(line)]
    return found


def test_the_patterns_find_history_and_nothing_else():
    history = [
        "the tunnel refined (issue 51)", "see issues 44 and 51", "fixed in #51.", "PR #12",
        'the issue "Rock masses that run" asked', "built at commit b0f612e", "as of 83839ee,",
        "(before: c6cd2b0)", "see the commit message", "measured 2026-11", "(2026-11-29)",
        "on 29 November 2026", "in Nov 2026", "Nov 29, 2026",
    ]
    for s in history:
        assert marks(s), s
    clean = [
        "Shi 1988", "Goodman & Bray 1976", "55 blocks from seed 2026", "1000000 points",
        "0.00209961 m", "2.61572904e-05 m", "colour #a1b2c3", "[a](page.md#2-results)",
        "version 0.4.1", "sha256 " + "0123456789abcdef" * 4, "img/tour-1a2b3c4d.png",
        "block #", "&#8212;", "`#51`", "the engine commits the step", "deadbeef",
        "decade", "1e10 and 2e-5", "Table 1 row 1", "Figure 11", "n = 1 … 20",
        "issue a warning", "May the step", "dt_max 10 d", "at 10.3 and 10.2 d",
    ]
    for s in clean:
        assert not marks(s), (s, marks(s))


def test_no_issue_numbers_commits_or_dates_outside_the_notes():
    assert len(pages()) > 20   # the guide, the reference, the design pages and the READMEs
    bad = [f"{p.relative_to(ROOT)}:{n}: {kind}: {found!r}"
           for p in pages() for n, kind, found in marks(p.read_text())]
    assert not bad, ("history in a guide, reference or design page (move it to the matching "
                     "note in docs/notes/ and link to it):\n" + "\n".join(bad))
