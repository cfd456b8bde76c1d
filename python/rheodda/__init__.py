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
    PythonLawError,
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
)
from . import _rheodda
from ._scripting import (  # noqa: F401  (re-exported API)
    Block,
    Blocks,
    Bolts,
    Callback,
    Contacts,
    JointSet,
    JointSets,
    Load,
    SimulationState,
)

__all__ = [
    "Error", "SceneError", "LawError", "DataError", "FitError", "ModelError", "PythonLawError", "RunError",
    "Law", "PythonLaw", "StepConstants", "UnitStepConstants", "laws", "law", "law_info",
    "creep_curve", "relaxation_curve", "exact_displacement", "exact_force", "law_step",
    "CreepData", "read_creep_csv", "creep_data", "FitResult", "FixedCombination", "fit", "fit_all",
    "ranking_frame",
    "Scene", "load_scene", "parse_scene", "scene_from_dict", "Simulation", "StepReport",
    "Block", "Blocks", "Load", "JointSet", "JointSets", "Contacts", "Bolts", "Callback", "SimulationState",
    "run", "run_study", "rheodda_binary", "to_dataframe",
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
    of parameters that are not identifiable, fixed or on a bound);
    identifiable: dict of bools, reasons: why not; vary: False for a parameter
    held by ``params`` (vary=False); at_bound: 'min' or 'max' for a parameter
    the fit ended on a bound of, '' otherwise; combinations: the combinations
    the data fix although their parts are not identifiable; aic, bic (from
    chi_square, k = varying), rss [length^2], chi_square (sum of
    ((model - data)/sigma)^2 [-] with sigma, = rss without),
    reduced_chi_square, varying (k), weighted, r2 (NaN without spread), rmse
    [length], points; minimum_certain, minimum_note, start_minima (chi_square
    reached by each start), singular_values; warnings; fitted (model at the
    data points [length]); yaml: the law block `rheodda fit --yaml` writes.
    ``str(result)`` and :meth:`fit_report` give the full table;
    :meth:`to_dataframe` the parameters as a pandas DataFrame.
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
        self.vary = {p.name: p.vary for p in self.parameters}
        self.at_bound = {p.name: p.at_bound for p in self.parameters}
        self.combinations = list(raw.combinations)
        self.correlation = _np.asarray(raw.correlation)
        err = _np.array([p.std_error for p in self.parameters])
        self.covariance = self.correlation * _np.outer(err, err)
        for attr in ("points", "rss", "chi_square", "reduced_chi_square", "varying", "weighted",
                     "scale_covariance", "r2", "rmse", "aic", "bic", "iterations", "starts",
                     "starts_agreeing", "structured_starts", "converged", "minimum_certain", "minimum_note",
                     "warnings"):
            setattr(self, attr, getattr(raw, attr))
        self.fitted = _np.asarray(raw.fitted)
        self.singular_values = _np.asarray(raw.singular_values)
        self.start_minima = _np.asarray(raw.start_minima)

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
            if not p.vary:
                note = "fixed"
            elif p.at_bound:
                note = "at its bound " + p.at_bound
            elif p.identifiable:
                note = "+- {:.3g}".format(p.std_error)
            else:
                note = "+- (not identifiable)"
            lines.append("  {}: {:.7g}   # {} {}".format(p.name, p.value, note, p.unit))
        return "\n".join(lines) + "\n"

    def to_dataframe(self):
        """The parameters as a pandas DataFrame indexed by name: value, std_error, relative_error,
        unit, vary, at_bound, min, max, identifiable (registry units; std_error NaN where none)."""
        rows = {k: [] for k in ("value", "std_error", "relative_error", "unit", "vary", "at_bound", "min",
                                "max", "identifiable")}
        for p in self.parameters:
            has_error = p.vary and not p.at_bound and p.identifiable
            err = p.std_error if has_error else _math.nan
            for k, v in (("value", p.value), ("std_error", err), ("relative_error", err / p.value),
                         ("unit", p.unit), ("vary", p.vary), ("at_bound", p.at_bound), ("min", p.min),
                         ("max", p.max), ("identifiable", p.identifiable)):
                rows[k].append(v)
        frame = to_dataframe(rows)
        frame.index = self.names
        frame.index.name = "name"
        return frame

    def fit_report(self, min_correlation=0.1):
        """A table in the manner of lmfit's fit_report: fit statistics, each parameter's value,
        standard error (and relative error), unit, bounds or 'fixed', identifiability, the
        combinations the data fix, the correlations above ``min_correlation`` in magnitude, the
        sums of squares the starts reached, and the warnings."""
        out = ["[[Fit of law {} to {}]]".format(self.law, self.data.source),
               "    points             = {}".format(self.points),
               "    varying            = {}".format(self.varying),
               "    iterations         = {} (best of {} starts, {} reached it)".format(
                   self.iterations, self.starts, self.starts_agreeing),
               "    chi-square         = {:.8g}{}".format(
                   self.chi_square, "" if self.weighted else " (no sigma: the RSS)"),
               "    reduced chi-square = {:.8g}".format(self.reduced_chi_square),
               "    RSS                = {:.8g} [length^2]".format(self.rss),
               "    RMSE               = {:.8g} [length]".format(self.rmse),
               "    R-squared          = {}".format(
                   "{:.10f}".format(self.r2) if _math.isfinite(self.r2) else "undefined (no spread)"),
               "    Akaike info crit   = {:.6f}".format(self.aic),
               "    Bayesian info crit = {:.6f}".format(self.bic),
               "    converged          = {}".format(self.converged),
               "    minimum certain    = {}{}".format(
                   self.minimum_certain, "" if self.minimum_certain else " (" + self.minimum_note + ")"),
               "    starts' minima     = {}".format(" ".join("{:.6g}".format(m) for m in self.start_minima))]
        if self.weighted:
            out.append("    standard errors    = {}".format(
                "scaled by sqrt(reduced chi-square)" if self.scale_covariance else "from sigma, absolute"))
        out.append("[[Variables]]")
        for p in self.parameters:
            line = "    {:<6} {:>14.8g}".format(p.name + ":", p.value)
            if not p.vary:
                line += " (fixed)"
            elif p.at_bound:
                line += " (at its bound {} = {:g})".format(p.at_bound, p.min if p.at_bound == "min" else p.max)
            elif p.identifiable:
                line += " +/- {:.6g} ({:.2f}%)".format(p.std_error, 100.0 * p.std_error / p.value)
            else:
                line += " (not identifiable: {})".format(p.reason)
            line += " [{}]".format(p.unit)
            if p.vary and (p.min > 0 or _math.isfinite(p.max)):
                line += " bounds [{:g}, {:g}]".format(p.min, p.max)
            out.append(line)
        if self.combinations:
            out.append("[[Combinations the data fix]]")
            for c in self.combinations:
                out.append("    {} = {:.8g} +/- {:.3g} [{}]".format(c.expression, c.value, c.std_error, c.unit))
        pairs = []
        for i in range(len(self.names)):
            for j in range(i + 1, len(self.names)):
                c = self.correlation[i, j]
                if _math.isfinite(c) and abs(c) >= min_correlation:
                    pairs.append((abs(c), "    C({}, {}) = {:+.4f}".format(self.names[i], self.names[j], c)))
        if pairs:
            out.append("[[Correlations]] (unreported correlations are < {:.3f})".format(min_correlation))
            out += [text for _, text in sorted(pairs, key=lambda x: -x[0])]
        if self.warnings:
            out.append("[[Warnings]]")
            out += ["    " + w for w in self.warnings]
        return "\n".join(out) + "\n"

    def __str__(self):
        return self.fit_report()

    def __repr__(self):
        r2 = "{:.6f}".format(self.r2) if _math.isfinite(self.r2) else "undefined"
        return "<FitResult {}: {} R^2 {} AIC {:.4g} BIC {:.4g}>".format(
            self.law, ", ".join("{}={:.6g}".format(k, v) for k, v in self.values.items()),
            r2, self.aic, self.bic)


