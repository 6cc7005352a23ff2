"""Studies, sweeps and sequences as tasks on an executor (``concurrent.futures`` or Dask).

Each storm of a study, each run of a sweep and each visit of a sequence is one task: a call of a
top-level function of this module, which reads the file again on the worker (so the file and the
files it names must be readable there: a shared filesystem on a cluster) and returns the task's
result as JSON text. JSON is exact here (catena writes and reads every float to the bit), so the
merged result is the same to the bit as a local run's.

A task that raises (a worker lost, a scene that does not read) does not stop the others. When
every task has ended, :class:`TasksFailed` names the failed ones. With ``checkpoint=DIR`` each
finished task's result is saved there as it arrives, and a second call with the same directory
runs only the tasks without a saved result (a result of an older scene is run again).
"""

import concurrent.futures as _cf
import json as _json
import os as _os
import traceback as _tb
from pathlib import Path as _Path

from . import _catena


class TasksFailed(_catena.CatenaError):
    """Some tasks of a study, sweep or sequence failed. ``failed`` maps each failed task's name to
    its error (the worker's traceback); ``checkpoint`` is where the finished ones are kept (or
    ``None``)."""

    def __init__(self, message, failed, checkpoint):
        super().__init__(message)
        self.failed = failed
        self.checkpoint = checkpoint


# The tasks: top-level functions, so that an executor can send them to another process.

# `threads`: the threads the task's run may keep busy (0: the worker's cores; 1 by default, as an
# executor runs a task per worker, usually one per core).

def study_storm(path, index, threads=1):
    """One storm of a study: its result as JSON text."""
    return _catena.study_storm(path, index, threads)


def sweep_run(path, index, threads=1):
    """One run of a sweep: its result as JSON text."""
    return _catena.sweep_run(path, index, threads)


def sequence_visit(path, index, carry, threads=1):
    """One visit with memory: ``(result, carry)`` as JSON texts."""
    return _catena.sequence_visit(path, index, carry, threads)


def sequence_as_laid(path, index, threads=1):
    """One visit from the as-laid state: its result as JSON text."""
    return _catena.sequence_as_laid(path, index, threads)


def _executor(executor):
    """A ``concurrent.futures`` executor: the one given, or a Dask client's."""
    if hasattr(executor, "get_executor") and hasattr(executor, "scheduler_info"):
        return executor.get_executor(pure=False)  # a dask.distributed.Client
    if not hasattr(executor, "submit"):
        raise TypeError(
            "executor: expected a concurrent.futures.Executor or a dask.distributed.Client, "
            f"got {type(executor).__name__}"
        )
    return executor


class _Store:
    """Finished tasks' results in a checkpoint folder (or nowhere), keyed by task name and scene
    hash: a result of an older scene is not used."""

    def __init__(self, checkpoint):
        self.dir = None if checkpoint is None else _Path(checkpoint)
        if self.dir is not None:
            self.dir.mkdir(parents=True, exist_ok=True)

    def _file(self, name):
        return self.dir / f"{name}.json"

    def get(self, name, scene_hash):
        if self.dir is None or not self._file(name).exists():
            return None
        saved = _json.loads(self._file(name).read_text())
        return saved["value"] if saved.get("scene_hash") == scene_hash else None

    def put(self, name, scene_hash, value):
        if self.dir is None:
            return
        tmp = self._file(name).with_suffix(".tmp")
        tmp.write_text(_json.dumps({"scene_hash": scene_hash, "value": value}))
        _os.replace(tmp, self._file(name))


def _error_text(e):
    return "".join(_tb.format_exception_only(type(e), e)).strip()


