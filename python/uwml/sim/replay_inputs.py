"""A replay's log, read and cleaned before it is simulated (:mod:`uwml.sim.replay`; the rules are
docs/simulation.md's, "Replaying a pool trial"): the streams joined on time, gaps checked, the
joints' repeated samples collapsed and their motion smoothed, the vehicle's start state estimated.

Streams
-------
One file holds the joint angles (``q1`` … ``qN``); at most one holds the vehicle's pose (``x``,
``y``, ``z`` and ``qw``, ``qx``, ``qy``, ``qz`` or ``roll``, ``pitch``, ``yaw``), the same file or
another with its own ``time``. The pose is resampled linearly onto the joint stream's time stamps
(``numpy.interp``; the quaternion's sign kept continuous, then normalized) and only the span both
cover is replayed (:func:`read_streams`).

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
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..domains import MAX_LENGTH
from ..errors import UwmlError
from ..io.logs import Log, _check_file, _header_hint, _parquet_columns, _parquet_table, read_log
from ..io.sampling import POLYORDER, WINDOW_S, savgol_window
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
    "start_state",
]

FloatArray = NDArray[np.float64]

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
_POSITION, _QUATERNION, _EULER = ("x", "y", "z"), ("qw", "qx", "qy", "qz"), ("roll", "pitch", "yaw")


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


def _quaternion(euler: FloatArray) -> FloatArray:
    roll, pitch, yaw = (euler[:, k] / 2.0 for k in range(3))
    cr, sr, cp, sp, cy, sy = np.cos(roll), np.sin(roll), np.cos(pitch), np.sin(pitch), np.cos(yaw), np.sin(yaw)
    return np.stack(
        [cr * cp * cy + sr * sp * sy, sr * cp * cy - cr * sp * sy, cr * sp * cy + sr * cp * sy, cr * cp * sy - sr * sp * cy], axis=1
    )


def _table(path: str | os.PathLike[str]) -> tuple[list[str], Callable[[Sequence[str]], dict[str, Any]]]:
    """A log's column names and a reader of named columns (CSV or Parquet by the suffix): one read
    of the file, whatever is asked of it after."""
    source = str(path)
    _check_file(path, source)
    if source.lower().endswith(".parquet"):
        table = _parquet_table(path, source)

        def read(names: Sequence[str]) -> dict[str, Any]:
            return _parquet_columns(table, names, source)  # numbers only, finite, by name

        return list(table.column_names), read
    from ..io._arrow_csv import CsvTable

    csv = CsvTable(path, f"{source}: ", "time")
    return list(csv.header), csv.read


def read_vehicle_pose(path: str | os.PathLike[str]) -> tuple[FloatArray, FloatArray] | None:
    """The measured pose in a log (see the module): ``(position (n, 3), quaternion (n, 4))``, or
    None when the log has no ``x`` column. A pose given in part (``x`` without ``y``, a quaternion
    without ``qz``, neither a quaternion nor Euler angles) is an error naming the columns."""
    return _pose(str(path), *_table(path))


def _pose(source: str, header: list[str], read: Callable[[Sequence[str]], dict[str, Any]]) -> tuple[FloatArray, FloatArray] | None:
    """:func:`read_vehicle_pose` of a table already open."""
    present = set(header)
    if "x" not in present:
        return None
    orientation = _QUATERNION if "qw" in present else _EULER
    missing = [name for name in (*_POSITION, *orientation) if name not in present]
    if missing:
        raise ValueError(
            f"{source}: the vehicle's pose needs x, y, z and qw, qx, qy, qz (or roll, pitch, yaw); missing {', '.join(missing)}"
        )
    columns = read((*_POSITION, *orientation))
    values = {name: np.asarray(columns[name], dtype=np.float64) for name in (*_POSITION, *orientation)}
    for name, column in values.items():
        if not np.all(np.isfinite(column)):
            raise ValueError(f"{source}: column {name!r} must hold finite numbers (row {int(np.argmin(np.isfinite(column))) + 2})")
    for name in _POSITION:
        far = np.flatnonzero(np.abs(values[name]) > MAX_LENGTH)
        if far.size:
            raise UwmlError(
                f"{source}: row {int(far[0]) + 2}, column {name!r}: the vehicle's position {values[name][far[0]]:g} m is beyond "
                f"±{MAX_LENGTH:g} m (uwml.domains.MAX_LENGTH, docs/domains.md): millimetres, or not a position?"
            )
    position = np.stack([values[name] for name in _POSITION], axis=1)
    angles = np.stack([values[name] for name in orientation], axis=1)
    if orientation == _EULER:
        return position, _continuous(_quaternion(angles))
    with np.errstate(over="ignore"):  # a huge quaternion's norm overflows: not a unit one
        norms = np.linalg.norm(angles, axis=1)
    if np.any(np.abs(norms - 1.0) > 1e-3):
        row = int(np.argmax(np.abs(norms - 1.0))) + 2
        raise ValueError(f"{source}: the quaternion (qw, qx, qy, qz) of row {row} is not of norm 1 (within 1e-3): {norms[row - 2]:.6g}")
    return position, _continuous(angles / norms[:, None])


def _continuous(quaternion: FloatArray) -> FloatArray:
    """Each quaternion on the sign nearest the one before it (q and −q are the same turn), so that
    slopes and interpolation between samples follow the turn, not a sign flip."""
    dots = np.einsum("ij,ij->i", quaternion[1:], quaternion[:-1])
    signs = np.concatenate([[1.0], np.where(dots < 0.0, -1.0, 1.0)])
    return np.asarray(quaternion * np.cumprod(signs)[:, None], dtype=np.float64)


def _time(source: str, header: list[str], read: Callable[[Sequence[str]], dict[str, Any]]) -> FloatArray:
    """The ``time`` column of a pose stream's table, checked."""
    if "time" not in header:
        raise ValueError(f"{source}: no column 'time'")
    time = np.asarray(read(("time",))["time"], dtype=np.float64)
    if time.size < 2:
        raise UwmlError(f"{source}: {time.size} sample{'s' if time.size != 1 else ''} of the pose: at least 2 to interpolate")
    if not np.all(np.isfinite(time)) or np.any(np.diff(time) <= 0.0):
        raise ValueError(f"{source}: column 'time' must hold finite, strictly increasing times")
    return time


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
    ``bridged``, the pose stream's gaps longer than ``max_gap`` that its interpolation bridged."""

    joints: Log
    first_row: int
    pose: tuple[FloatArray, FloatArray] | None = None
    pose_samples: tuple[FloatArray, FloatArray, FloatArray] | None = None
    pose_source: str | None = None
    bridged: int = 0


