"""A floating vehicle holding its pose through its thrusters while its arm moves
(:func:`hold_station`), in a :class:`uwml.sim.mujoco.Simulation`: the vehicle study of
:mod:`uwml.study.vehicle` is built on it (docs/scale.md, "A vehicle of your own").

**The controller** (:class:`StationKeeper`), each time step:

1. The pose error in the body frame: position ``e_p = Rᵀ (p − p₀)`` and attitude ``e_θ``, the
   rotation vector of ``q₀⁻¹ ⊗ q`` (``p₀``, ``q₀``: the pose held, the start's); the body twist
   ``ν = (Rᵀ v, ω)``.
2. The wrench asked, about the base origin in base axes: ``W = −K_p e − K_d ν − K_i ∫e dt``
   (+ the feedforward), each axis a critically damped loop of ``bandwidth_hz`` on the vehicle's
   mass there at the start (``ω = 2π·bandwidth_hz``, ``m`` the diagonal of the rigid and added
   mass: ``K_p = m ω²``, ``K_d = 2 m ω``; with ``integral``, ``K_i = K_p ω / 4``, integrated only
   while no thruster saturates).
3. The thrusts ``T = B⁺ W`` (``B`` the allocation matrix, :meth:`uwml.Robot.thruster_allocation`,
   at the arm's joint positions; ``B⁺`` its pseudo-inverse, the least-squares wrench where ``B``
   has rank below 6), then **saturated**: scaled down whole until each is within what its
   thruster gives (so the wrench keeps its direction), then clipped.
4. The commands: each thrust's command by its curve's inverse (:mod:`uwml.sim.thrust_inverse`),
   held until the next step (:meth:`Simulation.command_thrusters`).

**The feedforward** (``feedforward=True``) is the wrench the thrusters must give for the vehicle
to stay at zero acceleration at the state measured, the arm on its planned motion: the base rows
of the rigid body's inverse dynamics (MuJoCo's ``mj_inverse`` on the description's model as
the controller knows it: the arm at its planned acceleration, the vehicle's acceleration zero,
gravity and the velocity terms included), minus uwml's environment wrench on the base
(:meth:`uwml.Robot.hydro`'s ``base``: buoyancy with Froude-Krylov, plus
``coefficient_scale`` times drag and added mass, the latter at the arm's planned acceleration,
in the simulation's current). With the controller's model equal to the plant's, it is the whole
wrench of the arm and the water on the vehicle; a payload the controller does not know, or
``coefficient_scale ≠ 1``, is what the feedback must make up.

**What is measured** (:class:`StationRecord`): the position error ``p − p₀`` [m] (world), roll and
pitch of ``R₀ᵀ R`` [rad] (ZYX angles), each thruster's thrust [N] and whether it saturated, at
every step.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..robot.base_motion import BaseMotion
from ..robot.tree import Robot
from ._dof_map import map_degrees_of_freedom
from .mujoco import Simulation
from .prescribed import Trajectory
from .thrust_inverse import ThrustInverses

__all__ = ["StationKeeper", "StationRecord", "hold_station", "with_payload"]

FloatArray = NDArray[np.float64]


def _rotation(mj: Any, quaternion: FloatArray) -> FloatArray:
    """World from body, of a unit quaternion ``(w, x, y, z)`` (MuJoCo's ``mju_quat2Mat``)."""
    matrix = np.empty(9)
    mj.mju_quat2Mat(matrix, quaternion)
    return matrix.reshape(3, 3)


def _rotation_vector(mj: Any, held: FloatArray, quaternion: FloatArray) -> FloatArray:
    """The rotation vector of ``held⁻¹ ⊗ quaternion``, the shorter way round (MuJoCo's
    ``mju_quat2Vel`` over one second)."""
    inverse, turn, vector = np.empty(4), np.empty(4), np.empty(3)
    mj.mju_negQuat(inverse, held)
    mj.mju_mulQuat(turn, inverse, quaternion)
    mj.mju_quat2Vel(vector, turn, 1.0)
    return vector


def with_payload(model: Any, robot: Robot, mass: float) -> Any:
    """``model`` (changed in place, and returned) with ``mass`` [kg] added at the centre of mass
    of the body of the robot's last joint (a point mass: the body's inertia about its centre of
    mass unchanged); no volume, so no buoyancy: a payload of ``mass`` in the water's weight."""
    if mass == 0.0 or robot.n_joints == 0:
        return model
    import mujoco

    dofs = map_degrees_of_freedom(mujoco, model, robot)
    body = int(model.dof_bodyid[dofs.joint_dofs[-1]])
    model.body_mass[body] += mass
    return model


@dataclass(frozen=True)
class StationRecord:
    """What :func:`hold_station` measured (module docstring), at each of ``n`` steps' start and
    the end: ``time`` [s] ``(n + 1,)``, ``position_error`` [m] ``(n + 1, 3)``, ``roll`` and
    ``pitch`` [rad] ``(n + 1,)``; during each step: ``thrust`` [N] ``(n, thrusters)`` and
    ``saturated`` ``(n,)``."""

    time: FloatArray
    position_error: FloatArray
    roll: FloatArray
    pitch: FloatArray
    thrust: FloatArray
    saturated: NDArray[np.bool_]

    def metrics(self) -> dict[str, float]:
        """``rms_drift``, ``max_drift`` [m] (the distance from the pose held), ``rms_roll``,
        ``max_roll``, ``rms_pitch``, ``max_pitch`` [°], ``mean_thrust`` (``|T|`` over thrusters
        and time) and ``peak_thrust`` [N], ``thrust_energy`` (``∫ Σ |T_k|^{3/2} dt``
        [N^1.5·s], proportional to an ideal propeller's energy by momentum theory) and
        ``saturation`` (the fraction of steps with a thruster saturated)."""
        distance = np.linalg.norm(self.position_error, axis=1)
        roll, pitch = np.degrees(np.abs(self.roll)), np.degrees(np.abs(self.pitch))
        magnitude = np.abs(self.thrust)
        dt = np.diff(self.time)
        some = magnitude.size > 0
        return {
            "rms_drift": float(np.sqrt(np.mean(distance**2))),
            "max_drift": float(np.max(distance)),
            "rms_roll": float(np.sqrt(np.mean(roll**2))),
            "max_roll": float(np.max(roll)),
            "rms_pitch": float(np.sqrt(np.mean(pitch**2))),
            "max_pitch": float(np.max(pitch)),
            "mean_thrust": float(np.mean(magnitude)) if some else 0.0,
            "peak_thrust": float(np.max(magnitude)) if some else 0.0,
            "thrust_energy": float(np.sum(np.sum(magnitude**1.5, axis=1) * dt)) if some else 0.0,
            "saturation": float(np.mean(self.saturated)) if self.saturated.size else 0.0,
        }


class StationKeeper:
    """The controller of the module docstring for the floating vehicle of ``sim``, holding the
    pose it has now, the arm on ``motion`` (None: a vehicle without joints). ``known``: the
    MuJoCo model the controller knows (default the simulation's: a payload it does not know is
    added to the simulation's only)."""

    def __init__(
        self,
        sim: Simulation,
        motion: Trajectory | None,
        *,
        bandwidth_hz: float = 0.5,
        integral: bool = False,
        feedforward: bool = True,
        coefficient_scale: float = 1.0,
        known: Any = None,
    ) -> None:
        import mujoco

        if not (math.isfinite(bandwidth_hz) and bandwidth_hz > 0.0):
            raise ValueError(f"bandwidth_hz must be a positive number, got {bandwidth_hz!r}")
        if not (math.isfinite(coefficient_scale) and coefficient_scale >= 0.0):
            raise ValueError(f"coefficient_scale must be a non-negative number, got {coefficient_scale!r}")
        robot = sim.robot
        dofs = map_degrees_of_freedom(mujoco, sim.model, robot)
        if dofs.free_qpos is None or dofs.free_dof is None:
            raise ValueError("station keeping needs a floating vehicle: the simulation's base is fixed")
        if not robot.thrusters:
            raise ValueError("station keeping needs thrusters: the robot has none (a hydro file's [[links.NAME.thrusters]])")
        self._sim, self._motion, self._mj = sim, motion, mujoco
        self._qpos, self._dof = dofs.free_qpos, dofs.free_dof
        self._joint_qpos, self._joint_dofs = dofs.joint_qpos, dofs.joint_dofs
        self._inverses = ThrustInverses([t for _, t in robot.thrusters])
        self._on_links = any(body >= 0 for body, _ in robot.thrusters)
        self._allocation = None if self._on_links else np.asarray(np.linalg.pinv(robot.thruster_allocation()), dtype=np.float64)
        self._feedforward, self._scale = feedforward, float(coefficient_scale)
        self._known = sim.model if known is None else known
        self._known_data = mujoco.MjData(self._known)
        d = sim.data
        self.position = np.array(d.qpos[self._qpos : self._qpos + 3])
        self.orientation = np.array(d.qpos[self._qpos + 3 : self._qpos + 7])
        # Each axis's mass at the start: the rigid body's (the known model) and the added mass.
        k = self._known_data
        k.qpos[:], k.qvel[:] = d.qpos, 0.0
        mujoco.mj_forward(self._known, k)
        inertia = np.zeros((self._known.nv, self._known.nv))
        mujoco.mj_fullM(self._known, k, inertia)
        rigid = np.diag(inertia)[self._dof : self._dof + 6]
        added = np.diag(sim.environment()[1])[:6]
        mass = rigid + added
        omega = 2.0 * math.pi * bandwidth_hz
        self.kp, self.kd = mass * omega**2, 2.0 * mass * omega
        self.ki = self.kp * omega / 4.0 if integral else np.zeros(6)
        self._integral = np.zeros(6)

    def _state(self) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray, FloatArray, FloatArray]:
        d, i, v = self._sim.data, self._qpos, self._dof
        quaternion = np.array(d.qpos[i + 3 : i + 7])
        return (
            np.array(d.qpos[i : i + 3]),
            quaternion,
            _rotation(self._mj, quaternion),
            np.array(d.qvel[v : v + 6]),
            np.array(d.qpos[self._joint_qpos]),
            np.array(d.qvel[self._joint_dofs]),
        )

    def feedforward(self) -> FloatArray:
        """The feedforward wrench (module docstring) at the simulation's state and time."""
        d, mj = self._sim.data, self._mj
        _, quaternion, rotation, twist, q, qd = self._state()
        qdd = np.zeros_like(q) if self._motion is None else self._motion(float(d.time))[2]
        k = self._known_data
        k.qpos[:], k.qvel[:], k.qacc[:] = d.qpos, d.qvel, 0.0
        k.qacc[self._joint_dofs] = qdd
        mj.mj_inverse(self._known, k)
        needed = k.qfrc_inverse[self._dof : self._dof + 6]
        rigid = np.concatenate([rotation.T @ needed[:3], needed[3:]])
        v, w = rotation.T @ twist[:3], twist[3:]
        motion = BaseMotion(orientation=quaternion, velocity=v, angular_velocity=w, acceleration=-np.cross(w, v))
        base = self._sim.robot.hydro(q, qd, qdd, base=True, base_motion=motion, current=self._sim.current, water=self._sim.water).base
        assert base is not None
        return rigid - (self._scale * (base.drag + base.added_mass) + base.buoyancy)

    def step(self, dt: float) -> tuple[FloatArray, bool]:
        """Commands the thrusters for the next ``dt`` seconds: the thrusts asked [N] (after
        saturation) and whether any saturated."""
        position, quaternion, rotation, twist, q, _ = self._state()
        error = np.concatenate([rotation.T @ (position - self.position), _rotation_vector(self._mj, self.orientation, quaternion)])
        nu = np.concatenate([rotation.T @ twist[:3], twist[3:]])
        wrench = -self.kp * error - self.kd * nu - self.ki * self._integral
        if self._feedforward:
            wrench += self.feedforward()
        allocation = self._allocation if self._allocation is not None else np.linalg.pinv(self._sim.robot.thruster_allocation(q))
        thrust = allocation @ wrench
        low, high = self._inverses.low, self._inverses.high
        with np.errstate(divide="ignore", invalid="ignore"):
            room = np.where(thrust > high, high / thrust, np.where(thrust < low, low / thrust, 1.0))
        scale = float(np.clip(np.min(room, initial=1.0), 0.0, 1.0))
        thrust = np.clip(thrust * scale, low, high)
        saturated = scale < 1.0
        if not saturated:
            self._integral += error * dt
        self._sim.command_thrusters(self._inverses.commands(thrust))
        return thrust, saturated


