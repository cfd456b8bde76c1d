"""A setting declared once reaches Python (issue 53, "the physics owns its settings").

Each `analysis:` and `analysis.settle` key is declared once (the engine's settings and its
settling stage in core/settings.hpp, the contact layer's in contact_settings_specs.hpp, the
scene's acceptances and own keys in scene/src/keys.cpp); the docs tables of
docs/reference/scene-format.md are generated from the declarations (schema_test checks
them). Here every number, integer and flag key of those tables: its default as the docs
state it is Scene.analysis's, and a value given in a scene reaches Scene.analysis,
Scene.inputs (summary.json's), Scene.describe() (`rheodda check`) and, for the engine's
settings that may change between steps, Simulation.settings. The C++ side of the same
path is tests/scene/declared_settings_reach_test.cpp.
"""
import copy
import math
import re

import pytest

import rheodda

# A static scene, as tests/scene/test_support.hpp's kBaseScene.
BASE = {
    "units": {"length": "m", "force": "N", "time": "s"},
    "analysis": {"duration": 1, "dt": 0.01, "gravity": [0, -9.81]},
    "materials": {"rock": {"density": 2600, "young_modulus": 1.0e9, "poisson_ratio": 0.25}},
    "joint_sets": {"bedding": {"friction_angle": 30}},
    "blocks": [
        {"name": "base", "rectangle": {"x": 0, "y": 0, "width": 4, "height": 1}, "fixed": True},
        {"name": "top", "polygon": [[1, 1], [2, 1], [2, 2], [1, 2]]},
    ],
    "measurement_points": [{"name": "p", "point": [1.5, 1.5], "block": "top"}],
}
# The settling stage a key of `analysis.settle` is given in (the key replaces its entry).
STAGE = {"type": "dynamic", "until": 0.5, "dt": 0.001}

# Keys a setting needs beside it to apply (as declared_settings_reach_test.cpp's kContext).
CONTEXT = {
    "dynamic_ratio": {"type": "dynamic"},
    "step_extrapolation": {"step_tolerance": 0.001},
    "dt_max": {"creep_tolerance": 0.001},
    "explicit_safety": {"integrator": "automatic"},
    "explicit_damping": {"integrator": "automatic"},
    "stage_local_damping": {"integrator": "automatic"},
    "stage_cycles": {"integrator": "automatic"},
    "static_force_ratio": {"integrator": "explicit"},
    "static_max_cycles": {"integrator": "explicit", "static_force_ratio": 1e-5},
    "static_local_damping": {"integrator": "explicit", "static_force_ratio": 1e-5},
    "settle.force_ratio": {"integrator": "explicit"},
}
STAGE_CONTEXT = {"settle.force_ratio": {"rest_tolerance": 0.01}}
# Values the generic choice would make refused for what they tie to (duration 1, dt 0.01,
# the stage's end 0.5).
VALUE = {"duration": 2.0, "dt": 0.005, "output_interval": 0.5, "settle.until": 0.25, "settle.dt": 0.005,
         "settle.collapse_dt": 0.002, "settle.gravity_ramp": 0.25, "settle.force_ratio": 1e-5}


def doc_table(root, name):
    """The rows of the generated table `name` of docs/reference/scene-format.md: key, unit, range, default."""
    text = (root / "docs" / "reference" / "scene-format.md").read_text()
    body = text.split(f"<!-- keys-{name}:begin -->\n", 1)[1].split(f"<!-- keys-{name}:end -->", 1)[0]
    rows = []
    for line in body.splitlines()[2:]:
        cells = [c.strip() for c in line.strip().strip("|").split(" | ")]
        rows.append({"key": cells[0].strip("`"), "unit": cells[1], "range": cells[2], "default": cells[-1]})
    return rows


def parse_range(text):
    """(lo, lo_open, hi, hi_open) of "(0, 1]", "[1, ∞)"."""
    m = re.fullmatch(r"([\[(])(-?[0-9.e+-]+), (∞|-?[0-9.e+-]+)([\])])", text)
    assert m, text
    hi = math.inf if m.group(3) == "∞" else float(m.group(3))
    return float(m.group(2)), m.group(1) == "(", hi, m.group(4) == ")"


