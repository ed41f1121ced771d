"""A log read in chunks of rows, in bounded memory, for ``uwml torques`` and the fits.

:func:`log_chunks` checks the log as :func:`uwml.io.logs.read_log` does and yields it as
:class:`~uwml.io.logs.Log` chunks of ``rows`` rows (the last one shorter) with ``qd`` and ``qdd``,
the same values :meth:`~uwml.io.logs.Log.with_derivatives` gives the whole log:

* A first pass reads the time column alone: the number of rows, time strictly increasing, and,
  when ``qd`` or ``qdd`` are absent, the sampling checks and the median step of
  :func:`~uwml.io.logs.estimate_derivatives`. Errors in the header or the time column are raised
  by the call, before any chunk.
* A second pass reads the columns block by block (pyarrow's streaming CSV reader, or the row
  groups of a Parquet file). A bad cell raises when its block is reached, naming its row and
  column, after the chunks before it.
* Estimated derivatives: each chunk is filtered together with the ``window`` rows before and
  after it, and only its own rows are kept. Rows farther than half a window from a segment's
  ends see the same samples and coefficients as in the whole log; the log's first and last
  ``window`` rows are in the segments that start and end with the log, so the end fits
  (``mode="interp"``) are the whole log's too.

Memory: a few chunks and pyarrow's blocks, whatever the length of the log; when derivatives are
estimated, also the time column (8 bytes a row), for the median step.
"""

from __future__ import annotations

import os
from collections.abc import Iterator, Sequence
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from .logs import (
    Array,
    Families,
    Log,
    _arrays,
    _check_file,
    _is_parquet,
    _layout,
    _parquet,
    _parquet_columns,
    _parquet_error,
    _source,
)
from .sampling import POLYORDER, WINDOW_S, _check_derivatives, _check_time, _sampling, _savgol
from .vehicle_columns import TWIST


def _blocks(path: str | os.PathLike[str], names: Sequence[str], source: str) -> Iterator[dict[str, Array]]:
    """The checked columns ``names`` of a log file, block by block."""
    if _is_parquet(path):
        import pyarrow

        row = 2
        batches = iter(_parquet_file(path, source).iter_batches(columns=list(names)))
        while True:
            try:
                batch = next(batches, None)
            except (pyarrow.ArrowException, OSError) as exc:  # a damaged page
                raise _parquet_error(exc, source) from None
            if batch is None:
                return
            table = pyarrow.Table.from_batches([batch])
            yield {name: np.asarray(column, dtype=np.float64) for name, column in _parquet_columns(table, names, source, row).items()}
            row += batch.num_rows
    from . import _arrow_csv

    yield from _arrow_csv.CsvTable(path, f"{source}: ", "time").batches(names)


def _parquet_file(path: str | os.PathLike[str], source: str) -> Any:  # pyarrow has no type information
    """A ``pyarrow.parquet.ParquetFile``, or a ValueError naming a damaged file."""
    import pyarrow

    try:
        return _parquet().ParquetFile(path)
    except (pyarrow.ArrowException, OSError) as exc:
        raise _parquet_error(exc, source) from None


def _header(path: str | os.PathLike[str], source: str) -> list[str]:
    _check_file(path, source)
    if _is_parquet(path):
        names: list[str] = list(_parquet_file(path, source).schema_arrow.names)
        return names
    from ._arrow_csv import CsvTable

    return CsvTable(path, f"{source}: ", "time").header


def _rechunk(blocks: Iterator[dict[str, Array]], rows: int) -> Iterator[dict[str, Array]]:
    """Blocks of any length as chunks of exactly ``rows`` rows (the last one shorter)."""
    pending: list[dict[str, Array]] = []
    count = 0
    for block in blocks:
        pending.append(block)
        count += len(block["time"])
        while count >= rows:
            joined = {name: np.concatenate([b[name] for b in pending]) for name in block}
            yield {name: values[:rows] for name, values in joined.items()}
            rest = {name: values[rows:] for name, values in joined.items()}
            count -= rows
            pending = [rest] if count else []
    if count:
        yield {name: np.concatenate([b[name] for b in pending]) for name in pending[0]}


def _logs(chunks: Iterator[dict[str, Array]], families: Families, source: str) -> Iterator[Log]:
    """The chunks as logs (:func:`uwml.io.logs._arrays`: the orientation checked, row by row of
    the file, or converted from Euler angles)."""
    row = 2
    for chunk in chunks:
        yield Log(time=chunk["time"], source=source, **_arrays(chunk, families, source, row))
        row += len(chunk["time"])


