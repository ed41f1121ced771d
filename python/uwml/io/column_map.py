"""Column maps: a log read as it was recorded (docs/logs.md, "Recorded files: a column map").

A column map (TOML, or the same as a dict) says which column of the recorded file each uwml
column (:mod:`uwml.io.logs`, :mod:`uwml.io.vehicle_columns`) is, with its sign, offset and unit::

    [time]
    column = "stamp"          # default "time"
    unit = "ms"               # s (default), ms, us, ns
    [joints]
    q1 = { column = "elbow_pos", sign = -1, offset = -3.07 }
    q2 = "wrist_pos"          # a column as it is
    [vehicle]
    x = { column = "pos_n" }
    roll = { column = "roll_deg", unit = "deg" }

Each uwml column is ``sign · scale(unit) · source + offset``: ``sign`` 1 (default) or −1, the
``offset`` in uwml's SI unit (rad, m, s, …; default 0, finite), ``unit`` the source's (the
allowed units depend on the column: ``deg`` for an angle, ``mm`` for a length, …; default the SI
one). The log holds the columns the map names, no others. ``[joints]`` takes the joints'
columns (``q1``, ``qd1``, ``qdd1``, ``tau1``, ``tau_land1``, ``tau_water1``, …), ``[vehicle]`` the
vehicle's (``x`` … ``yaw``, ``u`` … ``r``, ``u_dot`` … ``r_dot``, ``fx`` … ``mz_water``, thruster
commands ``u1`` …).

Streams recorded apart (joint encoders at 500 Hz, motion capture at 100 Hz) are tables of
``[[streams]]``, each with its ``file`` (relative to the map's folder; omitted: the log given),
its ``time``, ``joints`` and ``vehicle``. The first stream's time stamps are the log's; every
other stream is interpolated linearly onto them (:func:`join_streams`: a quaternion kept on one
sign, then normalized; Euler angles turned into a quaternion first), and only the rows inside
every stream's time span are kept.

The map is untrusted input: its names are looked up, never evaluated; an unknown key or
column name is refused with the allowed ones; a source column that the file lacks is refused
naming the file and the column, with what the file has; a non-finite offset is refused.
"""

from __future__ import annotations

import math
import os
import re
import tomllib
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from .._checks import shown
from ..domains import MAX_ROBOT_JOINTS
from ._file_access import clipped, read_regular
from ._model_tables import _Reader
from .logs import Array, Log, PathOrFile, _from_columns, _header_hint, _layout, _source, open_table
from .sampling import _check_time
from .vehicle_columns import EULER, MAX_THRUSTERS, QUATERNION, VEHICLE_COLUMNS, quaternion_from_euler

__all__ = [
    "ColumnMap",
    "ColumnRule",
    "Stream",
    "continuous_quaternion",
    "join_streams",
    "load_column_map",
    "open_table",
    "read_map_streams",
    "read_mapped_log",
    "resample",
]

#: The largest column map read [bytes]; the most streams one has.
MAX_MAP_BYTES = 1 << 20
MAX_STREAMS = 16

_ANGLE = {"rad": 1.0, "deg": math.pi / 180.0}
_LENGTH = {"m": 1.0, "cm": 1e-2, "mm": 1e-3}


def _per(units: dict[str, float], suffix: str) -> dict[str, float]:
    return {f"{name}{suffix}": scale for name, scale in units.items()}


TIME_UNITS = {"s": 1.0, "ms": 1e-3, "us": 1e-6, "ns": 1e-9}
#: The units a uwml column's source may be in, by the column's quantity (the first one: SI).
UNITS: dict[str, dict[str, float]] = {
    "joint position": _ANGLE | _LENGTH,
    "joint velocity": _per(_ANGLE, "/s") | _per(_LENGTH, "/s"),
    "joint acceleration": _per(_ANGLE, "/s2") | _per(_LENGTH, "/s2"),
    "joint torque": {"N*m": 1.0, "N": 1.0},
    "position": _LENGTH,
    "angle": _ANGLE,
    "velocity": _per(_LENGTH, "/s"),
    "angular velocity": _per(_ANGLE, "/s"),
    "acceleration": _per(_LENGTH, "/s2"),
    "angular acceleration": _per(_ANGLE, "/s2"),
    "force": {"N": 1.0, "kN": 1e3},
    "moment": {"N*m": 1.0, "kN*m": 1e3},
    "number": {"1": 1.0},
}
_JOINT = re.compile(r"^(q|qd|qdd|tau|tau_land|tau_water)([1-9]\d{0,5})$")
_JOINT_QUANTITY = {"q": "joint position", "qd": "joint velocity", "qdd": "joint acceleration"}
_THRUSTER = re.compile(r"^u([1-9]\d{0,5})$")


