"""Running a study (:func:`run_study`): its runs in batches, on Ray (local by default, or a
cluster's ``address``) or serially in this process, each finished batch written at once to a
Parquet file of its own in ``OUT/runs/``, so that a study that stops keeps what it finished and
``resume=True`` runs only the rest.

* A run that raises becomes a row with its error (``error``: the exception's type and message)
  and NaN metrics: one bad parameter set does not stop the study.
* A batch whose worker dies is run again by Ray (``max_retries``); only the driver writes
  results, once per finished batch, so no run is lost or written twice. A batch that kills its
  worker every time becomes rows with that error.
* Batches: about eight per worker, at most ``MAX_BATCH`` runs each, so that the per-task
  overhead (a few milliseconds on Ray) stays small against the runs and the progress bar moves.
* ``OUT/study.json`` records the study's fingerprint (:meth:`StudyConfig.fingerprint`): a
  study resumes only into its own directory.
"""

from __future__ import annotations

import json
import math
import os
import sys
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ..io._files import atomic_file, write_atomically
from .config import StudyConfig
from .scenarios import run_one

__all__ = ["MAX_BATCH", "StudyOutcome", "run_batch", "run_study"]

#: The most runs in one task.
MAX_BATCH = 64
#: Batches kept in flight per worker (enough to keep every worker busy).
IN_FLIGHT_PER_WORKER = 2


@dataclass(frozen=True)
class StudyOutcome:
    """What :func:`run_study` did: the study's runs, those run now, those that raised."""

    out: Path
    n_runs: int
    ran: int
    errors: int
    skipped: int


def run_batch(kind: str, settings: dict[str, Any], metrics: tuple[str, ...], batch: list[dict[str, Any]]) -> list[dict[str, Any]]:
    """Each run of ``batch`` as a result row: its number and parameters, its metrics (NaN where
    it raised) and ``error`` (None, or the exception's type and message)."""
    rows = []
    for parameters in batch:
        row = dict(parameters)
        try:
            row |= run_one(kind, settings, {k: v for k, v in parameters.items() if k != "run"})
            row["error"] = None
        except Exception as exc:  # noqa: BLE001 (a run's failure is its row, the study goes on)
            row = _failed(parameters, metrics, f"{type(exc).__name__}: {exc}")
        rows.append(row)
    return rows


def _failed(run: dict[str, Any], metrics: tuple[str, ...], error: str) -> dict[str, Any]:
    """The row of a run that raised, or whose worker died: its parameters, NaN metrics, the error."""
    return {**run, **dict.fromkeys(metrics, math.nan), "error": error}


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
    (default all) started and stopped for the study. ``progress(done, total)`` after each batch."""
    if workers is not None and not (isinstance(workers, int) and workers >= 1):
        raise ValueError(f"workers must be a positive integer, got {workers!r}")
    root = Path(out)
    parts = root / "runs"
    done = _prepare(config, root, parts, resume)
    pending = [run for run in config.runs() if run["run"] not in done]
    total = len(pending)
    if progress is not None:
        progress(0, total)
    errors, finished = 0, 0
    if total:
        runner = _serial if serial else _on_ray
        for rows in runner(config, pending, address, workers):
            _write_part(parts, rows, config)
            errors += sum(row["error"] is not None for row in rows)
            finished += len(rows)
            if progress is not None:
                progress(finished, total)
    return StudyOutcome(root, config.n_runs, finished, errors, len(done))


def _batches(pending: list[dict[str, Any]], workers: int) -> list[list[dict[str, Any]]]:
    size = max(1, min(MAX_BATCH, math.ceil(len(pending) / (8 * max(workers, 1)))))
    return [pending[i : i + size] for i in range(0, len(pending), size)]


def _serial(config: StudyConfig, pending: list[dict[str, Any]], address: str | None, workers: int | None) -> Iterator[list[dict[str, Any]]]:
    for batch in _batches(pending, 1):
        yield run_batch(config.kind, config.settings, config.metrics, batch)


def _on_ray(config: StudyConfig, pending: list[dict[str, Any]], address: str | None, workers: int | None) -> Iterator[list[dict[str, Any]]]:
    from .._ray import ray_session

    with ray_session(address, workers) as ray:
        cpus = max(1, int(ray.cluster_resources().get("CPU", 1)))
        remote = ray.remote(max_retries=3, retry_exceptions=False)(run_batch)
        batches = _batches(pending, cpus)
        waiting: dict[Any, list[dict[str, Any]]] = {}
        queue = iter(batches)
        limit = IN_FLIGHT_PER_WORKER * cpus
        while True:
            while len(waiting) < limit:
                batch = next(queue, None)
                if batch is None:
                    break
                waiting[remote.remote(config.kind, config.settings, config.metrics, batch)] = batch
            if not waiting:
                return
            ready, _ = ray.wait(list(waiting), num_returns=1)
            for ref in ready:
                batch = waiting.pop(ref)
                try:
                    yield ray.get(ref)
                except ray.exceptions.RayError as exc:
                    # Its worker died on every try: the runs are rows with the error, not lost.
                    reason = " ".join(str(exc).split())[:300]
                    yield [_failed(run, config.metrics, f"{type(exc).__name__}: {reason}") for run in batch]


def _prepare(config: StudyConfig, root: Path, parts: Path, resume: bool) -> set[int]:
    """The runs already done in ``root`` (resuming), after checking that it is this study's; a
    new study's directory made."""
    record = root / "study.json"
    if record.exists():
        try:
            previous = json.loads(record.read_text(encoding="utf-8"))
        except (OSError, ValueError) as exc:
            raise ValueError(f"{record}: not a study record ({exc})") from None
        if not resume:
            raise ValueError(f"{root}: holds a study already; resume it (--resume) or choose another --out")
        if previous.get("fingerprint") != config.fingerprint():
            raise ValueError(f"{root}: holds another study ({previous.get('source')}); its runs are not this study's")
        from .results import done_runs

        return done_runs(root)
    parts.mkdir(parents=True, exist_ok=True)
    what = {
        "fingerprint": config.fingerprint(),
        "source": config.source,
        "kind": config.kind,
        "n_runs": config.n_runs,
        "parameters": config.parameter_names,
        "metrics": list(config.metrics),
    }
    write_atomically(record, (json.dumps(what, indent=1) + "\n").encode())
    return set()


def _write_part(parts: Path, rows: list[dict[str, Any]], config: StudyConfig) -> None:
    """One finished batch as ``part-<first run>.parquet``, whole or not at all."""
    import pyarrow
    import pyarrow.parquet

    columns = ["run", *config.parameter_names, *config.metrics, "error"]
    table = pyarrow.table({name: [row.get(name) for row in rows] for name in columns})
    parts.mkdir(parents=True, exist_ok=True)
    with atomic_file(parts / f"part-{rows[0]['run']:09d}.parquet") as handle:
        pyarrow.parquet.write_table(table, handle)


def progress_bar(done: int, total: int) -> None:
    """A one-line progress bar on standard error."""
    width = 30
    filled = round(width * done / total) if total else width
    end = "\n" if done == total else ""
    print(f"\ruwml study: [{'#' * filled}{'.' * (width - filled)}] {done}/{total} runs", end=end, file=sys.stderr, flush=True)
