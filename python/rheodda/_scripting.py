"""The scripting objects of :class:`rheodda.Simulation` (docs/guide/python.md, "Scripting"):
blocks, joint sets, contacts, bolts, loads added between steps, periodic callbacks and
saved states. Every value is in the scene's units (``sim.units``); every array is a
read-only copy of the state when it was read (a write raises instead of being lost).
"""

import math as _math
import operator as _operator
import os as _os

from . import _rheodda
from ._rheodda import Error


def _make_law(name, parameters):
    """A built-in law made again by its name and parameters (Law.__reduce__: pickle, copy)."""
    return _rheodda.law(name, parameters)


def _make_scene(text, file):
    """A scene parsed again from its text and file name (Scene.__reduce__: pickle, copy)."""
    return _rheodda.parse_scene(text, file)


def _index(value, names, what):
    """The index of ``value`` (an int, a numpy integer or a name) among ``names``."""
    if isinstance(value, str):
        if value not in names:
            raise Error("{} '{}' is not in the scene; {}s: {}".format(what, value, what, ", ".join(names)))
        return names.index(value)
    try:
        i = _operator.index(value)
    except TypeError:
        raise TypeError("a {} is given by its index (int) or its name (str), not {!r}".format(what, value)) from None
    if i < 0:
        i += len(names)
    if not 0 <= i < len(names):
        raise IndexError("{} {} does not exist; the scene has {} {}s".format(what, value, len(names), what))
    return i


# --- blocks ---------------------------------------------------------------------

