"""Inverse kinematics of the paper's leg and a walking foot trajectory with its joint states.

Everything here is for the paper's 3-DOF leg (docs/model.md section 2) in its hip frame, which is the
world frame of :func:`uwml.paper_leg`: x forward, z up, origin at the hip (the intersection of
the yaw and roll axes). The foot is the calf's tip,

    foot = L2 u2 + L3 u3,   u2 = cos q2 e_r + sin q2 z,   u3 = sin(q2+q3) e_r − cos(q2+q3) z,

with ``e_r = (cos q1, sin q1, 0)``. Forward kinematics, its Jacobian and the velocity-product
term ``J̇ q̇`` are written here in closed form (numpy), so the joint accelerations are exact.
"""

from __future__ import annotations

from typing import Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._checks import real_array as _real_array

__all__ = ["WalkingGait", "paper_leg_foot", "paper_leg_ik"]

FloatArray = NDArray[np.float64]
Knee = Literal["up", "down"]

#: The paper leg's thigh and shank lengths [m] (Table II of Liao et al.; docs/model.md section 2),
#: as the core's ``presets::paper_leg`` holds them (a test holds the three equal). Here, not taken from
#: ``uwml.reference``, so that ``import uwml`` does not load the numpy reference.
PAPER_L2 = 0.660
PAPER_L3 = 0.714

#: Feet closer than this to the yaw axis [m] have no defined hip yaw: the IK refuses them.
AXIS_CLEARANCE = 1e-9


def _lengths(lengths: ArrayLike) -> tuple[float, float]:
    array = _real_array(lengths, "lengths", "two real numbers (L2, L3)")
    if array.shape != (2,) or not np.all(np.isfinite(array)) or np.any(array <= 0):
        raise ValueError(f"lengths must be two positive finite numbers (L2, L3) [m], got {array.tolist()}")
    return float(array[0]), float(array[1])


def _knee(knee: object) -> Knee:
    if knee not in ("up", "down"):
        raise ValueError(f"knee must be 'up' or 'down', got {knee!r}")
    return knee


def _joint_angles(q: ArrayLike) -> FloatArray:
    array = _real_array(q, "q", "a rectangular array of real numbers")
    if array.ndim < 1 or array.shape[-1] != 3:
        raise ValueError(f"q must have shape (..., 3), got {array.shape}")
    return array


def paper_leg_foot(q: ArrayLike, lengths: ArrayLike = (PAPER_L2, PAPER_L3)) -> FloatArray:
    """Foot position ``L2 u2 + L3 u3`` [m] of the paper's leg for joint angles ``q`` ``(..., 3)``."""
    q = _joint_angles(q)
    l2, l3 = _lengths(lengths)
    q1, a, b = q[..., 0], q[..., 1], q[..., 1] + q[..., 2]
    rho = l2 * np.cos(a) + l3 * np.sin(b)
    return np.stack([rho * np.cos(q1), rho * np.sin(q1), l2 * np.sin(a) - l3 * np.cos(b)], axis=-1)


def _jacobian_and_bias(q: FloatArray, qd: FloatArray | None, l2: float, l3: float) -> tuple[FloatArray, FloatArray | None]:
    """The foot's linear Jacobian ``(..., 3, 3)`` and, given ``qd``, ``J̇ q̇`` ``(..., 3)``, in closed form.

    With ``ρ = L2 cos a + L3 sin b`` (a = q2, b = q2 + q3) and ``h = L2 sin a − L3 cos b``,
    ``foot = ρ e_r + h z``. Differentiating twice at ``q̈ = 0``:
    ``J̇ q̇ = (ρ̈₀ − ρ q̇1²) e_r + 2 ρ̇ q̇1 e_t + ḧ₀ z`` with ``ρ̈₀ = −L2 cos a ȧ² − L3 sin b ḃ²`` and
    ``ḧ₀ = −L2 sin a ȧ² + L3 cos b ḃ²``.
    """
    q1, a, b = q[..., 0], q[..., 1], q[..., 1] + q[..., 2]
    c1, s1 = np.cos(q1), np.sin(q1)
    ca, sa, cb, sb = np.cos(a), np.sin(a), np.cos(b), np.sin(b)
    rho = l2 * ca + l3 * sb
    e_r = np.stack([c1, s1, np.zeros_like(c1)], axis=-1)
    e_t = np.stack([-s1, c1, np.zeros_like(c1)], axis=-1)
    z = np.zeros_like(e_r)
    z[..., 2] = 1.0
    d_rho = (-l2 * sa + l3 * cb, l3 * cb)  # ∂ρ/∂q2, ∂ρ/∂q3
    d_h = (l2 * ca + l3 * sb, l3 * sb)
    columns = [rho[..., None] * e_t] + [dr[..., None] * e_r + dh[..., None] * z for dr, dh in zip(d_rho, d_h)]
    jacobian = np.stack(columns, axis=-1)
    if qd is None:
        return jacobian, None
    w1, wa, wb = qd[..., 0], qd[..., 1], qd[..., 1] + qd[..., 2]
    rho_dot = -l2 * sa * wa + l3 * cb * wb
    rho_bias = -l2 * ca * wa**2 - l3 * sb * wb**2
    h_bias = -l2 * sa * wa**2 + l3 * cb * wb**2
    bias = (rho_bias - rho * w1**2)[..., None] * e_r + (2.0 * rho_dot * w1)[..., None] * e_t + h_bias[..., None] * z
    return jacobian, bias