def _creep_data(data, t, stress, time_column, displacement_column, stress_column, sigma=None,
                weights=None, sigma_column=None):
    if sigma is not None and weights is not None:
        raise Error("fit: give sigma= (measurement standard deviations) or weights= (1/sigma), not both")
    if weights is not None:
        w = _np.asarray(weights, dtype=float)
        if w.ndim != 1 or not _np.all(_np.isfinite(w)) or not _np.all(w > 0):
            raise Error("fit: weights must be a 1-D array of finite positive numbers (1/sigma) [1/length]")
        sigma = 1.0 / w
    if sigma is not None:
        sigma = _np.asarray(sigma, dtype=float)
        if sigma.ndim != 1:
            raise Error("fit: sigma must be a 1-D array, one standard deviation per point [length]; got shape {}"
                        .format(sigma.shape))
        if sigma_column:
            raise Error("fit: sigma_column= reads sigma from the CSV; sigma= or weights= gives it: not both")
    if isinstance(data, CreepData):
        if sigma_column:
            raise Error("fit: sigma_column= reads a CSV column; the data are a CreepData already")
        return data if sigma is None else data._with_sigma(sigma.tolist())
    if isinstance(data, (str, _os.PathLike)):
        d = read_creep_csv(_os.fspath(data), time_column=time_column,
                           displacement_column=displacement_column,
                           stress_column=stress_column or "", stress=stress, sigma_column=sigma_column or "")
        return d if sigma is None else d._with_sigma(sigma.tolist())
    if sigma_column:
        raise Error("fit: sigma_column= reads a CSV column; with arrays give sigma= or weights=")
    if t is None or stress is None:
        raise Error("fit: give a CSV path, a CreepData, or arrays t=..., displacement, stress=...")
    return creep_data(_np.asarray(t, dtype=float).tolist(),
                      _np.asarray(data, dtype=float).tolist(), stress,
                      sigma=None if sigma is None else sigma.tolist())