def hold_station(sim: Simulation, motion: Trajectory | None, duration: float, keeper: StationKeeper | None) -> StationRecord:
    """``sim``'s floating vehicle for ``duration`` seconds from its state now (the pose held:
    that one), its joints on ``motion`` (prescribed, :meth:`Simulation.prescribe`; None: a
    vehicle without joints), ``keeper`` commanding the thrusters each step (None: the thrusters
    idle, the vehicle adrift)."""
    import mujoco

    dofs = map_degrees_of_freedom(mujoco, sim.model, sim.robot)
    if dofs.free_qpos is None:
        raise ValueError("hold_station needs a floating vehicle: the simulation's base is fixed")
    if not (math.isfinite(duration) and duration > 0.0):
        raise ValueError(f"duration must be a positive number of seconds, got {duration!r}")
    if motion is not None:
        sim.prescribe(list(range(sim.robot.n_joints)), motion)
    d, i = sim.data, dofs.free_qpos
    dt = float(sim.model.opt.timestep)
    steps = max(1, round(duration / dt))
    start_position = np.array(d.qpos[i : i + 3])
    held = _rotation(mujoco, np.array(d.qpos[i + 3 : i + 7]))
    n_thrusters = len(sim.robot.thrusters)
    time, position, roll, pitch = np.zeros(steps + 1), np.zeros((steps + 1, 3)), np.zeros(steps + 1), np.zeros(steps + 1)
    thrust, saturated = np.zeros((steps, n_thrusters)), np.zeros(steps, dtype=bool)
    for k in range(steps + 1):
        time[k] = d.time
        position[k] = d.qpos[i : i + 3] - start_position
        turn = held.T @ _rotation(mujoco, np.array(d.qpos[i + 3 : i + 7]))
        roll[k] = math.atan2(turn[2, 1], turn[2, 2])
        pitch[k] = -math.asin(min(max(turn[2, 0], -1.0), 1.0))
        if k == steps:
            break
        if keeper is not None:
            _, saturated[k] = keeper.step(dt)
        thrust[k] = sim.thrust
        sim.step()
        if not np.all(np.isfinite(d.qpos)):
            raise FloatingPointError(f"the simulation diverged at t = {d.time:.6g} s (a non-finite state)")
    return StationRecord(time, position, roll, pitch, thrust, saturated)
