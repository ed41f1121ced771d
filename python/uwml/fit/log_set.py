"""The logs a hydrodynamic fit reads (docs/identification.md, "Many logs, and logs larger than
memory"): one or several logs of whole experiments, given as :class:`uwml.io.logs.Log` objects,
files or glob patterns, or one (land, water) pair. Files are read chunk by chunk on every pass
(:func:`uwml.io._log_stream.check_log`: checked as :func:`uwml.io.logs.read_log` checks them,
derivatives estimated as :meth:`uwml.io.logs.Log.with_derivatives` estimates them), so a fit
holds a few chunks of a log at a time, never a whole file; a (land, water) pair is aligned in
memory (:func:`uwml.io.logs.align_logs`), and a file of up to ``STREAM_BYTES`` (64 MiB) is read
whole.
"""

from __future__ import annotations

import glob
import os
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass
from typing import Any

from ..io._log_stream import CheckedLog, _header, check_log
from ..io.logs import Log, _check_file, _layout, _source, align_logs, first_column, log_rows, read_log
from ..io.vehicle_columns import TWIST

#: The largest number of log files one fit takes.
MAX_LOGS = 100_000
#: Files up to this size are read whole (:func:`uwml.io.logs.read_log`, which names a file's
#: first bad cell before anything else); larger ones are read chunk by chunk on every pass.
STREAM_BYTES = 1 << 26


@dataclass(frozen=True)
class _Item:
    """One log: in memory (``log``, with its derivatives) or a file (``path``)."""

    source: str
    n_samples: int
    log: Log | None = None
    #: A file, checked once (its later passes skip the check of its time column).
    file: CheckedLog | None = None


class LogSet:
    """Logs read chunk by chunk, each pass anew (module docstring)."""

    def __init__(self, items: Sequence[_Item]) -> None:
        self.items = tuple(items)

    @property
    def n_samples(self) -> int:
        """Rows of every log together."""
        return sum(item.n_samples for item in self.items)

    @property
    def source(self) -> str:
        """The logs' names, for the result and the messages: one name, or the first and a count."""
        if len(self.items) == 1:
            return self.items[0].source
        return f"{self.items[0].source} and {len(self.items) - 1} more logs"

    def chunks(self, rows: int) -> Iterator[tuple[int, Log]]:
        """``(index of the log, chunk)``, log after log, chunks of at most ``rows`` rows with
        their derivatives; a chunk never spans two logs."""
        for index, item in enumerate(self.items):
            if item.log is not None:
                log = item.log
                for start in range(0, log.n_samples, rows):
                    yield index, log_rows(log, slice(start, start + rows))
            else:
                assert item.file is not None
                for chunk in item.file.chunks(rows):
                    yield index, chunk


def log_set(given: Any, n_joints: int, what: str, torques: bool, wrench: bool, columns: Any = None) -> LogSet:
    """The :class:`LogSet` of a fit's first argument: a :class:`Log`, a file, a glob pattern, a
    list of those (every one a log of the whole experiment), or a (land, water) pair of logs of
    one environment each (a tuple of two), each checked for the joints' torques of both runs
    (``torques``) and the vehicle's wrench and twist (``wrench``). Files are read through the
    column map ``columns`` where given (:mod:`uwml.io.column_map`; each then read whole)."""
    if isinstance(given, tuple):
        if len(given) != 2:
            raise ValueError(f"give one log of the whole experiment or a (land, water) pair of logs, got {len(given)} items")
        land, water = (item if isinstance(item, Log) else read_log(item, n_joints, columns=columns) for item in given)
        for item in (land, water):
            _check_joints(item.source, item.n_joints, n_joints, what)
        log = _with_columns(align_logs(land, water), torques, wrench).with_derivatives()
        return LogSet([_Item(log.source, log.n_samples, log=log)])
    entries = list(given) if isinstance(given, list) else [given]
    if not entries:
        raise ValueError("give at least one log")
    items: list[_Item] = []
    for entry in entries:
        for one in _expanded(entry):
            items.append(_item(one, n_joints, what, torques, wrench, columns))
            if len(items) > MAX_LOGS:
                raise ValueError(f"a fit takes at most {MAX_LOGS} logs")
    return LogSet(items)


def expand_patterns(entries: list[Any]) -> list[Any]:
    """Every entry, glob patterns replaced by their files, sorted (a pattern matching nothing is
    an error)."""
    return [one for entry in entries for one in _expanded(entry)]


def _expanded(entry: Any) -> list[Any]:
    """A glob pattern's files, sorted (none matching is an error); anything else as it is."""
    if isinstance(entry, str) and any(c in entry for c in "*?[") and not os.path.exists(entry):
        matches = sorted(glob.glob(entry, recursive=True))
        if not matches:
            raise ValueError(f"{entry}: no file matches the pattern")
        return matches
    return [entry]


def _item(entry: Any, n_joints: int, what: str, torques: bool, wrench: bool, columns: Any = None) -> _Item:
    """One checked log: in memory with its derivatives, or a file whose header and time column
    are checked now (and every cell when it is read)."""
    if isinstance(entry, Log):
        _check_joints(entry.source, entry.n_joints, n_joints, what)
        log = _with_columns(entry, torques, wrench).with_derivatives()
        return _Item(log.source, log.n_samples, log=log)
    if not isinstance(entry, str | os.PathLike):
        raise TypeError(f"a log must be a uwml.io.logs.Log, a file or a glob pattern, got {type(entry).__name__}")
    source = _source(entry)
    _check_file(entry, source)
    if columns is not None or os.path.getsize(entry) <= STREAM_BYTES:
        return _item(read_log(entry, n_joints, columns=columns), n_joints, what, torques, wrench)
    n, families, _ = _layout(_header(entry, source), n_joints, source)
    _check_joints(source, n, n_joints, what)
    _check_columns(source, set(families).__contains__, torques, wrench)
    checked = check_log(entry, n_joints)  # the header and the time column
    return _Item(source, checked.count, file=checked)


def _check_joints(source: str, n: int, n_joints: int, what: str) -> None:
    if n != n_joints:
        raise ValueError(f"{source}: row 1 (header), column 'q{n}': the log has {n} joints, {what} {n_joints}")


def _with_columns(log: Log, torques: bool, wrench: bool) -> Log:
    """``log``, or a ValueError naming the first column a fit of the joints' rows (``torques``)
    or of the base's (``wrench``) needs and the log lacks."""
    _check_columns(log.source, lambda family: getattr(log, family) is not None, torques, wrench)
    return log


def _check_columns(source: str, has: Callable[[str], bool], torques: bool, wrench: bool) -> None:
    """A ValueError naming the first column family (``has(family)``: whether the log holds it)
    a fit of the joints' rows (``torques``) or of the base's (``wrench``) needs and the log lacks."""
    needs = [("tau_land", "tau_water", "tau")] if torques else []
    needs += [("wrench_land", "wrench_water", "wrench")] if wrench else []
    for land, water, one in needs:
        if not has(land) or not has(water):
            named = [f"{first_column(field)} …" for field in (land, water, one)]
            raise ValueError(
                f"{source}: row 1 (header), column {first_column(land)!r}: need {named[0]} and {named[1]} columns "
                f"(or give a (land, water) pair of logs of one environment each, with {named[2]} columns)"
            )
    if wrench and not has("base_twist"):
        raise ValueError(f"{source}: row 1 (header), column 'u': a fit of the vehicle's wrench needs its twist ({', '.join(TWIST)})")
