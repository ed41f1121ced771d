"""Joint logs of the land/water experiment: reading, writing, aligning, differentiating.

The paper identifies Cd and Cm by driving the leg along the same trajectory on land and in
water and taking the difference of the motor torques (docs/model.md section 4; :mod:`uwml.fit`'s
:func:`~uwml.fit.hydro_coefficients`). This module holds such logs.

CSV format
----------
One header row, then one row per sample, in increasing time. Rows are numbered as in a
spreadsheet: the header is row 1, the first sample row 2. Joints are numbered from 1 in the
column names (``q1`` is joint index 0 in Python). Extra columns are ignored.

====================  ===========  =========================================================
column                required     meaning
====================  ===========  =========================================================
``time``              yes          time [s], strictly increasing, within ±``MAX_TIME_S``
``q1`` … ``qN``       yes          joint positions [rad]
``qd1`` … ``qdN``     no           joint velocities [rad/s]; estimated if absent
``qdd1`` … ``qddN``   no           joint accelerations [rad/s²]; estimated if absent
``tau_land1`` …       see below    motor torque on land [N·m]
``tau_water1`` …      see below    motor torque in water [N·m], same trajectory
``tau1`` … ``tauN``   see below    motor torque of a log of one environment [N·m]
====================  ===========  =========================================================

Torques are the **motor's** torque on the joint (what the drive supplies, positive in the
joint's positive direction), not the environment's. A log of the whole experiment carries
both ``tau_land*`` and ``tau_water*`` (one log with both columns, the trajectory run twice
with the same time stamps). Alternatively, two logs of one environment each carry ``tau*``
and :func:`align_logs` pairs them **by time**: the water log's torques are linearly
interpolated (``numpy.interp``) onto the land log's time stamps, and only land rows inside
the water log's time span are kept. The land log's positions (and velocities and
accelerations) describe the trajectory; both runs are assumed to follow it (time zero of both
logs at the same point of the trajectory, e.g. the start of the commanded motion).

A column family must be complete: ``q1`` … ``qN`` all present and no ``q(N+1)``; the same for
each optional family present. With ``n_joints`` given, a log with another number of joints
is an error. Joints are numbered 1 to ``MAX_ROBOT_JOINTS`` (64, the most a :class:`uwml.Robot`
has), without leading zeros; a column of the format (``time``, ``q1``, …) may appear once.

The time column's domain (docs/domains.md): finite, strictly increasing, and within
``±MAX_TIME_S`` = 1e10 s (317 years: Unix time in seconds fits, milli- or nanosecond time
stamps do not; beyond it the squares and cubes of time steps that the derivative estimation
takes overflow float64).

Files: UTF-8 text (a leading byte-order mark, as Excel writes, is skipped), any line endings;
a file that is missing, a directory, not UTF-8 or not Parquet though named ``.parquet`` is a
``ValueError`` naming it.

Parquet (``.parquet`` files) holds the same columns. Both formats are read and written with
``pyarrow`` (a dependency): CSV columns are parsed straight into float64 and written in the
shortest form that reads back to the same float64 (``uwml.io._arrow_csv``); a file that does not
parse is scanned again, slowly, only to name the row and column of its first bad cell.

Derivatives
-----------
If ``qd*`` or ``qdd*`` are absent, :meth:`Log.with_derivatives` (called by the fit) estimates
them from ``q`` with a Savitzky-Golay filter (``scipy.signal.savgol_filter``, ``deriv=1`` and
``2``, ``mode="interp"``, polynomial order 3). **Window rule**: the odd number of samples
closest to ``WINDOW_S = 0.1 s`` of log, ``2·round(WINDOW_S · rate / 2) + 1`` (21 samples
at 200 Hz, 101 at 1 kHz), and at least ``polyorder + 2`` rounded up to odd (5). The sample rate is
``1 / median(Δt)``. Savitzky-Golay assumes uniform sampling: every step must be within 1 %
(``UNIFORM_TOLERANCE``) of the median step, otherwise the error names the first offending row.
Estimated velocities and accelerations that overflow float64 (positions of 1e300 rad changing
every sample) are refused, naming the row and column.
0.1 s is short against the gait's features (a 0.8 s swing) and long enough to average out
sensor noise; the derivative error it leaves on our walking gait is bounded in
``tests/test_identification.py``.

Errors (``ValueError``) name the file (or ``<stream>``), the row and the column.
"""

