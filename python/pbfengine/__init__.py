"""pbfengine from Python: drive runs and read the particles as NumPy arrays without copying.

    import pbfengine
    sim = pbfengine.Simulation()
    sim.run_file("scenarios/dambreak.lua", steps=100)   # a Lua scenario, -v variables as keywords
    x, y, z = sim.field("position")                      # views of the engine's memory

or the scene built from Python, with the parameters Lua's tables take as keywords:

    sim.domain(lo=(0, 0, 0), hi=(1, 0.5, 0.5))
    sim.kernel_radius(0.04); sim.timestep(0.002)
    sim.lattice(lo=(0, 0, 0), hi=(0.3, 0.5, 0.5), spacing=0.02)
    sim.fix("solver", "pbf", iterations=4)
    sim.every("probe", 10, lambda step, time: print(step, sim.field("position").z.max()))
    sim.run(200)

docs/python.md is the guide: the API, when an array is valid, MPI.
"""
import os

# Threads that wait without taking the cores they share (engine/core/threads.hpp): set before
# the OpenMP runtime loads with the compiled module, unless the environment chose.
if not any(v in os.environ for v in ("OMP_WAIT_POLICY", "GOMP_SPINCOUNT", "KMP_BLOCKTIME", "PBF_WAITING")):
    os.environ.update(GOMP_SPINCOUNT="1000", KMP_BLOCKTIME="0", PBF_WAITING="pbfengine")

# Under an MPI launcher, mpi4py (where installed) starts MPI and ends it at exit; the engine
# joins it, so a program may use both.
if any(v in os.environ for v in ("OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_SIZE", "PMI_RANK")):
    try:
        from mpi4py import MPI as _MPI  # noqa: F401
    except ImportError:
        pass

from ._pbfengine import Engine as _Engine, Error, Interrupted, Motion, keyframes, rank, ranks, version, real
from ._views import StaleViewError, Components
from . import _views
from .readers import read_frame, read_vtu, read_pvd, read_thermo, frame_paths

__all__ = ["Simulation", "Error", "Interrupted", "StaleViewError", "Components", "Motion", "keyframes", "rank",
           "ranks", "version", "real", "read_frame", "read_vtu", "read_pvd", "read_thermo", "frame_paths"]


def _count(value, what):
    """An int that is not a bool (which Python would take as 0 or 1)."""
    if isinstance(value, bool) or not isinstance(value, int):
        raise TypeError(f"{what} must be an int, got {type(value).__name__} {value!r}")
    return value


def _number(value, what):
    """A number that is not a bool."""
    if isinstance(value, bool) or not isinstance(value, (int, float)) and not hasattr(value, "__float__"):
        raise TypeError(f"{what} must be a number, got {type(value).__name__} {value!r}")
    return float(value)


def _path(value, what):
    """A str or os.PathLike, not empty."""
    path = os.fspath(value)
    if isinstance(path, bytes):
        raise TypeError(f"{what} must be a str or a path, got bytes")
    if not path:
        raise Error(f"{what}: the path is empty" + ("; give None for no log" if what == "log" else ""))
    if "\0" in path:
        raise Error(f"{what}: the path {path!r} contains a zero byte")
    return path


