"""The ``vehicle`` scenario of a study (:mod:`uwml.study.scenarios`): a floating vehicle of one's
own, from its description, holding station through its thrusters while its arm moves
(:func:`uwml.sim.station_keeping.hold_station`; docs/scale.md, "A vehicle of your own").

A run: the description (``robot``, a URDF or MJCF file, and its ``hydro`` file, whose
``[base] floating = true`` floats it; or an MJCF whose root has a free joint) simulated in
MuJoCo with uwml's forces for ``duration`` seconds, at rest and level at the start, in a
``current`` [m/s] flowing at ``current_heading`` [°, from x towards y] in the horizontal plane, at
``depth`` [m]; a ``payload`` [kg, unknown to the controller] at the centre of mass of the last
joint's link (:func:`uwml.sim.station_keeping.with_payload`). The arm's joints are prescribed:

* sines: every joint ``amplitude · sin(2π t / period + j π/3)`` (joint ``j`` from 0), or
* a log of joint angles (``trajectory``: a file of :func:`uwml.io.read_log`'s format, ``time``
  and ``q1`` … ``qN`` for the description's joints, cleaned as a replay's,
  :func:`uwml.sim.replay_inputs.joint_motion`), from its first sample, over ``duration``.

``station_keeping``: ``off`` (thrusters idle), ``pd`` or ``pid`` (:class:`StationKeeper` of
``bandwidth_hz``), or ``log``: the thrusters driven open loop by the commands of a log
(``commands``: a file of :func:`uwml.io.read_log`'s format with ``time`` and ``u1`` … ``un``, one per
thruster of the description; each command held from its sample, as an ESC holds it, from the
log's first sample over ``duration``); ``feedforward``: ``none`` or ``uwml`` (the wrench of the arm and the water on
the vehicle, the controller's drag and added mass ``coefficient_scale`` times the plant's).
Metrics: :meth:`uwml.sim.station_keeping.StationRecord.metrics`.
"""

from __future__ import annotations

import copy
import math
from collections.abc import Iterable
from typing import Any

import numpy as np

__all__ = ["METRICS", "check_vehicle", "vehicle_run"]

#: The vehicle scenario's metrics and their units
#: (:meth:`uwml.sim.station_keeping.StationRecord.metrics`).
METRICS: dict[str, str] = {
    "rms_drift": "m",
    "max_drift": "m",
    "rms_roll": "°",
    "max_roll": "°",
    "rms_pitch": "°",
    "max_pitch": "°",
    "mean_thrust": "N",
    "peak_thrust": "N",
    "thrust_energy": "N^1.5·s",
    "saturation": "fraction of steps",
}


def _model_and_robot(values: dict[str, Any]) -> tuple[Any, Any]:
    """The description's model and robot, refused unless it floats."""
    import mujoco

    from ..robot.files import model_and_robot
    from ..sim._dof_map import map_degrees_of_freedom

    model, robot = model_and_robot(values["robot"], values.get("hydro"))
    if not map_degrees_of_freedom(mujoco, model, robot).floating:
        hydro = values.get("hydro")
        where = f"its hydro file {hydro}" if hydro else "no hydro file"
        raise ValueError(
            f"{values['robot']} does not float ({where}): a vehicle study needs a floating vehicle; "
            "set [base] floating = true in the hydro file (or give an MJCF root body a free joint)"
        )
    return model, robot


def check_vehicle(settings: dict[str, Any], station_keeping: Iterable[str]) -> None:
    """A ValueError if the vehicle scenario cannot run its description (``settings``): it does
    not float, it has no thrusters though a run keeps station (``station_keeping``: every value a
    run may take), or a thruster's curve cannot be inverted."""
    from ..sim.thrust_inverse import ThrustInverses

    _, robot = _model_and_robot(settings)
    keeping = sorted(set(station_keeping) - {"off"})
    if "log" in keeping:
        _recorded_commands(settings, len(robot.thrusters), float(settings.get("duration", 0.0)))
        keeping.remove("log")
    if keeping and not robot.thrusters:
        raise ValueError(
            f"{settings['robot']} has no thrusters (a hydro file's [[links.NAME.thrusters]]), so station_keeping = "
            f'{keeping[0]!r} cannot hold it: give it thrusters, or set station_keeping = "off"'
        )
    ThrustInverses([t for _, t in robot.thrusters])


