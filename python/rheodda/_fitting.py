"""Fitting laws to laboratory creep curves from Python, as lmfit users do (docs/guide/fitting.md,
docs/guide/python.md): :func:`fit`, :func:`fit_all`, :class:`FitResult`, :func:`ranking_frame`.
The fit itself is the library's (laws/fit), the one ``rheodda fit`` runs."""

import math as _math
import os as _os

import numpy as _np

from . import _rheodda
from ._frames import to_dataframe
from ._rheodda import CreepData, Error, creep_data, exact_displacement, law, read_creep_csv


class FitParameter:
    """One parameter of a fit as lmfit's Parameter shows it (``result.params[name]``): name,
    value, stderr (NaN where there is none: fixed, on a bound, not identifiable), vary
    (False when fixed or given by an expression), min, max (0 and inf: no bound), expr (the
    expression that gives it, None), and rheodda's unit, at_bound, identifiable."""

    def __init__(self, p, stderr):
        self.name = p.name
        self.value = p.value
        self.stderr = stderr
        self.vary = p.vary
        self.min = p.min
        self.max = p.max
        self.expr = p.expr or None
        self.unit = p.unit
        self.at_bound = p.at_bound
        self.identifiable = p.identifiable

    def __repr__(self):
        if self.expr:
            how = "expr='{}'".format(self.expr)
        elif not self.vary:
            how = "fixed"
        else:
            how = "bounds=[{:g}:{:g}]".format(self.min, self.max)
        return "<FitParameter '{}', value={!r} +/- {:.3g}, {}>".format(self.name, self.value, self.stderr, how)


