"""Replaying a recorded trial on a floating vehicle (``uwml replay``, :func:`replay`): the vehicle
floats freely while the arm's joints follow the log's angles exactly (docs/model.md section 12.4)
and its thrusters follow the log's commands, or stay idle without them; the vehicle's simulated
pose and twist over time are the answer, held against its measured pose where the log has one.
This is how vehicle-manipulator systems are identified and validated in pool trials
(docs/simulation.md, "Replaying a pool trial").

The log
-------
One file (CSV or Parquet) in the log schema (docs/logs.md, :mod:`uwml.io.logs`): ``time`` [s],
``q1`` … ``qN`` (the robot's joints, in its order) [rad or m], and optionally ``qd*``, ``qdd*``.
Optionally the vehicle's measured pose in the same rows: ``x``, ``y``, ``z`` [m] (world, z up)
and either a quaternion ``qw``, ``qx``, ``qy``, ``qz`` (world from vehicle) or ``roll``,
``pitch``, ``yaw`` [rad] (z-y-x Euler angles); and the thruster commands ``u1`` … ``un``, one per
thruster of the robot (``robot.thrusters``' order, in each curve's units). Or one file per stream,
recorded apart (joint encoders at 500 Hz, motion capture at 100 Hz with jitter, the ESCs'
commands), joined on time. A file recorded with other names, signs, offsets, units or in several
streams is read through a column map (``columns``, :mod:`uwml.io.column_map`). How the streams
are read and cleaned (joined, gaps, repeated samples collapsed, the joints' rates and
accelerations from a smoothing fit over ``smoothing`` seconds, the start twist fitted over
``start_window`` seconds) is :mod:`uwml.sim.replay_inputs`.

Thrusters
---------
Each command sample is held from its time until the next sample (a zero-order hold, as an ESC
holds the last pulse it got): :meth:`uwml.sim.mujoco.Simulation.command_thrusters` at the step
that starts at the sample's time, a sample between two steps of the grid given a step of its own
(:func:`held_commands`). The thrust starts at zero at the first sample and follows the commands
through each thruster's lag. A log with another number of commands than the robot has thrusters
is refused, naming both numbers.

What is refused before simulating, naming the file, row and column (a ``UwmlError``): fewer than 4
samples; another number of thruster commands than thrusters; a gap between joint samples longer than ``max_gap`` (0.1 s by default); a position beyond
``±MAX_LENGTH`` (1e4 m, docs/domains.md: millimetres, or 1e300); a joint sample outside the
joint's range (the description's limits, which would fight the replayed motion: an angle offset,
degrees, another joint order); a revolute joint moving more than half a turn between two samples
(a glitch, or an angle wrapped at ±π: unwrap it). A simulation that diverges all the same (its
state no longer finite) is an error naming the time and the log's rows around it.

The simulation starts at the log's first sample (of the span every stream covers), the vehicle at
its measured pose with the fitted start twist (or at rest: ``start_at_rest``, or no measured
pose), the joints on the log's motion, and runs to its last sample: steps of ``timestep`` (the
description's own by default) on the grid from the first sample, the last one shortened to end
on the last sample. ``integrator``: ``"euler"`` or ``"rk4"`` (:class:`uwml.sim.mujoco.Simulation`).
"""

from __future__ import annotations

import math
import os
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..errors import UwmlError
from ..io.logs import Log
from .prescribed import Trajectory
from .replay_inputs import (
    MAX_GAP_S,
    SMOOTHING_S,
    START_WINDOW_S,
    JointMotion,
    StartState,
    Streams,
    _euler,
    _seconds,
    check_joints,
    joint_motion,
    read_streams,
    start_state,
)

__all__ = ["MAX_TIMESTEP_S", "Replay", "command", "plot_replay", "replay", "step_times", "write_replay"]

FloatArray = NDArray[np.float64]