class Block:
    """One block of a simulation: ``sim.blocks[i]`` or ``sim.blocks['name']``.

    Its attributes read the state now (each read a new value): ``position``
    (alias ``centroid``) the centroid (x, y) [length]; ``rotation`` the rotation
    since t = 0 [rad], counter-clockwise positive (the polar decomposition of
    the block's affine map); ``velocity`` (u0, v0, r0, ex, ey, gxy) rates
    [length/time, 1/time] (zero in a static analysis); ``strain`` the
    Green-Lagrange strain since t = 0 (E_xx, E_yy, gamma_xy) [-]; ``stress``
    (sigma_x, sigma_y, tau_xy) [stress], tension positive; ``area`` [length^2];
    ``mass`` density x area per unit thickness [mass = force time^2/length];
    ``fixed`` (it holds a fixed point), ``removed``; ``vertices`` (n, 2)
    [length]. Its methods change the model from the next step on (Engine::edit,
    as a scene's stage): :meth:`fix`, :meth:`free`, :meth:`remove`,
    :meth:`add_load`.
    """

    __slots__ = ("_sim", "index")

    def __init__(self, sim, index):
        self._sim = sim
        self.index = index  #: the block's index in scene order (rows of the Blocks views)

    @property
    def name(self):
        """The block's name in the scene (``blocks[*].name``, or ``block<i>``)."""
        return self._sim._sim.block_names[self.index]

    def _get(self, quantity):
        return self._sim._sim._block_value(self.index, quantity)

    position = property(lambda self: self._get("position"), doc="centroid (x, y) [length]")
    centroid = property(lambda self: self._get("position"), doc="centroid (x, y) [length]; = position")
    rotation = property(lambda self: self._get("rotation"),
                        doc="rotation since t = 0 [rad], counter-clockwise > 0")
    def _set_velocity(self, value):
        self._sim._sim._set_velocity(self.index, [float(v) for v in value])

    velocity = property(lambda self: self._get("velocity"), _set_velocity,
                        doc="(u0, v0, r0, ex, ey, gxy) rates [length/time, 1/time]; settable between steps in a "
                            "dynamic analysis as (vx, vy, omega) (strain rates 0) or all six (Engine::edit; the "
                            "kinetic energy it adds is booked as -dissipation_edits)")
    strain = property(lambda self: self._get("strain"),
                      doc="Green-Lagrange strain since t = 0 (E_xx, E_yy, gamma_xy) [-]")
    stress = property(lambda self: self._get("stress"), doc="(sigma_x, sigma_y, tau_xy) [stress]")
    area = property(lambda self: self._get("area"), doc="current area [length^2]")
    mass = property(lambda self: self._get("mass"), doc="density x area [mass = force time^2/length]")
    fixed = property(lambda self: self._get("fixed"), doc="True while a fixed point holds the block")
    removed = property(lambda self: self._get("removed"), doc="True once the block was removed")

    @property
    def vertices(self):
        """Current vertices, counter-clockwise, shape (n, 2) [length]."""
        return self._sim._sim.block_vertices(self.index)

    def point_displacement(self, x, y):
        """Displacement (u, v) of the material point initially at (x, y) [length]."""
        return self._sim._sim.point_displacement(self.index, float(x), float(y))

    def fix(self, dofs=("x", "y", "rotation")):
        """Holds the block from the next step on in ``dofs`` (some of ``"x"``, ``"y"``, ``"rotation"``).
        All three (the default), as a scene's ``fixed: true``: a fixed point at every vertex, where it
        stands now. Otherwise one fixed point at the centroid, held in the directions given (as a scene's
        ``hold: x`` or ``hold: y``) and, with ``"rotation"``, the block's rotation held where it is now by
        a rotational spring p J/S [force length/rad] (as ``hold: rotation``; ``["rotation"]`` alone: the
        block moves freely without turning, ``["x", "rotation"]``: free in y only); without it the block
        turns freely about the point. A moving block stops in what is held (its kinetic energy there, a
        spin's I omega^2/2, booked as ``dissipation_edits``). Raises Error for an empty or unknown dofs,
        ModelError for a removed block."""
        if isinstance(dofs, str):
            dofs = (dofs,)
        self._sim._sim._fix(self.index, [str(d) for d in dofs])

    def free(self):
        """Removes every fixed point on the block (those of ``fixed: true``, of ``fixed_points:`` and of
        :meth:`fix`); the block starts from rest in the directions they held. Raises Error when it has none,
        ModelError when the model would keep no fixed point."""
        self._sim._sim._free(self.index)

    def remove(self):
        """Removes the block (excavation, as a stage's ``remove_blocks``): no contacts, no gravity, its
        fixed points and loads go with it. Raises ModelError for the last block or one removed before."""
        self._sim._sim._remove(self.index)

    def add_load(self, point, force=None, history=None):
        """Adds a point load on the material point standing at ``point`` (x, y) now [length]: a constant
        ``force`` (fx, fy) [force], or a ``history`` of (t [time] counted from now, fx, fy [force]) rows,
        piecewise linear as a scene's load. Returns the :class:`Load` (``.remove()``). Raises ModelError
        when the point lies outside the block where it stands now."""
        if (force is None) == (history is None):
            raise Error("Block.add_load: give force=(fx, fy) or history=[(t, fx, fy), ...], one of them")
        if force is not None:
            fx, fy = force
            samples = [(0.0, float(fx), float(fy))]
        else:
            samples = [tuple(float(v) for v in row) for row in history]
            if any(len(row) != 3 for row in samples):
                raise Error("Block.add_load: each history row is (t [time], fx, fy [force])")
        x, y = point
        load_id = self._sim._sim._add_load(self.index, float(x), float(y), samples)
        return Load(self._sim, load_id, self.index)

    def __eq__(self, other):
        return isinstance(other, Block) and other._sim is self._sim and other.index == self.index

    def __hash__(self):
        return hash((id(self._sim), self.index))

    def __repr__(self):
        x, y = self.position
        state = ", removed" if self.removed else (", fixed" if self.fixed else "")
        return "<Block {} '{}' at ({:.6g}, {:.6g}) {}{}>".format(
            self.index, self.name, x, y, self._sim.units["length"], state)


class _Collection:
    """Named items of a simulation in scene order (Blocks, JointSets): ``len``, indexing by index
    (numpy integers too) or name, iteration, ``names``."""

    __slots__ = ("_sim",)
    _item, _names, _what = None, "", ""

    def __init__(self, sim):
        self._sim = sim

    @property
    def names(self):
        """The names, in scene order."""
        return list(getattr(self._sim._sim, self._names))

    def __len__(self):
        return len(getattr(self._sim._sim, self._names))

    def __getitem__(self, key):
        return self._item(self._sim, _index(key, getattr(self._sim._sim, self._names), self._what))

    def __iter__(self):
        return (self._item(self._sim, i) for i in range(len(self)))


