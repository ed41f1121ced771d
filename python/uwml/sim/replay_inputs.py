"""A replay's log, read and cleaned before it is simulated (:mod:`uwml.sim.replay`; the rules are
docs/simulation.md's, "Replaying a pool trial"): the streams joined on time, gaps checked, the
joints' repeated samples collapsed and their motion smoothed, the vehicle's start state estimated.

Streams
-------
One file holds the joint angles (``q1`` … ``qN``); at most one holds the vehicle's pose (``x``,
``y``, ``z`` and ``qw``, ``qx``, ``qy``, ``qz`` or ``roll``, ``pitch``, ``yaw``) and at most one
the thruster commands (``u1`` … ``un``), the same file or others with their own ``time``; or the
streams of a column map (:func:`uwml.io.column_map.read_map_streams`, each file's columns named,
signed, offset and scaled into the schema's). Each is read and checked as
:func:`uwml.io.logs.read_log` reads a log (groups complete, Euler angles turned into a
quaternion, a quaternion of norm 1). The pose is resampled linearly onto the joint stream's time
stamps (:func:`uwml.io.column_map.resample`: the quaternion's sign kept continuous, then
normalized); the commands are kept as recorded, to be held sample to sample
(:mod:`uwml.sim.replay`); only the span every stream covers is replayed (:func:`read_streams`).

Gaps
----
A step longer than ``max_gap`` (default ``MAX_GAP_S``, 0.1 s) between two joint samples of the
replayed span is refused, naming its rows: the joints are prescribed, and a motion made up across
a gap would push the vehicle. Gaps in a separate pose stream are bridged by its linear
interpolation, whatever their length: the pose only sets the start and is compared with the
simulation (:attr:`Streams.bridged` counts those longer than ``max_gap``).

Joint motion
------------
Without ``qd*`` and ``qdd*`` columns, the joints' velocities and accelerations come from a
smoothing fit, never from differencing raw samples (:func:`joint_motion`):

1. **Repeated samples collapsed.** A logger that writes the same value 2–3 times in a row
   (faster than the encoder it reads) makes a staircase whose spline has accelerations of
   thousands of rad/s². In each joint, a run of identical values spanning less than the
   smoothing window keeps only its first sample (the time the value was new), and the stream's
   last sample; a longer run is a joint at rest and keeps its first and last samples.
2. **Resampled** linearly onto a uniform grid at the joint stream's median time step.
3. **Smoothed** by a Savitzky-Golay filter (``scipy.signal.savgol_filter``, polynomial order
   3, ``mode="interp"``) over the smoothing window (default ``SMOOTHING_S``, 0.1 s, the window
   rule of :mod:`uwml.io.logs`, "Derivatives"): the angles, their rates and accelerations.

A joint whose smoothed acceleration still exceeds ``PLAUSIBLE_ANGULAR_ACCELERATION`` (500
rad/s²; a prismatic joint ``PLAUSIBLE_LINEAR_ACCELERATION``, 50 m/s²) is named in a
:class:`uwml.PlausibilityWarning`. Columns the log gives (``qd*``, ``qdd*``) are used as given.

Start state
-----------
The vehicle starts at its measured pose at the replay's first time ``t0``, with the twist
(MuJoCo's free joint: world-frame velocity, body-frame angular velocity) of a least-squares fit
of the pose samples within ``[t0, t0 + START_WINDOW_S]`` (0.5 s by default) against time
(:func:`start_state`): position, and the rotation vector of ``q(t0)⁻¹ ⊗ q(t)`` (orientation
linearized about the start, body frame), each a polynomial of degree ``START_DEGREE`` (3) in
time (fewer with fewer samples), whose slope at ``t0`` is the twist. On the BlueROV2 example,
swinging at up to 0.25 rad/s as its arm waves, a cubic over 0.5 s of 100 Hz poses is off by 4e-3
rad/s from the true twist and spreads by 0.016 rad/s under motion-capture noise of 0.1° (0.5 mm:
5e-3 m/s); a quadratic is off by 0.025 rad/s and spreads by 7e-3 rad/s. ``at_rest`` (``--start-at-rest``) starts it with zero twist;
without a measured pose it starts at rest at the origin, level.

Errors (:class:`uwml.UwmlError`, a ``ValueError``) name the file, the row (the header is row 1)
and the column, and what is allowed.
"""

