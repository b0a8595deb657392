"""Simulation and its array context (the Python side of _drumlab._Simulation and _Arrays)."""
import numpy as np
from numpy.lib.mixins import NDArrayOperatorsMixin

from . import _drumlab

_ARRAYS = ("position", "velocity", "omega", "force", "radius", "mass", "id", "size_class", "film")


class View(NDArrayOperatorsMixin):
    """A read-only, zero-copy view of one particle array, valid inside its `with` block only.

    Inside the block it acts as a numpy array (indexing, arithmetic and numpy functions give
    new arrays); after the block every use raises RuntimeError, since stepping moves and
    re-orders the engine's memory. np.array(view) copies; np.asarray(view) does not, and is
    then the caller's to drop before the block ends.
    """

    __slots__ = ("_arrays", "_name", "_array")

    def __init__(self, arrays, name, array):
        self._arrays, self._name, self._array = arrays, name, array

    def _checked(self):
        if not self._arrays._open:
            raise RuntimeError(
                f"arrays.{self._name}: used outside its `with sim.arrays()` block "
                "(the memory may have moved)")
        return self._array

    def __array__(self, dtype=None, copy=None):
        a = self._checked()
        return a if dtype is None else a.astype(dtype)

    def __array_ufunc__(self, ufunc, method, *inputs, **kwargs):
        inputs = tuple(x._checked() if isinstance(x, View) else x for x in inputs)
        return getattr(ufunc, method)(*inputs, **kwargs)

    def __array_function__(self, func, types, args, kwargs):
        def unwrap(x):
            if isinstance(x, View):
                return x._checked()
            if isinstance(x, (list, tuple)):
                return type(x)(unwrap(e) for e in x)
            return x
        return func(*unwrap(args), **{k: unwrap(v) for k, v in kwargs.items()})

    def __getitem__(self, index):
        return np.array(self._checked()[index])

    def __setitem__(self, index, value):
        raise TypeError(f"arrays.{self._name} is read-only: use the Simulation's setters "
                        "(set_velocity) to change the state")

    def __len__(self):
        return len(self._checked())

    def __iter__(self):
        return iter(np.array(self._checked()))

    @property
    def shape(self):
        return self._checked().shape

    @property
    def dtype(self):
        return self._checked().dtype

    def __getattr__(self, name):  # mean(), sum(), T, ...
        return getattr(self._checked(), name)

    def __repr__(self):
        if not self._arrays._open:
            return f"<drumlab.View {self._name}: closed>"
        return f"View({self._name}, {self._array!r})"


class Arrays:
    """`with sim.arrays() as a:` the particle arrays as Views (storage order; `a.id` gives each
    row's stable id): position, velocity, omega, force, radius, mass, id, size_class, and film
    (liquid films, scenes with migration). Stepping is refused while the block is open."""

    def __init__(self, native):
        self._native = native
        self._open = False
        self._views = {}

    def __enter__(self):
        self._native._enter()
        self._open = True
        return self

    def __exit__(self, *exc):
        self._open = False
        for view in self._views.values():
            view._array = None  # the Views keep no pointer into the engine once closed
        self._views.clear()
        self._native._exit()
        return False

    def __getattr__(self, name):
        if name.startswith("_") or name not in _ARRAYS:
            raise AttributeError(f"arrays: no array '{name}' (arrays: {', '.join(_ARRAYS)})")
        if not self._open:
            raise RuntimeError(f"arrays.{name}: used outside its `with sim.arrays()` block "
                               "(the memory may have moved)")
        if name not in self._views:
            self._views[name] = View(self, name, self._native._get(name))
        return self._views[name]


class Simulation(_drumlab._Simulation):
    """A run of a scene, as `drumlab run` runs it (the same fill, settling and steps: the same
    bits). Simulation(scene, method="", threads=0, dt_factor=0): method replaces the scene's
    search ("auto" too), threads > 0 sets the OpenMP threads, dt_factor > 0 the time step.

    settle(): the settling phase with the drum at rest (run() does it first if needed).
    run(steps=None, revolutions=None, callback=None, every=100): turns the drum for `steps`,
    `revolutions` or the scene's own length; callback(sim) runs every `every` steps and stops
    the run by returning False; its exception stops the run and propagates. The GIL is released
    while stepping; Ctrl-C stops cleanly between two steps (KeyboardInterrupt).
    arrays(): the context of the particle arrays (Arrays).
    observables(), agglomerates(criterion="age"|"components"|"community", age=-1,
    resolution=1), contacts(), diagnostics(): the analysis `drumlab run` writes, as dicts.
    checkpoint(path), write_vtu(path): the CLI's checkpoint; one VTU frame of the particles.
    set_velocity(ids, velocities): the one setter (by stable id, finite values).
    """

    def arrays(self):
        return Arrays(self._arrays())

    def write_vtu(self, path):
        _drumlab._write_vtu(self, str(path))

    def checkpoint(self, path):
        super().checkpoint(str(path))

    def __repr__(self):
        return (f"<drumlab.Simulation N={self.n} t={self.time:.4g} s steps={self.steps} "
                f"method={self.method}>")
