"""The shipped examples' headline results stay what docs/reference/outputs.md documents
("Shipped examples: headline results", written by scripts/example_results.py):
every examples/*.yaml and examples/rockmass/*.yaml is run again and each documented value must hold within
its tolerance, and every example must be documented. And every number quoted in a
doc or an example's comment as <!--n:NAME-->TEXT<!--/n--> is what scripts/doc_numbers.py
regenerates from the same runs (or from the command it names)."""
import importlib.util
import pathlib
import tempfile

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]


def _module(name):
    spec = importlib.util.spec_from_file_location(name, ROOT / "scripts" / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


example_results = _module("example_results")
doc_numbers = _module("doc_numbers")

DOCUMENTED = example_results.documented()


@pytest.fixture(scope="module")
def work():
    with tempfile.TemporaryDirectory() as tmp:
        yield pathlib.Path(tmp)


@pytest.fixture(scope="module")
def runs(work):
    """Every example run once, side by side on every core: {example: output folder or exception}."""
    return example_results.runs(example_results.examples(), work / "runs")


@pytest.mark.parametrize("example", example_results.examples(), ids=example_results.label)
def test_headline_results_match_the_documented_values(example, runs):
    out = runs[example]
    if isinstance(out, Exception):
        raise out
    results = example_results.headline_of(out)
    name = example_results.label(example)
    assert results, f"{name}: no measurement point and no failure to report"
    for quantity, value, _unit in results:
        key = (name, quantity)
        assert key in DOCUMENTED, (
            f"{name}: '{quantity}' is not in docs/reference/outputs.md; run "
            "/usr/bin/python3 scripts/example_results.py --write")
        documented, tolerance = DOCUMENTED[key]
        assert abs(value - documented) <= tolerance * abs(documented), (
            f"{name}: {quantity} = {value:.9g}, documented {documented:.9g} "
            f"(tolerance {tolerance:g} relative): the behaviour changed; if on purpose, regenerate the table")


@pytest.mark.parametrize("example", example_results.examples(), ids=example_results.label)
def test_output_folders_stay_within_their_documented_bound(example, runs):
    # Outputs sized to the question (docs/reference/outputs.md, "Shipped examples: output
    # sizes"): history.csv at the output times, not a row per step.
    out = runs[example]
    if isinstance(out, Exception):
        raise out
    name = example_results.label(example)
    bounds = example_results.documented_sizes()
    assert name in bounds, (f"{name}: no output size in docs/reference/outputs.md; run "
                            "/usr/bin/python3 scripts/example_results.py --write")
    sizes = example_results.sizes_of(out)
    assert sizes["folder"] <= bounds[name], (
        f"{name}: the output folder holds {sizes['folder'] / 1e6:.3g} MB (history.csv {sizes['history_rows']} rows, "
        f"{sizes['history'] / 1e6:.3g} MB), above its bound of {bounds[name] / 1e6:.3g} MB")


def test_every_documented_example_still_exists():
    names = {example_results.label(e) for e in example_results.examples()}
    for example, quantity in DOCUMENTED:
        assert example in names, f"docs/reference/outputs.md documents {example} ({quantity}), which is not shipped"
    for example in example_results.documented_sizes():
        assert example in names, f"docs/reference/outputs.md gives the output size of {example}, which is not shipped"


def test_every_quoted_number_is_what_its_generator_gives(runs, work):
    problems = doc_numbers.problems(doc_numbers.Sources(work / "numbers", runs))
    assert not problems, "\n".join(problems)


def test_a_drifted_number_is_caught(tmp_path, monkeypatch):
    # The check itself: a span whose text differs from its generator's is reported, so is
    # a span no generator knows and a generator quoted nowhere.
    doc = tmp_path / "doc.md"
    doc.write_text("a <!--n:two-->3<!--/n--> and <!--n:unknown-->1<!--/n-->\n")
    monkeypatch.setattr(doc_numbers, "files", lambda: [doc])
    monkeypatch.setattr(doc_numbers, "ROOT", tmp_path)
    monkeypatch.setattr(doc_numbers, "NUMBERS", {"two": lambda s: "2", "orphan": lambda s: "0"})
    problems = doc_numbers.problems(None)
    assert any("'3'; it is now '2'" in p for p in problems), problems
    assert any("unknown" in p and "names no generator" in p for p in problems), problems
    assert any("'orphan' is quoted nowhere" in p for p in problems), problems
    doc_numbers.write(None)
    assert "<!--n:two-->2<!--/n-->" in doc.read_text()
