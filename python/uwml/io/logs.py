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
vehicle columns       no           the vehicle's pose, twist, wrench and thruster commands
                                   (:mod:`uwml.io.vehicle_columns`: ``x``, ``qw``, ``u``, …)
====================  ===========  =========================================================

The whole schema, the vehicle's included, is docs/logs.md. A file recorded with other names,
signs, offsets, units or several streams is read through a column map (``columns=``,
:mod:`uwml.io.column_map`).

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

Parquet (``.parquet`` files) holds the same columns, of integers or floating point (a boolean,
text or time stamp column is refused). A CSV cell is a decimal number in ASCII digits (``1_0``,
which Python's ``float`` reads as 10, is refused). The vehicle's quaternion is of norm 1 within
``ORIENTATION_TOLERANCE`` (1e-3), checked where it is read. Both formats are read and written with
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
sensor noise; the derivative error it leaves on our walking gait is bounded by a test against the
gait's analytic derivatives.

Errors (``ValueError``) name the file (or ``<stream>``), the row and the column.
"""

from __future__ import annotations

import io
import os
import re
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, replace
from typing import IO, Any

import numpy as np
from numpy.typing import NDArray

from .._checks import shown
from ..domains import MAX_ROBOT_JOINTS
from ..plausibility import check_time_step
from ._file_access import atomic_file, not_regular
from .sampling import (
    MAX_TIME_S,
    POLYORDER,
    UNIFORM_TOLERANCE,
    WINDOW_S,
    _check_time,
    estimate_derivatives,
    estimate_rates,
    savgol_window,
)
from .vehicle_columns import FIELDS, TWIST, is_vehicle_column, orientation, thruster_columns, vehicle_layout

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

#: The joints' column families, in the order they are written (one column per joint).
_JOINT_FAMILIES = ("q", "qd", "qdd", "tau_land", "tau_water", "tau")
#: The vehicle's fields (:mod:`uwml.io.vehicle_columns`), then its thruster commands.
_FAMILIES = (*_JOINT_FAMILIES, *FIELDS, "thruster_commands")
_COLUMN = re.compile(r"^(" + "|".join(sorted(_JOINT_FAMILIES, key=len, reverse=True)) + r")(\d+)$")
#: The environments' pairs of fields: (land, water, one environment).
_PAIRS = (("tau_land", "tau_water", "tau"), ("wrench_land", "wrench_water", "wrench"))


def first_column(field: str) -> str:
    """The first column of a :class:`Log` field, for the messages (``q1``, ``fx_land``, ``u``)."""
    return FIELDS[field][0] if field in FIELDS else "u1" if field == "thruster_commands" else f"{field}1"


@dataclass(frozen=True, eq=False)
class Log:
    """A log (module docstring): arrays of shape ``(n_samples,)`` (time), ``(n_samples,
    n_joints)`` (the joints') and ``(n_samples, 4)`` or ``(n_samples, 6)`` (the base's); absent
    columns are None."""

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
    #: The vehicle's (the base's) orientation, world from body, a quaternion ``(w, x, y, z)``
    #: (columns ``qw, qx, qy, qz``, or ``roll, pitch, yaw`` converted).
    base_orientation: Array | None = None
    #: Its twist ``ν = (u, v, w, p, q, r)`` in body components [m/s, rad/s], and ``ν̇``.
    base_twist: Array | None = None
    base_twist_dot: Array | None = None
    #: The measured wrench on the vehicle (``fx … mz``: force [N], moment about the body origin
    #: [N·m], body components) on land and in water, or of a log of one environment.
    wrench_land: Array | None = None
    wrench_water: Array | None = None
    wrench: Array | None = None
    #: The vehicle's position ``(x, y, z)`` [m], world frame, z up.
    base_position: Array | None = None
    #: Thruster commands ``u1 … un``, ``(n_samples, n_thrusters)``.
    thruster_commands: Array | None = None

    def __post_init__(self) -> None:
        time = np.asarray(self.time, dtype=np.float64)
        q = np.asarray(self.q, dtype=np.float64)
        if time.ndim != 1 or q.ndim != 2 or q.shape[0] != time.shape[0]:
            raise ValueError(f"{self.source}: time must have shape (n,) and q (n, n_joints), got {time.shape} and {q.shape}")
        object.__setattr__(self, "time", time)
        object.__setattr__(self, "q", q)
        shapes = {name: q.shape for name in _JOINT_FAMILIES[1:]} | {name: (q.shape[0], len(c)) for name, c in FIELDS.items()}
        for name in (*shapes, "thruster_commands"):
            value = getattr(self, name)
            if value is not None:
                array = np.asarray(value, dtype=np.float64)
                shape = shapes.get(name, (q.shape[0], array.shape[-1] if array.ndim == 2 and array.shape[-1] >= 1 else 1))
                if array.shape != shape:
                    raise ValueError(f"{self.source}: {name} must have shape {shape}, got {array.shape}")
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
        return self._half(0, "land")

    def water(self) -> Log:
        """The water half of a log of the whole experiment, as a log of one environment."""
        return self._half(1, "water")

    def _half(self, which: int, name: str) -> Log:
        if all(getattr(self, pair[which]) is None for pair in _PAIRS):
            raise ValueError(f"{self.source}: no tau_{name} (or fx_{name} … mz_{name}) columns")
        halves = {pair[2]: getattr(self, pair[which]) for pair in _PAIRS}
        return replace(self, tau_land=None, tau_water=None, wrench_land=None, wrench_water=None, **halves)

    def base_motion(self) -> dict[str, Array]:
        """The vehicle's motion as :class:`uwml.BaseMotion`'s arguments: its orientation
        (normalized; upright where absent) and twist (at rest where absent); a twist needs its
        rate (given, or :meth:`with_derivatives`)."""
        if self.base_twist is not None and self.base_twist_dot is None:
            raise ValueError(f"{self.source}: row 1 (header), column 'u_dot': the twist's rate is missing (estimate it: with_derivatives)")
        if self.base_orientation is None:
            orientation = np.array([1.0, 0.0, 0.0, 0.0])
        else:
            orientation = self.base_orientation / np.linalg.norm(self.base_orientation, axis=1, keepdims=True)
        nu = np.zeros(6) if self.base_twist is None else self.base_twist
        nu_dot = np.zeros(6) if self.base_twist_dot is None else self.base_twist_dot
        return {
            "orientation": orientation,
            "velocity": nu[..., :3],
            "angular_velocity": nu[..., 3:],
            "acceleration": nu_dot[..., :3],
            "angular_acceleration": nu_dot[..., 3:],
        }

    def with_derivatives(self, window_s: float = WINDOW_S, polyorder: int = POLYORDER) -> Log:
        """This log with ``qd`` and ``qdd`` filled in by :func:`estimate_derivatives` where absent,
        and ``base_twist_dot`` by :func:`uwml.io.sampling.estimate_rates` where the twist is given."""
        log = self
        if log.qd is None or log.qdd is None:
            qd, qdd = estimate_derivatives(log.time, log.q, window_s, polyorder, source=log.source)
            log = replace(log, qd=qd if log.qd is None else log.qd, qdd=qdd if log.qdd is None else log.qdd)
        if log.base_twist is not None and log.base_twist_dot is None:
            rates = estimate_rates(log.time, log.base_twist, window_s, polyorder, source=log.source, columns=TWIST)
            log = replace(log, base_twist_dot=rates)
        return log


def log_rows(log: Log, rows: slice) -> Log:
    """The rows ``rows`` of every column of ``log``."""
    fields: dict[str, Any] = {name: getattr(log, name) for name in log.__dataclass_fields__}
    return Log(**{name: value[rows] if hasattr(value, "ndim") else value for name, value in fields.items()})


def align_logs(land: Log, water: Log) -> Log:
    """One log of the whole experiment from a land log and a water log, paired by time.

    The water torques (and the rig's wrenches on the base) are interpolated linearly onto the
    land log's time stamps; land rows outside the water log's time span are dropped. Each log's
    torque is its ``tau`` (or, for a log of the whole experiment, its ``tau_land`` and
    ``tau_water`` respectively); the same for ``wrench``. The motion (joints and base) is the
    land log's.
    """
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
    paired: dict[str, Array] = {}
    for land_name, water_name, one in _PAIRS:
        on_land = getattr(land, one) if getattr(land, one) is not None else getattr(land, land_name)
        in_water = getattr(water, one) if getattr(water, one) is not None else getattr(water, water_name)
        if on_land is None and in_water is None:
            continue
        if on_land is None or in_water is None:
            log, which = (land, "land") if on_land is None else (water, "water")
            what = "torque" if one == "tau" else "wrench"
            raise ValueError(f"{log.source}: row 1 (header), column {first_column(one)!r}: the {which} log has no {what} columns")
        paired[land_name] = on_land[inside]
        paired[water_name] = np.column_stack([np.interp(t, water.time, column) for column in in_water.T])
    if not paired:
        raise ValueError(f"{land.source}: row 1 (header), column 'tau1': the land log has no torque columns")

    def cut(a: Array | None) -> Array | None:
        return None if a is None else a[inside]

    return Log(
        time=t,
        q=land.q[inside],
        qd=cut(land.qd),
        qdd=cut(land.qdd),
        base_orientation=cut(land.base_orientation),
        base_twist=cut(land.base_twist),
        base_twist_dot=cut(land.base_twist_dot),
        base_position=cut(land.base_position),
        thruster_commands=cut(land.thruster_commands),
        source=f"{land.source} + {water.source}",
        **paired,
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


#: A log's fields present, each with the columns of the file it is read from.
Families = dict[str, tuple[str, ...]]


def _layout(header: Sequence[str], n_joints: int | None, source: str) -> tuple[int, Families, list[str]]:
    """Check a log's header: the number of joints, the fields present (in ``_FAMILIES`` order,
    each with its columns) and the names of the columns to read."""
    if n_joints is not None and not (isinstance(n_joints, int | np.integer) and 1 <= n_joints <= MAX_ROBOT_JOINTS):
        raise ValueError(f"n_joints must be 1 to {MAX_ROBOT_JOINTS}, got {n_joints!r}")
    if "time" not in header:
        raise ValueError(f"{source}: row 1 (header), column 'time': missing column{_header_hint(header)}")
    first: dict[str, int] = {}
    present: dict[str, dict[int, str]] = {family: {} for family in _JOINT_FAMILIES}
    for index, name in enumerate(header):
        match = _COLUMN.match(name)
        if name != "time" and not match and not is_vehicle_column(name):
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
    families: Families = {family: tuple(f"{family}{k}" for k in range(1, n + 1)) for family in _JOINT_FAMILIES if present[family]}
    families |= vehicle_layout(header, source)
    thrusters = thruster_columns(header, source)
    if thrusters:
        families["thruster_commands"] = thrusters
    for land, water, one in _PAIRS:
        given = {family for family in (land, water, one) if family in families}
        if given and given not in ({land, water}, {one}):
            name = first_column(water) if water not in given else first_column(land)
            if given == {land, water, one}:
                name = first_column(one)
            columns = [f"{first_column(f)} …" for f in (land, water, one)]
            raise ValueError(
                f"{source}: row 1 (header), column {name!r}: a log carries either {columns[0]} and {columns[1]} (both environments) "
                f"or {columns[2]} (one environment)"
            )
    names = ["time"] + [name for columns in families.values() for name in columns]
    return n, families, names


def _header_hint(header: Sequence[str]) -> str:
    """What a header without ``time`` holds, for the error: its first names, and a word on the
    separator when the names look separated by something else than commas."""
    names = ", ".join(shown(name, 20) for name in header[:6]) + (f", … ({len(header)} columns)" if len(header) > 6 else "")
    hint = f" (the header has {names})"
    if any(";" in name or "\t" in name for name in header[:6]):
        hint += "; columns must be separated by commas"
    return hint


def _from_columns(columns: Mapping[str, Any], n: int, families: Families, source: str) -> Log:
    """A :class:`Log` from checked float64 columns (array-likes, e.g. Arrow columns): the family
    arrays are filled column by column, so that one copy of the data exists at a time besides
    the source columns."""
    time = np.asarray(columns["time"], dtype=np.float64)
    if time.size == 0:
        raise ValueError(f"{source}: row 2, column 'time': no data rows")
    _check_time(time, source)
    if time.size > 1:
        check_time_step(float(np.median(np.diff(time))), source, stacklevel=4)
    return Log(time=time, source=source, **_arrays(columns, families, source, 2))


def _arrays(columns: Mapping[str, Any], families: Families, source: str, first_row: int) -> dict[str, Array]:
    """The fields' arrays of float64 columns (the first row ``first_row`` of the file): the
    orientation as quaternions (Euler angles converted, a quaternion checked)."""
    arrays: dict[str, Array] = {}
    for family, names in families.items():
        out = np.empty((len(columns["time"]), len(names)))
        for k, name in enumerate(names):
            out[:, k] = np.asarray(columns[name], dtype=np.float64)
        arrays[family] = orientation(out, names, source, first_row) if family == "base_orientation" else out
    return arrays


def _parquet_columns(table: Any, names: Sequence[str], source: str, first_row: int = 2) -> dict[str, Any]:
    """The columns of a Parquet table (its first row is ``first_row`` of the file) as float64,
    checked column by column by the cell rule (:func:`uwml.io._arrow_csv.float64_column`). A
    column whose Parquet type is not a number (integers or floating point) is refused: a
    boolean, text or time stamp column is not a log's values."""
    import pyarrow

    from ._arrow_csv import float64_column

    for name in names:
        kind = table.schema.field(name).type
        if not (pyarrow.types.is_integer(kind) or pyarrow.types.is_floating(kind)):
            text = str(kind) if len(str(kind)) <= 40 else f"{str(kind)[:40]}…"
            raise ValueError(f"{source}: column {shown(name)}: Parquet type {text}; a log's columns are integers or floating point")
    return {name: float64_column(table.column(name), name, f"{source}: ", first_row) for name in names}


def open_table(path_or_file: PathOrFile) -> tuple[str, list[str], Callable[[Sequence[str]], dict[str, Any]]]:
    """A recorded file's name, its column names and a reader of named columns as float64 (CSV or
    Parquet by the suffix; the cell rule of :mod:`uwml.io.logs`): one read of the file,
    whatever is asked of it after."""
    source = _source(path_or_file)
    _check_file(path_or_file, source)
    if _is_parquet(path_or_file):
        table = _parquet_table(path_or_file, source)
        return source, list(table.column_names), lambda names: _parquet_columns(table, names, source)
    from ._arrow_csv import CsvTable

    csv_table = CsvTable(path_or_file, f"{source}: ", "time")
    return source, list(csv_table.header), csv_table.read


def read_log(path_or_file: PathOrFile, n_joints: int | None = None, *, columns: Any = None) -> Log:
    """Read and check a log (format in the module docstring).

    Parameters
    ----------
    path_or_file : str, path or text file
        A CSV file (or ``.parquet``), or an open text stream of CSV.
    n_joints : int, optional
        The number of joints the log must have; None: as many as its ``q`` columns.
    columns : path, dict or ColumnMap, optional
        A column map (:mod:`uwml.io.column_map`, docs/logs.md): the file as recorded, its
        columns renamed, signed, offset and scaled, its streams joined on one time base.

    Raises
    ------
    ValueError
        Naming the file, row (header = row 1) and column of the first problem: a missing column,
        a log with another number of joints, an incomplete column family, a column twice, a cell
        that is not a finite number, a row with fewer cells than the header, time not strictly
        increasing or beyond ``±MAX_TIME_S``, text that is not UTF-8; or naming the file alone: no
        such file, a directory, not a Parquet file.
    """
    if columns is not None:
        from .column_map import read_mapped_log

        return read_mapped_log(path_or_file, columns, n_joints)
    source, header, read = open_table(path_or_file)
    n, families, names = _layout(header, n_joints, source)
    return _from_columns(read(names), n, families, source)


def write_log(log: Log, path_or_file: PathOrFile) -> None:
    """Write a log (format in the module docstring): CSV, or Parquet for a ``.parquet`` path.

    Numbers are written in their shortest round-trip form (pyarrow's CSV writer), so
    :func:`read_log` gives the same float64 values back, bit for bit. The header is one line of
    the column names, unquoted. A path is written whole or not at all (a temporary file renamed
    over it): a failed write leaves an existing file as it was.
    """
    names = ["time"]
    columns = [log.time]
    for family in _FAMILIES:
        value = getattr(log, family)
        if value is not None:
            prefix = "u" if family == "thruster_commands" else family
            names += list(FIELDS.get(family, [f"{prefix}{k}" for k in range(1, value.shape[1] + 1)]))
            columns += [value[:, k] for k in range(value.shape[1])]
    if not isinstance(path_or_file, str | os.PathLike):
        buffer = io.BytesIO()
        _write_table(buffer, names, columns, parquet=False)
        path_or_file.write(buffer.getvalue().decode("utf-8"))
        return
    # Whole or not at all: a failed write leaves an existing file as it was.
    with atomic_file(path_or_file) as handle:
        _write_table(handle, names, columns, parquet=_is_parquet(path_or_file))


def _write_table(handle: IO[bytes], names: list[str], columns: list[Array], parquet: bool) -> None:
    """The columns as Parquet or CSV into a binary file."""
    if parquet:
        import pyarrow

        table = pyarrow.table({name: np.ascontiguousarray(column) for name, column in zip(names, columns, strict=True)})
        _parquet().write_table(table, handle)
        return
    from ._arrow_csv import write_table

    write_table(handle, names, columns)