from __future__ import annotations

import math
import os
import warnings
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..domains import MAX_LENGTH
from ..errors import UwmlError
from ..io.column_map import continuous_quaternion, open_table, read_map_streams, resample
from ..io.logs import Log, _arrays, _from_columns, _header_hint, _layout, log_rows
from ..io.sampling import POLYORDER, WINDOW_S, _check_time, savgol_window
from ..io.vehicle_columns import POSITION, QUATERNION, thruster_columns, vehicle_layout
from ..plausibility import PlausibilityWarning

__all__ = [
    "MAX_GAP_S",
    "PLAUSIBLE_ANGULAR_ACCELERATION",
    "PLAUSIBLE_LINEAR_ACCELERATION",
    "SMOOTHING_S",
    "START_DEGREE",
    "START_WINDOW_S",
    "JointMotion",
    "StartState",
    "Streams",
    "collapse_repeats",
    "joint_motion",
    "read_streams",
    "read_vehicle_pose",
    "start_fit",
    "start_state",
]

FloatArray = NDArray[np.float64]
LogPaths = str | os.PathLike[str] | Sequence[str | os.PathLike[str]]
#: A recorded file: its name, its column names and a reader of named columns.
Table = tuple[str, list[str], Callable[[Sequence[str]], dict[str, Any]]]

#: The longest step between two joint samples of a replayed log [s] unless chosen (``max_gap``).
MAX_GAP_S = 0.1
#: The joints' smoothing window [s] unless chosen (``smoothing``): the log reader's window.
SMOOTHING_S = WINDOW_S
#: The window of pose samples the start twist is fitted over [s] unless chosen (``start_window``).
START_WINDOW_S = 0.5
#: The degree of the polynomials in time fitted to the start window's poses.
START_DEGREE = 3
#: A revolute joint's smoothed acceleration beyond this [rad/s²] is warned about.
PLAUSIBLE_ANGULAR_ACCELERATION = 500.0
#: A prismatic joint's smoothed acceleration beyond this [m/s²] is warned about.
PLAUSIBLE_LINEAR_ACCELERATION = 50.0


def _seconds(value: float, name: str) -> float:
    """``value`` [s], checked finite and > 0, or a ValueError naming the option."""
    if isinstance(value, bool) or not isinstance(value, (int, float, np.floating, np.integer)) or not (math.isfinite(value) and value > 0):
        raise ValueError(f"{name} must be a finite number of seconds > 0, got {value!r}")
    return float(value)


def _euler(quaternion: FloatArray) -> FloatArray:
    w, x, y, z = quaternion.T
    roll = np.arctan2(2.0 * (w * x + y * z), 1.0 - 2.0 * (x * x + y * y))
    pitch = np.arcsin(np.clip(2.0 * (w * y - z * x), -1.0, 1.0))
    yaw = np.arctan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z))
    return np.stack([roll, pitch, yaw], axis=1)


def _tables(logs: LogPaths, columns: Any) -> list[Table]:
    """The replay's recorded files, each ``(name, header, reader of named columns)``: the files
    ``logs`` as they are (:func:`uwml.io.column_map.open_table`), or the streams of the column map
    ``columns`` (:func:`uwml.io.column_map.read_map_streams`), their uwml columns and time [s]
    read through it, named ``FILE (through MAP)``."""
    paths = [logs] if isinstance(logs, (str, os.PathLike)) else list(logs)
    if columns is None:
        if not paths:
            raise ValueError("replay needs a log")
        return [open_table(path) for path in paths]
    if len(paths) > 1:
        raise ValueError(
            f"with a column map, replay reads one log (the map's stream without a file) and the files its [[streams]] name, "
            f"got {len(paths)}: {[str(p) for p in paths]}"
        )
    column_map, streams = read_map_streams(paths[0] if paths else None, columns)
    tables: list[Table] = []
    for name, time, values in streams:
        table = {"time": time} | values
        tables.append((f"{name} (through {column_map.source})", list(table), _reader(table)))
    return tables


def _reader(table: dict[str, FloatArray]) -> Callable[[Sequence[str]], dict[str, Any]]:
    """The reader of named columns of a stream already read."""
    return lambda names: {name: table[name] for name in names}