@dataclass(frozen=True)
class CheckedLog:
    """What the first pass over a log file found (:func:`check_log`): its rows, joints, column
    families and names, and the sampling (time step, Savitzky-Golay window) where derivatives
    are estimated."""

    path: str | os.PathLike[str]
    source: str
    count: int
    n_joints: int
    families: Families
    names: list[str]
    sampling: tuple[float, int] | None
    polyorder: int

    def chunks(self, rows: int = 100_000) -> Iterator[Log]:
        """The log's chunks of ``rows`` rows, read anew (module docstring)."""
        if rows < 1:
            raise ValueError(f"rows must be >= 1, got {rows!r}")
        chunks = _logs(_rechunk(_blocks(self.path, self.names, self.source), rows), self.families, self.source)
        if self.sampling is None:
            yield from chunks
        else:
            yield from _with_derivatives(chunks, self.n_joints, self.families, self.source, self.sampling, self.polyorder)


def check_log(
    path: str | os.PathLike[str], n_joints: int | None = None, window_s: float = WINDOW_S, polyorder: int = POLYORDER
) -> CheckedLog:
    """The first pass over a log file (module docstring): its header and time column checked."""
    source = _source(path)
    n, families, names = _layout(_header(path, source), n_joints, source)
    estimate = "qd" not in families or "qdd" not in families or ("base_twist" in families and "base_twist_dot" not in families)
    count, last = 0, np.empty(0)
    times: list[Array] = []
    for block in _blocks(path, ["time"], source):
        time = block["time"]
        _check_time(np.concatenate([last, time]), source, first_row=count + 2 - last.size)
        if estimate:
            times.append(time)
        count += time.size
        last = time[-1:] if time.size else last
    if count == 0:
        raise ValueError(f"{source}: row 2, column 'time': no data rows")
    sampling = _sampling(np.concatenate(times), window_s, polyorder, source) if estimate else None
    return CheckedLog(path, source, count, n, families, names, sampling, polyorder)


def log_chunks(
    path: str | os.PathLike[str], n_joints: int | None = None, rows: int = 100_000, window_s: float = WINDOW_S, polyorder: int = POLYORDER
) -> tuple[int, int, Iterator[Log]]:
    """A log file checked and cut into chunks (module docstring): ``(n_samples, n_joints, chunks)``."""
    if rows < 1:
        raise ValueError(f"rows must be >= 1, got {rows!r}")
    checked = check_log(path, n_joints, window_s, polyorder)
    return checked.count, checked.n_joints, checked.chunks(rows)


def _with_derivatives(
    chunks: Iterator[Log], n: int, families: Families, source: str, sampling: tuple[float, int], polyorder: int
) -> Iterator[Log]:
    """Chunks with qd and qdd estimated over overlapping segments (module docstring)."""
    dt, window = sampling
    width = n + (6 if "base_twist" in families and "base_twist_dot" not in families else 0)
    before = np.empty((0, width))  # the last `window` positions (and twists) yielded (all while fewer)

    def _values(log: Log) -> Array:
        return np.concatenate([log.q, log.base_twist], axis=1) if width > n and log.base_twist is not None else log.q

    pending: list[Log] = []
    done = 0  # rows yielded

    def emit(log: Log, after: list[Log]) -> Log:
        nonlocal before, done
        ahead = np.concatenate([_values(a) for a in after], axis=0)[:window] if after else np.empty((0, before.shape[1]))
        # The joints' positions and, where its derivative is absent, the base's twist, filtered
        # together (one window, one step).
        twist = log.base_twist is not None and log.base_twist_dot is None
        values = np.concatenate([log.q, log.base_twist], axis=1) if twist and log.base_twist is not None else log.q
        segment = np.concatenate([before, values, ahead], axis=0)
        first, second = _savgol(segment, window, polyorder, dt)
        rows = slice(before.shape[0], before.shape[0] + log.n_samples)
        qd, qdd = first[rows, :n], second[rows, :n]
        _check_derivatives(qd, qdd, source, dt, first_row=done + 2)
        if twist:
            rates = first[rows, n:]
            if not np.all(np.isfinite(rates)):
                i = int(np.flatnonzero(~np.isfinite(rates).all(axis=1))[0])
                k = int(np.flatnonzero(~np.isfinite(rates[i]))[0])
                raise ValueError(
                    f"{source}: row {done + i + 2}, column {TWIST[k]!r}: its estimated rate is not finite for a time step of {dt:.6g} s"
                )
        before = np.concatenate([before, values], axis=0)[-window:]
        done += log.n_samples
        return replace(
            log,
            qd=log.qd if log.qd is not None else qd,
            qdd=log.qdd if log.qdd is not None else qdd,
            base_twist_dot=first[rows, n:] if twist else log.base_twist_dot,
        )

    for chunk in chunks:
        pending.append(chunk)
        while len(pending) > 1 and sum(p.n_samples for p in pending[1:]) >= window:
            yield emit(pending[0], pending[1:])
            pending.pop(0)
    while pending:
        yield emit(pending[0], pending[1:])
        pending.pop(0)