_SETTING_KEYS = ("value", "vary", "min", "max")


def _settings(params):
    """params= as {name: {"value", "vary", "min", "max"}} for the library (fit::ParameterSetting).

    Each entry: a number (the initial value), a dict with any of value, vary, min, max, or an
    object with those attributes (an lmfit.Parameter; an lmfit.Parameters is a dict of them).
    min -inf or None means no bound beyond positivity (0), max None means +inf."""
    out = {}
    if params is None:
        return out
    if not hasattr(params, "items"):
        raise Error("fit: params must be a dict {name: value | {'value', 'vary', 'min', 'max'}} "
                    "or an lmfit.Parameters; got {}".format(type(params).__name__))
    for name, spec in params.items():
        if isinstance(spec, (int, float)) and not isinstance(spec, bool):
            spec = {"value": spec}
        elif isinstance(spec, dict):
            unknown = sorted(set(spec) - set(_SETTING_KEYS))
            if unknown:
                raise Error("fit: params['{}']: unknown key(s) {}; the keys are {}".format(
                    name, ", ".join(unknown), ", ".join(_SETTING_KEYS)))
        elif all(hasattr(spec, k) for k in _SETTING_KEYS):
            spec = {k: getattr(spec, k) for k in _SETTING_KEYS}
        else:
            raise Error("fit: params['{}'] must be a number (initial value), a dict with value, vary, min, "
                        "max, or an lmfit.Parameter; got {!r}".format(name, spec))
        lo = spec.get("min")
        hi = spec.get("max")
        value = spec.get("value")
        out[str(name)] = {
            "value": None if value is None else float(value),
            "vary": bool(spec.get("vary", True)),
            "min": 0.0 if lo is None or lo == -_math.inf else float(lo),
            "max": _math.inf if hi is None else float(hi),
        }
    return out


