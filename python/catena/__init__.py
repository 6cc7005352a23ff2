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

import json as _json

import numpy as _np

from ._catena import CatenaError, Scene, version
from . import _catena, _tasks
from ._tasks import TasksFailed

__all__ = [
    "CatenaError",
    "TasksFailed",
    "Scene",
    "Results",
    "statics",
    "run",
    "fatigue_study",
    "sweep",
    "sequence",
    "animate",
    "version",
]


class Results(dict):
    """Arrays by name (numpy, SI units) and ``summary`` (a dict)."""

    def __init__(self, raw):
        super().__init__()
        for name, (data, shape) in raw["arrays"].items():
            self[name] = _np.frombuffer(data, dtype="<f8").reshape(shape)
        self.summary = _json.loads(raw["summary"])

    def at_arc(self, name, s):
        """A field's history (records) or profile, linearly interpolated at arc length ``s`` (m)."""
        arc = self["arc"]
        v = self[name]
        if v.ndim == 1:
            return _np.interp(s, arc, v)
        return _np.array([_np.interp(s, arc, row) for row in v])

    def __repr__(self):
        names = ", ".join(sorted(self))
        return f"Results({names}; summary keys: {', '.join(self.summary)})"


def _scene(scene):
    if isinstance(scene, Scene):
        return scene
    return Scene.from_file(str(scene))


def statics(scene) -> Results:
    """The static solution of a scene (a :class:`Scene` or a case file's path).

    Arrays along the arc (one value per node): ``arc`` (m from the top), ``x``, ``z`` (m),
    ``theta`` (rad), ``effective_tension`` (N), ``bending_moment`` (N*m, negative in a sag bend),
    ``penetration`` (m, of the invert, positive down), ``seabed_force`` (N/m). ``summary``:
    ``top_tension``, ``horizontal_tension`` (N), ``touchdown_arc`` (m), ``max_sag_moment`` (N*m)
    and where (m), ``top_angle_from_vertical`` (deg), ``newton_iterations``, ``wall_seconds``.
    """
    return Results(_catena.statics(_scene(scene)))


def run(scene, progress=None, every: int = 100, threads: int = 0) -> Results:
    """Statics, then the dynamics of a scene (a :class:`Scene` or a case file's path).

    Arrays: the records of ``results.h5``'s ``/dynamic`` (``time`` in s; ``top_x``, ``top_z`` in m;
    ``top_tension`` in N; ``touchdown_arc`` in m; fields of shape (records, nodes): ``x``, ``z``,
    ``penetration`` (m), ``effective_tension`` (N), ``bending_moment`` (N*m), ``seabed_force``
    (N/m)), the range graphs ``ranges/<quantity>/{min,max,mean}`` from ``envelope_start``, each
    gauge's ``gauges/<name>/bending_moment`` and ``effective_tension`` at every step, and with a
    ``[fatigue]`` table ``fatigue/damage_<fibre>`` (over the counted record).

    The interpreter lock is released while catena steps, so runs in several threads run in
    parallel. ``threads`` is the number of threads the run may keep busy. 0, the default: one when
    called from a Python thread other than the main one (a ``threading.Thread``, an executor's
    worker, a Dask worker's task) or from a process pool's worker, else the cores no other run of
    this process holds. From two, the line (or a lay's window) is stepped on two threads where it
    is long enough to cut and where two are measured to be faster than one (not on cores busy with
    other work), with the same results to the bit. ``progress(t, duration)`` (both in s) is called every ``every`` steps, at most five
    times a second, and at the last step; Ctrl-C stops the run and raises ``KeyboardInterrupt``. A
    run that stops early (a step that does not converge) still returns everything up to its last
    converged step: see ``summary["completed"]`` and ``summary["stop_reason"]``.

    A lay (a scene with ``[lay]``) returns ``results.h5``'s ``/lay`` arrays under the same names
    (``lay/time``, ``lay/paid_out``, ``lay/top_tension``, ``lay/kp``, ``lay/as_laid_embedment``, …;
    ``docs/results.md``) and ``summary.json`` with its ``lay``; ``progress`` is not called.
    """
    return Results(_catena.run(_scene(scene), progress, every, threads))


def fatigue_study(path, jobs: int = 0, executor=None, checkpoint=None,
                  task_threads: int = 1) -> Results:
    """A fatigue study file (storm table and fatigue table, ``docs/study.md``).

    Without ``executor`` the storms run in parallel on ``jobs`` threads (0: every core). With one
    (a ``concurrent.futures.Executor`` or a ``dask.distributed.Client``) each storm is a task on
    it, and the result is the same to the bit; ``checkpoint=DIR`` keeps each finished storm so that
    a second call after a failure (:class:`TasksFailed`) runs only the rest. ``task_threads`` is
    the threads each task may keep busy (0: the worker's cores): 1 by default, since an executor
    runs a task per worker, usually one per core; give more to workers that run fewer tasks than
    their cores.

    Arrays: ``arc`` (m), ``damage_<fibre>`` (per year) and ``life_<fibre>`` (years) along the arc;
    ``summary["lives"]`` gives each fibre's minimum life (years) and where (m), and
    ``summary["storms"]`` each storm's wall time (s) and whether it stopped.
    """
    if executor is not None:
        return Results(_tasks.fatigue_study(path, executor, checkpoint, task_threads))
    return Results(_catena.fatigue_study(str(path), jobs))


