"""Types and help (docs/guide/python.md, "Types"): the stubs (.pyi) and py.typed ship with the module,
mypy --strict accepts the examples against them, the stubs name every public name of the module,
and every public name, method and property carries a docstring."""
import ast
import inspect
import os
import pathlib
import shutil
import subprocess
import sys

import pytest

import rheodda
from conftest import ROOT

PACKAGE = pathlib.Path(rheodda.__file__).parent


def stub_names(path):
    """Top-level names a stub defines (classes, functions, assignments, re-exports)."""
    names = set()
    for node in ast.parse(path.read_text()).body:
        if isinstance(node, (ast.ClassDef, ast.FunctionDef)):
            names.add(node.name)
        elif isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name):
            names.add(node.target.id)
        elif isinstance(node, ast.Assign):
            names.update(t.id for t in node.targets if isinstance(t, ast.Name))
        elif isinstance(node, ast.ImportFrom):
            names.update(a.asname or a.name for a in node.names)
    return names


def test_stubs_and_py_typed_ship_with_the_module():
    for f in ("__init__.pyi", "_rheodda.pyi", "py.typed"):
        assert (PACKAGE / f).is_file(), f


def test_the_stubs_name_every_public_name():
    compiled = {n for n in dir(rheodda._rheodda) if not n.startswith("__")}
    missing = compiled - stub_names(PACKAGE / "_rheodda.pyi")
    assert not missing, "not in _rheodda.pyi: {}".format(sorted(missing))
    missing = set(rheodda.__all__) - stub_names(PACKAGE / "__init__.pyi")
    assert not missing, "not in __init__.pyi: {}".format(sorted(missing))


def test_every_public_name_has_a_docstring():
    undocumented = []
    for name in rheodda.__all__:
        obj = getattr(rheodda, name)
        if not (inspect.getdoc(obj) or "").strip():
            undocumented.append(name)
        if inspect.isclass(obj) and not issubclass(obj, BaseException):
            for attr, member in vars(obj).items():
                if attr.startswith("_"):
                    continue
                doc = member.__doc__ if isinstance(member, property) else getattr(member, "__doc__", None)
                if callable(member) or isinstance(member, property) or type(member).__name__ == "instancemethod":
                    if not (doc or "").strip():
                        undocumented.append(name + "." + attr)
    assert not undocumented, undocumented


def test_reprs_say_what_an_object_is(root):
    sim = rheodda.Simulation(str(root / "examples" / "shear-creep-test.yaml"))
    assert repr(sim).startswith("<rheodda.Simulation 'Shear creep test") and "0 steps" in repr(sim)
    assert repr(rheodda.StepConstants(2.0, "lagged")) == "<StepConstants dt 2 scheme 'lagged' with 0 element constants>"
    data = rheodda.read_creep_csv(str(root / "examples" / "creep-data" / "table1-row1.csv"), stress=0.232)
    assert repr(data).endswith("table1-row1.csv: 401 points, 1 stage, t from 0 to 200>")
    assert "object at 0x" not in repr(rheodda.UnitStepConstants())

    class Maxwell(rheodda.PythonLaw):
        def __init__(self) -> None:
            super().__init__("my-maxwell", {"E1": 26.87, "eta1": 34807.72}, instantaneous_stiffness=26.87)
    assert repr(Maxwell()) == "<PythonLaw 'my-maxwell' (test_reprs_say_what_an_object_is.<locals>.Maxwell) " \
                              "{'E1': 26.87, 'eta1': 34807.72}>"


@pytest.mark.skipif(shutil.which("mypy") is None and subprocess.run(
    [sys.executable, "-c", "import mypy"], capture_output=True).returncode != 0,
    reason="mypy is not installed (Debian: python3-mypy)")
def test_mypy_strict_accepts_the_examples():
    examples = sorted(str(p) for p in (ROOT / "examples" / "python").glob("*.py"))
    env = dict(os.environ, MYPYPATH=str(PACKAGE.parent))
    r = subprocess.run([sys.executable, "-m", "mypy", "--config-file", str(ROOT / "tests" / "python" / "mypy.ini"),
                        "--no-incremental", "--cache-dir", os.devnull] + examples,
                       capture_output=True, text=True, env=env, cwd=str(ROOT))
    assert r.returncode == 0, r.stdout + r.stderr
