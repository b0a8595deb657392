"""Attribute access to a Scene's keys: scene.liquid.surface_tension = 0.05 is
scene["liquid.surface_tension"] = 0.05 (the same checks, the same ValueError)."""
from . import _drumlab


class Table:
    """A table of a Scene (scene.liquid, scene.drum.orbit): its keys as attributes."""

    __slots__ = ("_scene", "_prefix")

    def __init__(self, scene, prefix):
        object.__setattr__(self, "_scene", scene)
        object.__setattr__(self, "_prefix", prefix)

    def __getattr__(self, name):
        return _attribute(self._scene, f"{self._prefix}.{name}")

    def __setattr__(self, name, value):
        self._scene[f"{self._prefix}.{name}"] = value

    def __repr__(self):
        return f"<drumlab.Scene table [{self._prefix}]: {self._scene[self._prefix]!r}>"


def _attribute(scene, key):
    try:
        value = scene[key]
    except KeyError as e:
        raise AttributeError(str(e)) from None
    return Table(scene, key) if isinstance(value, dict) else value


def _scene_getattr(self, name):
    if name.startswith("_"):
        raise AttributeError(name)
    return _attribute(self, name)


def _scene_setattr(self, name, value):
    if name.startswith("_"):
        object.__setattr__(self, name, value)
    else:
        self[name] = value


_drumlab.Scene.__getattr__ = _scene_getattr
_drumlab.Scene.__setattr__ = _scene_setattr
