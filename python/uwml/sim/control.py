"""Closed-loop control in simulation, on any robot in MuJoCo with uwml's forces
(:mod:`uwml.sim.mujoco`): a fixed-base robot following a joint trajectory under PD plus the
rigid body's inverse dynamics plus a feedforward (:func:`track`), and a vehicle holding station
in a current while its arm moves (:func:`rov_drift`). The paper's control question
(:mod:`uwml.paper.control_study`) and the studies' scenarios (:mod:`uwml.study.scenarios`) are
built on them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..examples import arm_on_rov
from ..model.parts import Link, Water
from ..robot.base_motion import BaseMotion
from ..robot.tree import Robot
from .mjcf import mjcf_of
from .mujoco import Simulation
from .prescribed import SineTrajectory

__all__ = ["ROV_CURRENT", "SEA", "TEMPERATURE_C", "Drift", "rov_drift", "track"]

FloatArray = NDArray[np.float64]

#: The sea water of the simulated studies (1025 kg/m³) and its temperature [°C].
SEA = Water(density=1025.0, gravity=9.81)
TEMPERATURE_C = 4.0


def track(
    sim: Simulation, known: Any, desired: tuple[FloatArray, FloatArray, FloatArray], feedforward: FloatArray, pd_hz: float
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """A fixed-base robot in ``sim`` following the ``desired`` joint trajectory ``(q, q̇, q̈)`` (one
    row per step) under PD (a critically damped ``pd_hz`` loop on each joint's rigid inertia at
    the start) plus the rigid body's inverse dynamics of the model ``known`` (what the controller
    knows: ``mj_inverse``) plus ``feedforward``: the joints' ``q``, ``q̇`` and the motor torque at
    every step."""
    import mujoco

    q_d, qd_d, qdd_d = desired
    land = mujoco.MjData(known)
    land.qpos[:] = q_d[0]
    mujoco.mj_forward(known, land)
    inertia = np.zeros((known.nv, known.nv))
    mujoco.mj_fullM(known, land, inertia)
    omega = 2.0 * math.pi * pd_hz
    kp, kd = np.diag(inertia) * omega**2, 2.0 * np.diag(inertia) * omega
    sim.data.qpos[:], sim.data.qvel[:] = q_d[0], qd_d[0]
    q, qd, torque = np.zeros_like(q_d), np.zeros_like(q_d), np.zeros_like(q_d)
    steps = len(q_d) - 1
    for k in range(steps + 1):
        q[k], qd[k] = sim.data.qpos, sim.data.qvel
        land.qpos[:], land.qvel[:], land.qacc[:] = q_d[k], qd_d[k], qdd_d[k]
        mujoco.mj_inverse(known, land)
        torque[k] = land.qfrc_inverse + feedforward[k] + kp * (q_d[k] - q[k]) + kd * (qd_d[k] - qd[k])
        if k < steps:
            sim.step(torque=torque[k])
    return q, qd, torque


@dataclass(frozen=True)
class Drift:
    """An ROV holding station while its arm moves, in a current: the vehicle's position [m]
    (world) and attitude error [rad] over time, with or without uwml's base wrench."""

    station_keeping: str
    time: FloatArray
    position: FloatArray
    attitude: FloatArray

    def summary(self) -> dict[str, Any]:
        distance = np.linalg.norm(self.position - self.position[0], axis=1)
        return {
            "station_keeping": self.station_keeping,
            "rms_drift_m": float(np.sqrt(np.mean(distance**2))),
            "max_drift_m": float(np.max(distance)),
            "rms_attitude_deg": float(np.degrees(np.sqrt(np.mean(self.attitude**2)))),
        }


#: The current of the vehicle study [m/s], along the world x axis.
ROV_CURRENT = 0.5