def fit(law_name, data, t=None, stress=None, *, params=None, sigma=None, weights=None, absolute_sigma=False,
        time_column="t", displacement_column="displacement", stress_column=None, sigma_column=None,
        restarts=4, max_iterations=500):
    """Fits one registered law (``rheodda fit DATA --law LAW``).

    ``data``: a CSV path (columns as in docs/guide/fitting.md; ``stress`` or
    ``stress_column`` gives the shear stress [stress]), a :class:`CreepData`,
    or an array of displacements [length] with ``t=`` times [time] and
    ``stress=`` (a number, 'T:V[,T:V...]' or (t, value) pairs [stress]).

    ``params``: per parameter an initial value, or a dict (or lmfit.Parameter)
    with ``value``, ``vary`` (False: held at value, ``--fix``), ``min``,
    ``max`` (bounds, ``--bounds``), in the parameter's registry unit.
    ``sigma``: each point's measurement standard deviation [length] (or
    ``weights`` = 1/sigma [1/length], as lmfit's; or ``sigma_column`` of the
    CSV, ``--sigma-column``): the fit minimizes sum ((model - data)/sigma)^2.
    ``absolute_sigma``: standard errors from sigma as absolute errors
    (``--absolute-sigma``); by default they are scaled by sqrt(reduced
    chi-square) as lmfit's. Returns a :class:`FitResult`.
    """
    d = _creep_data(data, t, stress, time_column, displacement_column, stress_column, sigma, weights,
                    sigma_column)
    return FitResult(_rheodda._fit_law(law_name, d, restarts, max_iterations, _settings(params),
                                       not absolute_sigma), d)


def fit_all(data, t=None, stress=None, *, rank_by="bic", params=None, sigma=None, weights=None,
            absolute_sigma=False, time_column="t", displacement_column="displacement", stress_column=None,
            sigma_column=None, restarts=4, max_iterations=500):
    """Fits every law and ranks them best first by ``rank_by`` ('bic' or 'aic'),
    as ``rheodda fit DATA --law all``; the other arguments as :func:`fit`
    (``params`` apply to every law; a law without one of the named parameters
    is skipped). Returns (results, skipped): skipped lists "law: reason" for
    laws that cannot be fitted."""
    d = _creep_data(data, t, stress, time_column, displacement_column, stress_column, sigma, weights,
                    sigma_column)
    results, skipped = _rheodda._fit_all(d, rank_by, restarts, max_iterations, _settings(params),
                                         not absolute_sigma)
    return [FitResult(r, d) for r in results], list(skipped)


def ranking_frame(results):
    """A list of :class:`FitResult` (as :func:`fit_all` returns) as a pandas DataFrame, one row per
    law in the given order: law, k (varying), points, rmse [length], r2, chi_square, aic, bic."""
    cols = {k: [] for k in ("law", "k", "points", "rmse", "r2", "chi_square", "aic", "bic")}
    for r in results:
        for k, v in (("law", r.law), ("k", r.varying), ("points", r.points), ("rmse", r.rmse), ("r2", r.r2),
                     ("chi_square", r.chi_square), ("aic", r.aic), ("bic", r.bic)):
            cols[k].append(v)
    return to_dataframe(cols)


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


def _as_scene(scene):
    """A :class:`Scene` of what Simulation and run accept: a Scene, a path (str or os.PathLike) or a
    dict that mirrors the scene file (:func:`scene_from_dict`)."""
    if isinstance(scene, Scene):
        return scene
    if isinstance(scene, dict):
        return scene_from_dict(scene)
    if isinstance(scene, (str, _os.PathLike)):
        return load_scene(_os.fspath(scene))
    raise TypeError("a scene is a rheodda.Scene, a path or a dict; got {}".format(type(scene).__name__))


def run(scene, out_dir, resume=False, progress=False):
    """``rheodda run SCENE -o OUT_DIR [--resume]``: history.csv, contacts.csv, ParaView frames,
    summary.json; returns the summary as a dict (status, steps, time [time], ...). ``scene``: what
    :class:`Simulation` accepts (a Scene, a path or a dict). Ctrl-C stops it after the current step
    (resumable) and raises KeyboardInterrupt."""
    return _rheodda.run(_as_scene(scene), _os.fspath(out_dir), resume=bool(resume), progress=bool(progress))


