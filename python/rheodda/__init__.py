"""rheodda from Python: contact rheology laws, fits, scenes and runs (docs/guide/python.md).

Set-up (from the repository root, after ``bash scripts/build.sh``)::

    PYTHONPATH=build/python /usr/bin/python3 -c "import rheodda; print(rheodda.laws()[0]['name'])"

Everything here calls the library the ``rheodda`` command uses, so results and
error messages are the command's: a bad scene raises :class:`SceneError` with
``file:line:column: key: message``, a bad law parameter :class:`LawError`, bad
creep data :class:`DataError` (all subclasses of :class:`Error`, a ValueError);
a run that fails raises :class:`RunError`.
"""

import json as _json
import math as _math
import os as _os
import shutil as _shutil

import numpy as _np

from ._rheodda import (  # noqa: F401  (re-exported API)
    __version__,
    Error,
    SceneError,
    LawError,
    DataError,
    FitError,
    ModelError,
    RunError,
    Law,
    PythonLaw,
    StepConstants,
    UnitStepConstants,
    Scene,
    StepReport,
    CreepData,
    ParameterEstimate,
    FixedCombination,
    laws,
    law,
    creep_curve,
    relaxation_curve,
    exact_displacement,
    exact_force,
    law_step,
    read_creep_csv,
    creep_data,
    load_scene,
    parse_scene,
    run,
)
from . import _rheodda

__all__ = [
    "Error", "SceneError", "LawError", "DataError", "FitError", "ModelError", "RunError",
    "Law", "PythonLaw", "StepConstants", "UnitStepConstants", "laws", "law", "law_info",
    "creep_curve", "relaxation_curve", "exact_displacement", "exact_force", "law_step",
    "CreepData", "read_creep_csv", "creep_data", "FitResult", "FixedCombination", "fit", "fit_all",
    "Scene", "load_scene", "parse_scene", "scene_from_dict", "Simulation", "StepReport",
    "run", "run_study", "to_dataframe",
]


def law_info(name):
    """The registry entry of one law (as in :func:`laws`); raises LawError for an unknown name."""
    for entry in laws():
        if entry["name"] == name:
            return entry
    law(name)  # raises LawError with the "did you mean" hint of the registry
    raise LawError(name)  # not reached


# --- outputs -----------------------------------------------------------------

def to_dataframe(columns):
    """A pandas DataFrame of a dict of equally long arrays (a history, a curve,
    contacts). Raises ImportError naming the Debian package when pandas is missing."""
    try:
        import pandas
    except ImportError as e:  # pragma: no cover - pandas is installed by scripts/install-deps.sh
        raise ImportError("to_dataframe needs pandas (apt-get install python3-pandas)") from e
    return pandas.DataFrame({k: _np.asarray(v) for k, v in columns.items()})


# --- fitting -------------------------------------------------------------------

