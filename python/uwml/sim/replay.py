"""Replaying a recorded arm motion on a floating vehicle (``uwml replay``, :func:`replay`): the
vehicle floats freely, thrusters off, while the arm's joints follow the log's angles exactly
(docs/model.md section 12.4); the vehicle's simulated pose and twist over time are the answer,
held against its measured pose where the log has one. This is how vehicle-manipulator systems
are identified and validated in pool trials.

The log
-------
One file (CSV or Parquet), the joint log format of :mod:`uwml.io.logs`: ``time`` [s], ``q1`` …
``qN`` (the robot's joints, in its order) [rad or m], and optionally ``qd*``, ``qdd*`` (else the
cubic spline of ``q`` estimates them, :class:`uwml.sim.prescribed.Trajectory`). Optionally the
vehicle's measured pose in the same rows: ``x``, ``y``, ``z`` [m] (world, z up) and either a
quaternion ``qw``, ``qx``, ``qy``, ``qz`` (world from vehicle) or ``roll``, ``pitch``, ``yaw``
[rad] (z-y-x Euler angles). Or one file per stream, recorded apart (joint encoders at 500 Hz,
motion capture at 100 Hz, with jitter): the one with the ``q`` columns is the joint stream, the
one with ``x`` the pose stream (its own ``time`` column), resampled linearly onto the joint
stream's time stamps (``numpy.interp``; the quaternion's sign kept continuous, then normalized),
and only the span both cover is replayed (:func:`joined`). Gaps: a step between samples longer than ``MAX_GAP_S``
(0.1 s) is refused, naming where, rather than bridged by the spline: split the log there.

What is refused before simulating, naming the file, row and column (a ``UwmlError``): fewer than 4
samples; a position beyond ``±MAX_LENGTH`` (1e4 m, docs/domains.md: millimetres, or 1e300); a joint
sample outside the joint's range (the description's limits, which would fight the replayed
motion: an angle offset, degrees, another joint order); a revolute joint moving more than half a
turn between two samples (a glitch, or an angle wrapped at ±π: unwrap it). The quaternion's sign
is kept continuous in every pose (q and −q are the same turn). A simulation that diverges all the
same (its state no longer finite) is an error naming the time and the log's rows around it.

The simulation starts at the log's first sample (of the span both streams cover), the vehicle at
its measured pose and moving as the pose's first samples say (else at rest at the origin, level),
the joints on the log's motion, and runs to its last.
"""

from __future__ import annotations

import math
import os
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..domains import MAX_LENGTH
from ..errors import UwmlError
from ..io.logs import Log, _check_file, _header_hint, _parquet_columns, _parquet_table, read_log
from .prescribed import Trajectory

__all__ = ["MAX_GAP_S", "Replay", "command", "plot_replay", "read_vehicle_pose", "replay", "write_replay"]

FloatArray = NDArray[np.float64]

#: The longest step between two samples of a replayed log [s]; a longer gap is refused.
MAX_GAP_S = 0.1
_POSITION, _QUATERNION, _EULER = ("x", "y", "z"), ("qw", "qx", "qy", "qz"), ("roll", "pitch", "yaw")


@dataclass(frozen=True)
class Replay:
    """A replay's result: at each ``time`` [s], the vehicle's simulated ``position`` (world, z
    up) [m], ``quaternion`` (world from vehicle, w first) and ``twist`` (MuJoCo's free joint:
    world-frame velocity [m/s], body-frame angular velocity [rad/s]); ``errors``: RMS of the
    simulated against the measured roll, pitch [rad], yaw rate [rad/s] and heave [m] (None
    without a measured pose)."""

    time: FloatArray
    position: FloatArray
    quaternion: FloatArray
    twist: FloatArray
    errors: dict[str, float] | None

    def euler(self) -> FloatArray:
        """Roll, pitch, yaw [rad] (z-y-x) of the simulated pose, ``(n, 3)``."""
        return _euler(self.quaternion)


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


def _starting_twist(time: FloatArray, position: FloatArray, quaternion: FloatArray) -> FloatArray:
    """The first sample's world velocity and body angular velocity (MuJoCo's free joint), from the
    second-order slopes of the first three samples of the measured pose (``ω = 2 q* ⊗ q̇``, vector part)."""
    if len(time) < 3:
        return np.zeros(6)
    velocity = np.gradient(position[:3], time[:3], axis=0, edge_order=2)[0]
    rate = np.gradient(quaternion[:3], time[:3], axis=0, edge_order=2)[0]
    w, x, y, z = quaternion[0]
    dw, dx, dy, dz = rate
    # The vector part of conj(q) ⊗ q̇, twice.
    omega = 2.0 * np.array([w * dx - x * dw - y * dz + z * dy, w * dy + x * dz - y * dw - z * dx, w * dz - x * dy + y * dx - z * dw])
    return np.concatenate([velocity, omega])


