"""Independent numpy reference for uwml's hydrodynamics of a serial chain (MODEL.md sections 3-5).

This module re-derives, with numpy only and a different algorithm, what the Rust core
(``uwml._core``) computes, so that tests can hold the core to it:

* kinematics by explicit Rodrigues rotation matrices and the joint-screw sums
  ``v(p) = Σ_j q̇_j z_j × (p − o_j)`` (and their time derivative), not the forward recursion;
* the drag integral ``∫ g h|h| ds`` (``g``, ``h`` affine in ``s``) in closed form on each
  interval where ``h`` keeps its sign, not Gauss-Legendre;
* the added-mass integral ``∫ g a ds`` in closed form.

It also carries the paper's UWML leg (:func:`paper_leg`) and its printed equations
(:func:`paper_equations`) for side-by-side comparison, and the joint losses of an oil-filled,
pressure-compensated joint (MODEL.md section 7: :func:`oil_drag_torque`, :func:`seal_torque`,
:func:`loss_current`, :func:`joint_loss_torques`, :func:`hydrostatic_pressure_mpa`), written
literally from MODEL.md's formulas.

Frames (as in :mod:`uwml.model`): every link frame is parallel to the world frame at ``q = 0``.
The world pose of link ``i`` is ``T_i = T_{i-1} · Trans(joint_i.origin) · Rot(joint_i.axis, q_i)``
with ``T_{-1}`` the identity; link ``i``'s geometry is given in its own frame. World z is up and
gravity points along −z. Every torque is the generalized force exerted *by the environment on
the joint* (MODEL.md section 1), so drag satisfies ``q̇ · τ_drag ≤ 0``.

The module imports only numpy and the standard library, so it can be loaded on its own from its
file path, without the compiled extension. Joints and links are duck-typed: any objects with the
attributes of :class:`uwml.model.Joint` and :class:`uwml.model.Link` (``origin``, ``axis``;
``mass``, ``com``, ``volume``, ``cob``, ``segment`` with ``start``, ``axis``, ``length``,
``normals``, ``widths``, ``area``) will do; so are the loss parameters (the attributes of
:class:`uwml.losses.OilDrag`, :class:`uwml.losses.Seal` and :class:`uwml.losses.Drive`).
"""

# No ``from __future__ import annotations``: dataclasses with string annotations need the module
# in sys.modules, which loading this file standalone (spec_from_file_location) does not provide.
import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = [
    "RefJoint",
    "RefLink",
    "RefSegment",
    "hydro",
    "hydrostatic_pressure_mpa",
    "joint_loss_torques",
    "loss_current",
    "oil_drag_torque",
    "paper_equations",
    "paper_leg",
    "regressors",
    "seal_torque",
    "smooth_sign",
]

Array = NDArray[np.float64]
Vec3 = tuple[float, float, float]

#: Tolerance on unit length and orthogonality of axes and normals.
_AXIS_TOLERANCE = 1e-6

# The paper's leg (Table II of Liao et al.; MODEL.md section 2).
PAPER_L2 = 0.660
PAPER_L3 = 0.714
PAPER_L2C = 0.506
PAPER_L3C = 0.560
PAPER_D21 = 0.131
PAPER_D22 = 0.238
PAPER_D31 = 0.131
PAPER_D32 = 0.279
PAPER_MASSES = (10.758, 19.261, 10.375)
PAPER_LINK_DENSITY = 2700.0

#: Gauss-Legendre nodes per sub-interval in :func:`paper_equations`.
_PAPER_NODES = 24
#: Extra calf breakpoints at ``near ± width · grading`` around the calf's closest approach to the
#: hip (see :func:`paper_equations`), for the near-pole of ``1/r32²`` when ``cos q3 ≈ 0``.
_PAPER_GRADING = 8.0 ** np.arange(11)


# --------------------------------------------------------------------------------------------
# Lightweight chain description (the paper's leg without importing uwml.model)
# --------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class RefJoint:
    """A revolute joint: origin and unit axis in the parent link's frame at ``q = 0``."""

    origin: Vec3
    axis: Vec3


@dataclass(frozen=True)
class RefSegment:
    """A straight link's hydrodynamic geometry in the link frame (see :class:`uwml.model.Segment`).

    A slice at arc length ``s`` in ``[0, length]`` lies at ``start + s * axis``; ``widths[k]`` is
    the frontal width seen by flow along ``normals[k]``; ``area`` is the section area for added
    mass.
    """

    start: Vec3
    axis: Vec3
    length: float
    normals: tuple[Vec3, Vec3]
    widths: tuple[float, float]
    area: float


@dataclass(frozen=True)
class RefLink:
    """A rigid link: mass and COM, displaced volume and centre of buoyancy, optional segment."""

    mass: float
    com: Vec3
    volume: float
    cob: Vec3
    segment: RefSegment | None = None


def paper_leg() -> tuple[tuple[RefJoint, RefJoint, RefJoint], tuple[RefLink, RefLink, RefLink]]:
    """The paper's 3-DOF underwater leg (Table II), as joints and links.

    Joint 1 is the hip yaw about world z, joints 2 and 3 (hip and knee roll) turn about the local
    −y axis, so that with ``e_r = (cos q1, sin q1, 0)`` the thigh axis is
    ``u2 = cos q2 e_r + sin q2 z`` and the calf axis ``u3 = sin(q2+q3) e_r − cos(q2+q3) z``
    (MODEL.md section 2). The first normal of each segment is the out-of-plane direction (local
    +y, width ``D_i1``), the second the in-plane one (width ``D_i2``); ``area = D_i1 · D_i2``.
    Centres of mass and buoyancy coincide; ``volume = mass / 2700``.

    Returns
    -------
    joints : tuple of RefJoint
        Hip yaw, hip roll, knee roll.
    links : tuple of RefLink
        Base (yaw housing, no segment), thigh, calf.
    """
    masses = PAPER_MASSES
    joints = (
        RefJoint(origin=(0.0, 0.0, 0.0), axis=(0.0, 0.0, 1.0)),
        RefJoint(origin=(0.0, 0.0, 0.0), axis=(0.0, -1.0, 0.0)),
        RefJoint(origin=(PAPER_L2, 0.0, 0.0), axis=(0.0, -1.0, 0.0)),
    )
    thigh = RefSegment(
        start=(0.0, 0.0, 0.0),
        axis=(1.0, 0.0, 0.0),
        length=PAPER_L2,
        normals=((0.0, 1.0, 0.0), (0.0, 0.0, 1.0)),
        widths=(PAPER_D21, PAPER_D22),
        area=PAPER_D21 * PAPER_D22,
    )
    calf = RefSegment(
        start=(0.0, 0.0, 0.0),
        axis=(0.0, 0.0, -1.0),
        length=PAPER_L3,
        normals=((0.0, 1.0, 0.0), (1.0, 0.0, 0.0)),
        widths=(PAPER_D31, PAPER_D32),
        area=PAPER_D31 * PAPER_D32,
    )
    thigh_com = (PAPER_L2C, 0.0, 0.0)
    calf_com = (0.0, 0.0, -PAPER_L3C)
    links = (
        RefLink(masses[0], (0.0, 0.0, 0.0), masses[0] / PAPER_LINK_DENSITY, (0.0, 0.0, 0.0)),
        RefLink(masses[1], thigh_com, masses[1] / PAPER_LINK_DENSITY, thigh_com, thigh),
        RefLink(masses[2], calf_com, masses[2] / PAPER_LINK_DENSITY, calf_com, calf),
    )
    return joints, links