def paper_leg_ik(foot: ArrayLike, knee: Knee = "up", lengths: ArrayLike = (PAPER_L2, PAPER_L3)) -> FloatArray:
    """Joint angles ``q`` ``(..., 3)`` [rad] that put the paper leg's foot at ``foot`` ``(..., 3)`` [m].

    Closed form. The foot is given in the hip frame (the world frame of :func:`uwml.paper_leg`).

    Conventions:

    * hip yaw ``q1 = atan2(y, x)`` in ``(−π, π]``: the foot lies on the positive side ``e_r`` of
      the leg plane (the other solution, ``q1 + π`` with the leg folded back over the hip, is not
      returned);
    * ``knee="up"``: the branch with ``cos q3 ≥ 0`` (``q3 ∈ [−π/2, π/2]``); for a foot below and
      in front of the hip it puts the knee above the hip–foot line, the paper's posture
      (``q2 = q3 = 0``: thigh horizontal, calf vertical). ``knee="down"``: ``cos q3 ≤ 0``, the
      mirror image of the knee about the hip–foot line. The branches coincide at the boundary
      of the workspace (leg stretched or fully folded, ``sin q3 = ±1``);
    * ``q2`` and ``q3`` are wrapped to ``(−π, π]``.

    ``lengths`` are ``(L2, L3)`` [m], Table II by default.

    Raises
    ------
    ValueError
        Naming the targets (index and position) that are unreachable: distance ``r`` from the hip
        outside ``[|L2 − L3|, L2 + L3]`` (within 1e-12 relative), or closer than 1e-9 m to the yaw
        axis, where ``q1`` is undefined. Also for non-finite targets, a bad ``knee`` or bad
        ``lengths``.
    """
    knee = _knee(knee)
    l2, l3 = _lengths(lengths)
    target = _real_array(foot, "foot", "a rectangular array of real numbers")
    if target.ndim < 1 or target.shape[-1] != 3:
        raise ValueError(f"foot must have shape (..., 3), got {target.shape}")
    x, y, z = target[..., 0], target[..., 1], target[..., 2]
    rho = np.hypot(x, y)
    r2 = rho**2 + z**2
    sin_q3 = (r2 - l2**2 - l3**2) / (2.0 * l2 * l3)
    slack = 1e-12 * (l2 + l3) ** 2 / (2.0 * l2 * l3)
    bad = ~np.isfinite(sin_q3) | (np.abs(sin_q3) > 1.0 + slack) | (rho < AXIS_CLEARANCE)
    if np.any(bad):
        indices = np.argwhere(np.atleast_1d(bad))
        shown = []
        for index in indices[:5]:
            key = tuple(int(i) for i in index) if target.ndim > 1 else ()
            point = target[key] if key else target
            reason = (
                "not finite"
                if not np.all(np.isfinite(point))
                else ("on the yaw axis (q1 undefined)" if np.hypot(point[0], point[1]) < AXIS_CLEARANCE else "out of reach")
            )
            shown.append(f"foot{list(key) if key else ''} = {point.tolist()} ({reason})")
        more = f" and {len(indices) - 5} more" if len(indices) > 5 else ""
        raise ValueError(
            f"unreachable foot target(s): {'; '.join(shown)}{more}. Reachable: distance from the hip in "
            f"[{abs(l2 - l3):.6g}, {l2 + l3:.6g}] m and off the yaw axis"
        )
    sin_q3 = np.clip(sin_q3, -1.0, 1.0)
    q3 = np.arcsin(sin_q3)
    if knee == "down":
        q3 = np.pi - q3
    q3 = np.pi - np.mod(np.pi - q3, 2.0 * np.pi)  # wrap to (−π, π]
    q1 = np.arctan2(y, x)
    # Planar two-link arm in the (ρ, z) plane: the calf turns by q3 − π/2 relative to the thigh.
    q2 = np.arctan2(z, rho) - np.arctan2(-l3 * np.cos(q3), l2 + l3 * np.sin(q3))
    q2 = np.pi - np.mod(np.pi - q2, 2.0 * np.pi)
    return np.stack([q1, q2, q3], axis=-1)