class FitResult:
    """A law fitted to a creep curve (fit::FitResult, docs/guide/fitting.md).

    values, errors: dicts by parameter name (registry units); covariance: the
    covariance of the values by the delta method from the fit's log-parameter
    covariance, cov_ij = corr_ij * err_i * err_j (``errors`` are the
    delta-method standard errors v_i * sd(ln v_i); NaN in the rows and columns
    of parameters that are not identifiable, fixed or on a bound);
    identifiable: dict of bools, reasons: why not; vary: False for a parameter
    held by ``params`` (vary=False) or given by an expression (expr=); at_bound: 'min' or 'max' for a parameter
    the fit ended on a bound of, '' otherwise; combinations: the combinations
    the data fix although their parts are not identifiable; aic, bic (from
    chi_square, k = varying), rss [length^2], chi_square (sum of
    ((model - data)/sigma)^2 [-] with sigma, = rss without),
    reduced_chi_square, varying (k), weighted, r2 (NaN without spread), rmse
    [length], points; minimum_certain, minimum_note, start_minima (chi_square
    reached by each start), singular_values; warnings; fitted (model at the
    data points [length]); residual ((fitted - data)/sigma, or fitted - data
    without sigma, as lmfit's); params: name -> :class:`FitParameter`;
    converged (the optimality conditions hold, with settings) and optimality
    (their largest violation, a cosine); yaml: the law block `rheodda fit
    --yaml` writes. ``errors`` and ``params[name].stderr`` are NaN where no
    standard error is given (fixed, on a bound, not identifiable), as in
    :meth:`to_dataframe`. :meth:`eval` gives the fitted curve at any times,
    :meth:`conf_interval` profile-likelihood intervals.
    ``str(result)`` and :meth:`fit_report` give the full table;
    :meth:`to_dataframe` the parameters as a pandas DataFrame.
    """

    def __init__(self, raw, data, call=None, units=None):
        self._raw = raw
        self._call = call  # (restarts, max_iterations, settings, scale_covariance) of the fit, for conf_interval
        self.data = data
        self.data_units = units  # "MPa, mm, h" as given to fit(units=), or None
        self._labels = _three_labels(units, "units", "'STRESS, LENGTH, TIME', e.g. \"MPa, mm, h\"") if units else None
        self.law = raw.law
        self.parameters = list(raw.parameters)
        self.names = [p.name for p in self.parameters]
        self.values = {p.name: p.value for p in self.parameters}
        self.errors = {p.name: p.std_error if _has_error(p) else _math.nan for p in self.parameters}
        self.params = {p.name: FitParameter(p, self.errors[p.name]) for p in self.parameters}
        self.expr = {p.name: p.expr for p in self.parameters if p.expr}
        self.units = {p.name: self._unit(p.unit) for p in self.parameters}
        self.identifiable = {p.name: p.identifiable for p in self.parameters}
        self.reasons = {p.name: p.reason for p in self.parameters if p.reason}
        self.vary = {p.name: p.vary for p in self.parameters}
        self.at_bound = {p.name: p.at_bound for p in self.parameters}
        self.combinations = list(raw.combinations)
        self.correlation = _np.asarray(raw.correlation)
        err = _np.array([self.errors[p.name] for p in self.parameters])
        self.covariance = self.correlation * _np.outer(err, err)
        for attr in ("points", "rss", "chi_square", "reduced_chi_square", "varying", "weighted",
                     "scale_covariance", "r2", "rmse", "aic", "bic", "iterations", "starts",
                     "starts_agreeing", "structured_starts", "converged", "optimality", "minimum_certain", "minimum_note",
                     "warnings"):
            setattr(self, attr, getattr(raw, attr))
        self.fitted = _np.asarray(raw.fitted)
        self.singular_values = _np.asarray(raw.singular_values)
        self.start_minima = _np.asarray(raw.start_minima)
        d = _np.asarray(data.displacement)
        self.residual = (self.fitted - d) / (1.0 if data.sigma is None else _np.asarray(data.sigma))

    def eval(self, t=None):
        """The fitted curve [length] at times ``t`` [time] (default: the data's), under the data's
        stress history: the law's exact staged response (rheodda.exact_displacement)."""
        times = _np.asarray(self.data.t if t is None else t, dtype=float)
        history = [(float(a), float(b)) for a, b in _np.asarray(self.data.stress)]
        return _np.asarray(exact_displacement(self.make_law(), history, times))

    def conf_interval(self, sigmas=(1, 2), names=None, details=False):
        """Confidence intervals by profile likelihood (docs/guide/fitting.md, "Confidence intervals
        by profile likelihood"), in the format of lmfit's ``conf_interval``: {name: [(probability,
        lower end) for the sigmas, largest first, (0.0, value), (probability, upper end) ...]}.
        Each end is where the chi-square minimized with the parameter held there rises to the
        level (lmfit's F test with scaled errors; the chi-square quantile with
        absolute_sigma=True). ``names``: the varying parameters to do (default: all of them).
        An end that chi-square does not reach before the parameter's bound is that bound, before
        1e6 times the value 0 or inf. ``details=True`` returns the library's records instead
        (per parameter: value, fits, levels with sigma, probability, chi_square, lower, upper,
        lower_found, upper_found)."""
        if self._call is None:
            raise Error("conf_interval: this FitResult does not hold the settings of its fit")
        restarts, max_iterations, settings, scale_covariance = self._call
        sig = sorted(float(x) for x in sigmas)
        raw = _rheodda._profile(self.law, self.data, restarts, max_iterations, settings, scale_covariance,
                                self._raw, sig, list(names or []))
        if details:
            return raw
        out = {}
        for r in raw:
            levels = r["levels"]
            out[r["name"]] = ([(lv["probability"], lv["lower"]) for lv in reversed(levels)] + [(0.0, r["value"])]
                              + [(lv["probability"], lv["upper"]) for lv in levels])
        return out

    def _unit(self, dimension):
        """A registry dimension spelled in the data's units (as `rheodda fit --units` spells it)."""
        if self._labels is None or dimension == "-":
            return dimension
        stress, length, time = self._labels
        return _rheodda._unit_of(dimension, length, "", time, stress)

    def scene_values(self, scene_units):
        """The fitted values in a scene's units: ``scene_units`` is 'LENGTH, FORCE, TIME' (e.g.
        'm, N, d'), a scene file's path or a :class:`Scene`; the fit must have been given
        ``units=``. Returns {name: (value, unit)}, converted by UDUNITS-2."""
        return {p.name: (p.value * f, u) for p, (f, u) in zip(self.parameters, self._scene_factors(scene_units)[1])}

    def _scene_factors(self, scene_units):
        if self._labels is None:
            raise Error("a law is written in a scene's units from the data's: give fit(..., units=\"STRESS, LENGTH, "
                        "TIME\"), e.g. units=\"MPa, mm, h\"")
        if isinstance(scene_units, str) and "," in scene_units:
            length, force, time = _three_labels(scene_units, "scene_units", "'LENGTH, FORCE, TIME', e.g. \"m, N, d\"")
        else:
            scene = scene_units
            if isinstance(scene_units, (str, _os.PathLike)):
                scene = _rheodda.load_scene(_os.fspath(scene_units))
            length, force, time = scene.units["length"], scene.units["force"], scene.units["time"]
        out = []
        for p in self.parameters:
            if p.unit == "-":
                out.append((1.0, "-"))
            else:
                unit = _rheodda._unit_of(p.unit, length, force, time)
                out.append((_rheodda._convert(1.0, self._unit(p.unit), unit), unit))
        # The tested range's factors (stress, time), as fit --yaml converts them.
        tested = tuple(_rheodda._convert(1.0, self._unit(d), _rheodda._unit_of(d, length, force, time))
                       for d in ("stress", "time"))
        return "{}, {}, {}".format(length, force, time), out, tested

    def scene_yaml(self, scene_units):
        """The YAML law block in a scene's units (``scene_units`` as :meth:`scene_values`): the
        same text as `rheodda fit --yaml FILE --units ... --scene-units ...` (or ``--scene``)."""
        return self._yaml(self._scene_factors(scene_units))

    def make_law(self):
        """The fitted law, ready for curves or a scene's joint set."""
        return law(self.law, self.values)

    @property
    def yaml(self):
        """The YAML law block of `rheodda fit --yaml` (paste under a joint set); the same
        text as apps/fit_command.cpp write_yaml (tests/python/test_fit.py compares them).
        In the data's units (``units=``); :meth:`scene_yaml` writes it in a scene's."""
        return self._yaml(None)

    def _yaml(self, scene):
        r2 = "{:.6f}".format(self.r2) if _math.isfinite(self.r2) else "undefined"
        lines = [
            "# rheodda fit: law {} fitted to {} ({} points, R^2 {}){}".format(
                self.law, self.data.source, self.points, r2,
                "; units {}".format(self.data_units) if self.data_units else ""),
        ]
        if scene is not None:
            lines.append("# in the scene's units {} (length, force, time), converted from the data's {}".format(
                scene[0], self.data_units))
        lines.append("# paste under a joint set of a scene; the comments give the standard errors")
        if not self.minimum_certain:
            lines.append("# warning: the minimum is not certain: {}".format(self.minimum_note))
        for c in self.combinations:
            lines.append("# fixed by the data: {} = {:.7g} +- {:.3g} {}".format(
                c.expression, c.value, c.std_error, self._unit(c.unit)))
        unidentified = self.unidentified
        if unidentified:
            lines.append("# the data do not determine {}: the value{} below {} one of many they allow "
                         "(unidentified)".format(", ".join(unidentified), "" if len(unidentified) == 1 else "s",
                                                 "is" if len(unidentified) == 1 else "are"))
        if scene is not None:
            lines.append("# tested_stress and tested_duration: the stresses and duration of the data, in the "
                         "scene's units")
        else:
            lines.append("# tested_stress and tested_duration: the stresses and duration of the data{}; the scene's "
                         "units must be the data's (or write it with --scene-units)".format(
                             " [{}], [{}]".format(self._unit("stress"), self._unit("time")) if self._labels else ""))
        lines += ["law:", "  name: {}".format(self.law)]
        for i, p in enumerate(self.parameters):
            factor, unit = (1.0, self._unit(p.unit)) if scene is None else scene[1][i]
            if p.expr:
                note = "= {}".format(p.expr)
            elif not p.vary:
                note = "fixed"
            elif p.at_bound:
                note = "at its bound " + p.at_bound
            elif p.identifiable:
                note = "+- {:.3g}".format(p.std_error * factor)
            else:
                note = "+- (not identifiable)"
            fitted = "" if scene is None else " (fitted {:.7g} {})".format(p.value, self._unit(p.unit))
            lines.append("  {}: {:.7g}   # {} {}{}".format(p.name, p.value * factor, note, unit, fitted))
        if unidentified:
            lines.append("  unidentified: [{}]".format(", ".join(unidentified)))
        lo, hi, duration = _rheodda._tested_range(self.data)
        fs, ft = (1.0, 1.0) if scene is None else scene[2]
        lines.append("  tested_stress: [{:.7g}, {:.7g}]".format(lo * fs, hi * fs))
        lines.append("  tested_duration: {:.7g}".format(duration * ft))
        return "\n".join(lines) + "\n"

    @property
    def unidentified(self):
        """The names of the parameters the data do not determine (varying, not on a bound, not
        identifiable): `yaml` marks them ``unidentified: [...]``, and a scene using the law warns."""
        return list(_rheodda._unidentified(self._raw))

    def to_dataframe(self):
        """The parameters as a pandas DataFrame indexed by name: value, std_error, relative_error,
        unit, vary, at_bound, min, max, identifiable, expr (registry units; std_error NaN where none,
        as in ``errors``; expr '' where none)."""
        rows = {k: [] for k in ("value", "std_error", "relative_error", "unit", "vary", "at_bound", "min",
                                "max", "identifiable", "expr")}
        for p in self.parameters:
            err = self.errors[p.name]
            for k, v in (("value", p.value), ("std_error", err), ("relative_error", err / p.value),
                         ("unit", p.unit), ("vary", p.vary), ("at_bound", p.at_bound), ("min", p.min),
                         ("max", p.max), ("identifiable", p.identifiable), ("expr", p.expr)):
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
            if p.expr:
                line += " == '{}'".format(p.expr)
                if _has_error(p):
                    line += " +/- {:.6g} ({:.2f}%)".format(p.std_error, 100.0 * p.std_error / p.value)
            elif not p.vary:
                line += " (fixed)"
            elif p.at_bound:
                line += " (at its bound {} = {:g})".format(p.at_bound, p.min if p.at_bound == "min" else p.max)
            elif p.identifiable:
                line += " +/- {:.6g} ({:.2f}%)".format(p.std_error, 100.0 * p.std_error / p.value)
            else:
                line += " (not identifiable: {})".format(p.reason)
            line += " [{}]".format(p.unit)
            if p.vary and not p.expr and (p.min > 0 or _math.isfinite(p.max)):
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