# --------------------------------------------------------------------------------------------
# Input checking
# --------------------------------------------------------------------------------------------


def _vector(value: Any, name: str, *, unit: bool = False) -> Array:
    try:
        v = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{name} must be 3 numbers, got {value!r}") from exc
    if v.shape != (3,) or not np.all(np.isfinite(v)):
        raise ValueError(f"{name} must be 3 finite numbers, got {value!r}")
    if unit and abs(float(np.linalg.norm(v)) - 1.0) > _AXIS_TOLERANCE:
        raise ValueError(f"{name} must be a unit vector, got norm {np.linalg.norm(v)}")
    return v


def _number(value: Any, name: str, *, positive: bool) -> float:
    try:
        x = float(value)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{name} must be a number, got {value!r}") from exc
    if not math.isfinite(x) or (x <= 0.0 if positive else x < 0.0):
        raise ValueError(f"{name} must be finite and {'> 0' if positive else '>= 0'}, got {value!r}")
    return x


@dataclass(frozen=True)
class _Segment:
    start: Array
    axis: Array
    length: float
    normals: Array  # (2, 3)
    widths: Array  # (2,)
    area: float


@dataclass(frozen=True)
class _Chain:
    origins: Array  # (n, 3)
    axes: Array  # (n, 3)
    masses: Array  # (n,)
    coms: Array  # (n, 3)
    volumes: Array  # (n,)
    cobs: Array  # (n, 3)
    segments: tuple[_Segment | None, ...]

    @property
    def size(self) -> int:
        return len(self.segments)


def _segment(segment: Any, name: str) -> _Segment:
    axis = _vector(segment.axis, f"{name}.axis", unit=True)
    normals = np.array([_vector(n, f"{name}.normals[{k}]", unit=True) for k, n in enumerate(segment.normals)])
    if normals.shape != (2, 3):
        raise ValueError(f"{name}.normals must hold 2 vectors, got {len(normals)}")
    for label, a, b in (
        ("normals[0]·axis", normals[0], axis),
        ("normals[1]·axis", normals[1], axis),
        ("normals[0]·normals[1]", normals[0], normals[1]),
    ):
        if abs(float(a @ b)) > _AXIS_TOLERANCE:
            raise ValueError(f"{name}.{label} must be 0 (orthonormal normals perpendicular to the axis), got {a @ b}")
    widths = tuple(segment.widths)
    if len(widths) != 2:
        raise ValueError(f"{name}.widths must hold 2 numbers, got {len(widths)}")
    return _Segment(
        start=_vector(segment.start, f"{name}.start"),
        axis=axis,
        length=_number(segment.length, f"{name}.length", positive=True),
        normals=normals,
        widths=np.array([_number(w, f"{name}.widths[{k}]", positive=True) for k, w in enumerate(widths)]),
        area=_number(segment.area, f"{name}.area", positive=True),
    )


def _chain(joints: Sequence[Any], links: Sequence[Any]) -> _Chain:
    joints, links = list(joints), list(links)
    if not joints or len(joints) != len(links):
        raise ValueError(f"joints and links must be non-empty and of equal length, got {len(joints)} joints and {len(links)} links")
    segments = tuple(None if link.segment is None else _segment(link.segment, f"links[{i}].segment") for i, link in enumerate(links))
    coms = np.array([_vector(link.com, f"links[{i}].com") for i, link in enumerate(links)])
    return _Chain(
        origins=np.array([_vector(j.origin, f"joints[{i}].origin") for i, j in enumerate(joints)]),
        axes=np.array([_vector(j.axis, f"joints[{i}].axis", unit=True) for i, j in enumerate(joints)]),
        masses=np.array([_number(link.mass, f"links[{i}].mass", positive=False) for i, link in enumerate(links)]),
        coms=coms,
        volumes=np.array([_number(link.volume, f"links[{i}].volume", positive=False) for i, link in enumerate(links)]),
        cobs=np.array([coms[i] if link.cob is None else _vector(link.cob, f"links[{i}].cob") for i, link in enumerate(links)]),
        segments=segments,
    )


def _states(q: ArrayLike, qd: ArrayLike, qdd: ArrayLike, n: int) -> tuple[tuple[int, ...], Array, Array, Array]:
    """Check the joint states and flatten them to (samples, n)."""
    arrays = []
    for name, value in (("q", q), ("qd", qd), ("qdd", qdd)):
        try:
            a = np.asarray(value, dtype=np.float64)
        except (TypeError, ValueError) as exc:
            raise ValueError(f"{name} must be an array of numbers, got {value!r}") from exc
        if a.ndim == 0 or a.shape[-1] != n:
            raise ValueError(f"{name} must have shape (n,) or (m, n) with n = {n} joints, got shape {a.shape}")
        if not np.all(np.isfinite(a)):
            raise ValueError(f"{name} must be finite")
        arrays.append(a)
    if not arrays[0].shape == arrays[1].shape == arrays[2].shape:
        raise ValueError(f"q, qd and qdd must have the same shape, got {arrays[0].shape}, {arrays[1].shape}, {arrays[2].shape}")
    shape = arrays[0].shape
    q2, qd2, qdd2 = (a.reshape(-1, n) for a in arrays)
    return shape, q2, qd2, qdd2


def _coefficients(value: ArrayLike, name: str, n_links: int) -> Array:
    """Broadcast a drag or added-mass coefficient to shape (n_links, 2)."""
    try:
        c = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{name} must be a number or an array of numbers, got {value!r}") from exc
    if c.shape == ():
        c = np.full((n_links, 2), float(c))
    elif c.shape == (n_links,):
        c = np.repeat(c[:, None], 2, axis=1)
    elif c.shape != (n_links, 2):
        raise ValueError(
            f"{name} must be a scalar, shape ({n_links},) (per link) or ({n_links}, 2) (per link and normal direction), got shape {c.shape}"
        )
    if not np.all(np.isfinite(c)) or np.any(c < 0.0):
        raise ValueError(f"{name} must be finite and non-negative, got {value!r}")
    return c


