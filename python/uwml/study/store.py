"""A study's folder (``--out``), kept so that no run is lost, mixed with another study's or
written twice (:func:`uwml.study.run_study` writes it, :mod:`uwml.study.study_results` reads it):

* ``study.json``: the study's fingerprint (:meth:`StudyConfig.fingerprint`), which covers the
  content of its robot's files, and each file's digest: a study resumes only into its own
  folder, and not after its robot changed (the refusal names the file that did); its
  parameters, its metrics and their ``units`` (the figures' axes).
* ``study.lock``: a lock held by the process running the study (an OS lock, ``flock``, which
  ends with its process, even one killed with SIGKILL): a second process refuses at once,
  naming the holder's pid.
* ``runs/part-<first run>.parquet``: the rows of one finished batch, written whole or not at
  all (a temporary file renamed). A row's ``error_kind`` says who failed: None (no error),
  ``"run"`` (the run's own exception, or a run that killed its worker every time, alone) or
  ``"infrastructure"`` (Ray lost the batch: a node or the object store, not the run). A resumed
  study runs again the runs it lacks and those of the last kind, and rewrites each part that
  held such a row with the new row in its place (whole or not at all): a run has one row.
"""

from __future__ import annotations

import json
import os
import socket
import sys
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import UwmlError
from ..io._file_access import atomic_file, write_atomically
from .config import StudyConfig

__all__ = ["INFRASTRUCTURE", "RUN", "Ledger", "StudyError", "error_kinds", "ledger", "locked", "prepare", "write_rows"]

#: ``error_kind`` of a run's own failure.
RUN = "run"
#: ``error_kind`` of a run whose batch Ray lost: ``--resume`` runs it again.
INFRASTRUCTURE = "infrastructure"
#: Ray's errors, as an earlier uwml wrote them in ``error`` (before ``error_kind``): a batch whose
#: worker crashed was recorded whole with the error, so its runs are run again on resuming.
_RAY_ERRORS = frozenset((
    "RayError", "RayTaskError", "RaySystemError", "WorkerCrashedError", "OutOfMemoryError", "NodeDiedError",
    "LocalRayletDiedError", "ObjectLostError", "ObjectFetchTimedOutError", "ObjectReconstructionFailedError",
    "OwnerDiedError", "ObjectStoreFullError", "OutOfDiskError", "TaskCancelledError", "TaskUnschedulableError",
    "TaskPlacementGroupRemoved", "RuntimeEnvSetupError", "GetTimeoutError", "RpcError",
))  # fmt: skip


class StudyError(UwmlError):
    """A study's folder that cannot take this run: another study's, one whose robot changed, or
    one that another process is running."""


@dataclass
class Ledger:
    """Which runs of a study its folder holds: ``done`` (a boolean per run: a row of its own, a
    result or its own error) and ``retry`` (the runs Ray lost, each with the part that holds its
    row)."""

    done: np.ndarray
    retry: dict[int, Path] = field(default_factory=dict)


@contextmanager
def locked(root: Path) -> Iterator[None]:
    """``root`` (made if absent) held by this process until the block ends (module docstring);
    a :class:`StudyError` at once if another process holds it."""
    root.mkdir(parents=True, exist_ok=True)
    path = root / "study.lock"
    fd = os.open(path, os.O_RDWR | os.O_CREAT, 0o666)  # not inherited by the processes started here
    try:
        if not _try_lock(fd):
            try:
                holder = path.read_text(encoding="utf-8", errors="replace").strip() or "its pid not yet written"
            except OSError:
                holder = "its pid unreadable"
            raise StudyError(f"{root}: a study is running in this folder already ({holder}); wait for it to end, or choose another --out")
        os.ftruncate(fd, 0)
        os.lseek(fd, 0, os.SEEK_SET)
        os.write(fd, f"pid {os.getpid()} on {socket.gethostname()}\n".encode())
        yield
    finally:
        os.close(fd)  # the lock ends with the file's last descriptor (or the process)


def _try_lock(fd: int) -> bool:
    if sys.platform == "win32":
        import msvcrt

        try:
            msvcrt.locking(fd, msvcrt.LK_NBLCK, 1)
        except OSError:
            return False
        return True
    import fcntl

    try:
        fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except BlockingIOError:
        return False
    return True


