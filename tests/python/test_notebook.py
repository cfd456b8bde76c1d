"""examples/python/rheodda-notebook.ipynb executed headless (nbclient, Debian's python3-nbclient;
the kernel is python3-ipykernel's), its printed numbers checked against closed forms and fits
made here."""
import json
import os

import numpy as np
import pytest

import rheodda
from conftest import ROOT, TABLE1

nbformat = pytest.importorskip("nbformat")
nbclient = pytest.importorskip("nbclient")

TAU = 0.232  # MPa


def burgers(t, E1, E2, eta1, eta2):
    """The seed's eq. 2 under a constant stress TAU [mm]."""
    return TAU / E1 + TAU / E2 * -np.expm1(-E2 * np.asarray(t) / eta2) + TAU * np.asarray(t) / eta1


@pytest.fixture(scope="module")
def executed():
    path = ROOT / "examples" / "python" / "rheodda-notebook.ipynb"
    nb = nbformat.read(str(path), as_version=4)
    # The kernel inherits this environment: the module of this build on PYTHONPATH (restored after).
    package_dir = os.path.dirname(os.path.dirname(os.path.abspath(rheodda.__file__)))
    saved = {k: os.environ.get(k) for k in ("PYTHONPATH", "MPLBACKEND")}
    os.environ["PYTHONPATH"] = os.pathsep.join([package_dir, saved["PYTHONPATH"] or ""]).rstrip(os.pathsep)
    os.environ.pop("MPLBACKEND", None)  # %matplotlib inline chooses the backend
    try:
        client = nbclient.NotebookClient(nb, timeout=600, kernel_name="python3",
                                         resources={"metadata": {"path": str(path.parent)}})
        client.execute()
    finally:
        for k, v in saved.items():
            if v is None:
                os.environ.pop(k, None)
            else:
                os.environ[k] = v
    return nb


def stdout_of(cell):
    return "".join(o.get("text", "") for o in cell.outputs if o.output_type == "stream" and o.name == "stdout")


def test_every_cell_runs_and_the_figures_are_inline(executed):
    code = [c for c in executed.cells if c.cell_type == "code"]
    for c in code:
        assert not [o for o in c.outputs if o.output_type == "error"], c.source[:80]
    pictures = sum(1 for c in code for o in c.outputs if o.output_type == "display_data" and "image/png" in o.data)
    assert pictures == 3  # the creep test, the fits, the study


def test_the_printed_numbers(executed):
    results = json.loads(stdout_of(executed.cells[-1]))
    # 1. The creep test against the closed form: the DDA run differs from the law alone by 1.1e-5 of
    # the displacement, as the examples of docs/guide/python.md do (load_in_a_loop.py: 1.1e-5).
    assert results["creep_exact_end"] == pytest.approx(burgers(200.0, **TABLE1), rel=1e-14)
    assert results["creep_relative_error"] < 1.5e-5
    assert results["creep_d_end"] == pytest.approx(burgers(200.0, **TABLE1), rel=1.5e-5)
    # 2. The free fit recovers the seed's parameters within two standard errors (noise 2e-5 mm).
    for name, value in TABLE1.items():
        assert abs(results["fit_free"][name] - value) <= 2 * results["fit_free_errors"][name], name
    # The bounded fit ends on E2 = 150 and equals the fit with E2 held there.
    assert results["fit_bounded"]["E2"] == 150.0 and results["fit_bounded_at_bound"]["E2"] == "max"
    held = rheodda.fit("burgers", str(ROOT / "examples" / "creep-data" / "table1-row1.csv"),
                       stress=TAU, params={"E2": {"value": 150.0, "vary": False}})
    for name in ("E1", "eta1", "eta2"):
        assert results["fit_bounded"][name] == pytest.approx(held.values[name], rel=1e-6), name
    assert results["fit_bounded_chi_square"] == pytest.approx(held.chi_square, rel=1e-8)
    # 3. The study: every case ran; each value within 1e-5 of its closed form.
    assert results["study_status"] == ["completed"] * 4
    for eta1, row in zip(results["study_eta1"], results["study_values"]):
        exact = burgers(results["study_times"], TABLE1["E1"], TABLE1["E2"], eta1, TABLE1["eta2"])
        np.testing.assert_allclose(row, exact, rtol=2e-5)
    assert results["study_relative_error"] < 2e-5