# --------------------------------------------------------------------------------------------
# Kinematics by joint screws
# --------------------------------------------------------------------------------------------


def _rodrigues(axis: Array, angle: Array) -> Array:
    """Rotation matrices (m, 3, 3) by ``angle`` (m,) about the unit ``axis`` (3,)."""
    k = np.array([[0.0, -axis[2], axis[1]], [axis[2], 0.0, -axis[0]], [-axis[1], axis[0], 0.0]])
    s, c = np.sin(angle)[:, None, None], np.cos(angle)[:, None, None]
    return np.eye(3) + s * k + (1.0 - c) * (k @ k)


@dataclass(frozen=True)
class _Kinematics:
    """World pose of every link and the joint screws, for m samples."""

    rotations: Array  # (m, n, 3, 3) link-to-world rotation
    origins: Array  # (m, n, 3) o_j, world position of joint j (origin of link j's frame)
    axes: Array  # (m, n, 3) z_j, world axis of joint j
    axis_rates: Array  # (m, n, 3) ż_j = ω_{j-1} × z_j
    origin_velocities: Array  # (m, n, 3) velocity of the point o_j
    qd: Array  # (m, n)
    qdd: Array  # (m, n)

    def point(self, local: Array, link: int) -> Array:
        """World position (m, 3) of a point given in the frame of ``link``."""
        return self.origins[:, link] + self.rotations[:, link] @ local

    def velocity(self, p: Array, link: int) -> Array:
        """Velocity (m, 3) of the point at world position ``p`` (m, 3) fixed to ``link``."""
        moved = slice(0, link + 1)
        r = p[:, None, :] - self.origins[:, moved]
        return np.einsum("mj,mjc->mc", self.qd[:, moved], np.cross(self.axes[:, moved], r))

    def acceleration(self, p: Array, v: Array, link: int) -> Array:
        """Acceleration (m, 3) of the point at ``p`` with velocity ``v`` fixed to ``link``.

        Time derivative of ``Σ_j q̇_j z_j × (p − o_j)``: ``d/dt z_j = ω_{j-1} × z_j`` and
        ``d/dt (p − o_j) = v − v(o_j)``.
        """
        moved = slice(0, link + 1)
        z = self.axes[:, moved]
        r = p[:, None, :] - self.origins[:, moved]
        dr = v[:, None, :] - self.origin_velocities[:, moved]
        terms = self.qdd[:, moved, None] * np.cross(z, r) + self.qd[:, moved, None] * (
            np.cross(self.axis_rates[:, moved], r) + np.cross(z, dr)
        )
        return terms.sum(axis=1)


def _kinematics(chain: _Chain, q: Array, qd: Array, qdd: Array) -> _Kinematics:
    m, n = q.shape
    rotations = np.empty((m, n, 3, 3))
    origins = np.empty((m, n, 3))
    axes = np.empty((m, n, 3))
    axis_rates = np.empty((m, n, 3))
    origin_velocities = np.empty((m, n, 3))
    parent_rotation = np.broadcast_to(np.eye(3), (m, 3, 3))
    parent_origin = np.zeros((m, 3))
    parent_omega = np.zeros((m, 3))
    for j in range(n):
        origins[:, j] = parent_origin + parent_rotation @ chain.origins[j]
        axes[:, j] = parent_rotation @ chain.axes[j]
        axis_rates[:, j] = np.cross(parent_omega, axes[:, j])
        before = slice(0, j)
        r = origins[:, j, None, :] - origins[:, before]
        origin_velocities[:, j] = np.einsum("mk,mkc->mc", qd[:, before], np.cross(axes[:, before], r))
        rotations[:, j] = parent_rotation @ _rodrigues(chain.axes[j], q[:, j])
        parent_rotation, parent_origin = rotations[:, j], origins[:, j]
        parent_omega = parent_omega + qd[:, j, None] * axes[:, j]
    return _Kinematics(rotations, origins, axes, axis_rates, origin_velocities, qd, qdd)


# --------------------------------------------------------------------------------------------
# Exact strip integrals over the unit interval (s = L t)
# --------------------------------------------------------------------------------------------


def _drag_integral(ga: Array, gb: Array, ha: Array, hb: Array) -> Array:
    """``∫₀¹ g(t) h(t)|h(t)| dt`` for ``g``, ``h`` affine in t with end values ``(ga, gb)``,
    ``(ha, hb)``; exact (elementwise, broadcasting).

    Where ``h`` keeps its sign σ the integrand is σ·g·h², a cubic whose exact integral over an
    interval is its length times the mean of its four Bernstein coefficients:
    ``(3 ga ha² + 3 gb hb² + gb ha² + ga hb² + 2 ha hb (ga + gb)) / 12`` per unit length. Where
    ``h`` changes sign the interval is split at the root ``t* = ha / (ha − hb)`` (h = 0 there,
    which kills most of the terms) and each piece enters with its own sign. With ``ha hb < 0``
    the denominator ``ha − hb`` has magnitude ``|ha| + |hb|``: nothing cancels.
    """
    keeps_sign = np.sign(ha) * np.sign(hb) >= 0.0  # not ha * hb, which may underflow to 0
    sign = np.sign(ha + hb)
    whole = sign * (3.0 * (ga * ha * ha + gb * hb * hb) + gb * ha * ha + ga * hb * hb + 2.0 * ha * hb * (ga + gb)) / 12.0
    denominator = np.where(keeps_sign, 1.0, ha - hb)
    t_root = ha / denominator
    t_rest = -hb / denominator
    g_root = ga + t_root * (gb - ga)
    split = (t_root * ha * np.abs(ha) * (3.0 * ga + g_root) + t_rest * hb * np.abs(hb) * (3.0 * gb + g_root)) / 12.0
    return np.where(keeps_sign, whole, split)


def _linear_integral(ga: Array, gb: Array, aa: Array, ab: Array) -> Array:
    """``∫₀¹ g(t) a(t) dt`` for ``g``, ``a`` affine in t with end values; exact."""
    return (2.0 * (ga * aa + gb * ab) + ga * ab + gb * aa) / 6.0


# --------------------------------------------------------------------------------------------
# Public API: uwml's model
# --------------------------------------------------------------------------------------------


