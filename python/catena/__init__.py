"""catena from Python.

The simulation is the Rust library that the ``catena`` command line uses; this package calls it in
process and returns numpy arrays, with the names and SI units of ``results.h5`` (``docs/results.md``):
arc length from the top (m), negative moment = sag (N*m), penetration of the invert positive down
(m), effective tension (N).

>>> import catena
>>> scene = catena.Scene.from_file("cases/benchmarks/scr-heave.toml")
>>> short = scene.edited({"dynamic.duration": 20.0, "dynamic.envelope_start": 10.0})
>>> run = catena.run(short)
>>> run["bending_moment"].shape            # (records, nodes)
>>> run["ranges/bending_moment/max"] - run["ranges/bending_moment/min"]   # the moment range along the arc

Errors are :class:`CatenaError`, with the command line's messages (file, key, what was expected).
"""

from __future__ import annotations

import json

import numpy as np

from ._catena import CatenaError, Scene, version
from . import _catena

__all__ = ["CatenaError", "Scene", "Results", "statics", "run", "fatigue_study", "sequence", "sweep", "version"]


class Results(dict):
    """Arrays by name (numpy, SI units) and ``summary`` (a dict)."""

    def __init__(self, raw):
        super().__init__()
        for name, (data, shape) in raw["arrays"].items():
            self[name] = np.frombuffer(data, dtype="<f8").reshape(shape)
        self.summary = json.loads(raw["summary"])

    def at_arc(self, name, s):
        """A field's history (records) or profile, linearly interpolated at arc length ``s`` (m)."""
        arc = self["arc"]
        v = self[name]
        if v.ndim == 1:
            return np.interp(s, arc, v)
        return np.array([np.interp(s, arc, row) for row in v])

    def __repr__(self):
        names = ", ".join(sorted(self))
        return f"Results({names}; summary keys: {', '.join(self.summary)})"


def _scene(scene):
    if isinstance(scene, Scene):
        return scene
    return Scene.from_file(str(scene))


def statics(scene) -> Results:
    """The static solution of a scene (a :class:`Scene` or a case file's path)."""
    return Results(_catena.statics(_scene(scene)))


def run(scene, progress=None, every: int = 100) -> Results:
    """Statics, then the dynamics of a scene.

    ``progress(t, duration)`` is called every ``every`` steps; Ctrl-C stops the run and raises
    ``KeyboardInterrupt``. A run that stops early (a step that does not converge) still returns
    everything up to its last converged step: see ``summary["completed"]`` and
    ``summary["stop_reason"]``.
    """
    return Results(_catena.run(_scene(scene), progress, every))


def fatigue_study(path, jobs: int = 0) -> Results:
    """A fatigue study file (storm table and fatigue table), the storms run in parallel on ``jobs``
    threads (0: every core). Arrays: ``arc``, ``damage_<fibre>`` (per year) and ``life_<fibre>``
    (years); ``summary["lives"]`` gives each fibre's minimum life and where."""
    return Results(_catena.fatigue_study(str(path), jobs))


def sequence(path, jobs: int = 0) -> Results:
    """Storms in sequence (a sequence file, ``docs/sequence.md``): each visit from the state the
    last one left (the trench, the degraded soil), the as-laid visits alongside on the other
    threads. Arrays: ``arc`` (m), ``trench`` (visits × nodes: penetration at rest after each visit,
    m, positive down), ``as_laid_penetration`` (m), ``life_memory`` and ``life_as_laid`` (years,
    the first fibre), ``strength`` (each node's strength factor after the last visit). In memory:
    the command line (``catena sequence``) writes files and resumes."""
    return Results(_catena.sequence(str(path), jobs))


def sweep(path, jobs: int = 0) -> list:
    """A sweep plan, every run in parallel: one dict per parameter point (``values``,
    ``min_life_years``, ``min_life_arc``, ``tdz_moment_range``, ``max_penetration``, ``failed``)."""
    return json.loads(_catena.sweep(str(path), jobs))