def _scalar(value: ArrayLike, name: str) -> float:
    array = _real_array(value, name, "a real number")
    if array.ndim != 0:
        raise TypeError(f"{name} must be a real number, got shape {array.shape}")
    number = float(array)
    if not np.isfinite(number):
        raise ValueError(f"{name} must be finite, got {value!r}")
    return number


class WalkingGait:
    """A periodic walking trajectory of the foot in the hip frame, and the joint states that follow it.

    Ours, not the paper's: the paper drives its leg along the trajectory of its reference [24],
    which is not published. This one, for the paper's leg (or any leg with the same geometry and
    other ``lengths``), is

    * **stance**, ``0 ≤ t mod period < duty_factor · period``: the foot slides on a straight line
      at constant speed ``step_length / (duty_factor · period)`` backward (−x, the body moving
      forward), from ``nominal + step_length/2`` to ``nominal − step_length/2`` in x, at the
      nominal height and y;
    * **swing**, the rest of the period: with ``u ∈ [0, 1]`` the swing's phase,
      ``x = x0 + v T_w u + (S − v T_w)(10u³ − 15u⁴ + 6u⁵)`` (x0 the lift-off point, v the stance
      velocity, T_w the swing duration, S the step length): a quintic that leaves and meets the
      stance line with its velocity and zero acceleration; the height is
      ``z = z_nominal + step_height · 64 u³ (1 − u)³`` (its peak ``step_height`` at mid-swing),
      which starts and ends with zero velocity and acceleration.

    Position, velocity and acceleration are continuous everywhere (the jerk is not); every
    function of time is periodic. Defaults (``nominal_foot = (0.7, 0, −0.6)`` m, step 0.3 m,
    height 0.1 m) keep the foot 0.78 to 1.06 m from the hip, well inside the paper leg's reach
    ``[0.054, 1.374]`` m and in front of the yaw axis.

    Joint states: ``q`` by :func:`paper_leg_ik`, ``q̇ = J⁻¹ ẋ`` and ``q̈ = J⁻¹ (ẍ − J̇ q̇)`` with the
    foot's Jacobian J and the velocity-product term ``J̇ q̇`` both in closed form (the analytic
    first and second derivatives of ``foot = L2 u2 + L3 u3``): exact up to rounding.
    """

    def __init__(
        self,
        period: float = 2.0,
        duty_factor: float = 0.6,
        step_length: float = 0.3,
        step_height: float = 0.1,
        nominal_foot: ArrayLike = (0.7, 0.0, -0.6),
        lengths: ArrayLike = (PAPER_L2, PAPER_L3),
    ) -> None:
        self.period = _scalar(period, "period")
        if self.period <= 0:
            raise ValueError(f"period must be positive, got {period!r}")
        duty = _scalar(duty_factor, "duty_factor")
        if not 0.0 < duty < 1.0:
            raise ValueError(f"duty_factor must be strictly between 0 and 1, got {duty_factor!r}")
        self.duty_factor = duty
        self.step_length = _scalar(step_length, "step_length")
        self.step_height = _scalar(step_height, "step_height")
        for name, value in (("step_length", self.step_length), ("step_height", self.step_height)):
            if value < 0:
                raise ValueError(f"{name} must be finite and non-negative, got {value!r}")
        nominal = _real_array(nominal_foot, "nominal_foot", "three real numbers")
        if nominal.shape != (3,) or not np.all(np.isfinite(nominal)):
            raise ValueError(f"nominal_foot must be three finite numbers (x, y, z) [m], got {nominal.tolist()}")
        self.nominal_foot = nominal.copy()
        self.lengths = _lengths(lengths)

    def __repr__(self) -> str:
        return (
            f"WalkingGait(period={self.period}, duty_factor={self.duty_factor}, step_length={self.step_length}, "
            f"step_height={self.step_height}, nominal_foot={tuple(self.nominal_foot.tolist())})"
        )

    @property
    def stance_duration(self) -> float:
        """Time the foot is on the ground per cycle [s]."""
        return self.duty_factor * self.period

    @property
    def swing_duration(self) -> float:
        """Time the foot is in the air per cycle [s]."""
        return self.period - self.stance_duration

    def _time(self, t: ArrayLike) -> FloatArray:
        times = _real_array(t, "t", "a real number or an array of real numbers")
        if not np.all(np.isfinite(times)):
            raise ValueError("t must be finite")
        return times

    def _derivatives(self, t: ArrayLike, order: int) -> FloatArray:
        """The foot's position (order 0), velocity (1) or acceleration (2), shape ``t.shape + (3,)``."""
        times = self._time(t)
        t_stance, t_swing, step = self.stance_duration, self.swing_duration, self.step_length
        tau = np.mod(times, self.period)
        swing = tau >= t_stance
        v = -step / t_stance
        u = np.where(swing, (tau - t_stance) / t_swing, 0.0)
        gap = step - v * t_swing  # the quintic's amplitude (S − v T_w)
        x_lift = self.nominal_foot[0] - step / 2
        quintic = (10 * u**3 - 15 * u**4 + 6 * u**5, 30 * u**2 - 60 * u**3 + 30 * u**4, 60 * u - 180 * u**2 + 120 * u**3)[order]
        bump = (64 * u**3 * (1 - u) ** 3, 192 * u**2 * (1 - u) ** 2 * (1 - 2 * u), 384 * u * (1 - u) * (5 * u**2 - 5 * u + 1))[order]
        scale = t_swing**-order
        if order == 0:
            x_stance = self.nominal_foot[0] + step / 2 + v * tau
            x_swing = x_lift + v * t_swing * u + gap * quintic
        elif order == 1:
            x_stance = np.full_like(tau, v)
            x_swing = v + gap * quintic * scale
        else:
            x_stance = np.zeros_like(tau)
            x_swing = gap * quintic * scale
        x = np.where(swing, x_swing, x_stance)
        z = np.where(swing, self.step_height * bump * scale, 0.0)
        out = np.zeros(times.shape + (3,))
        out[..., 0] = x
        out[..., 2] = z
        if order == 0:
            out[..., 1] = self.nominal_foot[1]
            out[..., 2] += self.nominal_foot[2]
        return out

    def foot(self, t: ArrayLike) -> FloatArray:
        """Foot position [m] in the hip frame at times ``t`` [s] (any shape), shape ``t.shape + (3,)``."""
        return self._derivatives(t, 0)

    def foot_velocity(self, t: ArrayLike) -> FloatArray:
        """Foot velocity [m/s], analytic, shape ``t.shape + (3,)``."""
        return self._derivatives(t, 1)

    def foot_acceleration(self, t: ArrayLike) -> FloatArray:
        """Foot acceleration [m/s²], analytic, shape ``t.shape + (3,)``."""
        return self._derivatives(t, 2)

    def joint_states(self, t: ArrayLike, knee: Knee = "up") -> tuple[FloatArray, FloatArray, FloatArray]:
        """Joint positions, velocities and accelerations ``(q, qd, qdd)``, each ``t.shape + (3,)``.

        ``q`` from :func:`paper_leg_ik` (``knee`` chooses the branch), then ``qd = J⁻¹ ẋ`` and
        ``qdd = J⁻¹ (ẍ − J̇ q̇)`` with J and ``J̇ q̇`` in closed form. Raises ValueError if the
        trajectory leaves the leg's reach (naming the target) or passes a singular posture.
        """
        knee = _knee(knee)
        x = self.foot(t)
        q = paper_leg_ik(x, knee=knee, lengths=self.lengths)
        jacobian, _ = _jacobian_and_bias(q, None, *self.lengths)
        qd = np.asarray(np.linalg.solve(jacobian, self.foot_velocity(t)[..., None])[..., 0], dtype=np.float64)
        _, bias = _jacobian_and_bias(q, qd, *self.lengths)
        assert bias is not None
        qdd = np.asarray(np.linalg.solve(jacobian, (self.foot_acceleration(t) - bias)[..., None])[..., 0], dtype=np.float64)
        return q, qd, qdd