def _static_torques(kin: _Kinematics, points: Array, forces: Array) -> Array:
    """Joint torques (m, n) of vertical forces ``forces[i]`` [N, along +z] at world ``points[:, i]``.

    ``τ_j = (z_j × (c_i − o_j)) · (F_i ẑ)`` summed over the links i ≥ j.
    """
    m, n = kin.qd.shape
    tau = np.zeros((m, n))
    for i in range(n):
        moved = slice(0, i + 1)
        arm = np.cross(kin.axes[:, moved], points[:, i, None, :] - kin.origins[:, moved])
        tau[:, moved] += arm[..., 2] * forces[i]
    return tau


def _regressors(chain: _Chain, kin: _Kinematics, density: float) -> tuple[Array, Array]:
    """Drag and added-mass regressors, each (m, n, n_links, 2): the torque on joint j of link l's
    direction k at Cd = 1 (resp. Cm = 1).
    """
    m, n = kin.qd.shape
    drag = np.zeros((m, n, chain.size, 2))
    added_mass = np.zeros((m, n, chain.size, 2))
    for i, seg in enumerate(chain.segments):
        if seg is None:
            continue
        moved = slice(0, i + 1)
        start = kin.point(seg.start, i)
        ends = (start, start + seg.length * (kin.rotations[:, i] @ seg.axis))
        normals = np.einsum("mab,kb->mka", kin.rotations[:, i], seg.normals)  # (m, 2, 3)
        g, h, a = [], [], []
        for p in ends:
            v = kin.velocity(p, i)
            arm = np.cross(kin.axes[:, moved], p[:, None, :] - kin.origins[:, moved])  # (m, j, 3)
            g.append(np.einsum("mjc,mkc->mjk", arm, normals))
            h.append(np.einsum("mc,mkc->mk", v, normals)[:, None, :])
            a.append(np.einsum("mc,mkc->mk", kin.acceleration(p, v, i), normals)[:, None, :])
        drag[:, moved, i, :] = -0.5 * density * seg.widths * seg.length * _drag_integral(g[0], g[1], h[0], h[1])
        added_mass[:, moved, i, :] = -density * seg.area * seg.length * _linear_integral(g[0], g[1], a[0], a[1])
    return drag, added_mass


def _prepare(
    joints: Sequence[Any], links: Sequence[Any], q: ArrayLike, qd: ArrayLike, qdd: ArrayLike, density: float, gravity: float
) -> tuple[_Chain, tuple[int, ...], _Kinematics, float, float]:
    """Check every input; return the chain, the states' shape, the kinematics, density, gravity."""
    chain = _chain(joints, links)
    shape, q2, qd2, qdd2 = _states(q, qd, qdd, chain.size)
    density = _number(density, "density", positive=True)
    gravity = _number(gravity, "gravity", positive=False)
    return chain, shape, _kinematics(chain, q2, qd2, qdd2), density, gravity


def _world_points(kin: _Kinematics, local: Array) -> Array:
    """World positions (m, n, 3) of one point per link, ``local[i]`` in link i's frame."""
    return np.stack([kin.point(local[i], i) for i in range(local.shape[0])], axis=1)


def regressors(
    joints: Sequence[Any],
    links: Sequence[Any],
    q: ArrayLike,
    qd: ArrayLike,
    qdd: ArrayLike,
    density: float = 1000.0,
    gravity: float = 9.81,
) -> dict[str, Array]:
    """Hydrodynamic regressors of a serial chain (MODEL.md section 4).

    Parameters
    ----------
    joints, links : sequence
        The chain (e.g. :class:`uwml.model.Joint` and :class:`uwml.model.Link`, or
        :func:`paper_leg`), one link per joint.
    q, qd, qdd : array_like
        Joint positions [rad], velocities [rad/s] and accelerations [rad/s²], each of shape
        ``(n,)`` or ``(m, n)`` (any leading shape works) with ``n = len(joints)``.
    density : float
        Water density [kg/m³], > 0.
    gravity : float
        Gravitational acceleration [m/s²], ≥ 0.

    Returns
    -------
    dict
        ``buoyancy``: shape of ``q``, buoyancy torque [N·m].
        ``drag``: shape ``q.shape + (n_links, 2)``; ``drag[..., j, l, k]`` is the drag torque on
        joint j of link l's normal direction k alone at Cd = 1.
        ``added_mass``: the same at Cm = 1.
        So ``total = buoyancy + einsum('...jlk,lk->...j', drag, cd) + einsum(..., added_mass, cm)``.

    Raises
    ------
    ValueError
        On malformed chains, states of the wrong shape or non-finite values, ``density <= 0`` or
        ``gravity < 0``.
    """
    chain, shape, kin, density, gravity = _prepare(joints, links, q, qd, qdd, density, gravity)
    drag, added_mass = _regressors(chain, kin, density)
    buoyancy = _static_torques(kin, _world_points(kin, chain.cobs), density * chain.volumes * gravity)
    tail = (chain.size, 2)
    return {
        "buoyancy": buoyancy.reshape(shape),
        "drag": drag.reshape(shape + tail),
        "added_mass": added_mass.reshape(shape + tail),
    }


def hydro(
    joints: Sequence[Any],
    links: Sequence[Any],
    q: ArrayLike,
    qd: ArrayLike,
    qdd: ArrayLike,
    cd: ArrayLike = 2.2,
    cm: ArrayLike = 0.5,
    density: float = 1000.0,
    gravity: float = 9.81,
) -> dict[str, Array]:
    """Hydrodynamic joint torques of a serial chain by strip theory (MODEL.md section 3).

    Per unit length of link i, along each normal direction ``n_k`` of its segment, drag
    ``−½ ρ Cd_k w_k v_k|v_k| n_k`` and added mass ``−ρ Cm_k A a_k n_k`` (``v_k``, ``a_k``: normal
    components of the slice's velocity and absolute acceleration), mapped on joint j by the
    virtual work ``∫ (z_j × (p(s) − o_j)) · f(s) ds``; buoyancy ``ρ V_i g ẑ`` at the centre of
    buoyancy. Tangential (skin-friction) force is neglected. All integrals are exact.

    Parameters
    ----------
    joints, links : sequence
        The chain (e.g. :class:`uwml.model.Joint` and :class:`uwml.model.Link`, or
        :func:`paper_leg`), one link per joint.
    q, qd, qdd : array_like
        Joint positions [rad], velocities [rad/s] and accelerations [rad/s²], each of shape
        ``(n,)`` or ``(m, n)`` (any leading shape works) with ``n = len(joints)``.
    cd, cm : float or array_like
        Drag and added-mass coefficients, ≥ 0: a scalar, shape ``(n_links,)`` (one per link) or
        ``(n_links, 2)`` (per link and normal direction k, matching ``segment.normals[k]``). With
        ``n_links == 2`` a shape ``(2,)`` means per link. Entries of links without a segment are
        ignored.
    density : float
        Water density [kg/m³], > 0.
    gravity : float
        Gravitational acceleration [m/s²], ≥ 0.

    Returns
    -------
    dict
        Arrays shaped like ``q`` [N·m], generalized forces exerted by the water on the joints:
        ``drag``, ``added_mass``, ``buoyancy``, ``total = drag + added_mass + buoyancy``, and
        ``gravity`` (the torque of the link weights ``−m g ẑ`` at the COMs; not in ``total``).

    Raises
    ------
    ValueError
        On malformed chains, states of the wrong shape or non-finite values, coefficients of a
        wrong shape or negative, ``density <= 0`` or ``gravity < 0``.
    """
    chain, shape, kin, density, gravity = _prepare(joints, links, q, qd, qdd, density, gravity)
    cd = _coefficients(cd, "cd", chain.size)
    cm = _coefficients(cm, "cm", chain.size)
    drag_regressor, added_mass_regressor = _regressors(chain, kin, density)
    drag = np.einsum("mjlk,lk->mj", drag_regressor, cd)
    added_mass = np.einsum("mjlk,lk->mj", added_mass_regressor, cm)
    buoyancy = _static_torques(kin, _world_points(kin, chain.cobs), density * chain.volumes * gravity)
    weight = _static_torques(kin, _world_points(kin, chain.coms), -chain.masses * gravity)
    return {
        "drag": drag.reshape(shape),
        "added_mass": added_mass.reshape(shape),
        "buoyancy": buoyancy.reshape(shape),
        "gravity": weight.reshape(shape),
        "total": (drag + added_mass + buoyancy).reshape(shape),
    }


