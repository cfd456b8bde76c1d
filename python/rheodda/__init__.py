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
    "CreepData", "read_creep_csv", "creep_data", "FitResult", "FitParameter", "FixedCombination", "fit", "fit_all",
    "ranking_frame", "model_weights",
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


# Outputs as DataFrames (_frames.py) and fitting (_fitting.py), re-exported here.
from ._frames import to_dataframe  # noqa: E402,F401  (re-exported API)
from ._fitting import FitParameter, FitResult, fit, fit_all, model_weights, ranking_frame  # noqa: E402,F401  (re-exported API)


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
        shortened to land on it. Raises Error when ``until`` is not a number or lies before the
        simulation's time (a run goes forward only; restore a saved state to go back)."""
        if until is None:
            end = self.duration
        else:
            end = float(until)
            if _math.isnan(end):
                raise Error("Simulation.run: until = nan is not a time")
            if end < self.time - 1e-12 * max(1.0, abs(end)):  # the sliver rule of Engine::run_until
                raise Error("Simulation.run: until = {:g} {} lies before the simulation's time {:g} {}: a run goes "
                            "forward only (restore a saved state to go back)".format(
                                end, self.units["time"], self.time, self.units["time"]))
        self._run(end, -1)
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

    in_stage = property(lambda self: self._sim.in_stage,
                        doc="True while the run is in a dynamic stage (the next step is dynamic; "
                            "docs/reference/engine.md, \"Dynamic stages\")")

    def stable_cycle(self):
        """The explicit step's cycle on the current state and the block that sets it, as
        ``rheodda check`` gives it for the initial state: ``(cycle [time], block index)``,
        ``(inf, -1)`` where nothing stiff holds a block (docs/reference/explicit-step.md,
        "The cycle"). The true masses, whatever the stage."""
        return self._sim._stable_cycle()

    def block_cycles(self):
        """Each block's explicit cycle on the current state, shape (blocks,) [time]: the
        cycle each block alone would allow, found as :meth:`stable_cycle` finds the scene's;
        ``inf`` for a block held, removed or touching nothing. Its minimum is
        ``stable_cycle()[0]``. Tells the few small blocks that set a rock mass's cycle from the
        rest (docs/reference/explicit-step.md, "Small blocks")."""
        return self._sim._block_cycles()

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
        .shear_force, energy terms), at full precision: a row after every accepted step,
        whatever the scene's analysis.history (a script steps the run itself and keeps
        what it needs; history.csv of `rheodda run` and rheodda.run follows the key)."""
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
        """Step settings by their scene names (``analysis.*``): the engine's declared settings
        that may change between steps, the keys of :attr:`settings`: numbers, integers and
        flags as such (``dt=0.001``), choices by their words (``solver="amg"``)."""
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