def _has_error(p):
    """A parameter has a standard error when it varies (or is given by an expression), is not on a
    bound and is identifiable; the others' errors are NaN in Python (0 in the library and the JSON)."""
    return (p.vary or bool(p.expr)) and not p.at_bound and p.identifiable


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


_SETTING_KEYS = ("value", "vary", "min", "max", "expr")


def _settings(params):
    """params= as {name: {"value", "vary", "min", "max", "expr"}} for the library (fit::ParameterSetting).

    Each entry: a number (the initial value), a dict with any of value, vary, min, max, expr, or
    an object with value, vary, min, max (and expr) attributes (an lmfit.Parameter; an
    lmfit.Parameters is a dict of them). min -inf or None means no bound beyond positivity (0),
    max None means +inf. A parameter with an expr is given by it: as lmfit does, its value and
    vary are not used (lmfit sets them itself); bounds on it are refused by the library."""
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
        elif all(hasattr(spec, k) for k in _SETTING_KEYS[:4]):
            spec = {k: getattr(spec, k, None) for k in _SETTING_KEYS}
        else:
            raise Error("fit: params['{}'] must be a number (initial value), a dict with value, vary, min, "
                        "max, or an lmfit.Parameter; got {!r}".format(name, spec))
        lo = spec.get("min")
        hi = spec.get("max")
        value = spec.get("value")
        expr = spec.get("expr")
        if expr is not None and not isinstance(expr, str):
            raise Error("fit: params['{}']: expr must be a text, e.g. '12*E2'; got {!r}".format(name, expr))
        if expr:  # lmfit fills in value and vary = False for a constrained parameter: not settings
            value = None
        out[str(name)] = {
            "value": None if value is None else float(value),
            "vary": True if expr else bool(spec.get("vary", True)),
            "min": 0.0 if lo is None or lo == -_math.inf else float(lo),
            "max": _math.inf if hi is None else float(hi),
            "expr": expr or None,
        }
    return out