class Simulation:
    """A scene driven step by step through the DDA engine (docs/guide/python.md, "Scripting").

    ``Simulation(scene, laws={joint_set: law}, callback=f, every_steps=N | every_time=dt)``:
    ``scene`` is a :class:`Scene`, a path or a dict (:func:`scene_from_dict`); ``laws``
    replaces joint sets' laws by built-in laws (:func:`law`) or laws written in Python
    (:class:`PythonLaw`); ``callback(sim, report)`` runs after accepted steps - every step, every
    ``every_steps`` steps or after the first step reaching each multiple of ``every_time``
    [time] - and may read the state and change the model (blocks, loads, joint sets, settings:
    from the next step on); :meth:`add_callback` adds more. ``sim.blocks``, ``sim.joint_sets``,
    ``sim.contacts``, ``sim.bolts`` read and change the model; :meth:`save` and :meth:`restore`
    keep and continue a state bit for bit; a Simulation pickles and copies through them. Values
    are in the scene's units (``sim.units``). The long calls release the GIL; Ctrl-C raises
    KeyboardInterrupt between two steps and leaves the simulation usable.
    """

    def __init__(self, scene, laws=None, callback=None, every_steps=None, every_time=None):
        self.scene = _as_scene(scene)
        self._laws = dict(laws or {})
        self._sim = _rheodda._Simulation(self.scene, self._laws, None)
        self._callbacks = []
        self._main = None
        if callback is not None:
            self._main = self.add_callback(callback, steps=every_steps, time=every_time)
        elif every_steps is not None or every_time is not None:
            raise Error("Simulation: every_steps= and every_time= are the period of callback=, which is missing")

    # --- running -----------------------------------------------------------------

    def step(self, n=1):
        """Advances n accepted steps (fewer if the scene's duration is reached)."""
        self._run(self.duration, int(n))
        return self

    def run(self, until=None):
        """Advances to time ``until`` [time] (default: the scene's duration); the last step is
        shortened to land on it."""
        self._run(self.duration if until is None else float(until), -1)
        return self

    def _run(self, end_time, max_steps):
        callbacks = self._callbacks

        def dispatch(_raw, report):
            for c in list(callbacks):
                if c in callbacks and c._due(report):
                    c.function(self, report)

        # Set for the call only: a callback holding the simulation would otherwise make a
        # reference cycle through the C++ object, which the garbage collector cannot see.
        self._sim._callback = dispatch if callbacks else None
        try:
            self._sim._run(end_time, max_steps)
        finally:
            self._sim._callback = None

    @property
    def callback(self):
        """The callback given to the constructor (or set here), called every step, or with the
        constructor's every_steps / every_time period; None: none."""
        return None if self._main is None else self._main.function

    @callback.setter
    def callback(self, f):
        steps, time = (None, None) if self._main is None else (self._main.steps, self._main.time)
        if self._main is not None:
            self._main.remove()
            self._main = None
        if f is not None:
            self._main = self.add_callback(f, steps=steps, time=time)

    def add_callback(self, function, steps=None, time=None):
        """Calls ``function(sim, report)`` after accepted steps: every ``steps`` steps (default 1),
        or after the first step that reaches each multiple of ``time`` [time] counted from now (the
        steps are not shortened to land on those times: a callback leaves the run as it is). It
        may change the model (from the next step on). Returns a :class:`Callback` (``.remove()``)."""
        c = Callback(self, function, steps=steps, time=time)
        self._callbacks.append(c)
        return c

    @property
    def callbacks(self):
        """The callbacks in the order they run (a copy of the list)."""
        return list(self._callbacks)

    # --- state -------------------------------------------------------------------

    time = property(lambda self: self._sim.time, doc="simulated time [time]")
    step_count = property(lambda self: self._sim.step_count, doc="accepted steps")
    duration = property(lambda self: self._sim.duration, doc="the scene's analysis.duration [time]")
    failed = property(lambda self: self._sim.failed,
                      doc="True after a step failed (no convergence, a Python law raised): build a new one")
    settings = property(lambda self: self._sim.settings, doc="the step settings by their scene names")
    loads = property(lambda self: self._sim.loads,
                     doc="per load now in the model, its samples as a read-only array of rows "
                         "(t [time], fx, fy [force])")
    units = property(lambda self: self._sim.units,
                     doc="the scene's unit names: dict of length, force, time, stress")
    columns = property(lambda self: self._sim.columns, doc="history columns (those of history.csv)")

    @property
    def blocks(self):
        """The blocks (:class:`Blocks`): ``sim.blocks[i]`` or ``['name']`` a :class:`Block`,
        ``sim.blocks.position`` ... read-only arrays of every block [scene units]."""
        return Blocks(self)

    @property
    def joint_sets(self):
        """The joint sets (:class:`JointSets`): ``sim.joint_sets['name']`` or ``[i]`` a
        :class:`JointSet` whose friction_angle [deg], cohesion [stress] ... are settable."""
        return JointSets(self)

    @property
    def contacts(self):
        """The contacts after the last accepted step (:class:`Contacts`): ``len``, columns as
        read-only arrays (``sim.contacts.normal_force`` [force/length], ...); ``sim.contacts()``
        the columns as a dict."""
        return Contacts(self._sim._contacts())

    @property
    def bolts(self):
        """The bolts after the last accepted step (:class:`Bolts`), read-only: name, state, force
        [force], length, elongation, plastic_elongation, creep_elongation [length], rupture_time
        [time]; empty without bolts."""
        return Bolts(self._sim._bolts())

    block_positions = property(lambda self: self.blocks.position,
                               doc="block centroids, shape (blocks, 2) [length]; = blocks.position")
    block_velocities = property(lambda self: self.blocks.velocity,
                                doc="(u0, v0, r0, ex, ey, gxy) rates per block, shape (blocks, 6) "
                                    "[length/time, 1/time]; zero in a static analysis; = blocks.velocity")
    block_stresses = property(lambda self: self.blocks.stress,
                              doc="(sigma_x, sigma_y, tau_xy) per block, shape (blocks, 3) [stress]; "
                                  "= blocks.stress")

    def block_vertices(self, block):
        """Current vertices of a block (index or name), shape (n, 2) [length]."""
        return self.blocks[block].vertices

    def point_displacement(self, block, x, y):
        """Displacement (u, v) of the material point initially at (x, y) of a block [length]."""
        return self.blocks[block].point_displacement(x, y)

    def history(self):
        """The history since t = 0 as a dict of numpy arrays, one per column of history.csv
        (time, step, dt, cuts, iterations, POINT.u/.v, SET.contacts/.shear_displacement/
        .shear_force, energy terms), at full precision."""
        return self._sim._history()

    def history_frame(self):
        """history() as a pandas DataFrame."""
        return to_dataframe(self.history())

    # --- changes between steps ------------------------------------------------------

    def set_load(self, index, force):
        """Load ``index`` (its index in ``sim.loads``: scene order until a load is removed) holds force
        (fx, fy) [force] from the next step on."""
        fx, fy = force
        self._sim.set_load(int(index), float(fx), float(fy))

    def set_load_history(self, index, samples):
        """Load ``index`` follows (t [time], fx, fy [force]) samples from now on (piecewise linear, as in
        a scene; t is run time)."""
        self._sim.set_load_history(int(index), [tuple(map(float, s)) for s in samples])

    def load(self, index):
        """The :class:`Load` at ``index`` in ``sim.loads`` now (to remove it: ``sim.load(i).remove()``)."""
        ids = list(self._sim._load_ids)
        if not 0 <= int(index) < len(ids):
            raise Error("load {} does not exist; the model has {} loads".format(index, len(ids)))
        return Load(self, ids[int(index)], None)

    def set_law_parameters(self, joint_set, parameters=None, **kw):
        """The built-in law of ``joint_set`` takes these parameters (others kept) from the next
        step on; validated by the registry (LawError) and as a stage's law change."""
        p = dict(parameters or {})
        p.update(kw)
        self._sim.set_law_parameters(joint_set, p)

    def law_parameters(self, joint_set):
        """The parameters of the built-in law of ``joint_set`` by name [their registry units]."""
        return self._sim.law_parameters(joint_set)

    def set_settings(self, **settings):
        """Step settings by their scene names: dt, dt_growth, dt_cut, max_cuts,
        max_displacement_ratio, creep_tolerance, step_tolerance, step_extrapolation, dt_max,
        open_close_limit, solver_tolerance, solver_max_iterations,
        solver_iterate_tolerance."""
        self._sim.set_settings(**settings)

    # --- saving and restoring ---------------------------------------------------------

    def save(self, path=None):
        """The state now as a :class:`SimulationState` (in memory; picklable), or, with ``path``,
        written to that file as well. :meth:`restore` continues it bit for bit. The callbacks are
        code, not state: they are not saved."""
        python_laws = {k: v for k, v in self._laws.items() if isinstance(v, PythonLaw)}
        state = SimulationState(self._sim._save(), python_laws, self.time, self.step_count)
        if path is not None:
            state.write(path)
        return state

    @classmethod
    def restore(cls, state, laws=None, callback=None, every_steps=None, every_time=None):
        """A simulation that continues ``state`` (a :class:`SimulationState`, its bytes, or the path of a
        file :meth:`save` wrote) as the saved one would have, bit for bit. ``laws``: the laws written in
        Python of the joint sets that had them (a state in memory carries them); ``callback`` and its
        period as in the constructor."""
        if isinstance(state, SimulationState):
            data, given = state.data, dict(state.laws)
        elif isinstance(state, (bytes, bytearray)):
            data, given = bytes(state), {}
        else:
            with open(_os.fspath(state), "rb") as f:
                data, given = f.read(), {}
        given.update(laws or {})
        header = _rheodda._Simulation._state_header(data)
        laws_now = {}
        for name, saved in header["laws"].items():
            if saved == "python":
                if name not in given:
                    raise Error("Simulation.restore: joint set '{}' had a law written in Python: give it with "
                                "laws={{'{}': ...}}".format(name, name))
                laws_now[name] = given[name]
            else:
                laws_now[name] = law(saved[0], saved[1])
        sim = cls(parse_scene(header["scene"], header["file"]), laws=laws_now, callback=callback,
                  every_steps=every_steps, every_time=every_time)
        sim._sim._restore(data)
        return sim

    def __reduce__(self):
        # pickle and copy: the saved state, and the callbacks with their periods (pickled by
        # reference: a lambda or a local function cannot be pickled, and says so).
        return (_unpickle_simulation, (self.save(), self._callbacks, self._main))

    def __repr__(self):
        return "<rheodda.Simulation '{}': t = {:g} of {:g} {}, {} steps{}>".format(
            self.scene.title, self.time, self.duration, self.units["time"], self.step_count,
            ", FAILED" if self.failed else "")