def sequence(path, jobs: int = 0, executor=None, checkpoint=None,
             task_threads: int = 1) -> Results:
    """Storms in sequence (a sequence file, ``docs/sequence.md``): each visit from the state the
    last one left (the trench, the degraded soil), the as-laid visits alongside.

    Without ``executor`` on ``jobs`` threads (at least 2: the chain and the as-laid visits). With
    one (``concurrent.futures`` or a Dask client) each visit is a task: the visits with memory a
    chain, each sent when the one before has finished with the state it left, the as-laid visits
    independent; ``checkpoint=DIR`` keeps finished visits (and the state after each) for a second
    call; ``task_threads`` as for :func:`fatigue_study`.

    Arrays: ``arc`` (m), ``trench`` (visits x nodes: penetration at rest after each visit, m,
    positive down), ``as_laid_penetration`` (m), ``life_memory`` and ``life_as_laid`` (years, the
    first fibre), ``strength`` (each node's strength factor after the last visit, 1 intact). In
    memory: the command line (``catena sequence``) writes files and resumes.
    """
    if executor is not None:
        return Results(_tasks.sequence(path, executor, checkpoint, task_threads))
    return Results(_catena.sequence(str(path), jobs))


def sweep(path, jobs: int = 0, executor=None, checkpoint=None, task_threads: int = 1) -> list:
    """A sweep plan (``docs/sweep.md``): one dict per parameter point, with ``values`` (the
    point's keys and values), ``min_life_years`` (years), ``min_life_arc`` (m),
    ``tdz_moment_range`` (N*m), ``max_penetration`` (m) and ``failed`` (why, or ``None``).

    Without ``executor`` every run in parallel on ``jobs`` threads (0: every core); with one
    (``concurrent.futures`` or a Dask client) each run (a point, or a point's storm for a study
    base) is a task, with the same result to the bit; ``checkpoint=DIR`` and ``task_threads`` as
    for :func:`fatigue_study`.
    """
    if executor is not None:
        return _json.loads(_tasks.sweep(path, executor, checkpoint, task_threads))
    return _json.loads(_catena.sweep(str(path), jobs))


def animate(results, out, frames: int = 120, fps: float = 12.0, colour: str = "penetration") -> dict:
    """An animated GIF of the touchdown zone from a run's ``results.h5`` (the command line's
    ``catena animate``): the whole line, the touchdown zone drawn to a true vertical scale with the
    seabed and the trench as it forms, nodes coloured by ``colour`` (``"penetration"``, m, or
    ``"seabed_force"``, N/m), the bending moment along the arc beneath (N*m), time and top motion.

    ``results`` is the path of a ``results.h5`` or a :class:`Results` of :func:`run`; at most
    ``frames`` frames, chosen evenly from the records, at ``fps`` frames a second. A lay's results
    (``lay/frames/...``) animate with the touchdown zone following the touchdown. Returns
    ``{"frames", "bytes", "seconds"}``.
    """
    lay_names = {"arc": "lay/arc", "time": "lay/frames/time", "x": "lay/frames/x",
                 "z": "lay/frames/z", "penetration": "lay/frames/penetration",
                 "seabed_force": "lay/frames/seabed_force",
                 "bending_moment": "lay/frames/bending_moment", "top_x": "lay/frames/top_x",
                 "top_z": "lay/frames/top_z", "outer_diameter": "lay/frames/contact_od"}
    follow = False
    if isinstance(results, Results) and "lay/frames/x" in results:
        arrays = {k: results[v] for k, v in lay_names.items()}
        follow = True
    elif isinstance(results, Results):
        arrays = results
    else:
        try:
            import h5py
        except ImportError as e:
            raise CatenaError(
                "animate: reading a results.h5 needs h5py (pip install h5py); or pass the "
                "Results of catena.run"
            ) from e
        with h5py.File(results, "r") as f:
            if "lay/frames" in f:
                arrays = {k: f[v][...] for k, v in lay_names.items()}
                follow = True
                return _animate(arrays, out, frames, fps, colour, follow)
            d = f["dynamic"]
            arrays = {name: d[name][...] for name in
                      ["arc", "time", "x", "z", "penetration", "seabed_force", "bending_moment",
                       "top_x", "top_z"]}
            text, case = (f.attrs[k] for k in ["scene", "case"])
            text, case = (v.decode() if isinstance(v, bytes) else str(v) for v in (text, case))
            # Each node's diameter as the run used it; a file written before /line existed:
            # from the scene it carries.
            od = f["line/contact_od"][...] if "line/contact_od" in f else None
            if od is None or od.size != arrays["arc"].size:
                od = _np.array(_catena.node_diameters(text, case, arrays["arc"].size))
            arrays["outer_diameter"] = od
    return _animate(arrays, out, frames, fps, colour, follow)


def _animate(arrays, out, frames, fps, colour, follow):
    raw = {k: (_np.ascontiguousarray(v, dtype="<f8").tobytes(), list(_np.shape(v)))
           for k, v in arrays.items() if isinstance(v, _np.ndarray)}
    return _json.loads(_catena.animate_arrays(raw, str(out), int(frames), float(fps), colour,
                                              bool(follow)))