def read_streams(
    logs: str | os.PathLike[str] | Sequence[str | os.PathLike[str]], n_joints: int | None, max_gap: float = MAX_GAP_S
) -> Streams:
    """The joint stream and the pose stream of one file or several, joined on time (the module):
    the file with the ``q`` columns is the joint stream; the one with ``x``, the pose stream,
    resampled linearly onto the joint stream's time stamps within the span both cover. Gaps in the
    joints over that span longer than ``max_gap`` [s] are refused; the pose's are bridged."""
    max_gap = _seconds(max_gap, "max_gap")
    paths = [logs] if isinstance(logs, (str, os.PathLike)) else list(logs)
    if not paths:
        raise ValueError("replay needs a log")
    tables = [_table(path) for path in paths]
    joint_files = [path for path, (header, _) in zip(paths, tables, strict=True) if "q1" in header]
    pose_tables = [(path, table) for path, table in zip(paths, tables, strict=True) if "x" in table[0]]
    pose_files = [path for path, _ in pose_tables]
    if not joint_files:
        which = [
            f"{path}: row 1 (header), column 'q1': missing column{_header_hint(header)}"
            for path, (header, _) in zip(paths, tables, strict=True)
        ]
        raise UwmlError(f"{'; '.join(which)}; replay needs exactly one file with the joint angles (q1 … qN)")
    for path, (header, _) in zip(paths, tables, strict=True):
        if "q1" not in header and "x" not in header:
            raise UwmlError(
                f"{path}: row 1 (header): neither joint angles (q1 … qN) nor a pose (x, y, z, ...) to replay{_header_hint(header)}"
            )
    if len(joint_files) > 1:
        raise ValueError(
            f"replay needs exactly one file with the joint angles (q1, ...), got {len(joint_files)}: {[str(p) for p in joint_files]}"
        )
    if len(pose_files) > 1:
        raise ValueError(f"at most one file may hold the vehicle's pose (x, y, z, ...), got {[str(p) for p in pose_files]}")
    recorded: Log = read_log(joint_files[0], n_joints=n_joints)
    if recorded.n_samples < 4:
        raise UwmlError(
            f"{recorded.source}: {recorded.n_samples} sample{'s' if recorded.n_samples != 1 else ''}: a replay needs at least 4"
        )
    if not pose_files:
        _check_gaps(recorded.time, recorded.source, max_gap, 2)
        return Streams(recorded, 2)
    pose = _pose(str(pose_files[0]), *pose_tables[0][1])
    if pose is None:  # its header has x: read_vehicle_pose returns one
        raise ValueError(f"{pose_files[0]}: no vehicle pose")
    if pose_files[0] == joint_files[0]:
        _check_gaps(recorded.time, recorded.source, max_gap, 2)
        return Streams(recorded, 2, pose, (recorded.time, *pose), recorded.source)
    pose_time = _time(str(pose_files[0]), *pose_tables[0][1])
    inside = (recorded.time >= pose_time[0]) & (recorded.time <= pose_time[-1])
    if np.count_nonzero(inside) < 4:
        raise ValueError(f"{pose_files[0]} and {joint_files[0]} share fewer than 4 joint samples in time: nothing to replay")

    def keep(a: FloatArray | None) -> FloatArray | None:
        return None if a is None else a[inside]

    first_row = 2 + int(np.argmax(inside))
    recorded = Log(recorded.time[inside], recorded.q[inside], keep(recorded.qd), keep(recorded.qdd), source=recorded.source)
    _check_gaps(recorded.time, recorded.source, max_gap, first_row)
    # The pose's quaternions are on one side already (_continuous): interpolated, then normalized.
    position, quaternion = pose
    on_joints = np.stack([np.interp(recorded.time, pose_time, position[:, k]) for k in range(3)], axis=1)
    turns = np.stack([np.interp(recorded.time, pose_time, quaternion[:, k]) for k in range(4)], axis=1)
    spanned = (pose_time[1:] > recorded.time[0]) & (pose_time[:-1] < recorded.time[-1])
    bridged = int(np.count_nonzero((np.diff(pose_time) > max_gap) & spanned))
    on_joints_pose = (on_joints, turns / np.linalg.norm(turns, axis=1, keepdims=True))
    return Streams(recorded, first_row, on_joints_pose, (pose_time, position, quaternion), str(pose_files[0]), bridged)


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
    from scipy.spatial.transform import Rotation

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
    slopes = np.polynomial.polynomial.polyfit(tau, samples, min(START_DEGREE, count - 1))[1] / window
    return StartState(np.asarray(slopes, dtype=np.float64), "fit", window, count)