from __future__ import annotations

import io
import math
import os
import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, replace
from typing import IO, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._checks import shown
from ..domains import MAX_ROBOT_JOINTS
from ._files import not_regular

__all__ = [
    "MAX_ROBOT_JOINTS",
    "MAX_TIME_S",
    "POLYORDER",
    "UNIFORM_TOLERANCE",
    "WINDOW_S",
    "Log",
    "align_logs",
    "estimate_derivatives",
    "read_log",
    "savgol_window",
    "write_log",
]

Array = NDArray[np.float64]
PathOrFile = str | os.PathLike[str] | IO[str]

#: Time covered by the Savitzky-Golay window [s].
WINDOW_S = 0.1
#: Polynomial order of the Savitzky-Golay filter.
POLYORDER = 3
#: Largest relative deviation of a time step from the median step for derivative estimation.
UNIFORM_TOLERANCE = 0.01
#: Largest magnitude of a time stamp [s] (module docstring).
MAX_TIME_S = 1e10
#: Column families, in the order they are written.
_FAMILIES = ("q", "qd", "qdd", "tau_land", "tau_water", "tau")
_COLUMN = re.compile(r"^(q|qd|qdd|tau_land|tau_water|tau)(\d+)$")


@dataclass(frozen=True, eq=False)
class Log:
    """A joint log (module docstring): arrays of shape ``(n_samples,)`` (time) and
    ``(n_samples, n_joints)`` (the rest); absent columns are None."""

    time: Array
    q: Array
    qd: Array | None = None
    qdd: Array | None = None
    #: Motor torques on land and in water (a log of the whole experiment).
    tau_land: Array | None = None
    tau_water: Array | None = None
    #: Motor torque of a log of one environment.
    tau: Array | None = None
    #: Where the log came from (a file name), for error messages.
    source: str = "<log>"

    def __post_init__(self) -> None:
        time = np.asarray(self.time, dtype=np.float64)
        q = np.asarray(self.q, dtype=np.float64)
        if time.ndim != 1 or q.ndim != 2 or q.shape[0] != time.shape[0]:
            raise ValueError(f"{self.source}: time must have shape (n,) and q (n, n_joints), got {time.shape} and {q.shape}")
        object.__setattr__(self, "time", time)
        object.__setattr__(self, "q", q)
        for name in ("qd", "qdd", "tau_land", "tau_water", "tau"):
            value = getattr(self, name)
            if value is not None:
                array = np.asarray(value, dtype=np.float64)
                if array.shape != q.shape:
                    raise ValueError(f"{self.source}: {name} must have the shape of q {q.shape}, got {array.shape}")
                object.__setattr__(self, name, array)

    @property
    def n_samples(self) -> int:
        """Number of samples (rows)."""
        return int(self.time.shape[0])

    @property
    def n_joints(self) -> int:
        """Number of joints."""
        return int(self.q.shape[1])

    def land(self) -> Log:
        """The land half of a log of the whole experiment, as a log of one environment."""
        if self.tau_land is None:
            raise ValueError(f"{self.source}: no tau_land columns")
        return replace(self, tau_land=None, tau_water=None, tau=self.tau_land)

    def water(self) -> Log:
        """The water half of a log of the whole experiment, as a log of one environment."""
        if self.tau_water is None:
            raise ValueError(f"{self.source}: no tau_water columns")
        return replace(self, tau_land=None, tau_water=None, tau=self.tau_water)

    def with_derivatives(self, window_s: float = WINDOW_S, polyorder: int = POLYORDER) -> Log:
        """This log with ``qd`` and ``qdd`` filled in by :func:`estimate_derivatives` where absent."""
        if self.qd is not None and self.qdd is not None:
            return self
        qd, qdd = estimate_derivatives(self.time, self.q, window_s, polyorder, source=self.source)
        return replace(self, qd=qd if self.qd is None else self.qd, qdd=qdd if self.qdd is None else self.qdd)