class Blocks(_Collection):
    """The blocks of a simulation, in scene order: ``len``, indexing by index or name, iteration
    (:class:`Block` objects), ``names``, and read-only numpy views of every block at once:
    ``position`` (alias ``centroid``, (n, 2) [length]), ``rotation`` ((n,) [rad]), ``velocity``
    ((n, 6) [length/time, 1/time]), ``strain`` ((n, 3) [-]), ``stress`` ((n, 3) [stress]),
    ``area`` ((n,) [length^2]), ``mass`` ((n,) [mass]), ``fixed`` and ``removed`` ((n,) bool)."""

    __slots__ = ()
    _item, _names, _what = Block, "block_names", "block"

    def _column(self, quantity):
        return self._sim._sim._block_column(quantity)

    position = property(lambda self: self._column("position"), doc="centroids, (n, 2) [length]")
    centroid = property(lambda self: self._column("position"), doc="centroids, (n, 2) [length]; = position")
    rotation = property(lambda self: self._column("rotation"), doc="rotations since t = 0, (n,) [rad]")
    velocity = property(lambda self: self._column("velocity"),
                        doc="(u0, v0, r0, ex, ey, gxy) rates, (n, 6) [length/time, 1/time]")
    strain = property(lambda self: self._column("strain"),
                      doc="Green-Lagrange strains since t = 0 (E_xx, E_yy, gamma_xy), (n, 3) [-]")
    stress = property(lambda self: self._column("stress"), doc="(sigma_x, sigma_y, tau_xy), (n, 3) [stress]")
    area = property(lambda self: self._column("area"), doc="areas, (n,) [length^2]")
    mass = property(lambda self: self._column("mass"), doc="masses, (n,) [mass = force time^2/length]")
    fixed = property(lambda self: self._column("fixed"), doc="held by a fixed point, (n,) bool")
    removed = property(lambda self: self._column("removed"), doc="removed, (n,) bool")

    def __repr__(self):
        removed = int(self.removed.sum())
        return "<Blocks: {} blocks{}>".format(len(self), ", {} removed".format(removed) if removed else "")


class Load:
    """A point load added between steps (:meth:`Block.add_load`), or one of the model's loads
    (``sim.load(i)``): ``id`` (scene loads 0..n-1, added ones after), ``block`` (index),
    ``index`` (its index in ``sim.loads`` now, None once removed), :meth:`remove`."""

    __slots__ = ("_sim", "id", "block")

    def __init__(self, sim, load_id, block):
        self._sim = sim
        self.id = load_id
        self.block = block

    @property
    def index(self):
        """Its index in ``sim.loads`` now (the argument of ``set_load``), or None once removed."""
        ids = list(self._sim._sim._load_ids)
        return ids.index(self.id) if self.id in ids else None

    @property
    def removed(self):
        """True once the load was removed (by :meth:`remove` or with its block)."""
        return self.index is None

    def remove(self):
        """Removes the load from the next step on. Raises Error when it is gone already."""
        self._sim._sim._remove_load(self.id)

    def __repr__(self):
        return "<Load {} on block {}{}>".format(self.id, self.block, ", removed" if self.removed else "")


# --- joint sets -----------------------------------------------------------------

def _joint_set_value(key, doc, settable=True):
    def get(self):
        return self._values()[key]

    def set_(self, value):
        self.set(**{key: value})

    return property(get, set_ if settable else None, doc=doc)


class JointSet:
    """One joint set: ``sim.joint_sets['name']`` or ``sim.joint_sets[i]``. Its values are the contact
    system's now, by the scene file's keys: one attribute per property the contact layer
    declares (contact/joint_set_specs.hpp: ``friction_angle``, ``cohesion``, ...; each
    attribute's doc is its declaration's meaning, unit, range and default; None while an
    optional one is unset). Those the declarations let change between steps (the strengths) are
    settable (from the next step on, as a stage's ``joint_sets:``; checked as the
    loader checks them, refused with its key and message as ModelError); the others are
    read-only. ``law`` is the law's name (None: no law) and ``law_parameters`` its parameters
    [their registry units], settable as a dict of the parameters to change (the others kept; as
    ``sim.set_law_parameters``)."""

    __slots__ = ("_sim", "index")

    def __init__(self, sim, index):
        self._sim = sim
        self.index = index  #: the joint set's index in scene order (contacts' ``joint_set`` column)

    def _values(self):
        return self._sim._sim._joint_set(self.index)

    @property
    def name(self):
        """The joint set's name in the scene."""
        return self._sim._sim.joint_set_names[self.index]

    law = _joint_set_value("law", "the law's registry name, or None", settable=False)

    @property
    def law_parameters(self):
        """The law's parameters by name [their registry units] (a copy); assign a dict of the
        parameters to change (the others kept)."""
        return self._values()["law_parameters"]

    @law_parameters.setter
    def law_parameters(self, values):
        self._sim.set_law_parameters(self.name, dict(values))

    def set(self, **values):
        """Changes several values at once by their scene keys (the settable properties, e.g.
        friction_angle, cohesion) from the next step on; checked together as a stage's
        ``joint_sets: {NAME: {...}}`` (ModelError with the loader's key and message)."""
        self._sim._sim._change_joint_set(self.index, values)

    def __repr__(self):
        v = self._values()
        law = " law {} {}".format(v["law"], v["law_parameters"]) if v["law"] else ""
        return "<JointSet {} '{}': friction_angle {:g} deg, cohesion {:g}, tensile_strength {:g} {}{}>".format(
            self.index, v["name"], v["friction_angle"], v["cohesion"], v["tensile_strength"],
            self._sim.units["stress"], law)