def given_value(key, default, range_text):
    """A value inside the declared range, other than the default."""
    if key in VALUE:
        return VALUE[key]
    if isinstance(default, bool):
        return not default
    lo, lo_open, hi, hi_open = parse_range(range_text)
    for c in ((lo + hi) / 2 if hi != math.inf else lo + 2, lo + 2, lo + 0.25):
        v = math.floor(c) if isinstance(default, int) else c
        inside = (v > lo if lo_open else v >= lo) and (v < hi if hi_open else v <= hi)
        if inside and v != default:
            return v
    pytest.fail(f"no value for {key} in {range_text}")


def scene_with(map_name, key, value):
    d = copy.deepcopy(BASE)
    full = key if map_name == "analysis" else "settle." + key
    d["analysis"].update(CONTEXT.get(full, {}))
    if map_name == "analysis":
        d["analysis"][key] = value
    else:
        d["analysis"]["settle"] = {**STAGE, **STAGE_CONTEXT.get(full, {}), key: value}
    return rheodda.scene_from_dict(d)


def value_text(v):
    if isinstance(v, bool):
        return "true" if v else "false"
    return str(v) if isinstance(v, int) else f"{v:g}"


def numeric_rows(root, map_name, defaults):
    """The table's keys whose value is a number, an integer or a flag (a map's, or the stage's `type`, not)."""
    return [r for r in doc_table(root, map_name)
            if isinstance(defaults.get(r["key"]), (bool, int, float)) and r["key"] != "gravity"]


@pytest.fixture(scope="module")
def base_scene():
    d = copy.deepcopy(BASE)
    d["analysis"]["settle"] = dict(STAGE)
    return rheodda.scene_from_dict(d)


@pytest.fixture(scope="module")
def step_settings():
    """The engine's settings Simulation.settings holds (those that may change between steps)."""
    return set(rheodda.Simulation(rheodda.scene_from_dict(copy.deepcopy(BASE))).settings)


def test_each_declared_default_the_docs_state_is_the_scenes(root, base_scene):
    # A plain default in the docs ("1.5", "false", "30", "1 (dynamic), 0 (static)") is the
    # value Scene.analysis holds in a static scene that does not give the key.
    checked = 0
    for map_name, values in (("analysis", base_scene.analysis), ("analysis.settle", base_scene.analysis["settle"])):
        for row in numeric_rows(root, map_name, values):
            default = row["default"]
            static = re.fullmatch(r"(\S+) \(dynamic\), (\S+) \(static\)", default)
            text = static.group(2) if static else default
            if not re.fullmatch(r"true|false|-?[0-9.]+(e[+-]?[0-9]+)?", text):
                continue  # a rule ("`true` in a dynamic analysis ...", "the analysis's ..."), or required
            value = values[row["key"]]
            expected = text == "true" if isinstance(value, bool) else float(text)
            assert value == expected, (map_name, row["key"], default, value)
            checked += 1
    assert checked >= 35  # 37 when written: every plain default of the analysis table


@pytest.mark.parametrize("map_name", ["analysis", "analysis.settle"])
def test_a_value_given_reaches_python_summary_check_and_the_engine(root, base_scene, step_settings, map_name):
    defaults = base_scene.analysis if map_name == "analysis" else base_scene.analysis["settle"]
    rows = numeric_rows(root, map_name, defaults)
    assert len(rows) >= (40 if map_name == "analysis" else 8)
    for row in rows:
        key = row["key"]
        full = key if map_name == "analysis" else "settle." + key
        default = defaults[key]
        value = given_value(full, default, row["range"])
        if isinstance(default, int) and not isinstance(default, bool):
            value = int(value)
        scene = scene_with(map_name, key, value)
        read = scene.analysis if map_name == "analysis" else scene.analysis["settle"]
        assert read[key] == value, full
        inputs = scene.inputs["analysis"]
        echoed = inputs if map_name == "analysis" else inputs["settle"]
        assert echoed[key] == value, full
        assert f" {full} {value_text(value)}" in scene.describe(), full
        if map_name == "analysis" and key in step_settings:
            assert rheodda.Simulation(scene).settings[key] == value, full
    if map_name == "analysis":
        assert {"dt", "max_displacement_ratio", "open_close_limit", "solver_tolerance"} <= step_settings


# Keys a choice's word needs beside it to apply (as declared_settings_reach_test.cpp's kChoiceContext).
CHOICE_CONTEXT = {
    ("time_integration", "trapezoidal"): {"type": "dynamic"},
    ("integrator", "explicit"): {"type": "dynamic"},
    ("integrator", "automatic"): {"type": "dynamic"},
}