def savgol_window(rate_hz: float, window_s: float = WINDOW_S, polyorder: int = POLYORDER) -> int:
    """The Savitzky-Golay window [samples] of the module docstring's rule."""
    if not (math.isfinite(rate_hz) and rate_hz > 0.0):
        raise ValueError(f"rate_hz must be finite and > 0, got {rate_hz!r}")
    if not (math.isfinite(window_s) and window_s > 0.0):
        raise ValueError(f"window_s must be finite and > 0, got {window_s!r}")
    window = 2 * round(0.5 * window_s * rate_hz) + 1
    smallest = polyorder + 2 + (polyorder + 2 + 1) % 2
    return max(int(window), smallest)


def estimate_derivatives(
    time: ArrayLike, q: ArrayLike, window_s: float = WINDOW_S, polyorder: int = POLYORDER, *, source: str = "<log>"
) -> tuple[Array, Array]:
    """Velocities and accelerations of ``q`` (shape ``(n, n_joints)``) by a Savitzky-Golay filter.

    Raises
    ------
    ValueError
        Naming the first row (the header is row 1) whose time step is not within
        ``UNIFORM_TOLERANCE`` of the median step, or when the log is shorter than the window.
    """
    t = np.asarray(time, dtype=np.float64)
    positions = np.asarray(q, dtype=np.float64)
    if t.ndim != 1 or positions.ndim != 2 or positions.shape[0] != t.shape[0]:
        raise ValueError(f"{source}: time must have shape (n,) and q (n, n_joints), got {t.shape} and {positions.shape}")
    dt, window = _sampling(t, window_s, polyorder, source)
    qd, qdd = _savgol(positions, window, polyorder, dt)
    _check_derivatives(qd, qdd, source, dt)
    return qd, qdd


def _sampling(t: Array, window_s: float, polyorder: int, source: str) -> tuple[float, int]:
    """The time step [s] and the Savitzky-Golay window [samples] of a log's time column, checked
    as :func:`estimate_derivatives` says."""
    if t.size < 2:
        raise ValueError(f"{source}: row 2, column 'time': need at least 2 samples to estimate derivatives")
    _check_time(t, source)
    step = np.diff(t)
    dt = float(np.median(step))
    bad = np.flatnonzero(~(np.abs(step - dt) <= UNIFORM_TOLERANCE * dt))
    if bad.size:
        i = int(bad[0])
        raise ValueError(
            f"{source}: row {i + 3}, column 'time': non-uniform sampling (step {step[i]:.6g} s, median {dt:.6g} s); "
            "velocities and accelerations are estimated by a Savitzky-Golay filter, which needs uniform sampling: "
            "resample the log, or give qd and qdd columns"
        )
    rate = 1.0 / dt
    if not math.isfinite(rate):  # a subnormal step
        raise ValueError(f"{source}: row 3, column 'time': median time step {dt!r} s, too short to estimate derivatives")
    window = savgol_window(rate, window_s, polyorder)
    if window > t.size:
        count = str(window) if window < 10**9 else f"{float(window):.3g}"
        raise ValueError(
            f"{source}: row {t.size + 1}, column 'time': {t.size} samples, fewer than the Savitzky-Golay window ({count} samples: "
            f"{window_s:g} s at a median time step of {dt:.6g} s)"
        )
    return dt, window


def _savgol(positions: Array, window: int, polyorder: int, dt: float) -> tuple[Array, Array]:
    # Imported here: scipy.signal takes most of a second to import, and `import uwml` should not.
    from scipy.signal import savgol_filter

    # Overflow gives inf (or NaN), refused by _check_derivatives, not a warning.
    with np.errstate(over="ignore", invalid="ignore"):
        qd = savgol_filter(positions, window, polyorder, deriv=1, delta=dt, axis=0, mode="interp")
        qdd = savgol_filter(positions, window, polyorder, deriv=2, delta=dt, axis=0, mode="interp")
    return np.asarray(qd, dtype=np.float64), np.asarray(qdd, dtype=np.float64)


def _check_derivatives(qd: Array, qdd: Array, source: str, dt: float, first_row: int = 2) -> None:
    """Estimated velocities and accelerations finite, or a ValueError naming the first row
    (``first_row`` for the first sample) and the joint's position column."""
    for what, unit, values in (("velocity", "rad/s", qd), ("acceleration", "rad/s²", qdd)):
        bad = np.flatnonzero(~np.isfinite(values).all(axis=1))
        if bad.size:
            i = int(bad[0])
            k = int(np.flatnonzero(~np.isfinite(values[i]))[0])
            raise ValueError(
                f"{source}: row {i + first_row}, column 'q{k + 1}': the estimated {what} [{unit}] is not finite: the positions "
                f"change too much for a time step of {dt:.6g} s"
            )


