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


def test_the_joint_set_stub_follows_the_declarations():
    """JointSet's properties in __init__.pyi are the declared ones (contact/joint_set_specs.hpp):
    an annotated attribute where the declaration lets it change between steps, a read-only
    property where it does not, and no property the declarations do not hold."""
    cls = next(n for n in ast.parse((PACKAGE / "__init__.pyi").read_text()).body
               if isinstance(n, ast.ClassDef) and n.name == "JointSet")
    settable = {n.target.id for n in cls.body if isinstance(n, ast.AnnAssign) and isinstance(n.target, ast.Name)}
    read_only = {n.name for n in cls.body if isinstance(n, ast.FunctionDef)
                 and any(isinstance(d, ast.Name) and d.id == "property" for d in n.decorator_list)}
    declared = rheodda._rheodda._Simulation._joint_set_properties()
    assert declared, "no joint-set property declared"
    for p in declared:
        if p["between_steps"]:
            assert p["name"] in settable, "{}: settable, not an attribute of the stub's JointSet".format(p["name"])
        else:
            assert p["name"] in read_only, "{}: read-only, not a property of the stub's JointSet".format(p["name"])
    names = {p["name"] for p in declared}
    # index: the joint set's position; name, law, law_parameters: the scene's, not properties
    assert settable - names == {"index"}, sorted(settable - names)
    assert read_only - names == {"name", "law", "law_parameters"}, sorted(read_only - names)


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
