"""A study run from Python (`rheodda study`): each case a `rheodda run` process."""
import numpy as np
import pytest

import rheodda
from conftest import TABLE1


def test_study_of_eta1_follows_the_burgers_closed_form(root, tmp_path):
    study = tmp_path / "eta1.yaml"
    study.write_text(
        "title: eta1 sweep of the shear creep test\n"
        "scene: {}\n"
        "set: {{analysis.output_interval: 100}}\n"
        "outputs: [plane.shear_displacement]\n"
        "times: [100, 200]\n"
        "cases:\n"
        "  - {{name: slow, set: {{joint_sets.plane.law.eta1: 69615.44}}}}\n"
        "  - {{name: seed, set: {{joint_sets.plane.law.eta1: 34807.72}}}}\n".format(
            root / "examples" / "shear-creep-test.yaml"))
    result = rheodda.run_study(str(study), str(tmp_path / "out"), jobs=2)
    assert [c["name"] for c in result["cases"]] == ["slow", "seed"]
    assert all(c["status"] == "completed" for c in result["cases"])
    # static cases that stand: the static steps' inertia term took next to nothing
    # (docs/reference/engine.md, "Mechanisms in static analysis")
    assert all(c["inertia_share"] is not None and 0.0 <= c["inertia_share"] < 0.01 for c in result["cases"])
    assert result["outputs"] == ["plane.shear_displacement"]
    np.testing.assert_array_equal(result["times"], [100.0, 200.0])
    for case, eta1 in zip(result["cases"], (69615.44, 34807.72)):
        law = rheodda.law("burgers", dict(TABLE1, eta1=eta1))
        # history.csv's 10 digits, the contact layer's 2e-5 against the closed form
        np.testing.assert_allclose(-case["values"][0], law.displacement_closed_form(0.232, result["times"]),
                                   rtol=2e-5)
    assert (tmp_path / "out" / "study.csv").exists()


def test_a_bad_study_raises_a_located_scene_error(tmp_path):
    study = tmp_path / "bad.yaml"
    study.write_text("title: bad\nscene: nowhere.yaml\noutputs: [x]\ntimes: [1]\ncases: [{name: a}]\n")
    with pytest.raises(rheodda.SceneError) as e:
        rheodda.run_study(str(study), str(tmp_path / "out"))
    assert str(e.value).startswith(str(study) + ":")