class FitResult:
    """A law fitted to a creep curve (fit::FitResult, docs/guide/fitting.md).

    values, errors: dicts by parameter name (registry units); covariance: the
    covariance of the values by the delta method from the fit's log-parameter
    covariance, cov_ij = corr_ij * err_i * err_j (``errors`` are the
    delta-method standard errors v_i * sd(ln v_i); NaN in the rows and columns
    of parameters that are not identifiable); identifiable: dict of bools,
    reasons: why not; combinations: the combinations the data fix although
    their parts are not identifiable; aic, bic, rss, r2 (NaN without spread),
    rmse, points; minimum_certain, minimum_note, singular_values; warnings;
    fitted (model at the data points); yaml: the law block `rheodda fit
    --yaml` writes.
    """

    def __init__(self, raw, data):
        self._raw = raw
        self.data = data
        self.law = raw.law
        self.parameters = list(raw.parameters)
        self.names = [p.name for p in self.parameters]
        self.values = {p.name: p.value for p in self.parameters}
        self.errors = {p.name: p.std_error for p in self.parameters}
        self.units = {p.name: p.unit for p in self.parameters}
        self.identifiable = {p.name: p.identifiable for p in self.parameters}
        self.reasons = {p.name: p.reason for p in self.parameters if p.reason}
        self.combinations = list(raw.combinations)
        self.correlation = _np.asarray(raw.correlation)
        err = _np.array([p.std_error for p in self.parameters])
        self.covariance = self.correlation * _np.outer(err, err)
        for attr in ("points", "rss", "r2", "rmse", "aic", "bic", "iterations", "starts",
                     "starts_agreeing", "structured_starts", "converged", "minimum_certain", "minimum_note",
                     "warnings"):
            setattr(self, attr, getattr(raw, attr))
        self.fitted = _np.asarray(raw.fitted)
        self.singular_values = _np.asarray(raw.singular_values)

    def make_law(self):
        """The fitted law, ready for curves or a scene's joint set."""
        return law(self.law, self.values)

    @property
    def yaml(self):
        """The YAML law block of `rheodda fit --yaml` (paste under a joint set); the same
        text as apps/fit_command.cpp write_yaml (tests/python/test_fit.py compares them)."""
        r2 = "{:.6f}".format(self.r2) if _math.isfinite(self.r2) else "undefined"
        lines = [
            "# rheodda fit: law {} fitted to {} ({} points, R^2 {})".format(
                self.law, self.data.source, self.points, r2),
            "# paste under a joint set of a scene; the comments give the standard errors",
        ]
        if not self.minimum_certain:
            lines.append("# warning: the minimum is not certain: {}".format(self.minimum_note))
        for c in self.combinations:
            lines.append("# fixed by the data: {} = {:.7g} +- {:.3g} {}".format(
                c.expression, c.value, c.std_error, c.unit))
        lines += ["law:", "  name: {}".format(self.law)]
        for p in self.parameters:
            err = "{:.3g}".format(p.std_error) if p.identifiable else "(not identifiable)"
            lines.append("  {}: {:.7g}   # +- {} {}".format(p.name, p.value, err, p.unit))
        return "\n".join(lines) + "\n"

    def __repr__(self):
        return "<FitResult {}: {} R^2 {:.6f} AIC {:.4g} BIC {:.4g}>".format(
            self.law, ", ".join("{}={:.6g}".format(k, v) for k, v in self.values.items()),
            self.r2, self.aic, self.bic)


def _creep_data(data, t, stress, time_column, displacement_column, stress_column):
    if isinstance(data, CreepData):
        return data
    if isinstance(data, (str, _os.PathLike)):
        return read_creep_csv(_os.fspath(data), time_column=time_column,
                              displacement_column=displacement_column,
                              stress_column=stress_column or "", stress=stress)
    if t is None or stress is None:
        raise Error("fit: give a CSV path, a CreepData, or arrays t=..., displacement, stress=...")
    return creep_data(_np.asarray(t, dtype=float).tolist(),
                      _np.asarray(data, dtype=float).tolist(), stress)


def fit(law_name, data, t=None, stress=None, *, time_column="t", displacement_column="displacement",
        stress_column=None, restarts=4, max_iterations=500):
    """Fits one registered law (``rheodda fit DATA --law LAW``).

    ``data``: a CSV path (columns as in docs/guide/fitting.md; ``stress`` or
    ``stress_column`` gives the shear stress), a :class:`CreepData`, or an
    array of displacements with ``t=`` times and ``stress=`` (a number,
    'T:V[,T:V...]' or (t, value) pairs). Returns a :class:`FitResult`.
    """
    d = _creep_data(data, t, stress, time_column, displacement_column, stress_column)
    return FitResult(_rheodda._fit_law(law_name, d, restarts, max_iterations), d)


