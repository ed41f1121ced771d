"""Prescribed joint motion (docs/model.md section 12.4): chosen joints of a simulated robot follow a
given trajectory exactly, their accelerations imposed, while the rest of the robot (the floating
base above all) responds through the coupled equations of motion with ``M + M_A``. This is how a
vehicle's response to a recorded arm motion is simulated (pool trials with the thrusters off).

:class:`Trajectory` holds the motion: samples of time and angle (and, if known, velocity and
acceleration) interpolated by a cubic spline, whose derivatives estimate what is not given; or
any callable ``t -> (q, q̇, q̈)``. :func:`imposing_torque` is the one computation: with ``qacc₀``
MuJoCo's accelerations at the state without it, the torque on the prescribed joints that makes
their accelerations the trajectory's is ``τ_p = [(M⁻¹)_pp]⁻¹ (q̈_target − qacc₀_p)``, and the
accelerations of every degree of freedom change by ``M⁻¹[:, p] τ_p`` (``M`` MuJoCo's mass matrix with
the added mass in it, factored). It is exact where no constraint (contact, limit, joint friction)
acts; where one does, the constraint's force is that of the motion without the torque.

:class:`SineTrajectory` is a motion in closed form: sines, one harmonic of a period per joint, an
exciting trajectory for any robot (the synthetic experiments of :mod:`uwml.paper.synthetic`, the
vehicle of :func:`uwml.sim.control.rov_drift`).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.interpolate import CubicSpline

__all__ = ["SineTrajectory", "Trajectory", "imposing_torque"]

FloatArray = NDArray[np.float64]
MotionFunction = Callable[[float], tuple[ArrayLike, ArrayLike, ArrayLike]]


def _samples(value: ArrayLike | None, name: str, shape: tuple[int, int]) -> FloatArray | None:
    if value is None:
        return None
    array = np.asarray(value, dtype=np.float64)
    if array.ndim == 1 and shape[1] == 1:
        array = array[:, None]
    if array.shape != shape:
        raise ValueError(f"trajectory {name} must have shape {shape} (samples, joints), got {array.shape}")
    if not np.all(np.isfinite(array)):
        raise ValueError(f"trajectory {name} must be finite")
    return array


@dataclass(frozen=True, init=False)
class Trajectory:
    """The motion of ``k`` joints: at each time ``t`` their angles (or slides), velocities and
    accelerations.

    ``Trajectory(time, q, qd=None, qdd=None)``: samples, ``time`` strictly increasing ``(n,)``
    [s], ``q`` ``(n, k)`` (``(n,)`` for one joint); velocities and accelerations interpolated by
    the cubic splines of those given (``qd`` and ``qdd`` given: each its own spline; not given:
    the derivatives of ``q``'s spline, which is "not-a-knot" like scipy's default). Outside the
    samples' span the motion is refused, not extrapolated (a time past an end by no more than a
    simulation clock's rounding, :meth:`rounding`, is that end). ``Trajectory.of(function, k)``: any
    callable ``t -> (q, qd, qdd)`` of ``k`` numbers each."""

    joints: int
    start: float
    end: float
    _function: MotionFunction

    def __init__(self, time: ArrayLike, q: ArrayLike, qd: ArrayLike | None = None, qdd: ArrayLike | None = None) -> None:
        t = np.asarray(time, dtype=np.float64)
        if t.ndim != 1 or t.size < 4 or not np.all(np.isfinite(t)) or np.any(np.diff(t) <= 0.0):
            raise ValueError("trajectory time must be at least 4 finite, strictly increasing samples [s]")
        positions = np.asarray(q, dtype=np.float64)
        k = 1 if positions.ndim == 1 else positions.shape[1] if positions.ndim == 2 else 0
        if k == 0:
            raise ValueError(f"trajectory q must have shape ({t.size},) or ({t.size}, joints), got {positions.shape}")
        shape = (t.size, k)
        angles = _samples(positions, "q", shape)
        assert angles is not None  # given
        velocities, accelerations = _samples(qd, "qd", shape), _samples(qdd, "qdd", shape)
        spline = CubicSpline(t, angles, axis=0)
        rate = spline.derivative(1) if velocities is None else CubicSpline(t, velocities, axis=0)
        acceleration = (
            (spline.derivative(2) if velocities is None else rate.derivative(1))
            if accelerations is None
            else CubicSpline(t, accelerations, axis=0)
        )

        def motion(at: float) -> tuple[ArrayLike, ArrayLike, ArrayLike]:
            return spline(at), rate(at), acceleration(at)

        object.__setattr__(self, "joints", k)
        object.__setattr__(self, "start", float(t[0]))
        object.__setattr__(self, "end", float(t[-1]))
        object.__setattr__(self, "_function", motion)

    def rounding(self) -> float:
        """How far past an end [s] a time still counts as the end: a simulation's clock, the sum
        of its steps, drifts from the step grid by rounding (about 1e-11 s after 10,000 steps to
        17 s); 1e-9 of the span (at least 1e-9 s) and 64 units in the last place of the times'
        magnitude cover that, far below any step."""
        if not math.isfinite(self.end - self.start):
            return 0.0
        return 1e-9 * max(self.end - self.start, 1.0) + 64.0 * float(np.spacing(max(abs(self.start), abs(self.end))))

    @classmethod
    def of(cls, function: MotionFunction, joints: int) -> Trajectory:
        """The motion of ``joints`` joints given by ``function(t) -> (q, qd, qdd)``, at any time."""
        if not callable(function):
            raise TypeError(f"the motion must be a callable t -> (q, qd, qdd), got {type(function).__name__}")
        if isinstance(joints, bool) or not isinstance(joints, int) or joints < 1:
            raise ValueError(f"joints must be a positive integer, got {joints!r}")
        trajectory = cls.__new__(cls)
        object.__setattr__(trajectory, "joints", joints)
        object.__setattr__(trajectory, "start", -np.inf)
        object.__setattr__(trajectory, "end", np.inf)
        object.__setattr__(trajectory, "_function", function)
        return trajectory

    def __call__(self, t: float) -> tuple[FloatArray, FloatArray, FloatArray]:
        """``(q, qd, qdd)`` at time ``t``, each ``(joints,)``, checked. A time past either end by
        no more than the rounding of a simulation's clock (:meth:`rounding`) is the end."""
        slack = self.rounding()
        if not self.start - slack <= t <= self.end + slack:
            raise ValueError(f"the prescribed motion is given from t = {self.start:.9g} to {self.end:.9g} s, not at t = {t:.9g} s")
        values = self._function(min(max(t, self.start), self.end))
        out = []
        for name, value in zip(("q", "qd", "qdd"), values, strict=True):
            array = np.asarray(value, dtype=np.float64).reshape(-1)
            if array.shape != (self.joints,) or not np.all(np.isfinite(array)):
                raise ValueError(f"the prescribed motion's {name} at t = {t:g} s must be {self.joints} finite numbers, got {value!r}")
            out.append(array)
        return out[0], out[1], out[2]


