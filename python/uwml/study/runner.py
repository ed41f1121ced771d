"""Running a study (:func:`run_study`): its runs in batches, on Ray (local by default, or a
cluster's ``address``) or serially in this process, each finished batch written at once to
``OUT/runs/`` (:mod:`uwml.study.store`: one Parquet file per batch, whole or not at all), so that
a study that stops keeps what it finished and ``resume=True`` runs only the rest.

* The runs are made as batches are taken (:meth:`StudyConfig.iter_runs`): a study of millions
  of runs starts at once, and what it keeps of the runs done is a boolean per run.
* A run that raises becomes a row with its error (``error``: the exception's type and message,
  ``error_kind`` ``"run"``) and NaN metrics: one bad parameter set does not stop the study.
* A batch whose worker dies is run again by Ray (``max_retries``); only the driver writes
  results, so no run is lost or written twice. A batch that kills its worker on every try is
  cut in two, and each half run again (once: a half that crashes is cut again), down to the
  run that kills its worker, run alone with Ray's retries: only that run gets a failed row
  (``WorkerCrashedError: this run killed its worker ...``, its own failure); the others' rows
  are their results.
* A batch that Ray loses otherwise (a node, the object store, ``run_batch`` itself failing)
  becomes rows with the error and ``error_kind`` ``"infrastructure"``: ``resume=True`` runs
  those again, not the runs' own failures.
* Batches: about eight per worker, at most ``MAX_BATCH`` runs each, so that the per-task
  overhead (a few milliseconds on Ray) stays small against the runs and the progress bar moves.
* ``OUT/study.json`` records the study's fingerprint, which covers its robot's files' content:
  a study resumes only into its own directory, and not after a file changed (nor goes on if one
  changes while it runs). ``OUT/study.lock`` keeps a second process out while one runs.
"""

from __future__ import annotations

import itertools
import math
import os
import sys
from collections.abc import Callable, Generator, Iterator
from contextlib import closing, suppress
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from .config import StudyConfig
from .scenarios import run_one
from .store import INFRASTRUCTURE, RUN, StudyError, locked, prepare, write_rows

__all__ = ["MAX_BATCH", "StudyOutcome", "run_batch", "run_study"]

#: The most runs in one task.
MAX_BATCH = 64
#: Batches kept in flight per worker (enough to keep every worker busy).
IN_FLIGHT_PER_WORKER = 2
#: Ray's retries of a batch whose worker died (and of a run alone, to find one that kills it).
RETRIES = 3


@dataclass(frozen=True)
class StudyOutcome:
    """What :func:`run_study` did: the study's runs, those run now, those that failed now (their
    own failure or Ray's), those done before."""

    out: Path
    n_runs: int
    ran: int
    errors: int
    skipped: int


def run_batch(kind: str, settings: dict[str, Any], metrics: tuple[str, ...], batch: list[dict[str, Any]]) -> list[dict[str, Any]]:
    """Each run of ``batch`` as a result row: its number and parameters, its metrics (NaN where
    it raised), ``error`` (None, or the exception's type and message) and ``error_kind`` (None,
    or ``"run"``)."""
    rows = []
    for parameters in batch:
        row = dict(parameters)
        try:
            row |= run_one(kind, settings, {k: v for k, v in parameters.items() if k != "run"})
            row |= {"error": None, "error_kind": None}
        except Exception as exc:  # noqa: BLE001 (a run's failure is its row, the study goes on)
            row = _failed(parameters, metrics, f"{type(exc).__name__}: {exc}", RUN)
        rows.append(row)
    return rows


def _failed(run: dict[str, Any], metrics: tuple[str, ...], error: str, kind: str) -> dict[str, Any]:
    """The row of a run that failed (``kind``: the run's failure or Ray's): its parameters, NaN
    metrics, the error."""
    return {**run, **dict.fromkeys(metrics, math.nan), "error": error, "error_kind": kind}


