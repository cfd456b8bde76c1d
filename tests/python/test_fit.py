"""Fitting from Python against `rheodda fit` (the same library) and a noise-free curve."""
import json
import subprocess

import numpy as np
import pytest

import rheodda
from conftest import TABLE1


def test_fit_of_a_noise_free_curve_recovers_the_parameters():
    law = rheodda.law("burgers", TABLE1)
    t = np.linspace(0.0, 400.0, 201)
    d = law.displacement_closed_form(0.232, t)
    r = rheodda.fit("burgers", d, t=t, stress=0.232)
    assert r.law == "burgers" and r.points == 201
    # The fit stops on a step tolerance of 1e-10 in log parameters (gsl_solver.cpp); eta2, the least
    # determined (retardation time eta2/E2 = 11 h of 400 h), comes within 2e-6 here.
    for name, value in TABLE1.items():
        assert r.values[name] == pytest.approx(value, rel=1e-5), name
        assert r.identifiable[name]
    # and the curve: RMSE 1.2e-10 mm, largest error 1.2e-9 mm (at t = 0) of 0.0086-0.0135 mm
    assert r.rmse < 1e-9
    np.testing.assert_allclose(r.fitted, d, rtol=0, atol=2e-9)


def test_fit_of_a_csv_equals_the_command_line(root, rheodda_binary, tmp_path):
    csv_path = root / "examples" / "creep-data" / "table1-row1.csv"
    r = rheodda.fit("burgers", str(csv_path), stress=0.232)
    out = tmp_path / "fit.json"
    yaml = tmp_path / "law.yaml"
    subprocess.run([rheodda_binary, "fit", str(csv_path), "--law", "burgers", "--stress", "0.232",
                    "--json", str(out), "--yaml", str(yaml)], check=True, capture_output=True)
    cli = json.loads(out.read_text())["fits"][0]
    assert cli["law"] == "burgers"
    assert r.aic == pytest.approx(cli["aic"], rel=1e-12)
    assert r.bic == pytest.approx(cli["bic"], rel=1e-12)
    assert r.yaml.replace(str(csv_path), "DATA") == yaml.read_text().replace(str(csv_path), "DATA")
    # covariance of the values: symmetric, the squared standard errors on its diagonal
    err = np.array([r.errors[n] for n in r.names])
    np.testing.assert_allclose(np.diag(r.covariance), err ** 2, rtol=1e-12)
    np.testing.assert_allclose(r.covariance, r.covariance.T, rtol=1e-12)
    assert r.make_law().parameters == r.values


def test_fit_all_ranks_by_bic_and_aic(root):
    csv_path = str(root / "examples" / "creep-data" / "steps-unloading.csv")
    ranked, skipped = rheodda.fit_all(csv_path, stress_column="tau")
    assert ranked[0].law == "burgers"
    assert [r.bic for r in ranked] == sorted(r.bic for r in ranked)
    by_aic, _ = rheodda.fit_all(csv_path, stress_column="tau", rank_by="aic")
    assert [r.aic for r in by_aic] == sorted(r.aic for r in by_aic)
    assert isinstance(skipped, list)


def test_bad_data_raises_the_command_line_message(root, rheodda_binary, tmp_path):
    bad = tmp_path / "bad.csv"
    bad.write_text("t,displacement\n0,0.1\n1,abc\n")
    with pytest.raises(rheodda.DataError) as e:
        rheodda.fit("burgers", str(bad), stress=0.232)
    assert e.value.line == 3 and e.value.column == "displacement"
    cli = subprocess.run([rheodda_binary, "fit", str(bad), "--law", "burgers", "--stress", "0.232"],
                         capture_output=True, text=True)
    assert cli.returncode == 2
    assert cli.stderr.strip() == "rheodda: error: " + str(e.value)
    with pytest.raises(rheodda.FitError):
        rheodda.fit("burgers", [0.1, 0.2], t=[0.0, 1.0], stress=0.232)  # fewer points than parameters + 1


def test_model_weights_are_the_hand_computed_akaike_weights(root):
    # w_i = exp(-(AIC_i - AIC_min)/2) / sum_j exp(-(AIC_j - AIC_min)/2) (Burnham & Anderson 2002, ch. 2)
    csv_path = str(root / "examples" / "creep-data" / "steps-unloading.csv")
    ranked, _ = rheodda.fit_all(csv_path, stress_column="tau")
    aic = np.array([r.aic for r in ranked])
    hand = np.exp(-0.5 * (aic - aic.min()))
    hand /= hand.sum()
    np.testing.assert_allclose(rheodda.model_weights(ranked), hand, rtol=1e-12, atol=1e-300)
    bic = np.array([r.bic for r in ranked])
    hand_bic = np.exp(-0.5 * (bic - bic.min()))
    np.testing.assert_allclose(rheodda.model_weights(ranked, "bic"), hand_bic / hand_bic.sum(), rtol=1e-12,
                               atol=1e-300)
    frame = rheodda.ranking_frame(ranked)
    np.testing.assert_allclose(frame["akaike_weight"].to_numpy(), hand, rtol=1e-12, atol=1e-300)
    assert list(frame["unidentified"]) == [", ".join(r.unidentified) for r in ranked]
    with pytest.raises(rheodda.Error):
        rheodda.model_weights(ranked, "dic")