class SineTrajectory:
    """Joint states ``q_j(t) = offset_j + amplitude_j sin(2π t / period · harmonic_j + phase_j)``,
    with their exact derivatives: an exciting trajectory for any robot (every joint moves with
    its own harmonic of ``period``, so the regressors of different joints are not proportional).

    ``amplitudes`` [rad or m], ``offsets`` (default 0), ``harmonics`` (default 1, 2, 3, ... per
    joint) and ``phases`` [rad] (default 0.7 j): one per joint; ``period`` [s] > 0.
    """

    def __init__(
        self,
        amplitudes: ArrayLike,
        period: float = 2.0,
        offsets: ArrayLike | None = None,
        harmonics: ArrayLike | None = None,
        phases: ArrayLike | None = None,
    ) -> None:
        amplitude = np.atleast_1d(np.asarray(amplitudes, dtype=np.float64))
        n = amplitude.size
        if amplitude.ndim != 1 or n == 0:
            raise ValueError(f"amplitudes must be one number per joint, got shape {np.shape(amplitudes)}")

        def per_joint(value: ArrayLike | None, default: NDArray[np.float64], name: str) -> NDArray[np.float64]:
            array = default if value is None else np.broadcast_to(np.asarray(value, dtype=np.float64), (n,)).copy()
            if not np.all(np.isfinite(array)):
                raise ValueError(f"{name} must be finite, got {value!r}")
            return array

        self.amplitudes = per_joint(amplitude, amplitude, "amplitudes")
        self.offsets = per_joint(offsets, np.zeros(n), "offsets")
        self.harmonics = per_joint(harmonics, np.arange(1.0, n + 1.0), "harmonics")
        self.phases = per_joint(phases, 0.7 * np.arange(n, dtype=np.float64), "phases")
        if not (np.isfinite(period) and period > 0.0):
            raise ValueError(f"period must be finite and > 0, got {period!r}")
        self.period = float(period)

    def joint_states(self, t: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
        """``(q, q̇, q̈)`` at times ``t`` [s], each ``(len(t), n_joints)``."""
        time = np.asarray(t, dtype=np.float64).reshape(-1, 1)
        omega = 2.0 * np.pi / self.period * self.harmonics
        angle = omega * time + self.phases
        q = self.offsets + self.amplitudes * np.sin(angle)
        qd = self.amplitudes * omega * np.cos(angle)
        qdd = -self.amplitudes * omega**2 * np.sin(angle)
        return q, qd, qdd


def imposing_torque(mujoco: Any, model: Any, data: Any, dofs: NDArray[np.int64], target: FloatArray) -> FloatArray:
    """The generalized force on the degrees of freedom ``dofs`` that makes their accelerations
    ``target`` (see the module), and ``data.qacc`` changed accordingly; ``data`` after a forward
    pass whose mass matrix is factored (``mj_factorM``)."""
    nv = model.nv
    unit = np.zeros((len(dofs), nv))
    unit[np.arange(len(dofs)), dofs] = 1.0
    solved = np.zeros((len(dofs), nv))
    mujoco.mj_solveM(model, data, solved, unit)  # one row per prescribed dof: M⁻¹ e_p
    columns = solved.T  # M⁻¹[:, p]
    block = columns[dofs, :]  # (M⁻¹)_pp
    torque = np.linalg.solve(block, target - data.qacc[dofs])
    data.qacc[:] += columns @ torque
    data.qacc[dofs] = target  # exact, not to rounding
    return torque
