"""Laws from Python: the registry, closed forms, single steps and curves against
the C++ command (`rheodda law curve`) and the closed forms."""
import csv
import io
import subprocess

import numpy as np
import pytest

import rheodda
from conftest import TABLE1


def burgers_closed_form(p, force, t):
    """Burgers creep under constant force (the seed's eqs. 20-21): F/E1 + F/E2 (1 - exp(-E2 t/eta2)) + F t/eta1."""
    return force / p["E1"] + force / p["E2"] * (1 - np.exp(-p["E2"] * t / p["eta2"])) + force * t / p["eta1"]


def test_registry_lists_every_law_with_parameters_and_units():
    entries = {e["name"]: e for e in rheodda.laws()}
    assert {"burgers", "maxwell", "kelvin", "nishihara"} <= set(entries)
    burgers = {p["name"]: p for p in entries["burgers"]["parameters"]}
    assert list(burgers) == ["E1", "E2", "eta1", "eta2"]
    assert burgers["E1"]["unit"] == "stress/length"
    assert burgers["eta1"]["unit"] == "stress*time/length"
    assert all(p["meaning"] for p in burgers.values())


def test_law_from_dict_keeps_its_parameters():
    law = rheodda.law("burgers", TABLE1)
    assert law.name == "burgers"
    assert law.parameters == TABLE1
    assert law.instantaneous_stiffness == TABLE1["E1"]
    assert law.internal_count == 2 and law.is_linear
    assert rheodda.law("burgers", **TABLE1).parameters == TABLE1


def test_burgers_closed_form_on_arrays():
    law = rheodda.law("burgers", TABLE1)
    t = np.linspace(0.0, 200.0, 41)
    np.testing.assert_allclose(law.displacement_closed_form(0.232, t), burgers_closed_form(TABLE1, 0.232, t),
                               rtol=1e-12, atol=0)
    # seed section 4: 0.00863 mm at once, 0.01117 mm at 200 h
    assert law.displacement_closed_form(0.232, 0.0) == pytest.approx(0.00863, abs=5e-6)
    assert law.displacement_closed_form(0.232, 200.0) == pytest.approx(0.01117, abs=5e-6)


def test_maxwell_relaxation_modulus_is_the_closed_form():
    law = rheodda.law("maxwell", {"E1": 26.87, "eta1": 34807.72})
    t = np.array([0.0, 10.0, 1000.0])
    np.testing.assert_allclose(law.relaxation_modulus(t), 26.87 * np.exp(-26.87 * t / 34807.72), rtol=1e-12)
    curve = rheodda.relaxation_curve(law, 0.01, t_end=100.0, dt=1.0)
    np.testing.assert_allclose(curve["exact"], 0.01 * 26.87 * np.exp(-26.87 * curve["t"] / 34807.72), rtol=1e-12)


def test_exponential_linear_step_is_exact_under_constant_force():
    # The exponential-linear scheme integrates a force ramp exactly (docs/reference/laws.md, "Schemes"):
    # one step from rest under a constant force gives the closed-form creep.
    law = rheodda.law("burgers", TABLE1)
    dd, q = rheodda.law_step(law, [0.0, 0.0], dt=50.0, force_start=0.232, force_end=0.232,
                             scheme="exponential-linear")
    assert dd == pytest.approx(burgers_closed_form(TABLE1, 0.232, 50.0) - 0.232 / TABLE1["E1"], rel=1e-12)
    assert q.shape == (4,) and q[0] + q[1] == pytest.approx(dd, rel=1e-15)
    k = law.step_constants(50.0, "implicit")
    h, c = law.linearize(k, [0.0, 0.0], 0.232, 0.232)
    dd_implicit, _ = law.advance(k, [0.0, 0.0], 0.232, 0.232)
    assert dd_implicit == pytest.approx(h + c * 0.232, rel=1e-14)


def test_creep_curve_follows_the_closed_form():
    law = rheodda.law("burgers", TABLE1)
    c = rheodda.creep_curve(law, 0.232, t_end=200.0, dt=1.0, scheme="exponential-linear")
    assert set(c) == {"t", "force", "displacement", "exact"}
    np.testing.assert_allclose(c["exact"], burgers_closed_form(TABLE1, 0.232, c["t"]), rtol=1e-12)
    np.testing.assert_allclose(c["displacement"], c["exact"], rtol=1e-12)


def test_staged_curve_equals_the_command_line(rheodda_binary):
    law = rheodda.law("burgers", TABLE1)
    force = "0:0.232,100:0.424,150:0"
    c = rheodda.creep_curve(law, force, t_end=200.0, dt=2.0, scheme="implicit")
    args = [rheodda_binary, "law", "curve", "burgers", "--force", force, "--t-end", "200", "--dt", "2",
            "--scheme", "implicit"] + ["--param={}={!r}".format(k, v) for k, v in TABLE1.items()]
    out = subprocess.run(args, check=True, capture_output=True, text=True).stdout
    rows = list(csv.DictReader(io.StringIO("".join(l for l in out.splitlines(True) if not l.startswith("#")))))
    assert len(rows) == len(c["t"])
    cli_t = np.array([float(r["t"]) for r in rows])
    cli_d = np.array([float(r["displacement"]) for r in rows])
    np.testing.assert_allclose(c["t"], cli_t, rtol=1e-12)
    # the command prints 10 significant digits or more: compare at that precision
    np.testing.assert_allclose(c["displacement"], cli_d, rtol=1e-9)
    # and both against the superposition closed form (first-order scheme: to 1e-3 relative at dt = 2 h)
    np.testing.assert_allclose(c["exact"], rheodda.exact_displacement(law, force, c["t"]), rtol=1e-12)


def test_bad_parameters_raise_the_command_line_message(rheodda_binary):
    with pytest.raises(rheodda.LawError) as e:
        rheodda.law("burgers", {"E1": -1.0, "E2": 1.0, "eta1": 1.0, "eta2": 1.0})
    assert isinstance(e.value, ValueError) and e.value.key == "E1"
    cli = subprocess.run([rheodda_binary, "law", "curve", "burgers", "--param", "E1=-1", "--param", "E2=1",
                          "--param", "eta1=1", "--param", "eta2=1", "--force", "0:1", "--t-end", "1", "--dt", "1"],
                         capture_output=True, text=True)
    assert cli.returncode == 2
    assert cli.stderr.strip() == "rheodda: error: " + str(e.value)
    with pytest.raises(rheodda.LawError, match="did you mean 'burgers'"):
        rheodda.law("burger", {})
    with pytest.raises(rheodda.LawError, match="eta1"):
        rheodda.law("burgers", {"E1": 1.0, "E2": 1.0, "eta2": 1.0})