def align_logs(land: Log, water: Log) -> Log:
    """One log of the whole experiment from a land log and a water log, paired by time.

    The water torques are interpolated linearly onto the land log's time stamps; land rows
    outside the water log's time span are dropped. Each log's torque is its ``tau`` (or, for a
    log of the whole experiment, its ``tau_land`` and ``tau_water`` respectively).
    """
    tau_land = land.tau if land.tau is not None else land.tau_land
    tau_water = water.tau if water.tau is not None else water.tau_water
    if tau_land is None:
        raise ValueError(f"{land.source}: row 1 (header), column 'tau1': the land log has no torque columns")
    if tau_water is None:
        raise ValueError(f"{water.source}: row 1 (header), column 'tau1': the water log has no torque columns")
    if land.n_joints != water.n_joints:
        raise ValueError(
            f"{water.source}: row 1 (header), column 'q{water.n_joints}': the water log has {water.n_joints} joints, "
            f"the land log ({land.source}) {land.n_joints}"
        )
    inside = (land.time >= water.time[0]) & (land.time <= water.time[-1])
    if np.count_nonzero(inside) < 2:
        raise ValueError(
            f"{water.source}: row 2, column 'time': its time span [{water.time[0]:g}, {water.time[-1]:g}] s overlaps "
            f"the land log ({land.source}) in fewer than 2 samples"
        )
    t = land.time[inside]
    interpolated = np.column_stack([np.interp(t, water.time, tau_water[:, j]) for j in range(water.n_joints)])

    def cut(a: Array | None) -> Array | None:
        return None if a is None else a[inside]

    return Log(
        time=t,
        q=land.q[inside],
        qd=cut(land.qd),
        qdd=cut(land.qdd),
        tau_land=tau_land[inside],
        tau_water=interpolated,
        source=f"{land.source} + {water.source}",
    )


# --------------------------------------------------------------------------------------------
# Files
# --------------------------------------------------------------------------------------------


def _source(path_or_file: Any) -> str:
    if isinstance(path_or_file, str | os.PathLike):
        return os.fspath(path_or_file)
    return str(getattr(path_or_file, "name", "<stream>"))


def _is_parquet(path_or_file: Any) -> bool:
    return isinstance(path_or_file, str | os.PathLike) and os.fspath(path_or_file).lower().endswith(".parquet")


def _check_file(path_or_file: Any, source: str) -> None:
    """A path names a file (and a ``.parquet`` path a Parquet file), or a ValueError naming it."""
    if not isinstance(path_or_file, str | os.PathLike):
        return
    if os.path.isdir(path_or_file):
        raise ValueError(f"{source}: is a directory, not a file")
    if not os.path.exists(path_or_file):
        raise ValueError(f"{source}: no such file")
    reason = not_regular(path_or_file)  # a named pipe or device would be waited on, or read forever
    if reason is not None:
        raise ValueError(f"{source}: {reason}; uwml reads regular files only")
    if _is_parquet(path_or_file):
        with open(path_or_file, "rb") as handle:
            head = handle.read(4)
            size = handle.seek(0, os.SEEK_END)
            handle.seek(max(size - 4, 0))
            tail = handle.read(4)
        if size < 12 or head != b"PAR1" or tail != b"PAR1":
            raise ValueError(
                f"{source}: not a Parquet file (it does not begin and end with the bytes PAR1); a CSV log must not be named .parquet"
            )


def _parquet() -> Any:
    import pyarrow.parquet as pq

    return pq


def _parquet_error(exc: Exception, source: str) -> ValueError:
    """A ValueError naming the file for pyarrow's error on a damaged Parquet file."""
    reason = " ".join(str(exc).split())
    reason = reason if len(reason) <= 200 else reason[:200] + "…"
    return ValueError(f"{source}: not a readable Parquet file ({reason})")


def _parquet_table(path: Any, source: str) -> Any:
    """The whole table of a Parquet file, or a ValueError naming it."""
    import pyarrow

    try:
        return _parquet().ParquetFile(path).read()  # not read_table, which refuses a name twice before _layout can say so
    except (pyarrow.ArrowException, OSError) as exc:
        raise _parquet_error(exc, source) from None