# --------------------------------------------------------------------------------------------
# Public API: the paper's printed equations
# --------------------------------------------------------------------------------------------


def _quadrature(length: float, breaks: Array) -> tuple[Array, Array]:
    """Gauss-Legendre nodes and weights (m, P) on [0, length] split at ``breaks`` (m, b).

    Breaks outside [0, length] (or non-finite) are clipped to the ends, giving empty pieces,
    whose nodes are put mid-interval (with zero weights) so that no integrand sees x = 0.
    """
    t, w = np.polynomial.legendre.leggauss(_PAPER_NODES)
    clipped = np.clip(np.nan_to_num(breaks, nan=length, posinf=length, neginf=0.0), 0.0, length)
    edges = np.sort(np.concatenate([np.zeros((breaks.shape[0], 1)), clipped, np.full((breaks.shape[0], 1), length)], axis=1), axis=1)
    half = 0.5 * np.diff(edges, axis=1)[:, :, None]  # (m, pieces, 1)
    nodes = np.where(half > 0.0, edges[:, :-1, None] + half * (t + 1.0), 0.5 * length)
    weights = half * w
    return nodes.reshape(len(breaks), -1), weights.reshape(len(breaks), -1)


def paper_equations(
    q: ArrayLike,
    qd: ArrayLike,
    qdd: ArrayLike,
    cd: float = 2.2,
    cm: float = 0.5,
    density: float = 1000.0,
    gravity: float = 9.81,
) -> dict[str, Array]:
    """The paper's printed eqs. (8)-(22) for its 3-DOF leg with Table II, in uwml's sign.

    For side-by-side comparison with :func:`hydro` (MODEL.md section 6). Returned: ``drag = −τ_d``,
    ``added_mass = −τ_m``, ``buoyancy = τ_f``, ``total = τ_w = τ_f − τ_d − τ_m``. The integrals
    are evaluated by Gauss-Legendre quadrature (24 nodes per piece). The calf is split at the
    root of ``v31``, at the calf's closest approach to the hip ``x0 = −L2 s3`` (where ``r32`` is
    least and may vanish) and, geometrically graded, at ``x0 ± L2 |c3| 8^k`` (k = 0..10) to
    resolve the near-pole of ``1/r32²`` in ``x cos α v̇32`` when ``cos q3 ≈ 0``; the result is
    converged to 1e-12 of the largest torque or better (1e-14 unless ``|cos q3| < 1e-9``; checked
    against 200 nodes and k = 0..14).
    Every joint-1 integrand is a polynomial of degree ≤ 3 on each piece, integrated exactly.
    Cost: about 0.1 s per 1000 samples.

    How the printed terms are read (x: distance of the slice from its link's joint; s_i, c_i are
    sin and cos of q_i, s23 = sin(q2 + q3), c23 = cos(q2 + q3)):

    * Eq. (8): the first term (link 1, ``D_11 = 0``, ``L_1 = 0``) is zero. The calf's moment arm
      is read ``L2 c2 + x s23`` (the printed ``x cos(q2+q3)`` is a typo: eqs. 7, 9, 17 use sin);
      this is the only change to the printed equations.
    * Eq. (9): ``A_1 = 0``, ``A_2 = D21 D22``, ``A_3 = D31 D32``. Its integrands are printed with
      ``v21``, ``v31``, without the dot; they are read as ``v̇21``, ``v̇31`` (eq. 4, MODEL.md
      section 6 item 2).
    * ``v̇`` is the time derivative of the printed scalar speed:
      ``v̇21 = q̈1 x c2 − q̇1 q̇2 x s2``,
      ``v̇31 = q̈1 (L2 c2 + x s23) + q̇1 (−q̇2 L2 s2 + (q̇2 + q̇3) x c23)``, ``v̇22 = q̈2 x``,
      ``v̇32 = q̈2 r32 + q̇2 q̇3 L2 x c3 / r32``, ``v̇33 = q̈3 x``.
    * ``r32 = sqrt(L2² + x² + 2 L2 x s3)`` (eq. 13; computed as ``hypot(x + L2 s3, L2 c3)``, the
      same number without cancellation), ``x`` from the knee; ``v32 = q̇2 r32``;
      ``cos α = (x² + r32² − L2²) / (2 x r32)`` evaluated as printed (so ``r32 cos α = x + L2 s3``).
    * Eq. (15): ``½ρCd [D22 ∫₀^L2 x v22|v22| + D32 ∫₀^L3 r32 v32|v32| + D32 ∫₀^L3 r32 cos α v33|v33|]``,
      one ``v|v|`` per joint as printed (superposed, not the total velocity).
    * Eq. (16): ``ρCm [A2 ∫ x v̇22 + A3 ∫ r32 v̇32 + A3 ∫ r32 cos α v̇33]``, the third term read with
      ``v̇33`` (printed ``v̇32``), as MODEL.md section 6 says.
    * Eqs. (19), (20): ``½ρCd D32 [∫ x v33|v33| + ∫ x cos α v32|v32|]`` and
      ``ρCm A3 [∫ x v̇33 + ∫ x cos α v̇32]``.
    * Eqs. (10), (17), (21): ``τ_f1 = 0``,
      ``τ_f2 = (m2 g L2c c2 + m3 g (L2 c2 + L3c s23)) ρ/ρm``, ``τ_f3 = m3 g L3c s23 ρ/ρm``, with
      ``ρm = 2700`` and ρ = ``density``.

    For pure yaw (``q̇2 = q̇3 = q̈2 = q̈3 = 0``) joint 1's drag and added mass equal :func:`hydro`'s
    for :func:`paper_leg`; the buoyancy equals it for every state.

    Parameters
    ----------
    q, qd, qdd : array_like
        Joint states, each of shape ``(3,)`` or ``(m, 3)``.
    cd, cm : float
        Drag and added-mass coefficients (one of each, as in the paper), ≥ 0.
    density : float
        Water density [kg/m³], > 0.
    gravity : float
        Gravitational acceleration [m/s²], ≥ 0.

    Returns
    -------
    dict
        ``drag``, ``added_mass``, ``buoyancy``, ``total``, each shaped like ``q`` [N·m].

    Raises
    ------
    ValueError
        On states of the wrong shape or non-finite values, negative coefficients,
        ``density <= 0`` or ``gravity < 0``.
    """
    shape, qs, qds, qdds = _states(q, qd, qdd, 3)
    cd = _number(cd, "cd", positive=False)
    cm = _number(cm, "cm", positive=False)
    rho = _number(density, "density", positive=True)
    g = _number(gravity, "gravity", positive=False)
    q2, q3 = qs[:, 1, None], qs[:, 2, None]  # the yaw angle q1 does not enter
    w1, w2, w3 = (qds[:, i, None] for i in range(3))
    a1, a2, a3 = (qdds[:, i, None] for i in range(3))
    s2, c2, s3, c3 = np.sin(q2), np.cos(q2), np.sin(q3), np.cos(q3)
    s23, c23 = np.sin(q2 + q3), np.cos(q2 + q3)
    L2, L3 = PAPER_L2, PAPER_L3
    A2, A3 = PAPER_D21 * PAPER_D22, PAPER_D31 * PAPER_D32
    m2, m3 = PAPER_MASSES[1], PAPER_MASSES[2]

    def vv(v: Array) -> Array:
        return v * np.abs(v)

    # Thigh (link 2), x in [0, L2]: no kinks.
    x, wx = _quadrature(L2, np.empty((len(qs), 0)))
    v21, dv21 = w1 * x * c2, a1 * x * c2 - w1 * w2 * x * s2
    v22, dv22 = w2 * x, a2 * x
    thigh_d1 = np.sum(x * c2 * vv(v21) * wx, axis=1)
    thigh_m1 = np.sum(x * c2 * dv21 * wx, axis=1)
    thigh_d2 = np.sum(x * vv(v22) * wx, axis=1)
    thigh_m2 = np.sum(x * dv22 * wx, axis=1)

    # Calf (link 3), x in [0, L3] from the knee: split where v31 = 0 and where r32 is least.
    with np.errstate(divide="ignore", over="ignore", invalid="ignore"):
        root = np.where(s23 != 0.0, -L2 * c2 / s23, np.inf)
    near, width = -L2 * s3, L2 * np.abs(c3)  # r32² = (x − near)² + width²
    grading = width * _PAPER_GRADING
    x, wx = _quadrature(L3, np.concatenate([root, near, near - grading, near + grading], axis=1))
    arm1 = L2 * c2 + x * s23
    v31, dv31 = w1 * arm1, a1 * arm1 + w1 * (-w2 * L2 * s2 + (w2 + w3) * x * c23)
    r32 = np.hypot(x + L2 * s3, L2 * c3)  # eq. 13's sqrt(L2² + x² + 2 L2 x s3), without cancellation
    v32, dv32 = w2 * r32, a2 * r32 + w2 * w3 * L2 * x * c3 / r32
    v33, dv33 = w3 * x, a3 * x
    cos_alpha = (x**2 + r32**2 - L2**2) / (2.0 * x * r32)
    calf_d1 = np.sum(arm1 * vv(v31) * wx, axis=1)
    calf_m1 = np.sum(arm1 * dv31 * wx, axis=1)
    calf_d2 = np.sum((r32 * vv(v32) + r32 * cos_alpha * vv(v33)) * wx, axis=1)
    calf_m2 = np.sum((r32 * dv32 + r32 * cos_alpha * dv33) * wx, axis=1)
    calf_d3 = np.sum((x * vv(v33) + x * cos_alpha * vv(v32)) * wx, axis=1)
    calf_m3 = np.sum((x * dv33 + x * cos_alpha * dv32) * wx, axis=1)

    half = 0.5 * rho * cd
    tau_d = np.stack(
        [
            half * (PAPER_D21 * thigh_d1 + PAPER_D31 * calf_d1),
            half * (PAPER_D22 * thigh_d2 + PAPER_D32 * calf_d2),
            half * PAPER_D32 * calf_d3,
        ],
        axis=1,
    )
    tau_m = np.stack(
        [
            rho * cm * (A2 * thigh_m1 + A3 * calf_m1),
            rho * cm * (A2 * thigh_m2 + A3 * calf_m2),
            rho * cm * A3 * calf_m3,
        ],
        axis=1,
    )
    ratio = rho / PAPER_LINK_DENSITY
    tau_f = np.concatenate(
        [
            np.zeros_like(c2),
            (m2 * g * PAPER_L2C * c2 + m3 * g * (L2 * c2 + PAPER_L3C * s23)) * ratio,
            m3 * g * PAPER_L3C * s23 * ratio,
        ],
        axis=1,
    )
    return {
        "drag": (-tau_d).reshape(shape),
        "added_mass": (-tau_m).reshape(shape),
        "buoyancy": tau_f.reshape(shape),
        "total": (tau_f - tau_d - tau_m).reshape(shape),
    }