#: The longest simulation step of a replay [s]: longer steps skip the arm's motion, and the
#: vehicle's explicit integration goes unstable.
MAX_TIMESTEP_S = 0.1


@dataclass(frozen=True)
class Thrusters:
    """The robot's thrusters in a replay: ``count``, how many it has (``robot.thrusters``);
    ``samples``, the log's command samples held over the replay (0: none, the thrusters idle);
    ``source``, the file they were read from; ``longest_hold_s``, the longest a command was held
    [s] (a long one: a logger's dropout, or commands logged only when they change)."""

    count: int
    samples: int = 0
    source: str | None = None
    longest_hold_s: float | None = None

    @property
    def driven(self) -> bool:
        """Whether the log's commands drove the thrusters."""
        return self.samples > 0

    def describe(self) -> str:
        """The thrusters in words."""
        if self.driven:
            return (
                f"thrusters driven by the log's commands u1 … u{self.count} ({self.samples} samples from {self.source}, each held "
                f"until the next; the longest held {self.longest_hold_s:.3g} s)"
            )
        return f"thrusters idle: the log has no thruster commands (u1 … u{self.count} for the robot's {self.count} thrusters)"

    def as_dict(self) -> dict[str, Any]:
        """The thrusters for JSON."""
        return {
            "count": self.count,
            "driven": self.driven,
            "samples": self.samples,
            "source": self.source,
            "longest_hold_s": self.longest_hold_s,
        }


@dataclass(frozen=True)
class Replay:
    """A replay's result: at each ``time`` [s], the vehicle's simulated ``position`` (world, z
    up) [m], ``quaternion`` (world from vehicle, w first) and ``twist`` (MuJoCo's free joint:
    world-frame velocity [m/s], body-frame angular velocity [rad/s]); ``errors``: RMS of the
    simulated against the measured roll, pitch [rad], yaw rate [rad/s] and heave [m] (None
    without a measured pose). How the log was read: ``start``, the vehicle's start twist and how
    it was set; ``motion``, the joints' prescribed motion (samples kept after collapsing
    repeats, the smoothing window); ``bridged``, the pose stream's gaps longer than ``max_gap``
    bridged by interpolation (:mod:`uwml.sim.replay_inputs`); ``measured``, the measured pose on
    the log's time stamps, ``(time, position, quaternion)`` (None without one); ``thrusters``,
    whether the log's commands drove the robot's thrusters (:class:`Thrusters`)."""

    time: FloatArray
    position: FloatArray
    quaternion: FloatArray
    twist: FloatArray
    errors: dict[str, float] | None
    start: StartState | None = None
    motion: JointMotion | None = None
    bridged: int = 0
    measured: tuple[FloatArray, FloatArray, FloatArray] | None = None
    thrusters: Thrusters | None = None

    def euler(self) -> FloatArray:
        """Roll, pitch, yaw [rad] (z-y-x) of the simulated pose, ``(n, 3)``."""
        return _euler(self.quaternion)

    def summary(self) -> dict[str, Any]:
        """The errors and how the log was read, for JSON (``uwml replay --json``)."""
        motion = None
        if self.motion is not None:
            motion = {"samples": self.motion.samples, "kept": list(self.motion.kept), "smoothing_s": self.motion.smoothing_s}
        start = None if self.start is None else self.start.as_dict()
        thrusters = None if self.thrusters is None else self.thrusters.as_dict()
        return {"errors": self.errors, "start": start, "joints": motion, "pose_gaps_bridged": self.bridged, "thrusters": thrusters}