def _joint_set_property(p):
    """The property of :class:`JointSet` that the declaration ``p`` describes (contact/joint_set_specs.hpp,
    ``_Simulation._joint_set_properties()``): its doc the declaration's meaning, unit, range and
    default; settable when it may change between steps."""
    unit = "" if p["unit"] == "\u2013" else " [{}]".format(p["unit"])
    doc = "{}{}; in {}; default {}{}".format(p["meaning"], unit, p["range"], p["default"],
                                             "" if p["between_steps"] else "; read-only (None: unset)")
    return _joint_set_value(p["name"], doc, settable=p["between_steps"])


for _p in _rheodda._Simulation._joint_set_properties():
    setattr(JointSet, _p["name"], _joint_set_property(_p))
del _p


class JointSets(_Collection):
    """The joint sets of a simulation, in scene order: ``len``, indexing by index or name,
    iteration (:class:`JointSet` objects), ``names``."""

    __slots__ = ()
    _item, _names, _what = JointSet, "joint_set_names", "joint set"

    def __repr__(self):
        return "<JointSets: {}>".format(", ".join(self.names))


# --- tables: contacts, bolts -----------------------------------------------------

class Table:
    """Columns of equal length as read-only numpy arrays, read when the table was made: ``len``
    is the number of rows; ``table['x']`` or ``table.x`` a column; ``columns``, ``keys()``,
    ``items()``; ``table()`` the columns as a dict (what ``sim.contacts()`` returned)."""

    def __init__(self, columns, rows_of):
        self._columns = dict(columns)
        self._rows = len(self._columns[rows_of])

    @property
    def columns(self):
        """The column names."""
        return list(self._columns)

    def keys(self):
        """The column names (as dict.keys)."""
        return self._columns.keys()

    def values(self):
        """The columns (as dict.values)."""
        return self._columns.values()

    def items(self):
        """(name, column) pairs (as dict.items): ``to_dataframe(table)`` takes the table."""
        return self._columns.items()

    def __getitem__(self, column):
        try:
            return self._columns[column]
        except KeyError:
            raise KeyError("no column '{}'; columns: {}".format(column, ", ".join(self._columns))) from None

    def __getattr__(self, column):
        columns = self.__dict__.get("_columns", {})
        if column in columns:
            return columns[column]
        raise AttributeError("no column '{}'; columns: {}".format(column, ", ".join(columns)))

    def __contains__(self, column):
        return column in self._columns

    def __iter__(self):
        return iter(self._columns)

    def __len__(self):
        return self._rows

    def __call__(self):
        return dict(self._columns)


class Contacts(Table):
    """The contacts after the last accepted step (``sim.contacts``), one row per contact: ``id``,
    ``joint_set`` (index into ``sim.joint_sets``), ``state`` (open, sliding, locked), ``kind``,
    ``vertex_block``, ``vertex``, ``edge_block``, ``edge``, ``x``, ``y`` [length],
    ``normal_force``, ``shear_force``, ``shear_strength`` [force/length], ``shear_displacement``,
    ``penetration``, ``length``, ``tributary_length``, ``creep_displacement``, ``creep_increment``
    [length], ``q`` (n, 4) [length]: the
    columns of contacts.csv plus the law state. ``sim.contacts()`` gives them as a dict."""

    def __init__(self, columns):
        Table.__init__(self, columns, "id")

    def __repr__(self):
        return "<Contacts: {} contacts>".format(len(self))