def _quantity(section: str, name: str) -> str | None:
    """The quantity of the uwml column ``name`` of ``[section]``, or None if it is none of its."""
    if section == "joints":
        match = _JOINT.match(name)
        if match is None or int(match.group(2)) > MAX_ROBOT_JOINTS:
            return None
        return _JOINT_QUANTITY.get(match.group(1), "joint torque")
    match = _THRUSTER.match(name)
    if match is not None:
        return "number" if int(match.group(1)) <= MAX_THRUSTERS else None
    if name not in VEHICLE_COLUMNS:
        return None
    base = name.removesuffix("_dot").removesuffix("_land").removesuffix("_water")
    rate = name.endswith("_dot")
    if base in ("x", "y", "z"):
        return "position"
    if base in EULER:
        return "angle"
    if base in QUATERNION:
        return "number"
    if base in ("u", "v", "w"):
        return "acceleration" if rate else "velocity"
    if base in ("p", "q", "r"):
        return "angular acceleration" if rate else "angular velocity"
    return "force" if base.startswith("f") else "moment"


@dataclass(frozen=True)
class ColumnRule:
    """One uwml column: ``sign · scale · source column + offset``."""

    target: str
    column: str
    sign: float = 1.0
    offset: float = 0.0
    scale: float = 1.0


@dataclass(frozen=True)
class Stream:
    """One recorded file of a map (``file`` None: the log given) and its columns."""

    file: str | None
    time: ColumnRule
    rules: tuple[ColumnRule, ...]


@dataclass(frozen=True)
class ColumnMap:
    """A checked column map (module docstring): its streams, and where it came from."""

    streams: tuple[Stream, ...]
    source: str = "<columns>"
    folder: str = "."

    @property
    def targets(self) -> list[str]:
        """The uwml columns the map gives, ``time`` first."""
        return ["time"] + [rule.target for stream in self.streams for rule in stream.rules]


def _number(value: Any) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise TypeError(f"not a number ({type(value).__name__})")
    number = float(value)
    if not math.isfinite(number):
        raise ValueError("not finite")
    return number


def _sign(value: Any) -> float:
    number = _number(value)
    if number not in (1.0, -1.0):
        raise ValueError("neither 1 nor -1")
    return number


def _text(value: Any) -> str:
    if not isinstance(value, str) or not value or len(value) > 200:
        raise TypeError("not a string of 1 to 200 characters")
    return value


def _rule(source: str, where: str, target: str, entry: Any, units: dict[str, float], default_column: str | None = None) -> ColumnRule:
    """A column's rule from its entry: a column's name, or a table."""
    if isinstance(entry, str) and default_column is None:
        entry = {"column": entry}
    r = _Reader(source, where, entry, ValueError)
    r.check_keys(("column", "sign", "offset", "unit") if default_column is None else ("column", "unit", "offset"))
    what = "the recorded file's column (a string)"
    column = (
        r.get("column", _text, what) if default_column is None else r.get("column", _text, what, required=False, default=default_column)
    )
    sign = 1.0 if default_column is not None else r.get("sign", _sign, "1 or -1", required=False, default=1.0)
    offset = r.get("offset", _number, "a finite number, in uwml's unit", required=False, default=0.0)
    unit = r.get("unit", _text, f"one of {', '.join(units)}", required=False, default=next(iter(units)))
    if unit not in units:
        r.fail("unit", f"{shown(unit, 40)} is not a unit of {target} (allowed: {', '.join(units)})")
    return ColumnRule(target, column, sign, offset, units[unit])


def _stream(source: str, label: str, table: Any, keys: Sequence[str]) -> Stream:
    """A stream's rules; ``label``: ``""`` (the map's top level) or ``"[[streams]] 2, "``."""
    r = _Reader(source, label.removesuffix(", ") or "top level", table, ValueError)
    r.check_keys(keys)
    file = r.get("file", _text, "the stream's file (a string)", required=False)
    time_table: Any = r.get("time", lambda t: t, "a table", required=False, default={})
    time = _rule(source, f"{label}[time]", "time", time_table, TIME_UNITS, default_column="time")
    rules: list[ColumnRule] = []
    for section in ("joints", "vehicle"):
        entries: Any = r.get(section, lambda t: t, "a table", required=False, default={})
        at = f"{label}[{section}]"
        if not isinstance(entries, dict):
            r.fail(section, f"must be a table, got {type(entries).__name__}")
        for target, entry in entries.items():
            quantity = _quantity(section, target)
            if quantity is None:
                allowed = (
                    "q1 … q64, qd1 …, qdd1 …, tau1 …, tau_land1 …, tau_water1 …"
                    if section == "joints"
                    else "x, y, z, qw, qx, qy, qz, roll, pitch, yaw, u, v, w, p, q, r, u_dot … r_dot, fx, fy, fz, mx, my, mz, "
                    f"fx_land … mz_land, fx_water … mz_water, u1 … u{MAX_THRUSTERS} (thruster commands)"
                )
                raise ValueError(f"{source}: {at}: {shown(target, 40)} is not a uwml column of [{section}] (allowed: {allowed})")
            rules.append(_rule(source, f"{at} {target}", target, entry, UNITS[quantity]))
    return Stream(file, time, tuple(rules))