class Simulation:
    """One simulation: its scene, pipeline and particles (the engine's Simulation).

    Simulation(threads=None, log="log.pbfengine", log_level="info", check_every_hook=False):
    threads as `pbfengine run --threads` (default: one per core this process may use); log a
    file that copies what the run prints, or None; check_every_hook as `pbfengine run
    --check-every-hook` (after every fix, look for non-finite values and name the fix).
    """

    def __init__(self, threads=None, log="log.pbfengine", log_level="info", check_every_hook=False):
        if threads is not None:
            _count(threads, "threads")
        if log is not None:
            log = _path(log, "log")
        self._engine_ = _Engine(threads, log, log_level, bool(check_every_hook))

    @property
    def _engine(self):
        engine = self.__dict__.get("_engine_")
        if engine is None:
            raise Error("this Simulation was not initialised: Simulation.__init__ was not called")
        return engine

    # --- Lua ---
    def run_file(self, path, **variables):
        """Runs a Lua scenario; keywords are its -v variables (restart="FILE" continues a run)."""
        self._engine.run_file(_path(path, "run_file"), variables)

    def lua(self, statements):
        """Runs Lua statements against this simulation (the pbf table of scenarios)."""
        if not isinstance(statements, str):
            raise TypeError(f"lua takes the statements as a str, got {type(statements).__name__}")
        self._engine.lua(statements)

    # --- the scene ---
    def domain(self, **params):
        """Sets the domain (lo=, hi=, periodic=) when given; returns it as a dict."""
        return self._engine.domain(**params)

    def kernel_radius(self, h=None):
        """Sets the kernel radius h (m) when given; returns it."""
        return self._engine.kernel_radius(None if h is None else _number(h, "kernel_radius"))

    def timestep(self, dt=None):
        """Sets the time step (s) when given; returns it."""
        return self._engine.timestep(None if dt is None else _number(dt, "timestep"))

    def rest_density(self, rho=None):
        """Sets the rest density (kg/m^3) when given; returns it."""
        return self._engine.rest_density(None if rho is None else _number(rho, "rest_density"))

    def lattice(self, **params):
        """Particles on a cubic lattice (pbf.lattice's parameters); returns how many were added."""
        return self._engine.lattice(**params)

    def delete(self, **region):
        """Removes the particles inside a region (pbf.delete's parameters); returns how many."""
        return self._engine.delete(**region)

    def read_scene(self, path):
        return self._engine.read_scene(_path(path, "read_scene"))

    def read_particles(self, path):
        return self._engine.read_particles(_path(path, "read_particles"))

    def write_restart(self, path):
        return self._engine.write_restart(_path(path, "write_restart"))

    def read_restart(self, path):
        return self._engine.read_restart(_path(path, "read_restart"))

    # --- the pipeline ---
    def fix(self, id, style, **params):
        """Adds the fix `id` of `style` with its parameters as keywords."""
        self._engine.fix(id, style, **params)

    def unfix(self, id):
        self._engine.unfix(id)

    def compute(self, id, style, **params):
        """Adds the compute `id` of `style` with its parameters as keywords."""
        self._engine.compute(id, style, **params)

    def uncompute(self, id):
        self._engine.uncompute(id)

    def value(self, id):
        """The compute's value: a float, a dict by name, or {"id": ids, "value": values}."""
        return self._engine.value(id)

    def thermo(self, every=100, columns=("step", "time"), csv=""):
        """Thermo lines every EVERY steps with these columns; csv names a file that keeps them
        (thermo_history() reads it back)."""
        if isinstance(columns, str):
            raise TypeError(f"thermo: columns is a list of names, got the str {columns!r}")
        self._thermo_csv = os.fspath(csv)
        self._engine.thermo(_count(every, "thermo: every"), list(columns), self._thermo_csv)

    def thermo_history(self):
        """The thermo CSV's columns so far as arrays (a thermo(csv=...) must name one)."""
        path = getattr(self, "_thermo_csv", "")
        if not path:
            raise Error("thermo_history: no thermo CSV; call thermo(every=..., columns=[...], csv=PATH) first")
        return read_thermo(path)

    def every(self, id, steps, function):
        """Calls function(step, time) at the end of every STEPS-th step of a run."""
        self._engine.every(id, _count(steps, "every: steps"), function)

    def run(self, steps):
        """Runs STEPS steps."""
        self._engine.run(_count(steps, "run: steps"))

    def run_until(self, time):
        """Runs until the time TIME (s)."""
        self._engine.run_until(_number(time, "run_until: time"))

    step = property(lambda self: self._engine.step, doc="the steps taken")
    time = property(lambda self: self._engine.time, doc="the simulated time (s)")
    count = property(lambda self: self._engine.count, doc="the particles of every rank")
    rank_count = property(lambda self: self._engine.rank_count, doc="this rank's particles")
    _epoch = property(lambda self: self._engine._epoch)

    def timing(self):
        """The last run's timing table: {"wall", "particle_steps_per_second", "rows"}."""
        return self._engine.timing()

    def outputs(self):
        """What the runs wrote, as the command line lists it at the end."""
        return self._engine.outputs()

    # --- the particle arrays ---
    def fields(self):
        """[(name, components, meaning)] of the fields there are now."""
        return self._engine.fields()

    def field(self, name, writable=False):
        """Views of the field NAME for this rank's particles, in memory order: one array for a
        field of one component, a Components (x, y, z) of arrays for a vector. Valid until the
        particles next move (a run, a scene command; inside a callback, until it returns);
        take a copy() to keep values. writable=True lets you set initial conditions."""
        components = self._components(name)
        arrays = [_views.wrap(self._engine._view(name, c, bool(writable)), self, name, c) for c in range(components)]
        return arrays[0] if components == 1 else Components(name, arrays)

    def ids(self):
        """The particles' ids (read-only view, in memory order: the order of field())."""
        return _views.wrap(self._engine._ids(), self, "id", None)

    def copy(self, name):
        """A copy of the field (N,) or (N, components) in memory order, to keep."""
        views = self.field(name)
        return views.copy()

    def gather(self, name):
        """Every rank's values of the field on rank 0, in id order: {"id": ids, NAME: values}
        (None on the other ranks; every rank must call it)."""
        return self._engine.gather(name)

    def _address(self, name, component):
        return self._engine._address(name, component)

    def _components(self, name):
        if not isinstance(name, str):
            raise TypeError(f"a field's name is a str, got {type(name).__name__}")
        for field_name, components, _ in self._engine.fields():
            if field_name == name:
                return components
        self._engine._view(name, 0, False)  # raises the engine's message (with "did you mean")
