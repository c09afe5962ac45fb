"""Views of the engine's particle arrays that refuse use once stale.

Each view is a NumPy array over the engine's memory (no copy), pinned so that the memory stays
(engine/core/field_array.hpp). The engine moves its arrays as it runs: it re-sorts the particles
every 20 steps, adds and removes them, frees fields no pipeline uses. A view taken before such a
change shows what the memory holds now, which is no longer that field of those particles, so a
view remembers the engine's count of such changes when it was taken and, once the count has
moved on, raises StaleViewError on any use: indexing, arithmetic, printing, copying.
(np.asarray(view) strips the check, and then reads the old memory, never freed memory.)
"""
import numpy as np

from ._pbfengine import Error


class StaleViewError(Error):
    """A view of particle data used after the particles moved in memory."""


class FieldView(np.ndarray):
    """One component of one particle field, over the engine's memory."""

    def __array_finalize__(self, obj):
        self._pbf = getattr(obj, "_pbf", None)

    def _check(self):
        token = self._pbf
        if token is not None and token[0]._epoch != token[1]:
            engine, _, name, component, step = token
            what = name if component is None else f"{name}[{component}]"
            again = "ids()" if name == "id" else f"field('{name}')"
            raise StaleViewError(
                f"this view of '{what}' was taken at step {step} and the particles have moved in memory since "
                f"(a run, a sort, particles added or removed): take a new one with {again} "
                f"(now at step {engine.step}), or keep values with .copy()")

    def _plain(self):
        self._check()
        return self.view(np.ndarray)

    def __getitem__(self, key):
        self._check()
        result = super().__getitem__(key)
        return result

    def __setitem__(self, key, value):
        self._check()
        super().__setitem__(key, value)

    def __array_ufunc__(self, ufunc, method, *inputs, out=None, **kwargs):
        inputs = tuple(x._plain() if isinstance(x, FieldView) else x for x in inputs)
        if out is not None:
            kwargs["out"] = tuple(x._plain() if isinstance(x, FieldView) else x for x in out)
        return getattr(ufunc, method)(*inputs, **kwargs)

    def __array_function__(self, func, types, args, kwargs):
        def plain(x):
            if isinstance(x, FieldView):
                return x._plain()
            if isinstance(x, (list, tuple)):
                return type(x)(plain(y) for y in x)
            return x
        return func(*plain(args), **{k: plain(v) for k, v in kwargs.items()})

    def __array__(self, dtype=None, *args, **kwargs):
        plain = self._plain()
        return plain if dtype is None else plain.astype(dtype)

    def __iter__(self):
        return iter(self._plain())

    def __repr__(self):
        return f"FieldView({np.ndarray.__repr__(self._plain())})"

    def __str__(self):
        return str(self._plain())

    def __reduce__(self):
        return self._plain().copy().__reduce__()

    def copy(self, order="C"):
        """A copy in memory of its own (an ordinary array), valid for ever."""
        return np.array(self._plain(), order=order, copy=True)

    def tolist(self):
        return self._plain().tolist()

    def tobytes(self, order="C"):
        return self._plain().tobytes(order)

    def item(self, *args):
        return self._plain().item(*args)


# The reductions as methods go through the plain array: NumPy 1.24 keeps a reference to an
# array whose __array_ufunc__ raises inside a reduction, which would keep a stale view's memory
# pinned for ever.
def _through_plain(method):
    def call(self, *args, **kwargs):
        return getattr(self._plain(), method)(*args, **kwargs)
    call.__name__ = method
    return call


for _method in ("max", "min", "sum", "mean", "std", "var", "prod", "any", "all", "argmax", "argmin", "cumsum",
                "cumprod", "ptp", "round", "clip", "dot", "astype", "nonzero", "searchsorted", "argsort", "sort",
                "fill"):
    setattr(FieldView, _method, _through_plain(_method))


def wrap(array, engine, name, component):
    view = array.view(FieldView)
    view._pbf = (engine, engine._epoch, name, component, engine.step)
    return view


class Components(tuple):
    """The components of a vector field: views x, y, z (also [0], [1], [2])."""

    def __new__(cls, name, arrays):
        self = super().__new__(cls, arrays)
        self.name = name
        return self

    x = property(lambda self: self[0])
    y = property(lambda self: self[1])
    z = property(lambda self: self[2])

    def copy(self):
        """An (N, components) array of its own."""
        return np.stack([c.copy() for c in self], axis=1)