def _layout(header: Sequence[str], n_joints: int | None, source: str) -> tuple[int, list[str], list[str]]:
    """Check a log's header: the number of joints, the column families present (in ``_FAMILIES``
    order) and the names of the columns to read."""
    if n_joints is not None and not (isinstance(n_joints, int | np.integer) and 1 <= n_joints <= MAX_ROBOT_JOINTS):
        raise ValueError(f"n_joints must be 1 to {MAX_ROBOT_JOINTS}, got {n_joints!r}")
    if "time" not in header:
        raise ValueError(f"{source}: row 1 (header), column 'time': missing column{_header_hint(header)}")
    first: dict[str, int] = {}
    present: dict[str, dict[int, str]] = {family: {} for family in _FAMILIES}
    for index, name in enumerate(header):
        match = _COLUMN.match(name)
        if name != "time" and not match:
            continue  # an extra column, ignored
        if name in first:
            raise ValueError(
                f"{source}: row 1 (header), column {shown(name)}: the column appears twice (columns {first[name] + 1} and {index + 1})"
            )
        first[name] = index
        if match:
            digits = match.group(2)
            if digits.startswith("0"):
                why = "joints are numbered from 1" if digits.strip("0") == "" else "joint numbers have no leading zero"
                raise ValueError(f"{source}: row 1 (header), column {shown(name)}: {why} ({match.group(1)}1, {match.group(1)}2, …)")
            # Beyond MAX_ROBOT_JOINTS, the exact number does not matter (and int() refuses 4300 digits).
            number = int(digits) if len(digits) <= 6 else 10**6
            present[match.group(1)].setdefault(number, name)
    if not present["q"]:
        raise ValueError(f"{source}: row 1 (header), column 'q1': missing column (joint positions q1 … qN)")
    n = max(present["q"]) if n_joints is None else int(n_joints)
    if n > MAX_ROBOT_JOINTS:
        raise ValueError(
            f"{source}: row 1 (header), column {shown(present['q'][n])}: a log has at most {MAX_ROBOT_JOINTS} joints (the most a robot has)"
        )
    for family, numbers in present.items():
        if not numbers:
            continue
        extra = sorted(k for k in numbers if k > n)
        if extra:
            raise ValueError(f"{source}: row 1 (header), column {shown(numbers[extra[0]])}: the log has more joints than the {n} expected")
        for k in range(1, n + 1):
            if k not in numbers:
                raise ValueError(f"{source}: row 1 (header), column '{family}{k}': missing column (the log has {n} joints)")
    torques = {family for family in ("tau_land", "tau_water", "tau") if present[family]}
    if torques and torques not in ({"tau_land", "tau_water"}, {"tau"}):
        name = "tau_water1" if "tau_water" not in torques else "tau_land1"
        if torques == {"tau_land", "tau_water", "tau"}:
            name = "tau1"
        raise ValueError(
            f"{source}: row 1 (header), column {name!r}: a log carries either tau_land and tau_water (both environments) "
            "or tau (one environment)"
        )
    families = [family for family in _FAMILIES if present[family]]
    names = ["time"] + [f"{family}{k}" for family in families for k in range(1, n + 1)]
    return n, families, names


def _header_hint(header: Sequence[str]) -> str:
    """What a header without ``time`` holds, for the error: its first names, and a word on the
    separator when the names look separated by something else than commas."""
    names = ", ".join(shown(name, 20) for name in header[:6]) + (f", … ({len(header)} columns)" if len(header) > 6 else "")
    hint = f" (the header has {names})"
    if any(";" in name or "\t" in name for name in header[:6]):
        hint += "; columns must be separated by commas"
    return hint