def fit_all(data, t=None, stress=None, *, rank_by="bic", time_column="t",
            displacement_column="displacement", stress_column=None, restarts=4, max_iterations=500):
    """Fits every law and ranks them best first by ``rank_by`` ('bic' or 'aic'),
    as ``rheodda fit DATA --law all``. Returns (results, skipped): skipped lists
    "law: reason" for laws the data cannot constrain."""
    d = _creep_data(data, t, stress, time_column, displacement_column, stress_column)
    results, skipped = _rheodda._fit_all(d, rank_by, restarts, max_iterations)
    return [FitResult(r, d) for r in results], list(skipped)


# --- scenes --------------------------------------------------------------------

def scene_from_dict(scene, file="<dict>"):
    """A scene from a dict that mirrors the scene file (docs/reference/scene-format.md).

    The dict is written as JSON (which is YAML) and read by the same loader as a
    file, so every check and every error message is the file's; error lines
    refer to that text (``Scene.text``), one key per line.
    """
    text = _json.dumps(_plain(scene), indent=1, allow_nan=False)
    return parse_scene(text, file)


def _plain(value):
    """The scene as JSON values: numpy numbers and arrays as numbers and lists, and NaN and
    infinities as YAML's .nan and .inf, so that the loader refuses them with their key."""
    if hasattr(value, "tolist") and not isinstance(value, (str, bytes)):
        value = value.tolist()
    if isinstance(value, dict):
        return {k: _plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    if isinstance(value, float) and not _math.isfinite(value):
        return ".nan" if _math.isnan(value) else (".inf" if value > 0 else "-.inf")
    return value


class Simulation:
    """A scene driven step by step through the DDA engine.

    ``Simulation(scene, laws={joint_set: law}, callback=f)``: ``scene`` is a
    :class:`Scene`, a path or a dict (:func:`scene_from_dict`); ``laws``
    replaces joint sets' laws by built-in laws (:func:`law`) or laws written in
    Python (:class:`PythonLaw`); ``callback(sim, report)`` runs after every
    accepted step and may read the state and call ``set_load``,
    ``set_law_parameters``, ``set_settings`` (they take effect from the next
    step). The long calls release the GIL; Ctrl-C raises KeyboardInterrupt
    between two steps and leaves the simulation usable.
    """

    def __init__(self, scene, laws=None, callback=None):
        if isinstance(scene, dict):
            scene = scene_from_dict(scene)
        elif isinstance(scene, (str, _os.PathLike)):
            scene = load_scene(_os.fspath(scene))
        self.scene = scene
        self._sim = _rheodda._Simulation(scene, dict(laws or {}), None)
        self.callback = callback

    def step(self, n=1):
        """Advances n accepted steps (fewer if the scene's duration is reached)."""
        self._run(self.duration, int(n))
        return self

    def run(self, until=None):
        """Advances to time ``until`` [scene time] (default: the scene's duration);
        the last step is shortened to land on it."""
        self._run(self.duration if until is None else float(until), -1)
        return self

    def _run(self, end_time, max_steps):
        f = self.callback
        # Set for the call only: a callback holding the simulation would otherwise make a
        # reference cycle through the C++ object, which the garbage collector cannot see.
        self._sim._callback = None if f is None else (lambda _raw, report: f(self, report))
        try:
            self._sim._run(end_time, max_steps)
        finally:
            self._sim._callback = None

    # state
    time = property(lambda self: self._sim.time, doc="simulated time [scene time]")
    step_count = property(lambda self: self._sim.step_count, doc="accepted steps")
    duration = property(lambda self: self._sim.duration, doc="the scene's analysis.duration [time]")
    failed = property(lambda self: self._sim.failed,
                      doc="True after a step failed (no convergence, a Python law raised): build a new one")
    block_positions = property(lambda self: self._sim.block_positions,
                               doc="block centroids, shape (blocks, 2) [length]")
    block_velocities = property(lambda self: self._sim.block_velocities,
                                doc="(u0, v0, r0, ex, ey, gxy) rates per block, shape (blocks, 6) "
                                    "[length/time, 1/time]; zero in a static analysis")
    block_stresses = property(lambda self: self._sim.block_stresses,
                              doc="(sigma_x, sigma_y, tau_xy) per block, shape (blocks, 3) [stress]")
    settings = property(lambda self: self._sim.settings, doc="the step settings by their scene names")
    loads = property(lambda self: self._sim.loads, doc="each load's (t, fx, fy) samples")
    units = property(lambda self: self._sim.units)
    joint_sets = property(lambda self: self._sim.joint_sets)
    blocks = property(lambda self: self._sim.blocks)
    columns = property(lambda self: self._sim.columns, doc="history columns (those of history.csv)")

    def block_vertices(self, block):
        """Current vertices of a block (index in scene order), shape (n, 2) [length]."""
        return self._sim.block_vertices(self._block_index(block))

    def point_displacement(self, block, x, y):
        """Displacement (u, v) of the material point initially at (x, y) of a block [length]."""
        return self._sim.point_displacement(self._block_index(block), x, y)

    def contacts(self):
        """Each contact as numpy arrays: id, joint_set (index), state, kind, vertex_block,
        vertex, edge_block, edge, x, y, normal_force, shear_force [force/length],
        shear_displacement, penetration, length, creep_displacement, creep_increment [length],
        q (internal displacements of the law, shape (n, 4)) [length]."""
        return self._sim.contacts()

    def history(self):
        """The history since t = 0 as a dict of numpy arrays, one per column of history.csv
        (time, step, dt, cuts, iterations, POINT.u/.v, SET.contacts/.shear_displacement/
        .shear_force, energy terms), at full precision."""
        return self._sim._history()

    def history_frame(self):
        """history() as a pandas DataFrame."""
        return to_dataframe(self.history())

    # changes between steps
    def set_load(self, index, force):
        """Load ``index`` (scene order) holds force (fx, fy) [force] from the next step on."""
        fx, fy = force
        self._sim.set_load(int(index), float(fx), float(fy))

    def set_load_history(self, index, samples):
        """Load ``index`` follows (t, fx, fy) samples from now on (piecewise linear, as in a scene)."""
        self._sim.set_load_history(int(index), [tuple(map(float, s)) for s in samples])

    def set_law_parameters(self, joint_set, parameters=None, **kw):
        """The built-in law of ``joint_set`` takes these parameters (others kept) from the next
        step on; validated by the registry (LawError)."""
        p = dict(parameters or {})
        p.update(kw)
        self._sim.set_law_parameters(joint_set, p)

    def law_parameters(self, joint_set):
        return self._sim.law_parameters(joint_set)

    def set_settings(self, **settings):
        """Step settings by their scene names: dt, dt_growth, dt_cut, max_cuts,
        max_displacement_ratio, creep_tolerance, step_tolerance, step_extrapolation, dt_max,
        open_close_limit, solver_tolerance, solver_max_iterations,
        solver_iterate_tolerance."""
        self._sim.set_settings(**settings)

    def _block_index(self, block):
        if isinstance(block, str):
            names = self.blocks
            if block not in names:
                raise Error("block '{}' is not in the scene".format(block))
            return names.index(block)
        return int(block)


def run_study(path, out_dir, jobs=0, plot=False, rheodda_binary=None):
    """``rheodda study STUDY -o OUT_DIR -j JOBS``: runs every case (each a `rheodda run`
    process) and returns {'cases': [...], 'outputs': [...], 'times': array, 'table': dict}
    where each case has name, status, message, exit_code, steps, wall_seconds,
    inertia_share (static cases: the share of the work the static steps' inertia term took;
    None for a dynamic case) and values
    (outputs x times, NaN where not reached); out_dir/study.csv is written as by the command."""
    binary = rheodda_binary
    if binary is None:
        binary = _rheodda._build_rheodda_binary
        if not _os.path.exists(binary):
            binary = _shutil.which("rheodda") or binary
    cases, outputs, times = _rheodda._run_study(_os.fspath(path), _os.fspath(out_dir), int(jobs),
                                                bool(plot), binary)
    return {"cases": list(cases), "outputs": list(outputs), "times": _np.asarray(times)}
