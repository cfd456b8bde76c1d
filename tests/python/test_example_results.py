"""The shipped examples' headline results stay what docs/outputs.md documents
("Shipped examples: headline results", written by scripts/example_results.py):
every examples/*.yaml and examples/rockmass/*.yaml is run again and each documented value must hold within
its tolerance, and every example must be documented."""
import importlib.util
import pathlib
import tempfile

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
_spec = importlib.util.spec_from_file_location("example_results", ROOT / "scripts" / "example_results.py")
example_results = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(example_results)

DOCUMENTED = example_results.documented()


@pytest.fixture(scope="module")
def headlines():
    """Every example run once, side by side on every core."""
    with tempfile.TemporaryDirectory() as tmp:
        yield example_results.headlines(example_results.examples(), tmp)


@pytest.mark.parametrize("example", example_results.examples(), ids=example_results.label)
def test_headline_results_match_the_documented_values(example, headlines):
    results = headlines[example]
    if isinstance(results, Exception):
        raise results
    name = example_results.label(example)
    assert results, f"{name}: no measurement point and no failure to report"
    for quantity, value, _unit in results:
        key = (name, quantity)
        assert key in DOCUMENTED, (
            f"{name}: '{quantity}' is not in docs/outputs.md; run "
            "/usr/bin/python3 scripts/example_results.py --write")
        documented, tolerance = DOCUMENTED[key]
        assert abs(value - documented) <= tolerance * abs(documented), (
            f"{name}: {quantity} = {value:.9g}, documented {documented:.9g} "
            f"(tolerance {tolerance:g} relative): the behaviour changed; if on purpose, regenerate the table")


def test_every_documented_example_still_exists():
    names = {example_results.label(e) for e in example_results.examples()}
    for example, quantity in DOCUMENTED:
        assert example in names, f"docs/outputs.md documents {example} ({quantity}), which is not shipped"