def _check_time(time: Array, source: str, first_row: int = 2) -> None:
    """The time column in its domain (module docstring): finite, within ±MAX_TIME_S, strictly
    increasing, or a ValueError naming the row (``first_row`` for ``time[0]``)."""
    outside = np.flatnonzero(~(np.abs(time) <= MAX_TIME_S))
    if outside.size:
        i = int(outside[0])
        value = float(time[i])
        if not math.isfinite(value):
            raise ValueError(f"{source}: row {i + first_row}, column 'time': expected a finite number, got {value!r}")
        raise ValueError(
            f"{source}: row {i + first_row}, column 'time': {value!r} s is beyond ±{MAX_TIME_S:g} s (317 years): "
            "time must be in seconds (Unix time in seconds fits; milli- or nanosecond stamps do not)"
        )
    bad = np.flatnonzero(np.diff(time) <= 0.0)
    if bad.size:
        i = int(bad[0]) + 1
        raise ValueError(
            f"{source}: row {i + first_row}, column 'time': time must increase strictly ({float(time[i - 1])!r} then {float(time[i])!r})"
        )


def _from_columns(columns: Mapping[str, Any], n: int, families: Sequence[str], source: str) -> Log:
    """A :class:`Log` from checked float64 columns (array-likes, e.g. Arrow columns): the family
    arrays are filled column by column, so that one copy of the data exists at a time besides
    the source columns."""
    time = np.asarray(columns["time"], dtype=np.float64)
    if time.size == 0:
        raise ValueError(f"{source}: row 2, column 'time': no data rows")
    _check_time(time, source)
    arrays: dict[str, Array] = {}
    for family in families:
        out = np.empty((time.size, n))
        for k in range(n):
            out[:, k] = np.asarray(columns[f"{family}{k + 1}"], dtype=np.float64)
        arrays[family] = out
    return Log(time=time, source=source, **arrays)


def _parquet_columns(table: Any, names: Sequence[str], source: str, first_row: int = 2) -> dict[str, Any]:
    """The columns of a Parquet table (its first row is ``first_row`` of the file) as float64,
    checked column by column by the cell rule (:func:`uwml.io._arrow_csv.float64_column`)."""
    from ._arrow_csv import float64_column

    return {name: float64_column(table.column(name), name, f"{source}: ", first_row) for name in names}


def read_log(path_or_file: PathOrFile, n_joints: int | None = None) -> Log:
    """Read and check a log (format in the module docstring).

    Parameters
    ----------
    path_or_file : str, path or text file
        A CSV file (or ``.parquet``), or an open text stream of CSV.
    n_joints : int, optional
        The number of joints the log must have; None: as many as its ``q`` columns.

    Raises
    ------
    ValueError
        Naming the file, row (header = row 1) and column of the first problem: a missing column,
        a log with another number of joints, an incomplete column family, a column twice, a cell
        that is not a finite number, a row with fewer cells than the header, time not strictly
        increasing or beyond ``±MAX_TIME_S``, text that is not UTF-8; or naming the file alone: no
        such file, a directory, not a Parquet file.
    """
    source = _source(path_or_file)
    _check_file(path_or_file, source)
    if _is_parquet(path_or_file):
        table = _parquet_table(path_or_file, source)
        n, families, names = _layout(table.column_names, n_joints, source)
        return _from_columns(_parquet_columns(table, names, source), n, families, source)
    from ._arrow_csv import CsvTable

    csv_table = CsvTable(path_or_file, f"{source}: ", "time")
    n, families, names = _layout(csv_table.header, n_joints, source)
    return _from_columns(csv_table.read(names), n, families, source)


def write_log(log: Log, path_or_file: PathOrFile) -> None:
    """Write a log (format in the module docstring): CSV, or Parquet for a ``.parquet`` path.

    Numbers are written in their shortest round-trip form (pyarrow's CSV writer), so
    :func:`read_log` gives the same float64 values back, bit for bit. The header is one line of
    the column names, unquoted.
    """
    names = ["time"]
    columns = [log.time]
    for family in _FAMILIES:
        value = getattr(log, family)
        if value is not None:
            names += [f"{family}{k}" for k in range(1, log.n_joints + 1)]
            columns += [value[:, k] for k in range(log.n_joints)]
    if _is_parquet(path_or_file):
        import pyarrow

        table = pyarrow.table({name: np.ascontiguousarray(column) for name, column in zip(names, columns, strict=True)})
        _parquet().write_table(table, path_or_file)
        return
    from ._arrow_csv import write_table

    if isinstance(path_or_file, str | os.PathLike):
        with open(path_or_file, "wb") as handle:
            write_table(handle, names, columns)
        return
    buffer = io.BytesIO()
    write_table(buffer, names, columns)
    path_or_file.write(buffer.getvalue().decode("utf-8"))