def replay(
    log: str | os.PathLike[str] | Sequence[str | os.PathLike[str]],
    description: str | os.PathLike[str],
    hydro: str | os.PathLike[str] | None = None,
    *,
    progress: bool = False,
    smoothing: float = SMOOTHING_S,
    max_gap: float = MAX_GAP_S,
    start_window: float = START_WINDOW_S,
    start_at_rest: bool = False,
    timestep: float | None = None,
    integrator: str = "euler",
    columns: Any = None,
    **options: Any,
) -> Replay:
    """Replay the joint motion of ``log`` (one file, or several streams:
    :func:`uwml.sim.replay_inputs.read_streams`) on the robot of ``description`` (URDF or MJCF,
    with its ``hydro`` file) floating freely (see the module).

    ``smoothing`` [s]: the window of the joints' smoothing fit (their rates and accelerations,
    when the log has no ``qd*``, ``qdd*``); ``max_gap`` [s]: the longest step between joint
    samples; ``start_window`` [s]: the pose samples the start twist is fitted over, or
    ``start_at_rest``; ``timestep`` [s] (at most ``MAX_TIMESTEP_S``; None: the description's)
    and ``integrator`` (``"euler"`` or ``"rk4"``) of the simulation; ``options`` as for
    :class:`uwml.sim.mujoco.Simulation` (``current``, ``depth``, ...). ``columns``: a column map
    (:mod:`uwml.io.column_map`; a TOML path, a dict or a ``ColumnMap``) that reads ``log`` as it
    was recorded, its streams named by the map. A progress bar on standard error with
    ``progress``."""
    sim = _floating(description, hydro, timestep, integrator, options)
    streams = read_streams(log, sim.robot.n_joints, max_gap, columns)
    return _simulate(sim, streams, str(description), progress, smoothing, start_window, start_at_rest)


def _floating(
    description: str | os.PathLike[str],
    hydro: str | os.PathLike[str] | None,
    timestep: float | None,
    integrator: str,
    options: dict[str, Any],
) -> Any:
    """The simulation of :func:`replay`: the robot of ``description`` with its base floating,
    stepped by ``integrator`` at ``timestep`` (checked: the module)."""
    from .mujoco import INTEGRATORS, Simulation

    if not isinstance(integrator, str) or integrator.lower() not in INTEGRATORS:
        raise ValueError(
            f"integrator must be one of {', '.join(INTEGRATORS)} (uwml steps MuJoCo itself, with the added mass in the mass "
            f"matrix: semi-implicit Euler or Runge-Kutta 4; MuJoCo's implicit integrators are not used), got {integrator!r}"
        )
    if timestep is not None and _seconds(timestep, "timestep") > MAX_TIMESTEP_S:
        raise ValueError(
            f"timestep must be at most {MAX_TIMESTEP_S:g} s (longer steps skip the arm's motion and the vehicle's explicit "
            f"integration goes unstable), got {timestep!r}"
        )
    sim = Simulation.from_file(description, hydro, floating=True, integrator=integrator.lower(), **options)
    if sim._free_dof is None:
        raise ValueError(f"{description}: the robot's base did not float (its root hangs from the world by a joint)")
    if timestep is not None:
        sim.model.opt.timestep = float(timestep)
    return sim


def _diverged(recorded: Log, first_row: int, at: float) -> UwmlError:
    """The error of a replay whose state stopped being finite at time ``at``: the log's rows around it."""
    time = recorded.time
    k = int(np.clip(np.searchsorted(time, at, side="right") - 1, 0, time.size - 2))
    return UwmlError(
        f"{recorded.source}: the replay diverged at t = {at:.6g} s, between rows {first_row + k} and {first_row + k + 1} "
        f"(t = {time[k]:.6g} and {time[k + 1]:.6g} s): the vehicle's state is no longer finite; look at the log's motion there "
        "(a jump, accelerations or velocities in the wrong unit)"
    )


def step_times(start: float, end: float, timestep: float) -> FloatArray:
    """The times a replay from ``start`` to ``end`` [s] steps to: the grid ``start + k·timestep``,
    the last step shortened to land on ``end`` exactly (one within a millionth of a step of the
    grid's last point is that point, moved onto ``end``). Each time is computed from the start, so
    no rounding accumulates over the steps."""
    ratio = (end - start) / timestep
    steps = max(1, math.ceil(ratio - 1e-6))
    times = start + timestep * np.arange(1, steps + 1, dtype=np.float64)
    times[-1] = end
    return times