def _check_gaps(time: FloatArray, source: str) -> None:
    steps = np.diff(time)
    if steps.size and float(steps.max()) > MAX_GAP_S:
        k = int(np.argmax(steps))
        raise ValueError(
            f"{source}: a gap of {steps[k]:.3g} s between t = {time[k]:.6g} and {time[k + 1]:.6g} s (rows {k + 2} and {k + 3}), longer "
            f"than {MAX_GAP_S:g} s: split the log there and replay the parts"
        )


def joined(
    logs: str | os.PathLike[str] | Sequence[str | os.PathLike[str]], n_joints: int | None = None
) -> tuple[Log, tuple[FloatArray, FloatArray] | None]:
    """The joint log and the measured pose on its time stamps, from one file or several (the module:
    the file with the ``q`` columns is the joint stream; the one with ``x``, the pose stream,
    resampled linearly onto the joint stream's time stamps within the span both cover, the
    quaternion's sign kept continuous and its interpolation normalized). Gaps are checked in each
    stream."""
    recorded, pose, _ = _joined(logs, n_joints)
    return recorded, pose


def _joined(
    logs: str | os.PathLike[str] | Sequence[str | os.PathLike[str]], n_joints: int | None
) -> tuple[Log, tuple[FloatArray, FloatArray] | None, int]:
    """:func:`joined`, and the row of the joint file that the joint log starts at."""
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
            f"{recorded.source}: {recorded.n_samples} sample{'s' if recorded.n_samples != 1 else ''}: a replay needs at least 4 "
            "(the joint angles' cubic spline)"
        )
    _check_gaps(recorded.time, recorded.source)
    if not pose_files:
        return recorded, None, 2
    pose = _pose(str(pose_files[0]), *pose_tables[0][1])
    if pose is None:  # its header has x: read_vehicle_pose returns one
        raise ValueError(f"{pose_files[0]}: no vehicle pose")
    if pose_files[0] == joint_files[0]:
        return recorded, pose, 2
    pose_time = _time(str(pose_files[0]), *pose_tables[0][1])
    _check_gaps(pose_time, str(pose_files[0]))
    inside = (recorded.time >= pose_time[0]) & (recorded.time <= pose_time[-1])
    if np.count_nonzero(inside) < 4:
        raise ValueError(f"{pose_files[0]} and {joint_files[0]} share fewer than 4 joint samples in time: nothing to replay")

    def keep(a: FloatArray | None) -> FloatArray | None:
        return None if a is None else a[inside]

    first_row = 2 + int(np.argmax(inside))
    recorded = Log(recorded.time[inside], recorded.q[inside], keep(recorded.qd), keep(recorded.qdd), source=recorded.source)
    # The pose's quaternions are on one side already (_continuous): interpolated, then normalized.
    position, quaternion = pose
    position = np.stack([np.interp(recorded.time, pose_time, position[:, k]) for k in range(3)], axis=1)
    quaternion = np.stack([np.interp(recorded.time, pose_time, quaternion[:, k]) for k in range(4)], axis=1)
    return recorded, (position, quaternion / np.linalg.norm(quaternion, axis=1, keepdims=True)), first_row


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


def replay(
    log: str | os.PathLike[str] | Sequence[str | os.PathLike[str]],
    description: str | os.PathLike[str],
    hydro: str | os.PathLike[str] | None = None,
    *,
    progress: bool = False,
    **options: Any,
) -> Replay:
    """Replay the joint motion of ``log`` (one file, or several streams: :func:`joined`) on the
    robot of ``description`` (URDF or MJCF, with its ``hydro`` file) floating freely (see the module); ``options`` as for
    :class:`uwml.sim.mujoco.Simulation` (``current``, ``depth``, ``integrator``, ...). A
    progress bar on standard error with ``progress``."""
    sim = _floating(description, hydro, options)
    recorded, measured, first_row = _joined(log, sim.robot.n_joints)
    return _simulate(sim, recorded, measured, progress, first_row)


def _floating(description: str | os.PathLike[str], hydro: str | os.PathLike[str] | None, options: dict[str, Any]) -> Any:
    """The simulation of :func:`replay`: the robot of ``description`` with its base floating."""
    from .mujoco import Simulation

    sim = Simulation.from_file(description, hydro, floating=True, **options)
    if sim._free_dof is None:
        raise ValueError(f"{description}: the robot's base did not float (its root hangs from the world by a joint)")
    return sim