# --------------------------------------------------------------------------------------------
# Joint losses (MODEL.md section 7)
# --------------------------------------------------------------------------------------------

#: Absolute zero [°C]: temperatures must lie above it.
_ABSOLUTE_ZERO_C = -273.15


def _samples(value: ArrayLike, name: str, *, low: float | None = None, strict: bool = False) -> Array:
    """A float array of finite numbers, optionally ``>= low`` (``> low`` if ``strict``)."""
    try:
        a = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{name} must be a number or an array of numbers, got {value!r}") from exc
    if not np.all(np.isfinite(a)):
        raise ValueError(f"{name} must be finite")
    if low is not None and np.any(a <= low if strict else a < low):
        raise ValueError(f"{name} must be {'>' if strict else '>='} {low}, got minimum {a.min()}")
    return a


def _oil_parameters(oil: Any) -> tuple[float, float, float, float, float, float]:
    """``(k_oil, n, a_p, a_T, p_ref, θ_ref)`` of a duck-typed :class:`uwml.losses.OilDrag`, checked."""
    exponent = _number(oil.exponent, "oil.exponent", positive=True)
    if not 1.0 <= exponent <= 2.0:
        raise ValueError(f"oil.exponent must lie in [1, 2], got {exponent}")
    reference_temperature = float(_samples(oil.reference_temperature_c, "oil.reference_temperature_c", low=_ABSOLUTE_ZERO_C, strict=True))
    return (
        _number(oil.k_oil, "oil.k_oil", positive=False),
        exponent,
        _number(oil.pressure_sensitivity_per_mpa, "oil.pressure_sensitivity_per_mpa", positive=False),
        _number(oil.temperature_sensitivity_per_k, "oil.temperature_sensitivity_per_k", positive=False),
        _number(oil.reference_pressure_mpa, "oil.reference_pressure_mpa", positive=False),
        reference_temperature,
    )