def prepare(config: StudyConfig, root: Path, resume: bool) -> Ledger:
    """What ``root`` holds of ``config`` (resuming), after checking that it is this study's with
    the same robot; a new study's record written."""
    record = root / "study.json"
    if not record.exists():
        (root / "runs").mkdir(parents=True, exist_ok=True)
        what = {
            "fingerprint": config.fingerprint(),
            "source": config.source,
            "kind": config.kind,
            "n_runs": config.n_runs,
            "parameters": config.parameter_names,
            "metrics": list(config.metrics),
            "units": dict(config.units),
            "inputs": {key: {"path": config.settings[key], "sha256": digest} for key, digest in config.inputs.items()},
        }
        write_atomically(record, (json.dumps(what, indent=1) + "\n").encode())
        return Ledger(np.zeros(config.n_runs, dtype=bool))
    try:
        previous = json.loads(record.read_text(encoding="utf-8"))
    except (OSError, ValueError) as exc:
        raise StudyError(f"{record}: not a study record ({exc})") from None
    if not resume:
        raise StudyError(f"{root}: holds a study already; resume it (--resume) or choose another --out")
    if previous.get("fingerprint") != config.fingerprint():
        recorded = {key: entry.get("sha256") for key, entry in previous.get("inputs", {}).items()}
        if config.inputs and previous.get("fingerprint") == config.fingerprint(recorded):
            changed = [config.settings[key] for key in config.inputs if recorded.get(key) != config.inputs[key]]
            if recorded:
                them = "it" if len(changed) == 1 else "them"
                raise StudyError(f"{', '.join(changed)} changed since the study began; start a new --out or restore {them}")
            raise StudyError(
                f"{root}: begun by an earlier uwml, which kept no digest of {', '.join(changed)}: it may have changed since; "
                "start a new --out"
            )
        raise StudyError(f"{root}: holds another study ({previous.get('source')}); its runs are not this study's")
    return ledger(root, config.n_runs)


def error_kinds(table: Any) -> list[str | None]:
    """Each row's ``error_kind`` (module docstring); for a part an earlier uwml wrote, without
    the column, inferred from ``error`` (a Ray error's name: Ray's; any other error: the run's)."""
    if "error_kind" in table.column_names:
        kinds: list[str | None] = table.column("error_kind").to_pylist()
        return kinds
    return [
        None if error is None else INFRASTRUCTURE if error.split(":")[0].split("(")[0] in _RAY_ERRORS else RUN
        for error in table.column("error").to_pylist()
    ]


def parts(root: Path) -> list[Path]:
    """The parts of the study in ``root``, in their names' order."""
    return sorted((root / "runs").glob("part-*.parquet"))


def ledger(root: Path, n_runs: int) -> Ledger:
    """What the parts of ``root`` hold (:class:`Ledger`), reading their ``run``, ``error`` and
    ``error_kind`` columns alone; a run with a row of its own is done even if another part holds
    a lost row of it."""
    import pyarrow.parquet

    done = np.zeros(n_runs, dtype=bool)
    retry: dict[int, Path] = {}
    for path in parts(root):
        names = pyarrow.parquet.read_schema(path).names
        table = pyarrow.parquet.read_table(path, columns=[c for c in ("run", "error", "error_kind") if c in names])
        runs = np.asarray(table.column("run").to_numpy(), dtype=np.int64)
        lost = np.array([kind == INFRASTRUCTURE for kind in error_kinds(table)], dtype=bool)
        ours = (runs >= 0) & (runs < n_runs)
        done[runs[ours & ~lost]] = True
        retry.update((int(run), path) for run in runs[ours & lost])
    return Ledger(done, {run: path for run, path in retry.items() if not done[run]})


def write_rows(root: Path, rows: list[dict[str, Any]], config: StudyConfig, ledger: Ledger) -> None:
    """A finished batch's rows into ``root``: the runs new to it as ``part-<first run>.parquet``,
    and each run Ray had lost in place of its row in the part that held it (each file whole or
    not at all), so that a run has one row whenever the process stops."""
    fresh = [row for row in rows if row["run"] not in ledger.retry]
    again: dict[Path, dict[int, dict[str, Any]]] = {}
    for row in rows:
        if row["run"] in ledger.retry:
            again.setdefault(ledger.retry[row["run"]], {})[row["run"]] = row
    if fresh:
        path = root / "runs" / f"part-{fresh[0]['run']:09d}.parquet"
        if path.exists():  # a part holds its first run, and a run new to the folder is in none
            raise StudyError(f"{path}: exists already, holding runs this study has not run; is another process writing {root}?")
        _write_table(path, fresh, config)
        _account(ledger, fresh, path)
    for path, new in again.items():
        import pyarrow.parquet

        table = pyarrow.parquet.read_table(path)
        old = [row | {"error_kind": kind} for row, kind in zip(table.to_pylist(), error_kinds(table), strict=True)]
        _write_table(path, [new.get(row["run"], row) for row in old], config)
        _account(ledger, list(new.values()), path)


def _account(ledger: Ledger, rows: list[dict[str, Any]], path: Path) -> None:
    """``ledger`` after ``rows`` were written to ``path``."""
    for row in rows:
        if row.get("error_kind") == INFRASTRUCTURE:
            ledger.retry[row["run"]] = path
        else:
            ledger.retry.pop(row["run"], None)
            ledger.done[row["run"]] = True


def _write_table(path: Path, rows: list[dict[str, Any]], config: StudyConfig) -> None:
    import pyarrow
    import pyarrow.parquet

    columns = ["run", *config.parameter_names, *config.metrics, "error", "error_kind"]
    table = pyarrow.table({name: [row.get(name) for row in rows] for name in columns})
    path.parent.mkdir(parents=True, exist_ok=True)
    with atomic_file(path) as handle:
        pyarrow.parquet.write_table(table, handle)