def rov_drift(with_uwml: bool, duration: float = 10.0, timestep: float = 2e-3, current: float = ROV_CURRENT) -> Drift:
    """The arm of :func:`uwml.examples.arm_on_rov` on its free-floating hull (trimmed neutrally
    buoyant in the study's sea water) moves its joints along sines in a ``current`` along x
    [m/s, default 0.5] while a
    station-keeping PD (0.3 Hz, critically damped, on the vehicle's total rigid mass and inertia,
    ideal thrusters) holds the vehicle, ``with_uwml``: plus the feedforward of uwml's predicted
    wrench on the vehicle (hydrodynamics, buoyancy and the robot's weight, at the measured state)."""
    import mujoco

    arm = arm_on_rov()
    hull = arm.base
    assert hull is not None
    arm_mass = sum(link.mass for link in arm.links)
    volume = hull.volume + sum(link.volume for link in arm.links)
    trimmed = Link(SEA.density * volume - arm_mass, hull.com, hull.volume, cob=hull.cob, segments=hull.segments, name="hull")
    robot = Robot(arm.joints, arm.links, base=trimmed, water=SEA)
    model = mujoco.MjModel.from_xml_string(mjcf_of(robot, floating=True, timestep=timestep))
    sim = Simulation(model, robot, current=(current, 0.0, 0.0), depth=1000.0, temperature_c=TEMPERATURE_C)
    mujoco.mj_forward(sim.model, sim.data)
    inertia = np.zeros((sim.model.nv, sim.model.nv))
    mujoco.mj_fullM(sim.model, sim.data, inertia)
    rigid = np.diag(inertia)
    omega = 2.0 * math.pi * 0.3
    kp_base, kd_base = rigid[:6] * omega**2, rigid[:6] * 2.0 * omega
    arm_omega = 2.0 * math.pi * 3.0
    kp_arm, kd_arm = rigid[6:] * arm_omega**2, rigid[6:] * 2.0 * arm_omega
    trajectory = SineTrajectory([0.4, 0.3, 0.5, 0.6, 0.4, 0.6, 0.0], period=4.0)
    steps = round(duration / timestep)
    time = np.arange(steps + 1, dtype=np.float64) * timestep
    q_d, qd_d, _ = trajectory.joint_states(time)
    sim.data.qpos[7:], sim.data.qvel[6:] = q_d[0], qd_d[0]
    start = np.array(sim.data.qpos[:3])
    position, attitude = np.zeros((steps + 1, 3)), np.zeros(steps + 1)
    for k in range(steps + 1):
        d = sim.data
        position[k] = d.qpos[:3]
        w, x, y, z = d.qpos[3:7]
        angle = 2.0 * math.atan2(math.sqrt(x * x + y * y + z * z), abs(w))
        attitude[k] = angle
        if k == steps:
            break
        axis_angle = np.array([x, y, z]) * (angle / max(math.sqrt(x * x + y * y + z * z), 1e-300)) * (1.0 if w >= 0.0 else -1.0)
        thrust = np.zeros(sim.model.nv)
        thrust[:3] = -kp_base[:3] * (d.qpos[:3] - start) - kd_base[:3] * d.qvel[:3]
        thrust[3:6] = -kp_base[3:6] * axis_angle - kd_base[3:6] * d.qvel[3:6]
        if with_uwml:
            mujoco.mj_kinematics(sim.model, d)
            rotation = d.xmat[1].reshape(3, 3)
            q, qd = d.qpos[7:].copy(), d.qvel[6:].copy()
            v_body, w_body = rotation.T @ d.qvel[:3], d.qvel[3:6].copy()
            motion = BaseMotion(orientation=np.array(d.qpos[3:7]), velocity=v_body, angular_velocity=w_body)
            wrench = robot.hydro(q, qd, np.zeros_like(q), base=True, base_motion=motion, current=(current, 0.0, 0.0)).base
            assert wrench is not None
            predicted = wrench.total + wrench.gravity
            thrust[:3] -= rotation @ predicted[:3]
            thrust[3:6] -= predicted[3:6]
        torque = kp_arm * (q_d[k] - d.qpos[7:]) + kd_arm * (qd_d[k] - d.qvel[6:])
        sim.step(torque=torque, qfrc=thrust)
    return Drift("PD + uwml base wrench" if with_uwml else "PD", time, position, attitude)