def read_vehicle_pose(path: str | os.PathLike[str]) -> tuple[FloatArray, FloatArray] | None:
    """The measured pose in a log (see the module): ``(position (n, 3), quaternion (n, 4))``, or
    None when the log has no ``x`` column. A pose given in part (``x`` without ``y``, a quaternion
    without ``qz``, neither a quaternion nor Euler angles) is an error naming the columns."""
    source, header, read = open_table(path)
    if "x" not in header:
        return None
    return _pose(source, _samples((source, header, read), ("base_position", "base_orientation"))[1])


def _samples(table: Table, fields: Sequence[str]) -> tuple[FloatArray, dict[str, FloatArray]]:
    """The time [s] and the vehicle's ``fields`` (:data:`uwml.io.vehicle_columns.FIELDS`' names, or
    ``"thruster_commands"``) of a stream other than the joints', as :func:`uwml.io.logs.read_log`
    reads them: groups complete, Euler angles turned into a quaternion, a quaternion of norm 1."""
    source, header, read = table
    if "time" not in header:
        raise ValueError(f"{source}: row 1 (header), column 'time': missing column{_header_hint(header)}")
    layout = vehicle_layout(header, source) | {"thruster_commands": thruster_columns(header, source)}
    families = {field: layout[field] for field in fields if layout.get(field)}
    columns = read(["time", *(name for names in families.values() for name in names)])
    time = np.asarray(columns["time"], dtype=np.float64)
    _check_time(time, source)
    if time.size < 2:
        raise UwmlError(f"{source}: {time.size} sample{'s' if time.size != 1 else ''}: at least 2 to interpolate or hold")
    return time, _arrays(columns, families, source, 2)


def _pose(source: str, fields: Mapping[str, FloatArray | None]) -> tuple[FloatArray, FloatArray]:
    """The measured pose of a stream's ``base_position`` and ``base_orientation`` (its first
    sample the file's row 2), checked: an orientation given, positions within ``MAX_LENGTH``;
    the quaternion normalized and kept on one sign (:func:`uwml.io.column_map.continuous_quaternion`)."""
    position, quaternion = fields.get("base_position"), fields.get("base_orientation")
    if position is None or quaternion is None:
        raise ValueError(
            f"{source}: row 1 (header), column 'qw': missing column (the vehicle's pose needs x, y, z and qw, qx, qy, qz "
            "or roll, pitch, yaw)"
        )
    for k, name in enumerate(POSITION):
        far = np.flatnonzero(np.abs(position[:, k]) > MAX_LENGTH)
        if far.size:
            raise UwmlError(
                f"{source}: row {int(far[0]) + 2}, column {name!r}: the vehicle's position {position[far[0], k]:g} m is beyond "
                f"±{MAX_LENGTH:g} m (uwml.domains.MAX_LENGTH, docs/domains.md): millimetres, or not a position?"
            )
    return position, continuous_quaternion(quaternion / np.linalg.norm(quaternion, axis=1, keepdims=True))


def _gaps(time: FloatArray, max_gap: float) -> NDArray[np.intp]:
    """The indices ``k`` of the steps ``time[k]`` to ``time[k + 1]`` longer than ``max_gap``."""
    return np.flatnonzero(np.diff(time) > max_gap)


def _check_gaps(time: FloatArray, source: str, max_gap: float, first_row: int) -> None:
    """No step between joint samples longer than ``max_gap``; ``first_row``: the file's row of ``time[0]``."""
    long = _gaps(time, max_gap)
    if long.size:
        k = int(long[0])
        raise UwmlError(
            f"{source}: a gap of {time[k + 1] - time[k]:.3g} s between t = {time[k]:.6g} and {time[k + 1]:.6g} s (rows "
            f"{first_row + k} and {first_row + k + 1}), longer than {max_gap:g} s: split the log there and replay the parts, or "
            f"allow longer gaps (max_gap, --max-gap); the prescribed joints have {long.size} such gap{'s' if long.size > 1 else ''}"
        )