def _three_labels(text, name, what):
    """'A, B, C' -> [A, B, C], as the command line's --units and --scene-units read them."""
    items = [x.strip(" \t") for x in str(text).split(",")]
    if len(items) != 3 or not all(items):
        raise Error("{} '{}': expected three units {}".format(name, text, what))
    return items


def fit(law_name, data, t=None, stress=None, *, params=None, sigma=None, weights=None, absolute_sigma=False,
        time_column="t", displacement_column="displacement", stress_column=None, sigma_column=None,
        restarts=4, max_iterations=500, units=None):
    """Fits one registered law (``rheodda fit DATA --law LAW``).

    ``data``: a CSV path (columns as in docs/guide/fitting.md; ``stress`` or
    ``stress_column`` gives the shear stress [stress]), a :class:`CreepData`,
    or an array of displacements [length] with ``t=`` times [time] and
    ``stress=`` (a number, 'T:V[,T:V...]' or (t, value) pairs [stress]).

    ``params``: per parameter an initial value, or a dict (or lmfit.Parameter)
    with ``value``, ``vary`` (False: held at value, ``--fix``), ``min``,
    ``max`` (bounds, ``--bounds``), ``expr`` (the parameter is this expression of the
    others, e.g. '12*E2': + - * / ^ or **, parentheses, numbers, names; lmfit's expr,
    ``--expr``), in the parameter's registry unit. ``max_iterations``: per start
    (``--max-iterations``); a fit that stops before the optimality conditions hold says
    ``converged = False`` with a warning.
    ``sigma``: each point's measurement standard deviation [length] (or
    ``weights`` = 1/sigma [1/length], as lmfit's; or ``sigma_column`` of the
    CSV, ``--sigma-column``): the fit minimizes sum ((model - data)/sigma)^2.
    ``absolute_sigma``: standard errors from sigma as absolute errors
    (``--absolute-sigma``); by default they are scaled by sqrt(reduced
    chi-square) as lmfit's. ``units``: the data's units 'STRESS, LENGTH, TIME' (e.g.
    'MPa, mm, h', ``--units``): the result's ``units`` and ``yaml`` spell them, and
    :meth:`FitResult.scene_yaml` writes the law in a scene's units. Returns a :class:`FitResult`.
    """
    d = _creep_data(data, t, stress, time_column, displacement_column, stress_column, sigma, weights,
                    sigma_column)
    settings = _settings(params)
    call = (restarts, max_iterations, settings, not absolute_sigma)
    return FitResult(_rheodda._fit_law(law_name, d, restarts, max_iterations, settings, not absolute_sigma), d,
                     call, units)