def declared_words(map_name, key):
    """The words of the choice `key`, as the refusal of a word that is none of them lists them."""
    with pytest.raises(rheodda.SceneError, match=r"'nonesuch' is not one of: ") as refused:
        scene_with(map_name, key, "nonesuch")
    assert key in str(refused.value)
    return re.search(r"'nonesuch' is not one of: ([^(]*?)(?: \(did you mean|$)", str(refused.value)).group(1).split(", ")


@pytest.mark.parametrize("map_name", ["analysis", "analysis.settle"])
def test_each_word_of_a_declared_choice_reaches_python_summary_check_and_the_engine(root, base_scene, step_settings,
                                                                                   map_name):
    # The choices (laws::ChoiceSpec: core::Settings', the settling stage's, the contact layer's,
    # the scene's own): the docs' default is Scene.analysis's, and each word given reaches
    # Scene.analysis, Scene.inputs, Scene.describe() and, for the choices that may change
    # between steps, Simulation.settings, which set_settings changes by the same words.
    defaults = base_scene.analysis if map_name == "analysis" else base_scene.analysis["settle"]
    rows = [r for r in doc_table(root, map_name) if isinstance(defaults.get(r["key"]), str)]
    assert len(rows) >= (7 if map_name == "analysis" else 1)  # 7 and 1 when written
    for row in rows:
        key = row["key"]
        full = key if map_name == "analysis" else "settle." + key
        if map_name == "analysis":
            assert row["default"] == f"`{defaults[key]}`", full
        words = declared_words(map_name, key)
        assert defaults[key] in words, full
        for word in words:
            d = copy.deepcopy(BASE)
            d["analysis"].update(CHOICE_CONTEXT.get((key, word), {}))
            if map_name == "analysis":
                d["analysis"][key] = word
            else:
                d["analysis"]["settle"] = {**STAGE, key: word}
            scene = rheodda.scene_from_dict(d)
            read = scene.analysis if map_name == "analysis" else scene.analysis["settle"]
            assert read[key] == word, (full, word)
            inputs = scene.inputs["analysis"]
            assert (inputs if map_name == "analysis" else inputs["settle"])[key] == word, (full, word)
            assert f" {full} {word}" in scene.describe(), (full, word)
            if map_name == "analysis" and key in step_settings:
                sim = rheodda.Simulation(scene)
                assert sim.settings[key] == word, (full, word)
                other = next(w for w in words if w != word)
                sim.set_settings(**{key: other})
                assert sim.settings[key] == other, (full, other)
                with pytest.raises(rheodda.Error, match=f"set_settings: {key} 'nonesuch' is not one of: {', '.join(words)}"):
                    sim.set_settings(**{key: "nonesuch"})
                with pytest.raises(rheodda.Error, match=f"set_settings: {key} is a word"):
                    sim.set_settings(**{key: 1.0})
    if map_name == "analysis":
        assert {"solver", "contact_solver"} <= step_settings


def test_the_material_plane_is_its_declared_choice(root):
    # materials.NAME.plane: declared beside the material's properties (core/property_specs.hpp),
    # the scene's default plane strain; each word reaches Scene.inputs (summary.json's).
    row = next(r for r in doc_table(root, "materials") if r["key"] == "plane")
    assert row["default"] == "`strain`"
    d = copy.deepcopy(BASE)
    d["materials"]["rock"]["plane"] = "nonesuch"
    with pytest.raises(rheodda.SceneError, match=r"materials\.rock\.plane.*'nonesuch' is not one of: strain, stress"):
        rheodda.scene_from_dict(d)
    for word in ("strain", "stress"):
        d["materials"]["rock"]["plane"] = word
        assert rheodda.scene_from_dict(d).inputs["materials"]["rock"]["plane"] == word


def test_the_guide_lists_the_step_settings_python_takes(root, step_settings):
    # docs/guide/python.md's row of set_settings names exactly the keys of Simulation.settings.
    text = (root / "docs" / "guide" / "python.md").read_text()
    row = next(line for line in text.splitlines() if line.startswith("| `sim.set_settings("))
    named = set(re.findall(r"`([a-z_]+)`", row.split("step settings by their scene names:", 1)[1].split("; the keys", 1)[0]))
    assert named == step_settings