def load_column_map(given: Any) -> ColumnMap:
    """A checked :class:`ColumnMap` of a TOML file (a path), a dict of its tables, or a
    :class:`ColumnMap`; a ValueError naming the map, the table and the key."""
    if isinstance(given, ColumnMap):
        return given
    if isinstance(given, str | os.PathLike):
        source = os.fspath(given)
        data = read_regular(given, "column map")
        if len(data) > MAX_MAP_BYTES:
            raise ValueError(f"{source}: a column map is at most {MAX_MAP_BYTES} bytes, got {len(data)}")
        try:
            document: Any = tomllib.loads(data.decode("utf-8"))
        except UnicodeDecodeError:
            raise ValueError(f"{source}: not UTF-8 text") from None
        except (ValueError, RecursionError) as exc:  # tomllib.TOMLDecodeError is a ValueError
            raise ValueError(f"{source}: not valid TOML: {clipped(str(exc))}") from None
        folder = os.path.dirname(os.path.abspath(source))
    elif isinstance(given, Mapping):
        source, document, folder = "<columns>", dict(given), os.getcwd()
    else:
        raise TypeError(f"columns must be a column map's path, a dict or a ColumnMap, got {type(given).__name__}")
    top = _Reader(source, "top level", document, ValueError)
    if "streams" not in document:
        top.check_keys(("time", "joints", "vehicle", "streams"))
        return _checked(ColumnMap((_stream(source, "", document, ("time", "joints", "vehicle")),), source, folder))
    top.check_keys(("streams",))
    streams = document["streams"]
    if not isinstance(streams, list) or not 1 <= len(streams) <= MAX_STREAMS:
        top.fail("streams", f"must be 1 to {MAX_STREAMS} tables [[streams]]")
    keys = ("file", "time", "joints", "vehicle")
    return _checked(ColumnMap(tuple(_stream(source, f"[[streams]] {k + 1}, ", s, keys) for k, s in enumerate(streams)), source, folder))


def _checked(column_map: ColumnMap) -> ColumnMap:
    """The map, or a ValueError: a uwml column given twice, two streams reading the log given."""
    seen: set[str] = set()
    for stream in column_map.streams:
        for rule in stream.rules:
            if rule.target in seen:
                raise ValueError(f"{column_map.source}: {rule.target!r} is given by two streams")
            seen.add(rule.target)
    if sum(stream.file is None for stream in column_map.streams) > 1:
        raise ValueError(f"{column_map.source}: several streams without a file (at most one reads the log given)")
    return column_map


def _read_stream(stream: Stream, path_or_file: PathOrFile, map_source: str) -> tuple[str, Array, dict[str, Array]]:
    """A stream's file, time [s] and uwml columns (Euler angles as a quaternion)."""
    source, header, read = open_table(path_or_file)
    present = set(header)
    for rule in (stream.time, *stream.rules):
        if rule.column not in present:
            raise ValueError(
                f"{source}: row 1 (header), column {shown(rule.column)}: no such column (the column map {map_source} reads "
                f"{rule.target} from it){_header_hint(header)}"
            )
    names = list(dict.fromkeys(rule.column for rule in (stream.time, *stream.rules)))
    raw = {name: np.asarray(values, dtype=np.float64) for name, values in read(names).items()}
    with np.errstate(over="ignore", invalid="ignore"):
        time = stream.time.scale * raw[stream.time.column] + stream.time.offset
        columns = {rule.target: rule.sign * (rule.scale * raw[rule.column]) + rule.offset for rule in stream.rules}
    _check_time(time, source)
    for rule in stream.rules:
        bad = np.flatnonzero(~np.isfinite(columns[rule.target]))
        if bad.size:
            raise ValueError(
                f"{source}: row {int(bad[0]) + 2}, column {shown(rule.column)}: {rule.target} of it is not finite (the column map's sign, "
                "unit and offset)"
            )
    return source, time, columns