def fit_all(data, t=None, stress=None, *, rank_by="bic", params=None, sigma=None, weights=None,
            absolute_sigma=False, time_column="t", displacement_column="displacement", stress_column=None,
            sigma_column=None, restarts=4, max_iterations=500, units=None):
    """Fits every law and ranks them best first by ``rank_by`` ('bic' or 'aic'),
    as ``rheodda fit DATA --law all``; the other arguments as :func:`fit`
    (``params`` apply to every law; a law without one of the named parameters
    is skipped). Returns (results, skipped): skipped lists "law: reason" for
    laws that cannot be fitted."""
    d = _creep_data(data, t, stress, time_column, displacement_column, stress_column, sigma, weights,
                    sigma_column)
    settings = _settings(params)
    results, skipped = _rheodda._fit_all(d, rank_by, restarts, max_iterations, settings, not absolute_sigma)
    call = (restarts, max_iterations, settings, not absolute_sigma)
    return [FitResult(r, d, call, units) for r in results], list(skipped)


def model_weights(results, criterion="aic"):
    """The weight of evidence for each of ``results`` (as :func:`fit_all` returns), in their
    order: w_i = exp(-Delta_i/2) / sum_j exp(-Delta_j/2), Delta_i the law's ``criterion``
    ('aic' or 'bic') minus the lowest. On AIC these are the Akaike weights (Burnham & Anderson
    2002, Model Selection and Multimodel Inference, ch. 2); they sum to 1 [-]. As
    `rheodda fit --law all`'s verdict (docs/guide/fitting.md, "The verdict")."""
    if criterion not in ("aic", "bic"):
        raise Error("model_weights: criterion '{}' is not one of aic, bic".format(criterion))
    return _np.asarray(_rheodda._model_weights([getattr(r, criterion) for r in results]))


def ranking_frame(results):
    """A list of :class:`FitResult` (as :func:`fit_all` returns) as a pandas DataFrame, one row per
    law in the given order: law, k (varying), points, rmse [length], r2, chi_square, aic, bic,
    akaike_weight, bic_weight (:func:`model_weights`), unidentified (the parameters the data do not
    determine, comma-separated)."""
    cols = {k: [] for k in ("law", "k", "points", "rmse", "r2", "chi_square", "aic", "bic", "akaike_weight",
                            "bic_weight", "unidentified")}
    wa, wb = model_weights(results, "aic"), model_weights(results, "bic")
    for i, r in enumerate(results):
        for k, v in (("law", r.law), ("k", r.varying), ("points", r.points), ("rmse", r.rmse), ("r2", r.r2),
                     ("chi_square", r.chi_square), ("aic", r.aic), ("bic", r.bic), ("akaike_weight", wa[i]),
                     ("bic_weight", wb[i]), ("unidentified", ", ".join(r.unidentified))):
            cols[k].append(v)
    return to_dataframe(cols)