def _seal_parameters(seal: Any) -> tuple[float, float, float, float, float, float, float]:
    """``(C0, C1, S0, S1, D0, D1, ω_s)`` of a duck-typed :class:`uwml.losses.Seal`, checked."""
    c0 = _number(seal.c0, "seal.c0", positive=False)
    c1 = _number(seal.c1_per_mpa, "seal.c1_per_mpa", positive=False)
    s0 = _number(seal.s0, "seal.s0", positive=False)
    s1 = _number(seal.s1_per_mpa, "seal.s1_per_mpa", positive=False)
    if s0 < c0:
        raise ValueError(f"seal.s0 must be >= seal.c0 = {c0} (breakaway at least running friction), got {s0}")
    if s1 < c1:
        raise ValueError(f"seal.s1_per_mpa must be >= seal.c1_per_mpa = {c1} (breakaway at least running friction), got {s1}")
    return (
        c0,
        c1,
        s0,
        s1,
        _number(seal.d0, "seal.d0", positive=False),
        _number(seal.d1_per_mpa, "seal.d1_per_mpa", positive=False),
        _number(seal.stribeck_speed, "seal.stribeck_speed", positive=True),
    )


def _drive_parameters(drive: Any) -> tuple[float, float, float]:
    """``(K_t, N, η)`` of a duck-typed :class:`uwml.losses.Drive`, checked."""
    efficiency = _number(drive.efficiency, "drive.efficiency", positive=True)
    if efficiency > 1.0:
        raise ValueError(f"drive.efficiency must lie in (0, 1], got {efficiency}")
    return (
        _number(drive.torque_constant, "drive.torque_constant", positive=True),
        _number(drive.ratio, "drive.ratio", positive=True),
        efficiency,
    )


def smooth_sign(x: ArrayLike, epsilon: float) -> Array:
    """The smooth sign ``sgn_ε(x) = x / sqrt(x² + ε²)`` (MODEL.md section 7).

    Odd, strictly inside (−1, 1) for ε > 0, and ``sgn_ε(0) = 0``; ε = 0 gives the hard sign
    ``np.sign`` (again with ``sgn(0) = 0``).

    Parameters
    ----------
    x : array_like
        Finite numbers (typically a speed).
    epsilon : float
        Smoothing width, ≥ 0, in the units of ``x``.

    Returns
    -------
    ndarray
        Shaped like ``x``.

    Raises
    ------
    ValueError
        If ``x`` is not finite or ``epsilon`` is negative or not finite.
    """
    x = _samples(x, "x")
    epsilon = _number(epsilon, "epsilon", positive=False)
    if epsilon == 0.0:
        return np.sign(x)
    # hypot, not sqrt(x² + ε²): the same number where the squares neither underflow (x = 0 with
    # ε below 1e-154 would give 0/0) nor overflow.
    return x / np.hypot(x, epsilon)


def oil_drag_torque(
    oil: Any,
    motor_speed: ArrayLike,
    pressure_mpa: ArrayLike,
    temperature_c: ArrayLike,
    epsilon: float = 0.0,
) -> Array:
    """Viscous (churning) torque of the compensation oil at the motor shaft (MODEL.md section 7).

    ``T_oil = K_oil · exp(a_p (p − p_ref)) · exp(−a_T (θ − θ_ref)) · |ω_m|^n · sgn_ε(ω_m)``: the
    torque that drives the oil, in the direction of ``ω_m`` (the motor supplies it).

    Parameters
    ----------
    oil : OilDrag-like
        ``k_oil`` [N·m·(rad/s)^−n] ≥ 0, ``exponent`` n in [1, 2], ``pressure_sensitivity_per_mpa``
        a_p ≥ 0, ``temperature_sensitivity_per_k`` a_T ≥ 0, ``reference_pressure_mpa`` ≥ 0,
        ``reference_temperature_c`` > −273.15.
    motor_speed : array_like
        Motor speed ``ω_m = N·ω`` [rad/s].
    pressure_mpa : array_like
        Ambient (gauge) pressure [MPa], ≥ 0.
    temperature_c : array_like
        Oil temperature [°C], > −273.15.
    epsilon : float
        Smooth-sign width [rad/s, at the motor], ≥ 0.

    Returns
    -------
    ndarray
        ``T_oil`` [N·m], the broadcast shape of the three inputs.

    Raises
    ------
    ValueError
        On parameters out of range, non-finite inputs, negative pressures, temperatures at or
        below absolute zero, or a negative ``epsilon``; the message names the argument.
    """
    k_oil, exponent, a_p, a_t, p_ref, theta_ref = _oil_parameters(oil)
    omega_m = _samples(motor_speed, "motor_speed")
    p = _samples(pressure_mpa, "pressure_mpa", low=0.0)
    theta = _samples(temperature_c, "temperature_c", low=_ABSOLUTE_ZERO_C, strict=True)
    omega_m, p, theta = np.broadcast_arrays(omega_m, p, theta)
    scale = k_oil * np.exp(a_p * (p - p_ref)) * np.exp(-a_t * (theta - theta_ref))
    return scale * np.abs(omega_m) ** exponent * smooth_sign(omega_m, epsilon)