class Bolts(Table):
    """The bolts after the last accepted step (``sim.bolts``), one row per bolt as bolts.csv:
    ``name``, ``state`` (elastic, yielding, ruptured), ``force`` [force] (tension > 0),
    ``length``, ``elongation``, ``plastic_elongation``, ``creep_elongation`` [length],
    ``rupture_time`` [time] (-1 while intact). Read-only."""

    def __init__(self, columns):
        Table.__init__(self, columns, "name")

    def __repr__(self):
        return "<Bolts: {} bolts>".format(len(self))


# --- callbacks with a period ------------------------------------------------------

class Callback:
    """A function called after accepted steps, as f(sim, report) (:meth:`Simulation.add_callback`):
    every ``steps`` accepted steps, or after the first step that reaches each multiple of ``time``
    [time] counted from when it was added (as YADE's PyRunner iterPeriod / virtPeriod). The steps
    are never shortened to land on those times: a callback does not change the run.
    :meth:`remove` stops it."""

    __slots__ = ("function", "steps", "time", "_sim", "_start_step", "_start_time", "_k")

    def __init__(self, sim, function, steps=None, time=None):
        if not callable(function):
            raise TypeError("a callback is a function f(sim, report); got {!r}".format(function))
        if steps is not None and time is not None:
            raise Error("a callback runs every steps=N accepted steps or every time=dt [time], not both")
        if steps is not None:
            if isinstance(steps, bool) or _operator.index(steps) < 1:
                raise Error("callback steps={!r}: a whole number of steps >= 1".format(steps))
            steps = _operator.index(steps)
        if time is not None:
            time = float(time)
            if not (_math.isfinite(time) and time > 0):
                raise Error("callback time={!r}: a positive finite period [time]".format(time))
        self.function = function
        self.steps = steps if time is None else None
        if self.steps is None and time is None:
            self.steps = 1
        self.time = time
        self._sim = sim
        self._start_step = sim.step_count
        self._start_time = sim.time
        self._k = 1

    def _due(self, report):
        if self.steps is not None:
            return (report.step + 1 - self._start_step) % self.steps == 0
        due = False
        while True:
            t = self._start_time + self._k * self.time
            if report.time < t - 1e-12 * max(1.0, abs(t)):  # the sliver rule of Engine::run_until
                return due
            self._k += 1
            due = True

    def remove(self):
        """Stops calling the function."""
        if self in self._sim._callbacks:
            self._sim._callbacks.remove(self)

    def __getstate__(self):
        return {k: getattr(self, k) for k in self.__slots__ if k != "_sim"}

    def __setstate__(self, state):
        for k, v in state.items():
            setattr(self, k, v)

    def __repr__(self):
        period = "every {} steps".format(self.steps) if self.steps else "every {:g} [time]".format(self.time)
        return "<Callback {} {}>".format(getattr(self.function, "__name__", repr(self.function)), period)


# --- saved states -------------------------------------------------------------------

class SimulationState:
    """A simulation saved between two steps (:meth:`Simulation.save`): ``data`` the bytes (a JSON
    header with the scene, the laws given, every change made and the history, then the engine
    and contact state bit for bit, the format of a checkpoint's state file), ``laws`` the laws
    written in Python it was built with (objects; empty for built-in laws). Picklable (the bytes
    and those laws); :meth:`write` puts it in a file; ``Simulation.restore(state)`` continues it.
    ``time`` [time] and ``step_count`` say where it stands."""

    __slots__ = ("data", "laws", "time", "step_count")

    def __init__(self, data, laws=None, time=0.0, step_count=0):
        self.data = bytes(data)
        self.laws = dict(laws or {})
        self.time = time
        self.step_count = step_count

    def __getstate__(self):
        return {k: getattr(self, k) for k in self.__slots__}

    def __setstate__(self, state):
        for k, v in state.items():
            setattr(self, k, v)

    def write(self, path):
        """Writes the bytes to ``path`` (read back by ``Simulation.restore(path)``). Raises Error
        when the simulation has laws written in Python, which a file cannot hold."""
        if self.laws:
            raise Error("the simulation has laws written in Python (joint sets {}), which a file cannot hold; "
                        "keep the state in memory or pickle it with the laws".format(", ".join(sorted(self.laws))))
        tmp = _os.fspath(path) + ".tmp"
        with open(tmp, "wb") as f:
            f.write(self.data)
        _os.replace(tmp, path)

    def __repr__(self):
        return "<SimulationState at t = {:g}, {} steps, {} bytes>".format(self.time, self.step_count, len(self.data))