def _check_joints(recorded: Log, joints: Sequence[Any], first_row: int) -> None:
    """The log's joint samples against the robot's joints (module docstring): no revolute joint
    moving more than half a turn between two samples, none outside its range. ``first_row``:
    the file's row of the log's first sample."""
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
                raise UwmlError(
                    f"{source}: row {first_row + k}, {column}: {q[k]:.6g} {unit} is outside the range of {label}, {lower:g} to "
                    f"{upper:g} {unit} (the description's limits, which would fight the replayed motion): an angle offset, "
                    "degrees, or another joint order?"
                )


def _diverged(recorded: Log, first_row: int, at: float) -> UwmlError:
    """The error of a replay whose state stopped being finite at time ``at``: the log's rows around it."""
    time = recorded.time
    k = int(np.clip(np.searchsorted(time, at, side="right") - 1, 0, time.size - 2))
    return UwmlError(
        f"{recorded.source}: the replay diverged at t = {at:.6g} s, between rows {first_row + k} and {first_row + k + 1} "
        f"(t = {time[k]:.6g} and {time[k + 1]:.6g} s): the vehicle's state is no longer finite; look at the log's motion there "
        "(a jump, accelerations or velocities in the wrong unit)"
    )


def _simulate(sim: Any, recorded: Log, measured: tuple[FloatArray, FloatArray] | None, progress: bool, first_row: int = 2) -> Replay:
    """:func:`replay` of a log already read (:func:`joined`, its first sample at row ``first_row``
    of its file) on a floating simulation."""
    _check_joints(recorded, sim.robot.joints, first_row)
    time = recorded.time
    trajectory = Trajectory(time, recorded.q, recorded.qd, recorded.qdd)
    d, m = sim.data, sim.model
    d.time = float(time[0])
    free, dof = int(sim._free_qpos), int(sim._free_dof)
    if measured is not None:
        # The vehicle's measured pose at the start, and its twist there from the pose's rates.
        position, quaternion = measured
        d.qpos[free : free + 3], d.qpos[free + 3 : free + 7] = position[0], quaternion[0]
        d.qvel[dof : dof + 6] = _starting_twist(time, position, quaternion)
    sim.prescribe(list(range(sim.robot.n_joints)), trajectory)
    steps = max(1, math.floor((time[-1] - time[0]) / m.opt.timestep + 1e-9))
    times: list[float] = []
    positions, quaternions, twists = [], [], []

    def record() -> None:
        times.append(float(d.time))
        positions.append(d.qpos[free : free + 3].copy())
        quaternions.append(d.qpos[free + 3 : free + 7].copy())
        twists.append(d.qvel[dof : dof + 6].copy())

    record()
    bar = _progress(steps) if progress else None
    for k in range(steps):
        try:
            sim.step()
            record()
            if not (np.all(np.isfinite(positions[-1])) and np.all(np.isfinite(twists[-1]))):
                raise FloatingPointError
        except (FloatingPointError, np.linalg.LinAlgError):  # a state no longer finite, a singular mass matrix
            if bar is not None:
                bar(None)  # the error on a line of its own
            raise _diverged(recorded, first_row, float(d.time)) from None
        if bar is not None and (k % max(1, steps // 100) == 0 or k == steps - 1):
            bar(k + 1)
    result = Replay(np.array(times), np.array(positions), np.array(quaternions), np.array(twists), None)
    if measured is None:
        return result
    return Replay(result.time, result.position, result.quaternion, result.twist, _errors(result, time, *measured))


def _errors(result: Replay, time: FloatArray, position: FloatArray, quaternion: FloatArray) -> dict[str, float]:
    """RMS of simulated against measured roll, pitch, yaw rate and heave, on the log's samples."""
    simulated = result.euler()
    measured = _euler(quaternion)

    def at(column: FloatArray) -> FloatArray:
        return np.asarray(np.interp(time, result.time, column), dtype=np.float64)

    def rms(error: FloatArray) -> float:
        return float(np.sqrt(np.mean(error * error)))

    def wrap(angle: FloatArray) -> FloatArray:
        return np.asarray((angle + np.pi) % (2.0 * np.pi) - np.pi, dtype=np.float64)

    sim_yaw_rate = np.gradient(np.unwrap(simulated[:, 2]), result.time)
    measured_yaw_rate = np.gradient(np.unwrap(measured[:, 2]), time)
    return {
        "roll": rms(wrap(at(simulated[:, 0]) - measured[:, 0])),
        "pitch": rms(wrap(at(simulated[:, 1]) - measured[:, 1])),
        "yaw_rate": rms(at(sim_yaw_rate) - measured_yaw_rate),
        "heave": rms(at(result.position[:, 2]) - position[:, 2]),
    }


def _progress(total: int) -> Any:
    import sys

    shown = [False]

    def show(done: int | None) -> None:
        """The bar at ``done`` steps; None: its line ended where it stands (the run stopped)."""
        if done is not None:
            filled = int(40 * done / total)
            sys.stderr.write(f"\rreplay [{'#' * filled}{'.' * (40 - filled)}] {done}/{total} steps")
        if done == total or (done is None and shown[0]):
            sys.stderr.write("\n")
        shown[0] = done is not None
        sys.stderr.flush()

    return show


def write_replay(result: Replay, path: str | os.PathLike[str]) -> None:
    """The replay's time, pose and twist as a CSV or Parquet file (by the suffix), written whole
    or not at all (a temporary file renamed over ``path``)."""
    from ..io._file_access import atomic_file, write_atomically

    names = ["time", "x", "y", "z", "qw", "qx", "qy", "qz", "vx", "vy", "vz", "wx", "wy", "wz"]
    table = np.column_stack([result.time, result.position, result.quaternion, result.twist])
    if str(path).endswith(".parquet"):
        import pyarrow as pa
        import pyarrow.parquet as pq

        with atomic_file(path) as handle:
            pq.write_table(pa.table({name: table[:, k] for k, name in enumerate(names)}), handle)
        return
    lines = [",".join(names)] + [",".join(repr(float(x)) for x in row) for row in table]
    write_atomically(path, ("\n".join(lines) + "\n").encode("utf-8"))


def plot_replay(result: Replay, path: str | os.PathLike[str], measured: tuple[FloatArray, FloatArray, FloatArray] | None = None) -> None:
    """A figure of the vehicle's roll, pitch, yaw and heave over time (and the measured ones,
    ``(time, position, quaternion)``, if given), saved to ``path``."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    euler = result.euler()
    figure, axes = plt.subplots(4, 1, sharex=True, figsize=(8, 8))
    labels = ["roll [rad]", "pitch [rad]", "yaw [rad]", "heave z [m]"]
    series = [euler[:, 0], euler[:, 1], np.unwrap(euler[:, 2]), result.position[:, 2]]
    for axis, label, values in zip(axes, labels, series, strict=True):
        axis.plot(result.time, values, label="simulated")
        axis.set_ylabel(label)
        axis.grid(True, alpha=0.3)
    if measured is not None:
        time, position, quaternion = measured
        angles = _euler(quaternion)
        for axis, values in zip(axes, [angles[:, 0], angles[:, 1], np.unwrap(angles[:, 2]), position[:, 2]], strict=True):
            axis.plot(time, values, "--", label="measured")
    axes[0].legend(loc="best")
    axes[-1].set_xlabel("time [s]")
    figure.suptitle("vehicle response to the replayed arm motion")
    figure.tight_layout()
    figure.savefig(path, dpi=120)
    plt.close(figure)


def command(
    log: str | os.PathLike[str] | Sequence[str | os.PathLike[str]],
    description: str | os.PathLike[str],
    hydro: str | os.PathLike[str] | None,
    out: str | os.PathLike[str],
    *,
    parquet: bool = False,
    as_json: bool = False,
) -> int:
    """``uwml replay``: replay, write ``replay.csv`` (``.parquet``) and ``replay.png`` in ``out``,
    print the errors (a table, or JSON with ``as_json``)."""
    import json
    from pathlib import Path

    sim = _floating(description, hydro, {})
    recorded, measured, first_row = _joined(log, sim.robot.n_joints)
    result = _simulate(sim, recorded, measured, not as_json, first_row)
    folder = Path(out)
    folder.mkdir(parents=True, exist_ok=True)
    write_replay(result, folder / ("replay.parquet" if parquet else "replay.csv"))
    plot_replay(result, folder / "replay.png", None if measured is None else (recorded.time, *measured))
    if as_json:
        print(json.dumps(result.errors))
        return 0
    print(f"replayed {result.time[-1] - result.time[0]:.3f} s; outputs in {folder}")
    if result.errors is None:
        print("no measured pose in the log: nothing to compare")
        return 0
    units = {"roll": "rad", "pitch": "rad", "yaw_rate": "rad/s", "heave": "m"}
    for name, value in result.errors.items():
        print(f"  RMS {name:9s} {value:.4g} {units[name]}")
    return 0