@dataclass(frozen=True)
class Streams:
    """A replay's log, read and joined (:func:`read_streams`): ``joints``, the joint log over the
    replayed span, whose first sample is row ``first_row`` of its file; ``pose``, the measured
    ``(position, quaternion)`` on the joints' time stamps (None without one); ``pose_samples``,
    the pose stream as recorded, ``(time, position, quaternion)``, read from ``pose_source``;
    ``bridged``, the pose stream's gaps longer than ``max_gap`` that its interpolation bridged;
    ``thrusters``, the thruster commands as recorded, ``(time, commands (n, thrusters))``, read
    from ``thruster_source`` (None: the log has none)."""

    joints: Log
    first_row: int
    pose: tuple[FloatArray, FloatArray] | None = None
    pose_samples: tuple[FloatArray, FloatArray, FloatArray] | None = None
    pose_source: str | None = None
    bridged: int = 0
    thrusters: tuple[FloatArray, FloatArray] | None = None
    thruster_source: str | None = None


def _one(tables: list[Table], what: str) -> int | None:
    """The index of the one table of ``tables`` that holds ``what`` (:data:`_HELD`), None if none
    does; two or more are refused."""
    found = [k for k, table in enumerate(tables) if _holds(table, what)]
    if len(found) > 1:
        raise ValueError(f"at most one file may hold {_HELD[what]}, got {len(found)}: {[tables[k][0] for k in found]}")
    return found[0] if found else None


#: What a replay's stream holds, by the column that says so.
_HELD = {"q1": "the joint angles (q1 … qN)", "x": "the vehicle's pose (x, y, z, ...)", "u1": "the thruster commands (u1 … un)"}


def _holds(table: Table, what: str) -> bool:
    """Whether a table's header holds ``what`` (:data:`_HELD`; thruster commands checked:
    :func:`uwml.io.vehicle_columns.thruster_columns`)."""
    source, header, _ = table
    return bool(thruster_columns(header, source)) if what == "u1" else what in header


def read_streams(logs: LogPaths, n_joints: int | None, max_gap: float = MAX_GAP_S, columns: Any = None) -> Streams:
    """The joint stream, the pose stream and the thruster commands of one file or several (or of
    the streams of the column map ``columns``), joined on time (the module): the file with the
    ``q`` columns is the joint stream; the one with ``x``, the pose stream, resampled linearly
    onto the joint stream's time stamps within the span every stream covers; the one with ``u1``
    … ``un``, the commands, kept as recorded (held from sample to sample). Gaps in the joints
    over that span longer than ``max_gap`` [s] are refused; the pose's are bridged."""
    max_gap = _seconds(max_gap, "max_gap")
    tables = _tables(logs, columns)
    if not any(_holds(table, "q1") for table in tables):
        which = [f"{source}: row 1 (header), column 'q1': missing column{_header_hint(header)}" for source, header, _ in tables]
        raise UwmlError(f"{'; '.join(which)}; replay needs exactly one file with the joint angles (q1 … qN)")
    for table in tables:
        if not any(_holds(table, what) for what in _HELD):
            raise UwmlError(
                f"{table[0]}: row 1 (header): neither joint angles (q1 … qN) nor a pose (x, y, z, ...) nor thruster commands "
                f"(u1 … un) to replay{_header_hint(table[1])}"
            )
    j, p, u = (_one(tables, what) for what in _HELD)
    assert j is not None  # one table holds q1: above
    source, header, read = tables[j]
    n, families, names = _layout(header, n_joints, source)
    recorded = _from_columns(read(names), n, families, source)
    if recorded.n_samples < 4:
        raise UwmlError(f"{source}: {recorded.n_samples} sample{'s' if recorded.n_samples != 1 else ''}: a replay needs at least 4")
    apart = sorted({k for k in (p, u) if k is not None and k != j})
    read_apart = {k: _samples(tables[k], ("base_position", "base_orientation", "thruster_commands")) for k in apart}
    inside = np.ones(recorded.n_samples, dtype=bool)
    for time, _ in read_apart.values():
        inside &= (recorded.time >= time[0]) & (recorded.time <= time[-1])
    if np.count_nonzero(inside) < 4:
        others = " and ".join(tables[k][0] for k in read_apart)
        raise ValueError(f"{others} and {source} share fewer than 4 joint samples in time: nothing to replay")
    first = int(np.argmax(inside))
    rows = slice(first, first + int(np.count_nonzero(inside)))  # the span every stream covers: one run of rows
    joints = log_rows(recorded, rows)
    _check_gaps(joints.time, source, max_gap, 2 + first)
    pose, pose_samples, bridged = None, None, 0
    if p == j:
        position, quaternion = _pose(source, {"base_position": recorded.base_position, "base_orientation": recorded.base_orientation})
        pose, pose_samples = (position[rows], quaternion[rows]), (recorded.time, position, quaternion)
    elif p is not None:
        pose_samples = (read_apart[p][0], *_pose(tables[p][0], read_apart[p][1]))
        pose, bridged = _on_joints(joints.time, pose_samples, max_gap)
    thrusters = None
    if u is not None:
        time, commands = (
            (recorded.time, recorded.thruster_commands) if u == j else (read_apart[u][0], read_apart[u][1]["thruster_commands"])
        )
        assert commands is not None  # the header has u1: read_log's layout reads them
        thrusters = (time, commands)
    named = [None if k is None else tables[k][0] for k in (p, u)]
    return Streams(joints, 2 + first, pose, pose_samples, named[0], bridged, thrusters, named[1])