def _unpickle_simulation(state, callbacks, main):
    sim = Simulation.restore(state)
    for c in callbacks:
        c._sim = sim
    sim._callbacks = list(callbacks)
    sim._main = main
    return sim


def rheodda_binary():
    """The path of the ``rheodda`` program :func:`run_study` runs: the installed program next to an
    installed package (``cmake --install``: <prefix>/bin/rheodda), the build tree's for the package
    of a build (PYTHONPATH=<build>/python), else ``rheodda`` on the PATH."""
    try:
        from ._installed import RHEODDA_BINARY_FROM_PACKAGE
    except ImportError:  # the build tree's package
        path = _rheodda._build_rheodda_binary
    else:
        path = _os.path.normpath(_os.path.join(_os.path.dirname(_os.path.abspath(__file__)),
                                               RHEODDA_BINARY_FROM_PACKAGE))
    if _os.path.exists(path):
        return path
    return _shutil.which("rheodda") or path


def run_study(path, out_dir, jobs=0, plot=False, rheodda_binary=None):
    """``rheodda study STUDY -o OUT_DIR -j JOBS``: runs every case (each a `rheodda run`
    process) and returns {'cases': [...], 'outputs': [...], 'times': array, 'table': dict}
    where each case has name, status, message, exit_code, steps, wall_seconds,
    inertia_share (static cases: the share of the work the static steps' inertia term took;
    None for a dynamic case) and values
    (outputs x times, NaN where not reached); out_dir/study.csv is written as by the command."""
    binary = _rheodda_binary_default() if rheodda_binary is None else _os.fspath(rheodda_binary)
    cases, outputs, times = _rheodda._run_study(_os.fspath(path), _os.fspath(out_dir), int(jobs),
                                                bool(plot), binary)
    return {"cases": list(cases), "outputs": list(outputs), "times": _np.asarray(times)}


_rheodda_binary_default = rheodda_binary  # run_study's parameter of the same name shadows it