def test_nishihara_under_one_stress_reports_what_the_data_fix(root, rheodda_binary, tmp_path):
    # One stress level: the Bingham part creeps at (F - Fs)/eta3, so only that combination is fixed.
    csv_path = str(root / "examples" / "creep-data" / "table1-row1.csv")
    r = rheodda.fit("nishihara", csv_path, stress=0.232)
    assert not r.identifiable["eta3"] and not r.identifiable["Fs"]
    assert r.identifiable["E1"] and r.identifiable["E2"] and r.identifiable["eta2"]
    assert set(r.reasons) == {"eta3", "Fs"}
    (c,) = r.combinations
    assert c.expression == "(0.232 - Fs)/eta3" and set(c.parameters) == {"eta3", "Fs"}
    assert c.value == pytest.approx((0.232 - r.values["Fs"]) / r.values["eta3"], rel=1e-12)
    # the seed's Burgers creeps at 0.232/eta1 in the long run: the same rate
    assert c.value == pytest.approx(0.232 / TABLE1["eta1"], rel=0.01)
    cov = r.covariance
    assert np.isnan(cov[3:, :]).all() and np.isfinite(cov[:3, :3]).all()
    yaml = tmp_path / "law.yaml"
    subprocess.run([rheodda_binary, "fit", csv_path, "--law", "nishihara", "--stress", "0.232", "--yaml", str(yaml)],
                   check=True, capture_output=True)
    assert r.yaml == yaml.read_text()
    # the scene loader's mark of what the data do not determine, and the range they cover
    assert r.unidentified == ["eta3", "Fs"]
    assert "\n  unidentified: [eta3, Fs]\n" in r.yaml
    assert "\n  tested_stress: [0.232, 0.232]\n  tested_duration: 200\n" in r.yaml


def test_fit_with_units_writes_the_law_in_a_scenes_units_as_the_command_line(root, rheodda_binary, tmp_path):
    # units= states the data's units (--units); scene_yaml() writes the law in a scene's
    # (--scene-units, --scene), converted by UDUNITS-2: the same text as the command line.
    csv_path = root / "examples" / "creep-data" / "table1-row1.csv"
    r = rheodda.fit("burgers", str(csv_path), stress=0.232, units="MPa, mm, h")
    assert r.data_units == "MPa, mm, h"
    assert r.units["eta1"] == "MPa*h/mm" and r.units["E1"] == "MPa/mm"
    data_yaml, scene_yaml = tmp_path / "law.yaml", tmp_path / "law-si.yaml"
    base = [rheodda_binary, "fit", str(csv_path), "--law", "burgers", "--stress", "0.232", "--units", "MPa, mm, h"]
    subprocess.run(base + ["--yaml", str(data_yaml)], check=True, capture_output=True)
    subprocess.run(base + ["--yaml", str(scene_yaml), "--scene-units", "m, N, d"], check=True, capture_output=True)
    assert r.yaml == data_yaml.read_text()
    assert r.scene_yaml("m, N, d") == scene_yaml.read_text()
    goodman = root / "examples" / "goodman-toppling.yaml"  # m, N, d
    assert r.scene_yaml(goodman) == scene_yaml.read_text()
    assert r.scene_yaml(rheodda.load_scene(str(goodman))) == scene_yaml.read_text()
    values = r.scene_values("m, N, d")
    assert values["E1"][0] == pytest.approx(r.values["E1"] * 1e9, rel=1e-14) and values["E1"][1] == "N/m^2/m"
    assert values["eta1"][0] == pytest.approx(r.values["eta1"] * 1e9 / 24, rel=1e-14)
    with pytest.raises(rheodda.Error, match="give fit"):
        rheodda.fit("burgers", str(csv_path), stress=0.232).scene_yaml("m, N, d")
    with pytest.raises(rheodda.Error, match="three units"):
        rheodda.fit("burgers", str(csv_path), stress=0.232, units="MPa, mm")


def _cli_correlation(report):
    """The lower triangle `rheodda fit` prints under "correlation of the estimates", as
    {(row, column): value or None for '-'}."""
    lines = report.splitlines()
    at = next(i for i, line in enumerate(lines) if "correlation of the estimates" in line)
    names = lines[at + 1].split()
    out = {}
    for line in lines[at + 2:at + 2 + len(names)]:
        row, *cells = line.split()
        assert row == names[len({k[0] for k in out})]
        for name, cell in zip(names, cells):
            out[(row, name)] = None if cell == "-" else float(cell)
    return names, out


@pytest.mark.parametrize("law", ["burgers", "nishihara"])
def test_the_command_lines_report_prints_the_correlation_of_the_fit_result(root, rheodda_binary, law):
    # issue 52: the report of `rheodda fit` left out the correlation matrix FitResult has.
    csv_path = str(root / "examples" / "creep-data" / "table1-row1.csv")
    r = rheodda.fit(law, csv_path, stress=0.232)
    cli = subprocess.run([rheodda_binary, "fit", csv_path, "--law", law, "--stress", "0.232"],
                         check=True, capture_output=True, text=True)
    names, printed = _cli_correlation(cli.stdout)
    assert names == r.names
    assert len(printed) == len(names) * (len(names) + 1) // 2  # the lower triangle, diagonal included
    for (a, b), value in printed.items():
        c = r.correlation[r.names.index(a), r.names.index(b)]
        if value is None:  # not identifiable (nishihara's eta3 and Fs under one stress)
            assert np.isnan(c), (a, b)
        else:
            assert value == pytest.approx(c, abs=5e-5), (a, b)
    if law == "nishihara":
        assert printed[("Fs", "E1")] is None and printed[("E2", "E1")] is not None