def _recorded_commands(values: dict[str, Any], count: int, duration: float) -> tuple[np.ndarray, np.ndarray]:
    """The times and thruster commands of ``values["commands"]`` (``station_keeping = "log"``),
    checked: ``count`` commands (one per thruster), spanning ``duration`` from the first sample."""
    from ..io.column_map import open_table
    from ..io.vehicle_columns import thruster_columns

    path = values.get("commands")
    if path is None:
        raise ValueError('station_keeping = "log" needs commands = "a log of time and u1 … un" in [scenario]')
    source, header, read = open_table(path)
    names = thruster_columns(header, source)
    if len(names) != count:
        raise ValueError(f"{source}: the log has {len(names)} thruster commands (u1 …), the description {count} thrusters")
    columns = read(["time", *names])
    time, commands = np.asarray(columns["time"], dtype=float), np.column_stack([columns[name] for name in names])
    if time.size < 1 or np.any(np.diff(time) <= 0.0) or not np.all(np.isfinite(commands)):
        raise ValueError(f"{source}: the commands' times must increase and the commands be finite numbers")
    span = float(time[-1] - time[0])
    if span < duration:
        raise ValueError(f"{source}: the commands span {span:.6g} s, shorter than the run's duration of {duration:g} s")
    return time - time[0], commands


class _LoggedCommands:
    """The thrusters of ``sim`` driven by recorded commands (``station_keeping = "log"``): each
    step holds the last sample at or before its start (the interface of :class:`StationKeeper`'s
    ``step``)."""

    def __init__(self, sim: Any, times: np.ndarray, commands: np.ndarray) -> None:
        self._sim, self._times, self._commands, self._start = sim, times, commands, float(sim.data.time)

    def step(self, dt: float) -> tuple[np.ndarray, bool]:
        at = float(self._sim.data.time) - self._start
        index = max(0, int(np.searchsorted(self._times, at + 1e-9, side="right")) - 1)
        self._sim.command_thrusters(self._commands[index])
        return self._sim.thrust, False


def _motion(values: dict[str, Any], robot: Any, duration: float, timestep: float) -> Any:
    """The arm's prescribed motion (module docstring), starting at t = 0; None without joints."""
    from ..sim.prescribed import SineTrajectory, Trajectory

    n = robot.n_joints
    if n == 0:
        return None
    if values.get("trajectory") is None:
        sine = SineTrajectory(
            [float(values["amplitude"])] * n, float(values["period"]), harmonics=np.ones(n), phases=np.arange(n) * math.pi / 3.0
        )
        time = np.arange(max(4, math.ceil(duration / timestep) + 3)) * timestep
        return Trajectory(time, *sine.joint_states(time))
    from ..io.logs import read_log
    from ..sim.replay_inputs import check_joints, joint_motion

    recorded = read_log(values["trajectory"])
    check_joints(recorded, robot.joints, 2, str(values["robot"]))
    motion = joint_motion(recorded, robot.joints)
    span = float(motion.time[-1] - motion.time[0])
    if span < max(1, round(duration / timestep)) * timestep * (1.0 - 1e-12):  # hold_station's last step
        raise ValueError(f"{values['trajectory']}: the log spans {span:.6g} s, shorter than the run's duration of {duration:g} s")
    return Trajectory(motion.time - motion.time[0], motion.q, motion.qd, motion.qdd)


def vehicle_run(values: dict[str, Any]) -> dict[str, float]:
    """One run of the vehicle scenario (module docstring): its metrics."""
    from ..sim.mujoco import Simulation
    from ..sim.station_keeping import StationKeeper, hold_station, with_payload

    model, robot = _model_and_robot(values)
    known = copy.deepcopy(model)  # the controller's: without the payload
    with_payload(model, robot, float(values["payload"]))
    heading = math.radians(float(values["current_heading"]))
    speed = float(values["current"])
    current = (speed * math.cos(heading), speed * math.sin(heading), 0.0)
    sim = Simulation(model, robot, depth=float(values["depth"]), current=current)
    duration = float(values["duration"])
    motion = _motion(values, robot, duration, float(model.opt.timestep))
    if motion is not None:  # the arm on its motion before the controller measures the vehicle's mass
        sim.prescribe(list(range(robot.n_joints)), motion)
    keeper: Any = None
    if values["station_keeping"] == "log":
        keeper = _LoggedCommands(sim, *_recorded_commands(values, len(robot.thrusters), duration))
    elif values["station_keeping"] != "off":
        keeper = StationKeeper(
            sim,
            motion,
            bandwidth_hz=float(values["bandwidth_hz"]),
            integral=values["station_keeping"] == "pid",
            feedforward=values["feedforward"] == "uwml",
            coefficient_scale=float(values["coefficient_scale"]),
            known=known,
        )
    return hold_station(sim, motion, duration, keeper).metrics()