def seal_torque(seal: Any, speed: ArrayLike, pressure_mpa: ArrayLike, epsilon: float = 0.0) -> Array:
    """Friction torque of the output-shaft dynamic seal at the joint output (MODEL.md section 7).

    ``T_seal = sgn_ε(ω) · [C(p) + (S(p) − C(p)) · exp(−(|ω|/ω_s)²)] + D(p) · ω`` with
    ``C = C0 + C1 p``, ``S = S0 + S1 p``, ``D = D0 + D1 p``: the torque that overcomes the seal,
    in the direction of ω. At ``ω → 0⁺`` (ε = 0) it is the breakaway level S(p).

    Parameters
    ----------
    seal : Seal-like
        ``c0``, ``c1_per_mpa``, ``s0``, ``s1_per_mpa`` [N·m, N·m/MPa] with ``s0 >= c0 >= 0`` and
        ``s1_per_mpa >= c1_per_mpa >= 0``; ``d0``, ``d1_per_mpa`` [N·m·s/rad, per MPa] ≥ 0;
        ``stribeck_speed`` ω_s [rad/s] > 0.
    speed : array_like
        Output speed ω [rad/s].
    pressure_mpa : array_like
        Ambient (gauge) pressure [MPa], ≥ 0.
    epsilon : float
        Smooth-sign width [rad/s], ≥ 0.

    Returns
    -------
    ndarray
        ``T_seal`` [N·m], the broadcast shape of ``speed`` and ``pressure_mpa``.

    Raises
    ------
    ValueError
        On parameters out of range or out of order, non-finite inputs, negative pressures or a
        negative ``epsilon``; the message names the argument.
    """
    c0, c1, s0, s1, d0, d1, omega_s = _seal_parameters(seal)
    omega = _samples(speed, "speed")
    p = _samples(pressure_mpa, "pressure_mpa", low=0.0)
    omega, p = np.broadcast_arrays(omega, p)
    running = c0 + c1 * p
    breakaway = s0 + s1 * p
    viscous = d0 + d1 * p
    stribeck = np.exp(-((np.abs(omega) / omega_s) ** 2))
    return smooth_sign(omega, epsilon) * (running + (breakaway - running) * stribeck) + viscous * omega


def loss_current(drive: Any, oil_torque: ArrayLike, seal_torque: ArrayLike) -> Array:
    """Motor current that the two losses cost: ``I_loss = T_oil/K_t + T_seal/(N η K_t)`` [A].

    Parameters
    ----------
    drive : Drive-like
        ``torque_constant`` K_t [N·m/A] > 0, ``ratio`` N > 0, ``efficiency`` η in (0, 1].
    oil_torque : array_like
        ``T_oil`` at the motor shaft [N·m] (:func:`oil_drag_torque`).
    seal_torque : array_like
        ``T_seal`` at the joint output [N·m] (:func:`seal_torque`).

    Returns
    -------
    ndarray
        ``I_loss`` [A], the broadcast shape of the two torques (signed like them).

    Raises
    ------
    ValueError
        On drive parameters out of range or non-finite torques.
    """
    torque_constant, ratio, efficiency = _drive_parameters(drive)
    t_oil = _samples(oil_torque, "oil_torque")
    t_seal = _samples(seal_torque, "seal_torque")
    return t_oil / torque_constant + t_seal / (ratio * efficiency * torque_constant)


def joint_loss_torques(
    drive: Any,
    oil: Any | None,
    seal: Any | None,
    speed: ArrayLike,
    pressure_mpa: ArrayLike,
    temperature_c: ArrayLike,
    epsilon: float = 0.0,
) -> dict[str, Array]:
    """Joint losses as environment torques at the output and as motor current (MODEL.md section 7).

    The oil is sheared at the motor speed ``ω_m = N ω``; the seal slides at the output speed ω.
    In section 1's sign (the environment's torque on the joint, so losses oppose motion):
    ``visc = −N η T_oil(N ω, p, θ)`` and ``seal = −T_seal(ω, p)``; ``current`` is
    ``I_loss = T_oil/K_t + T_seal/(N η K_t)``, the extra motor current they cost.

    Parameters
    ----------
    drive : Drive-like
        ``torque_constant`` K_t [N·m/A], ``ratio`` N, ``efficiency`` η.
    oil : OilDrag-like or None
        Oil drag parameters (:func:`oil_drag_torque`); None: no oil (zero).
    seal : Seal-like or None
        Seal parameters (:func:`seal_torque`); None: no seal (zero).
    speed : array_like
        Output speed ω [rad/s].
    pressure_mpa : array_like
        Ambient (gauge) pressure [MPa], ≥ 0.
    temperature_c : array_like
        Oil temperature [°C], > −273.15.
    epsilon : float
        Smooth-sign width [rad/s at the output], ≥ 0; the oil's sign uses ``N ε`` at the motor,
        so both signs switch over the same output speeds.

    Returns
    -------
    dict
        ``visc``, ``seal`` [N·m at the output] and ``current`` [A], each of the broadcast shape
        of ``speed``, ``pressure_mpa`` and ``temperature_c``.

    Raises
    ------
    ValueError
        On parameters out of range or out-of-range inputs; the message names the argument.
    """
    _, ratio, efficiency = _drive_parameters(drive)
    omega = _samples(speed, "speed")
    p = _samples(pressure_mpa, "pressure_mpa", low=0.0)
    theta = _samples(temperature_c, "temperature_c", low=_ABSOLUTE_ZERO_C, strict=True)
    epsilon = _number(epsilon, "epsilon", positive=False)
    omega, p, theta = np.broadcast_arrays(omega, p, theta)
    t_oil = np.zeros(omega.shape) if oil is None else oil_drag_torque(oil, ratio * omega, p, theta, ratio * epsilon)
    t_seal = np.zeros(omega.shape) if seal is None else seal_torque(seal, omega, p, epsilon)
    return {
        "visc": -ratio * efficiency * t_oil,
        "seal": -t_seal,
        "current": loss_current(drive, t_oil, t_seal),
    }


def hydrostatic_pressure_mpa(depth_m: ArrayLike, sea_density: float = 1025.0, gravity: float = 9.81) -> Array:
    """Gauge pressure of a uniform sea at depth: ``p = ρ g z`` [MPa].

    The core's model (MODEL.md section 7); :func:`uwml.seawater.pressure_at_depth_mpa` gives the
    TEOS-10 value, and docs/losses.md the measured difference.

    Parameters
    ----------
    depth_m : array_like
        Depth below the surface z [m], ≥ 0.
    sea_density : float
        Sea-water density ρ [kg/m³], > 0.
    gravity : float
        Gravitational acceleration g [m/s²], ≥ 0.

    Returns
    -------
    ndarray
        Pressure [MPa], shaped like ``depth_m``.

    Raises
    ------
    ValueError
        If ``depth_m`` is negative or not finite, ``sea_density <= 0`` or ``gravity < 0``.
    """
    z = _samples(depth_m, "depth_m", low=0.0)
    rho = _number(sea_density, "sea_density", positive=True)
    g = _number(gravity, "gravity", positive=False)
    return rho * g * z * 1e-6