def _on_joints(
    time: FloatArray, samples: tuple[FloatArray, FloatArray, FloatArray], max_gap: float
) -> tuple[tuple[FloatArray, FloatArray], int]:
    """A separate pose stream's ``samples`` on the joints' ``time`` (:func:`uwml.io.column_map.resample`:
    the quaternion kept on one sign, then normalized), and its gaps longer than ``max_gap`` bridged."""
    pose_time, position, quaternion = samples
    at = resample(time, pose_time, dict(zip((*POSITION, *QUATERNION), np.column_stack([position, quaternion]).T, strict=True)))
    spanned = (pose_time[1:] > time[0]) & (pose_time[:-1] < time[-1])
    bridged = int(np.count_nonzero((np.diff(pose_time) > max_gap) & spanned))
    return (np.column_stack([at[c] for c in POSITION]), np.column_stack([at[c] for c in QUATERNION])), bridged


def check_joints(recorded: Log, joints: Sequence[Any], first_row: int, description: str) -> None:
    """The log's joint samples against the robot's joints (docs/simulation.md): no revolute joint
    moving more than half a turn between two samples, none outside its range (the limits of
    ``description``, which would fight the replayed motion). ``first_row``: the file's row of
    the log's first sample."""
    time, source = recorded.time, recorded.source
    for j, joint in enumerate(joints):
        q, column = recorded.q[:, j], f"column 'q{j + 1}'"
        label = f"joint {j + 1}" + (f" ({joint.name!r})" if joint.name is not None else "")
        unit = "rad" if joint.kind == "revolute" else "m"
        steps = np.abs(np.diff(q))
        if joint.kind == "revolute" and steps.size and float(steps.max()) > math.pi:
            k = int(np.flatnonzero(steps > math.pi)[0])
            raise UwmlError(
                f"{source}: row {first_row + k + 1}, {column}: {label} jumps by {steps[k]:.6g} rad from the row before "
                f"(t = {time[k]:.6g} to {time[k + 1]:.6g} s), more than half a turn between two samples: a glitch, or an angle "
                "wrapped at ±π (unwrap it)"
            )
        if joint.range is not None:
            lower, upper = joint.range
            outside = np.flatnonzero((q < lower) | (q > upper))
            if outside.size:
                k = int(outside[0])
                where = "at the start" if k == 0 else f"at t = {time[k]:.6g} s"
                raise UwmlError(
                    f"{source}: row {first_row + k}, {column} ({where}): {q[k]:.6g} {unit} is outside the range of {label}, "
                    f"{lower:g} to {upper:g} {unit}, allowed by {description} ({outside.size} sample{'s' if outside.size > 1 else ''} "
                    "outside; the description's limits would fight the replayed motion): an angle offset, degrees, or another "
                    "joint order?"
                )


def collapse_repeats(time: FloatArray, values: FloatArray, window: float) -> NDArray[np.intp]:
    """The samples of one joint's ``values`` kept when repeated samples are collapsed (the
    module): of each run of identical values spanning less than ``window`` [s], its first sample;
    of a longer run (a joint at rest), its first and last; and the stream's last sample."""
    starts = np.concatenate([[True], values[1:] != values[:-1]])
    first = np.flatnonzero(starts)
    last = np.concatenate([first[1:] - 1, [values.size - 1]])
    at_rest = last[(time[last] - time[first]) >= window]
    kept = np.union1d(np.union1d(first, at_rest), [values.size - 1])
    return np.asarray(kept, dtype=np.intp)