def _run_all(executor, tasks, store):
    """Runs independent tasks ``[(name, scene_hash, fn, args)]``; returns ``{name: value}`` and
    ``{name: error}``."""
    done, failed, futures = {}, {}, {}
    for name, scene_hash, fn, args in tasks:
        saved = store.get(name, scene_hash)
        if saved is not None:
            done[name] = saved
        else:
            futures[executor.submit(fn, *args)] = (name, scene_hash)
    for f in _cf.as_completed(futures):
        name, scene_hash = futures[f]
        try:
            value = f.result()
        except Exception as e:  # a task's failure is reported with the others, at the end
            failed[name] = _error_text(e)
            continue
        store.put(name, scene_hash, value)
        done[name] = value
    return done, failed


def _raise_failed(what, failed, total, checkpoint):
    names = ", ".join(sorted(failed))
    first = next(iter(failed.values()))
    again = (
        f"the finished ones are saved in {checkpoint}: call again with checkpoint={str(checkpoint)!r} "
        "to run only the rest"
        if checkpoint is not None
        else "pass checkpoint=DIR to keep the finished ones for a second call"
    )
    raise TasksFailed(
        f"{what}: {len(failed)} of {total} tasks failed ({names}); the first: {first}; {again}",
        failed,
        checkpoint,
    )


def _independent(path, plan, name, task, executor, checkpoint, threads):
    """Runs a plan's independent tasks (``name(t)`` names each, ``task`` runs it on the path, the
    task's index and ``threads``); returns their results in the plan's order (every one: a failure
    raises)."""
    store = _Store(checkpoint)
    tasks = [(name(t), t["scene_hash"], task, (path, t["index"], threads)) for t in plan]
    done, failed = _run_all(_executor(executor), tasks, store)
    if failed:
        _raise_failed(path, failed, len(tasks), checkpoint)
    return [done[n] for n, *_ in tasks]


def fatigue_study(path, executor, checkpoint, threads=1):
    path = str(_Path(path).resolve())
    plan = _json.loads(_catena.study_tasks(path))
    results = _independent(path, plan, lambda t: f"storm-{t['id']}", study_storm, executor,
                           checkpoint, threads)
    return _catena.study_merge(path, results)


def sweep(path, executor, checkpoint, threads=1):
    path = str(_Path(path).resolve())
    plan = _json.loads(_catena.sweep_tasks(path))
    results = _independent(path, plan, lambda t: f"run-{t['id']}", sweep_run, executor,
                           checkpoint, threads)
    return _catena.sweep_merge(path, results)


def sequence(path, executor, checkpoint, threads=1):
    """The visits with memory as a chain of tasks (each submitted when the one before has
    finished, with its carry), the as-laid visits as independent tasks alongside."""
    path = str(_Path(path).resolve())
    plan = _json.loads(_catena.sequence_tasks(path))
    visits = plan["visits"]
    ex = _executor(executor)
    store = _Store(checkpoint)
    laid_tasks = [
        (f"as-laid-{v['index']}", v["scene_hash"], sequence_as_laid, (path, v["index"], threads))
        for v in visits
    ] if plan["as_laid"] else []
    # The as-laid visits go first to the executor; the chain runs alongside them.
    with _cf.ThreadPoolExecutor(1) as side:
        laid = side.submit(_run_all, ex, laid_tasks, store)
        memory, carry, failed = [], None, {}
        for v in visits:
            name = f"visit-{v['index']}"
            saved = store.get(name, v["scene_hash"])
            if saved is None:
                try:
                    task = ex.submit(sequence_visit, path, v["index"], carry, threads)
                    saved = list(task.result())
                except Exception as e:
                    failed[name] = _error_text(e)
                    break
                store.put(name, v["scene_hash"], saved)
            result, carry = saved
            memory.append(result)
            if carry is None:  # the visit's run stopped early: the sequence stops there
                break
        laid_done, laid_failed = laid.result()
    failed.update(laid_failed)
    if failed:
        _raise_failed(path, failed, len(visits) + len(laid_tasks), checkpoint)
    return _catena.sequence_merge(path, memory, [laid_done[name] for name, *_ in laid_tasks])