def held_commands(times: FloatArray, start: float, targets: FloatArray, timestep: float) -> tuple[FloatArray, NDArray[np.intp]]:
    """A zero-order hold of commands sampled at ``times`` (increasing, the first at or before
    ``start``) over a replay stepping from ``start`` to ``targets`` (:func:`step_times`): the step
    times with every sample time inside the span added, unless within a millionth of ``timestep``
    of one already there (rounding: it is that one), so that each command starts at its sample;
    and, for each step, the index of the sample it holds, the last one at or before the step's
    start."""
    tolerance = 1e-6 * timestep
    grid = np.concatenate([[start], targets])
    inner = times[(times > start + tolerance) & (times < targets[-1] - tolerance)]
    at = np.searchsorted(grid, inner)
    near = np.minimum(inner - grid[at - 1], grid[np.minimum(at, grid.size - 1)] - inner) <= tolerance
    steps = np.union1d(targets, inner[~near])
    starts = np.concatenate([[start], steps[:-1]])
    held = np.searchsorted(times, starts + tolerance, side="right") - 1
    return steps, np.asarray(np.maximum(held, 0), dtype=np.intp)


def _commands(
    streams: Streams, count: int, description: str, start: float, targets: FloatArray, timestep: float
) -> tuple[FloatArray, NDArray[np.intp] | None, FloatArray, Thrusters]:
    """The thrusters' schedule of a replay (:func:`held_commands`): ``(step times, the sample each
    step holds, the log's commands, Thrusters)``; without commands in the log, ``(targets, None,
    no commands, Thrusters)``. A log with another number of commands than the robot's ``count``
    thrusters is refused."""
    if streams.thrusters is None:
        return targets, None, np.zeros((0, count)), Thrusters(count)
    times, commands = streams.thrusters
    if commands.shape[1] != count:
        raise UwmlError(
            f"{streams.thruster_source}: row 1 (header), column 'u{min(commands.shape[1], count) + 1}': the log has "
            f"{commands.shape[1]} thruster commands (u1 … u{commands.shape[1]}), the robot of {description} has {count} thrusters: "
            "one command per thruster, in the order of robot.thrusters (the hydro file's [[links.NAME.thrusters]])"
        )
    steps, held = held_commands(times, start, targets, timestep)
    used = np.arange(held[0], held[-1] + 1)
    bounds = np.concatenate([[start], times[used[1:]], [steps[-1]]])
    drive = Thrusters(count, int(used.size), streams.thruster_source, float(np.max(np.diff(bounds))))
    return steps, held, commands, drive