@dataclass(frozen=True)
class JointMotion:
    """The prescribed joints' motion (:func:`joint_motion`): at each ``time`` [s] (uniform, the
    log's median step, when smoothed) the angles ``q``, rates ``qd`` and accelerations ``qdd``
    ``(n, joints)``; ``kept``, each joint's samples left after collapsing repeats (of ``samples``
    in the log's span); ``smoothing_s``, the smoothing window [s] (None: the log's ``qd*`` and
    ``qdd*`` as given) and ``window``, its samples."""

    time: FloatArray
    q: FloatArray
    qd: FloatArray
    qdd: FloatArray
    samples: int
    kept: tuple[int, ...]
    smoothing_s: float | None
    window: int


def joint_motion(recorded: Log, joints: Sequence[Any], smoothing: float = SMOOTHING_S, first_row: int = 2) -> JointMotion:
    """The joints' motion from the log (the module, "Joint motion"): the log's ``qd*`` and
    ``qdd*`` as given; else repeated samples collapsed, resampled onto a uniform grid and
    smoothed by a Savitzky-Golay filter over ``smoothing`` [s], a joint's implausible smoothed
    acceleration warned about (``joints``: the robot's, for names and kinds)."""
    smoothing = _seconds(smoothing, "smoothing")
    time, n = recorded.time, recorded.n_samples
    if recorded.qd is not None and recorded.qdd is not None:
        return JointMotion(time, recorded.q, recorded.qd, recorded.qdd, n, (n,) * recorded.q.shape[1], None, 0)
    from scipy.signal import savgol_filter

    dt = float(np.median(np.diff(time)))
    points = max(round(float(time[-1] - time[0]) / dt), 1) + 1
    grid = np.linspace(time[0], time[-1], points)
    step = (time[-1] - time[0]) / (points - 1)
    window = savgol_window(1.0 / step, smoothing, POLYORDER)
    if window > points:
        raise UwmlError(
            f"{recorded.source}: the smoothing window of {smoothing:g} s ({window} samples at the log's median step of {step:.6g} s) "
            f"is longer than the replayed span ({time[-1] - time[0]:.6g} s, {points} samples): choose a shorter window "
            "(smoothing, --smoothing) or give qd and qdd columns"
        )
    resampled, kept = np.empty((points, recorded.q.shape[1])), []
    for j in range(recorded.q.shape[1]):
        rows = collapse_repeats(time, recorded.q[:, j], smoothing)
        kept.append(int(rows.size))
        resampled[:, j] = np.interp(grid, time[rows], recorded.q[rows, j])
    q, qd, qdd = (savgol_filter(resampled, window, POLYORDER, deriv=k, delta=step, axis=0, mode="interp") for k in range(3))
    if recorded.qd is not None:
        qd = np.stack([np.interp(grid, time, recorded.qd[:, j]) for j in range(q.shape[1])], axis=1)
    if recorded.qdd is not None:
        qdd = np.stack([np.interp(grid, time, recorded.qdd[:, j]) for j in range(q.shape[1])], axis=1)
    motion = JointMotion(grid, q, qd, qdd, n, tuple(kept), smoothing, window)
    _warn_accelerations(motion, joints, recorded, first_row)
    return motion


def _warn_accelerations(motion: JointMotion, joints: Sequence[Any], recorded: Log, first_row: int) -> None:
    """A :class:`uwml.PlausibilityWarning` naming each joint whose smoothed acceleration exceeds
    the plausible bound of its kind (the module)."""
    for j, joint in enumerate(joints):
        revolute = joint.kind == "revolute"
        bound, unit = (PLAUSIBLE_ANGULAR_ACCELERATION, "rad/s²") if revolute else (PLAUSIBLE_LINEAR_ACCELERATION, "m/s²")
        size = np.abs(motion.qdd[:, j])
        k = int(np.argmax(size))
        if size[k] <= bound:
            continue
        at = float(motion.time[k])
        row = first_row + int(np.clip(np.searchsorted(recorded.time, at), 0, recorded.n_samples - 1))
        label = f"joint {j + 1}" + (f" ({joint.name!r})" if joint.name is not None else "")
        bound_name = "PLAUSIBLE_ANGULAR_ACCELERATION" if revolute else "PLAUSIBLE_LINEAR_ACCELERATION"
        warnings.warn(
            f"{recorded.source}: column 'q{j + 1}': {label}'s acceleration, smoothed over {motion.smoothing_s:g} s, reaches "
            f"{size[k]:.4g} {unit} at t = {at:.6g} s (near row {row}), beyond a plausible {bound:g} {unit} "
            f"(uwml.sim.replay_inputs.{bound_name}): a glitch, samples repeated over longer than the window, or another unit? "
            "A longer window (smoothing, --smoothing) smooths more",
            PlausibilityWarning,
            stacklevel=3,
        )