def resample(time: Array, stream_time: Array, columns: Mapping[str, Array]) -> dict[str, Array]:
    """``columns`` sampled at ``stream_time``, linearly interpolated at ``time`` (inside its
    span): a quaternion (``qw, qx, qy, qz``) kept on one sign before (q and −q are one turn) and
    normalized after; Euler angles (``roll, pitch, yaw``) turned into that quaternion first."""
    values = dict(columns)
    if all(name in values for name in EULER):
        quaternion = quaternion_from_euler(np.column_stack([values.pop(name) for name in EULER]))
        values |= {name: quaternion[:, k] for k, name in enumerate(QUATERNION)}
    out = {name: np.interp(time, stream_time, column) for name, column in values.items() if name not in QUATERNION}
    if all(name in values for name in QUATERNION):
        quaternion = continuous_quaternion(np.column_stack([values[name] for name in QUATERNION]))
        at = np.column_stack([np.interp(time, stream_time, quaternion[:, k]) for k in range(4)])
        at /= np.linalg.norm(at, axis=1, keepdims=True)
        out |= {name: at[:, k] for k, name in enumerate(QUATERNION)}
    return out


def continuous_quaternion(quaternion: Array) -> Array:
    """Each quaternion on the sign nearest the one before it (q and −q are the same turn), so that
    interpolation between samples follows the turn, not a sign flip."""
    dots = np.einsum("ij,ij->i", quaternion[1:], quaternion[:-1])
    signs = np.concatenate([[1.0], np.where(dots < 0.0, -1.0, 1.0)])
    return np.asarray(quaternion * np.cumprod(signs)[:, None], dtype=np.float64)


def join_streams(streams: Sequence[tuple[str, Array, Mapping[str, Array]]]) -> tuple[Array, dict[str, Array]]:
    """Streams ``(name, time, columns)`` on the first one's time stamps (module docstring): its
    rows inside every stream's time span, as a boolean mask, and every stream's columns on
    them (the first's as they are, the others by :func:`resample`). Fewer than 2 rows in
    common is an error naming the streams."""
    first_name, time, first = streams[0]
    inside = np.ones(time.shape, dtype=bool)
    for _, other, _ in streams[1:]:
        inside &= (time >= other[0]) & (time <= other[-1])
    if np.count_nonzero(inside) < 2:
        names = ", ".join(name for name, _, _ in streams)
        raise ValueError(f"{names}: the streams share fewer than 2 of {first_name}'s time stamps: nothing to join")
    joined = {name: np.asarray(column)[inside] for name, column in first.items()}
    for _, other, columns in streams[1:]:
        joined |= resample(time[inside], other, columns)
    return inside, joined


def _same(path_or_file: Any, path: str) -> bool:
    """Whether ``path_or_file`` is the file ``path``."""
    try:
        return isinstance(path_or_file, str | os.PathLike) and os.path.samefile(path_or_file, path)
    except OSError:
        return False


def read_map_streams(path_or_file: PathOrFile | None, columns: Any) -> tuple[ColumnMap, list[tuple[str, Array, dict[str, Array]]]]:
    """The checked map of ``columns`` and its streams as recorded, each ``(file name, time [s],
    uwml columns)`` with every row of its file (not joined: :func:`join_streams` does that);
    a stream without a file reads ``path_or_file``."""
    column_map = load_column_map(columns)
    files = [os.path.join(column_map.folder, stream.file) for stream in column_map.streams if stream.file is not None]
    if path_or_file is not None and len(files) == len(column_map.streams) and not any(_same(path_or_file, f) for f in files):
        raise ValueError(
            f"{column_map.source}: every stream names its file, and the log given ({_source(path_or_file)}) is none of them: "
            "leave out the file of its stream"
        )
    read: list[tuple[str, Array, dict[str, Array]]] = []
    for stream in column_map.streams:
        if stream.file is None:
            if path_or_file is None:
                raise ValueError(f"{column_map.source}: a stream without a file reads the log given, and none was")
            target: PathOrFile = path_or_file
        else:
            target = os.path.join(column_map.folder, stream.file)
        read.append(_read_stream(stream, target, column_map.source))
    return column_map, read


def read_mapped_log(path_or_file: PathOrFile | None, columns: Any, n_joints: int | None = None) -> Log:
    """The log of a recorded file (or of several streams) read through the column map
    ``columns`` (module docstring), checked as :func:`uwml.io.logs.read_log` checks a log."""
    column_map, read = read_map_streams(path_or_file, columns)
    names = " + ".join(name for name, _, _ in read)
    source = f"{names} (through {column_map.source})"
    if len(read) == 1:
        _, time, values = read[0]
    else:
        inside, values = join_streams(read)
        time = read[0][1][inside]
    canonical = {"time": time} | values
    n, families, names_read = _layout(list(canonical), n_joints, source)
    return _from_columns({name: canonical[name] for name in names_read}, n, families, source)
