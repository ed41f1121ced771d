"""Prescribed joint motion (docs/model.md section 12.4): chosen joints of a simulated robot follow a
given trajectory exactly, their accelerations imposed, while the rest of the robot (the floating
base above all) responds through the coupled equations of motion with ``M + M_A``. This is how a
vehicle's response to a recorded arm motion is simulated (pool trials with the thrusters off).

:class:`Trajectory` holds the motion: samples of time and angle (and, if known, velocity and
acceleration) interpolated by a cubic spline, whose derivatives estimate what is not given; or
any callable ``t -> (q, q̇, q̈)``. The simulation imposes it (natively, each step: the motion's
cubics are evaluated there, :attr:`Trajectory.pieces`): with ``qacc₀`` MuJoCo's accelerations at
the state without it, the torque on the prescribed joints that makes their accelerations the
trajectory's is ``τ_p = [(M⁻¹)_pp]⁻¹ (q̈_target − qacc₀_p)``, and the accelerations of every degree
of freedom change by ``M⁻¹[:, p] τ_p`` (``M`` MuJoCo's mass matrix with the added mass in it,
factored). It is exact where no constraint (contact, limit, joint friction) acts; where one does,
the constraint's force is that of the motion without the torque.

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

__all__ = ["PrescribedJoints", "SineTrajectory", "Trajectory"]

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
    simulation clock's rounding, :meth:`rounding`, is that end). ``Trajectory.of(function, joints=k)``: any
    callable ``t -> (q, qd, qdd)`` of ``k`` numbers each."""

    joints: int
    start: float
    end: float
    #: The motion from samples as cubics: its knots (the sample times) and the coefficients of
    #: ``q``, ``q̇``, ``q̈`` on each interval, each ``(4, n_samples - 1, joints)`` (scipy's
    #: ``PPoly.c``, highest degree first, in ``t - knots[i]``); None for ``Trajectory.of``.
    pieces: tuple[FloatArray, tuple[FloatArray, FloatArray, FloatArray]] | None
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
        from scipy.interpolate import CubicSpline  # here: scipy takes a while to import

        spline = CubicSpline(t, angles, axis=0)
        rate = spline.derivative(1) if velocities is None else CubicSpline(t, velocities, axis=0)
        acceleration = (
            (spline.derivative(2) if velocities is None else rate.derivative(1))
            if accelerations is None
            else CubicSpline(t, accelerations, axis=0)
        )

        def motion(at: float) -> tuple[ArrayLike, ArrayLike, ArrayLike]:
            return spline(at), rate(at), acceleration(at)

        def cubic(piecewise: Any) -> FloatArray:
            # A derivative's pieces are of lower degree: zeros for the missing leading powers.
            c = np.asarray(piecewise.c, dtype=np.float64)
            return np.concatenate([np.zeros((4 - c.shape[0], *c.shape[1:])), c]) if c.shape[0] < 4 else c

        object.__setattr__(self, "pieces", (t.copy(), tuple(cubic(p) for p in (spline, rate, acceleration))))
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
    def of(cls, function: MotionFunction, *, joints: int) -> Trajectory:
        """The motion of ``joints`` joints given by ``function(t) -> (q, qd, qdd)``, at any time
        (``joints`` a keyword: a bare number would read as a duration)."""
        if not callable(function):
            raise TypeError(f"the motion must be a callable t -> (q, qd, qdd), got {type(function).__name__}")
        if isinstance(joints, bool) or not isinstance(joints, int) or joints < 1:
            raise ValueError(f"joints must be a positive integer, got {joints!r}")
        trajectory = cls.__new__(cls)
        object.__setattr__(trajectory, "pieces", None)
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


def joint_index(joint: str | int, names: list[str | None]) -> int:
    """The index among the robot's joint ``names`` of ``joint`` (a name or an index), or a
    ValueError listing them."""
    if isinstance(joint, str) and joint in names:
        return names.index(joint)
    if isinstance(joint, int) and not isinstance(joint, bool) and 0 <= joint < len(names):
        return joint
    raise ValueError(f"no joint {joint!r} in the robot (its joints: {', '.join(str(n) for n in names)}, or 0 to {len(names) - 1})")


class PrescribedJoints:
    """Joints of a simulation held on a :class:`Trajectory` (what :meth:`uwml.sim.mujoco.
    Simulation.prescribe` makes): the joints by name or index among ``names``, their degrees of
    freedom and ``qpos`` entries among ``dofs`` and ``qpos``; the native ``coupling`` imposes
    the motion (its cubics where it has them, else the values this evaluates) and puts the
    joints back on it after each step. ``nv``: the model's degrees of freedom."""

    def __init__(
        self,
        joints: Any,
        motion: Trajectory,
        names: list[str | None],
        dofs: NDArray[np.int64],
        qpos: NDArray[np.int64],
        nv: int,
        coupling: Any,
    ) -> None:
        if not isinstance(motion, Trajectory):
            raise TypeError(f"motion must be a uwml.sim.prescribed.Trajectory or None, got {type(motion).__name__}")
        indices = [joint_index(joint, names) for joint in joints]
        if len(set(indices)) != len(indices) or not indices:
            raise ValueError(f"joints must name each prescribed joint once, got {list(joints)!r}")
        if motion.joints != len(indices):
            raise ValueError(f"the motion is of {motion.joints} joints, {len(indices)} are prescribed")
        self.motion, self.dofs, self.qpos = motion, dofs[indices], qpos[indices]
        #: ``M⁻¹``'s rows of the prescribed degrees of freedom are solved from these unit rows,
        #: into ``solved``, which the coupling reads.
        self.unit = np.zeros((len(indices), nv))
        self.unit[np.arange(len(indices)), self.dofs] = 1.0
        self.solved = np.zeros_like(self.unit)
        self._coupling = coupling
        pieces: dict[str, Any] = {}
        if motion.pieces is not None:
            knots, coefficients = motion.pieces
            pieces = {
                "knots": knots.tolist(),
                "coefficients": [np.ascontiguousarray(c).ravel() for c in coefficients],
                "slack": motion.rounding(),
            }
        coupling.prescribe(self.dofs.tolist(), self.qpos.tolist(), self.solved, **pieces)

    def impose(self, mujoco: Any, model: Any, data: Any) -> None:
        """The imposing torque at the data's time, after a forward pass whose ``M`` is factored
        (``data.qacc`` and ``data.qfrc_applied`` changed: see the module)."""
        mujoco.mj_solveM(model, data, self.solved, self.unit)
        t = float(data.time)
        status = self._coupling.impose(t) if self.motion.pieces is not None else self._coupling.impose(t, self.motion(t)[2].tolist())
        if status:
            self._refused(t, status)

    def put_on_motion(self, time: float) -> None:
        """The joints' ``qpos`` and ``qvel`` the motion's at ``time``."""
        if self.motion.pieces is not None:
            status = self._coupling.put_on_motion(time)
        else:
            q, qd, _ = self.motion(time)
            status = self._coupling.put_on_motion(time, q.tolist(), qd.tolist())
        if status:
            self._refused(time, status)

    def _refused(self, t: float, status: int) -> None:
        """The error of a motion the coupling could not impose (``status`` 1: ``t`` outside it;
        2: the prescribed joints' block of ``M⁻¹`` singular, or a value not finite)."""
        if status == 1:
            self.motion(t)  # raises the motion's own error
        raise FloatingPointError(
            f"the prescribed motion cannot be imposed at t = {t:.9g} s: its accelerations are not finite, or the prescribed "
            "joints' inverse inertia is singular"
        )