def _simulate(
    sim: Any,
    streams: Streams,
    description: str,
    progress: bool,
    smoothing: float,
    start_window: float,
    at_rest: bool,
    start: StartState | None = None,
) -> Replay:
    """:func:`replay` of a log already read on a floating simulation; ``start``: the start twist
    (None: :func:`uwml.sim.replay_inputs.start_state`'s)."""
    recorded, first_row, measured = streams.joints, streams.first_row, streams.pose
    start_time, timestep = float(recorded.time[0]), float(sim.model.opt.timestep)
    targets = step_times(start_time, float(recorded.time[-1]), timestep)
    targets, held, commands, thrusters = _commands(streams, len(sim.robot.thrusters), description, start_time, targets, timestep)
    check_joints(recorded, sim.robot.joints, first_row, description)
    motion = joint_motion(recorded, sim.robot.joints, smoothing, first_row)
    start = start_state(streams, start_window, at_rest) if start is None else start
    trajectory = Trajectory(motion.time, motion.q, motion.qd, motion.qdd)
    d, m = sim.data, sim.model
    d.time = float(motion.time[0])
    free, dof = int(sim._free_qpos), int(sim._free_dof)
    if measured is not None:
        position, quaternion = measured
        d.qpos[free : free + 3], d.qpos[free + 3 : free + 7] = position[0], quaternion[0]
    d.qvel[dof : dof + 6] = start.twist
    sim.prescribe(list(range(sim.robot.n_joints)), trajectory)
    steps = targets.size
    times: list[float] = []
    positions, quaternions, twists = [], [], []

    def record() -> None:
        times.append(float(d.time))
        positions.append(d.qpos[free : free + 3].copy())
        quaternions.append(d.qpos[free + 3 : free + 7].copy())
        twists.append(d.qvel[dof : dof + 6].copy())

    record()
    bar = _progress(steps) if progress else None
    try:
        for k, target in enumerate(targets):
            if held is not None and (k == 0 or held[k] != held[k - 1]):
                sim.command_thrusters(commands[held[k]])  # held from this step on, as an ESC holds it
            m.opt.timestep = target - times[-1]  # the grid's step; the last one lands on the end
            sim.step()
            d.time = float(target)  # the grid's time, not the sum of the steps
            record()
            if not (np.all(np.isfinite(positions[-1])) and np.all(np.isfinite(twists[-1]))):
                raise FloatingPointError
            if bar is not None and (k % max(1, steps // 100) == 0 or k == steps - 1):
                bar(k + 1)
    except (FloatingPointError, np.linalg.LinAlgError):  # a state no longer finite, a singular mass matrix
        if bar is not None:
            bar(None)  # the error on a line of its own
        raise _diverged(recorded, first_row, float(d.time)) from None
    finally:
        m.opt.timestep = timestep
    pose = np.array(positions), np.array(quaternions)
    errors = None if measured is None else _errors(np.array(times), *pose, recorded.time, *measured)
    observed = None if measured is None else (recorded.time, *measured)
    return Replay(np.array(times), *pose, np.array(twists), errors, start, motion, streams.bridged, observed, thrusters)


def _errors(
    time: FloatArray, position: FloatArray, quaternion: FloatArray, at_time: FloatArray, measured_position: FloatArray, measured: FloatArray
) -> dict[str, float]:
    """RMS of simulated (``time``, ``position``, ``quaternion``) against measured roll, pitch,
    yaw rate and heave, on the log's samples (``at_time``)."""
    simulated, angles = _euler(quaternion), _euler(measured)

    def at(column: FloatArray) -> FloatArray:
        return np.asarray(np.interp(at_time, time, column), dtype=np.float64)

    def rms(error: FloatArray) -> float:
        return float(np.sqrt(np.mean(error * error)))

    def wrap(angle: FloatArray) -> FloatArray:
        return np.asarray((angle + np.pi) % (2.0 * np.pi) - np.pi, dtype=np.float64)

    sim_yaw_rate = np.gradient(np.unwrap(simulated[:, 2]), time)
    measured_yaw_rate = np.gradient(np.unwrap(angles[:, 2]), at_time)
    return {
        "roll": rms(wrap(at(simulated[:, 0]) - angles[:, 0])),
        "pitch": rms(wrap(at(simulated[:, 1]) - angles[:, 1])),
        "yaw_rate": rms(at(sim_yaw_rate) - measured_yaw_rate),
        "heave": rms(at(position[:, 2]) - measured_position[:, 2]),
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


def plot_replay(result: Replay, path: str | os.PathLike[str]) -> None:
    """A figure of the vehicle's roll, pitch, yaw and heave over time (and the measured ones,
    when the log has them, with each panel's RMS error of simulated against measured: of the yaw
    rate on the yaw's), what drove it in its title (the arm, and the thrusters when the log's
    commands drove them), its start twist written below, saved to ``path``. Drawn without pyplot
    (no backend chosen, no window)."""
    from matplotlib.figure import Figure

    euler = result.euler()
    figure = Figure(figsize=(8, 8))
    axes = figure.subplots(4, 1, sharex=True)
    labels = ["roll [rad]", "pitch [rad]", "yaw [rad]", "heave z [m]"]
    series = [euler[:, 0], euler[:, 1], np.unwrap(euler[:, 2]), result.position[:, 2]]
    for axis, label, values in zip(axes, labels, series, strict=True):
        axis.plot(result.time, values, label="simulated")
        axis.set_ylabel(label)
        axis.grid(True, alpha=0.3)
    if result.measured is not None:
        time, position, quaternion = result.measured
        angles = _euler(quaternion)
        for axis, values in zip(axes, [angles[:, 0], angles[:, 1], np.unwrap(angles[:, 2]), position[:, 2]], strict=True):
            axis.plot(time, values, "--", label="measured")
    if result.errors is not None:
        said = (("roll", "rad"), ("pitch", "rad"), ("yaw_rate", "rad/s"), ("heave", "m"))
        for axis, (name, unit) in zip(axes, said, strict=True):
            what = "yaw rate" if name == "yaw_rate" else name
            text = f"RMS error of the {what}, simulated − measured: {result.errors[name]:.2g} {unit}"
            axis.set_title(text, loc="right", fontsize=7, color="0.3")  # above the panel: over no curve
    axes[0].legend(loc="best")
    axes[-1].set_xlabel("time [s]")
    driven = result.thrusters is not None and result.thrusters.driven
    idle = result.thrusters is not None and result.thrusters.count > 0 and not driven
    figure.suptitle(
        "the vehicle's response to the replayed arm motion"
        + (" and the log's thruster commands" if driven else " (its thrusters idle: the log has no commands)" if idle else "")
    )
    figure.tight_layout(rect=(0.0, 0.03, 1.0, 1.0))
    if result.start is not None:
        figure.text(0.01, 0.005, result.start.describe(), fontsize=8)
    figure.savefig(path, dpi=120)


def command(
    log: str | os.PathLike[str] | Sequence[str | os.PathLike[str]],
    description: str | os.PathLike[str],
    hydro: str | os.PathLike[str] | None,
    out: str | os.PathLike[str],
    *,
    parquet: bool = False,
    as_json: bool = False,
    **settings: Any,
) -> int:
    """``uwml replay``: :func:`replay` (``settings``: its keywords), write ``replay.csv``
    (``.parquet``) and ``replay.png`` in ``out``, print the errors and the start twist (a table,
    or JSON with ``as_json``: :meth:`Replay.summary`)."""
    import json
    from pathlib import Path

    result = replay(log, description, hydro, progress=not as_json, **settings)
    folder = Path(out)
    folder.mkdir(parents=True, exist_ok=True)
    write_replay(result, folder / ("replay.parquet" if parquet else "replay.csv"))
    plot_replay(result, folder / "replay.png")
    if as_json:
        print(json.dumps(result.summary()))
        return 0
    print(f"replayed {result.time[-1] - result.time[0]:.3f} s; outputs in {folder}")
    if result.start is not None:
        print(f"  {result.start.describe()}")
    if result.motion is not None and result.motion.smoothing_s is not None:
        kept = ", ".join(str(k) for k in result.motion.kept)
        print(
            f"  joints smoothed over {result.motion.smoothing_s:g} s; samples kept of {result.motion.samples} after collapsing repeats: {kept}"
        )
    if result.bridged:
        print(f"  {result.bridged} gap{'s' if result.bridged > 1 else ''} in the pose stream bridged by interpolation")
    if result.thrusters is not None and (result.thrusters.count or result.thrusters.driven):
        print(f"  {result.thrusters.describe()}")
    if result.errors is None:
        print("no measured pose in the log: nothing to compare")
        return 0
    units = {"roll": "rad", "pitch": "rad", "yaw_rate": "rad/s", "heave": "m"}
    for name, value in result.errors.items():
        print(f"  RMS {name:9s} {value:.4g} {units[name]}")
    return 0