def run_study(
    config: StudyConfig,
    out: str | os.PathLike[str],
    *,
    address: str | None = None,
    serial: bool = False,
    workers: int | None = None,
    resume: bool = False,
    progress: Callable[[int, int], None] | None = None,
) -> StudyOutcome:
    """Runs ``config``'s runs (module docstring) into the directory ``out``: serially here with
    ``serial=True``, else on Ray: the running one if this process has initialized it, else a
    cluster's ``address`` (``ray://…`` or ``auto``), else a local Ray of ``workers`` CPUs
    (default all) started for the study and ended with it (even if this process is killed).
    ``progress(done, total)`` after each batch. A :class:`~uwml.study.store.StudyError` if
    ``out`` is another study's, its robot's files changed, or another process is running it."""
    if workers is not None and not (isinstance(workers, int) and workers >= 1):
        raise ValueError(f"workers must be a positive integer, got {workers!r}")
    root = Path(out)
    with locked(root):
        ledger = prepare(config, root, resume)
        skipped = int(ledger.done.sum())
        total = config.n_runs - skipped
        if progress is not None:
            progress(0, total)
        errors, finished = 0, 0
        if total:
            pending = config.iter_runs(~ledger.done)
            runner = _serial if serial else _on_ray
            with closing(runner(config, pending, total, address, workers)) as batches:  # a local Ray stopped at once
                for rows in batches:
                    changed = config.changed_inputs()
                    if changed:
                        raise StudyError(
                            f"{', '.join(changed)} changed during the study; the runs since are not written: "
                            "restore it and --resume, or start a new --out"
                        )
                    write_rows(root, rows, config, ledger)
                    errors += sum(row["error"] is not None for row in rows)
                    finished += len(rows)
                    if progress is not None:
                        progress(finished, total)
    return StudyOutcome(root, config.n_runs, finished, errors, skipped)


def _batches(pending: Iterator[dict[str, Any]], total: int, workers: int) -> Iterator[list[dict[str, Any]]]:
    """``pending`` (``total`` runs) cut into batches (module docstring), taken as needed."""
    size = max(1, min(MAX_BATCH, math.ceil(total / (8 * max(workers, 1)))))
    while batch := list(itertools.islice(pending, size)):
        yield batch


def _serial(
    config: StudyConfig, pending: Iterator[dict[str, Any]], total: int, address: str | None, workers: int | None
) -> Generator[list[dict[str, Any]]]:
    for batch in _batches(pending, total, 1):
        yield run_batch(config.kind, config.settings, config.metrics, batch)


def _on_ray(
    config: StudyConfig, pending: Iterator[dict[str, Any]], total: int, address: str | None, workers: int | None
) -> Generator[list[dict[str, Any]]]:
    from .._ray import ray_session

    with ray_session(address, workers) as ray:
        cpus = max(1, int(ray.cluster_resources().get("CPU", 1)))
        whole = ray.remote(max_retries=RETRIES, retry_exceptions=False)(run_batch)
        piece = whole.options(max_retries=0)  # a crashed batch's half: a crash cuts it again at once
        waiting: dict[Any, list[dict[str, Any]]] = {}
        limit = IN_FLIGHT_PER_WORKER * cpus
        try:
            yield from _keep_busy(ray, config, whole, piece, _batches(pending, total, cpus), waiting, limit)
        finally:  # stopped early (an error, an interruption): on a cluster, its tasks are not left running
            for ref in waiting:
                with suppress(Exception):
                    ray.cancel(ref)


def _keep_busy(
    ray: Any, config: StudyConfig, whole: Any, piece: Any, queue: Iterator[list[dict[str, Any]]], waiting: dict[Any, Any], limit: int
) -> Generator[list[dict[str, Any]]]:
    """The rows of each batch of ``queue`` on Ray as it finishes, ``limit`` batches in flight
    (in ``waiting``), a crashed batch cut in two (module docstring)."""
    pieces: list[list[dict[str, Any]]] = []  # halves of crashed batches, run first
    while True:
        while len(waiting) < limit:
            if pieces:  # a half of more than one run has one try; one run alone, Ray's retries
                batch = pieces.pop()
                task = piece if len(batch) > 1 else whole
            else:
                next_batch = next(queue, None)
                if next_batch is None:
                    break
                batch, task = next_batch, whole
            waiting[task.remote(config.kind, config.settings, config.metrics, batch)] = batch
        if not waiting:
            return
        ready, _ = ray.wait(list(waiting), num_returns=1)
        for ref in ready:
            batch = waiting.pop(ref)
            try:
                yield ray.get(ref)
            except ray.exceptions.WorkerCrashedError as exc:
                if len(batch) > 1:
                    half = len(batch) // 2
                    pieces += [batch[half:], batch[:half]]
                else:
                    reason = _reason(exc)
                    error = (
                        f"WorkerCrashedError: this run killed its worker on each of its {RETRIES + 1} tries, alone in its task ({reason})"
                    )
                    yield [_failed(batch[0], config.metrics, error, RUN)]
            except ray.exceptions.RayError as exc:
                # Lost by Ray, not by its runs: rows with the error, run again on resuming.
                error = f"{type(exc).__name__}: {_reason(exc)}"
                yield [_failed(run, config.metrics, error, INFRASTRUCTURE) for run in batch]


def _reason(exc: BaseException) -> str:
    return " ".join(str(exc).split())[:300]


def progress_bar(done: int, total: int) -> None:
    """A one-line progress bar on standard error."""
    width = 30
    filled = round(width * done / total) if total else width
    end = "\n" if done == total else ""
    print(f"\ruwml study: [{'#' * filled}{'.' * (width - filled)}] {done}/{total} runs", end=end, file=sys.stderr, flush=True)