@dataclass(frozen=True)
class StartState:
    """The vehicle's start (:func:`start_state`): ``twist``, MuJoCo's free joint's velocity
    (world-frame velocity of the origin [m/s], body-frame angular velocity [rad/s]); ``how``:
    ``"fit"`` (estimated from ``samples`` pose samples over ``window_s`` seconds), ``"rest"``
    (asked for) or ``"no pose"`` (the log has none)."""

    twist: FloatArray
    how: str
    window_s: float | None
    samples: int

    def describe(self) -> str:
        """The start in words, with the twist."""
        v, w = self.twist[:3], self.twist[3:]
        numbers = f"v = ({v[0]:.3g}, {v[1]:.3g}, {v[2]:.3g}) m/s, ω = ({w[0]:.3g}, {w[1]:.3g}, {w[2]:.3g}) rad/s"
        if self.how == "fit":
            return f"start twist {numbers} (fitted to {self.samples} pose samples over {self.window_s:g} s)"
        return f"start twist {numbers} ({'at rest, as asked' if self.how == 'rest' else 'at rest: no measured pose'})"

    def as_dict(self) -> dict[str, Any]:
        """The start for JSON: the twist by component, how it was set, the window and samples."""
        names = ("vx", "vy", "vz", "wx", "wy", "wz")
        return {
            "twist": {name: float(value) for name, value in zip(names, self.twist, strict=True)},
            "how": self.how,
            "window_s": self.window_s,
            "samples": self.samples,
        }


def start_state(streams: Streams, window: float = START_WINDOW_S, at_rest: bool = False) -> StartState:
    """The vehicle's start twist (the module, "Start state"): fitted to the pose samples within
    ``window`` [s] of the replay's first time, zero with ``at_rest`` or without a measured pose."""
    window = _seconds(window, "start_window")
    if streams.pose is None or streams.pose_samples is None:
        return StartState(np.zeros(6), "no pose", None, 0)
    if at_rest:
        return StartState(np.zeros(6), "rest", None, 0)
    coefficients, count = start_fit(streams, window)
    return StartState(np.asarray(coefficients[1] / window, dtype=np.float64), "fit", window, count)


def start_fit(streams: Streams, window: float) -> tuple[FloatArray, int]:
    """The polynomials fitted to the measured pose within ``window`` [s] of the replay's first time
    (the module, "Start state"): their coefficients ``(degree + 1, 6)``, constant first, in time
    scaled by ``window`` (position, then the rotation vector about the first sample's
    orientation, body frame), and the samples' count (fewer than 2 refused)."""
    from scipy.spatial.transform import Rotation

    assert streams.pose is not None and streams.pose_samples is not None
    t0 = float(streams.joints.time[0])
    time, position, quaternion = streams.pose_samples
    inside = (time >= t0) & (time <= t0 + window * (1.0 + 1e-9))  # a sample at the window's end, to rounding, in it
    count = int(np.count_nonzero(inside))
    if count < 2:
        raise UwmlError(
            f"{streams.pose_source}: {count} pose sample{'s' if count != 1 else ''} within the start window, t = {t0:.6g} to {t0 + window:.6g} s: "
            "the start twist needs at least 2; widen the window (start_window, --start-window) or start at rest "
            "(start_at_rest, --start-at-rest)"
        )
    start = Rotation.from_quat(np.roll(streams.pose[1][0], -1))  # scipy's quaternions are scalar last
    turns = (start.inv() * Rotation.from_quat(np.roll(quaternion[inside], -1, axis=1))).as_rotvec()
    tau = (time[inside] - t0) / window  # scaled: a well-conditioned fit
    samples = np.column_stack([position[inside], turns])
    return np.asarray(np.polynomial.polynomial.polyfit(tau, samples, min(START_DEGREE, count - 1)), dtype=np.float64), count
