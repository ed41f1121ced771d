"""Independent numpy reference for uwml's hydrodynamics of a serial chain (docs/model.md sections 2-5).

This module re-derives, with numpy only and a different algorithm, what the Rust core
(``uwml._core``) computes, so that tests can hold the core to it:

* kinematics by explicit Rodrigues rotation matrices and the joint-screw sums
  ``v(p) = Σ_j q̇_j z_j × (p − o_j)`` (and their time derivative), not the forward recursion;
* the drag integral ``∫ g h|h| ds`` (``g``, ``h`` affine in ``s``) in closed form on each
  interval where ``h`` keeps its sign, not Gauss-Legendre;
* the added-mass integral ``∫ g a ds`` in closed form.

It also carries the paper's UWML leg (:func:`paper_leg`, Table II).

Frames (as in :mod:`uwml.model`): every link frame is parallel to the world frame at ``q = 0``.
The world pose of link ``i`` is ``T_i = T_{i-1} · Trans(joint_i.origin) · Rot(joint_i.axis, q_i)``
with ``T_{-1}`` the identity; link ``i``'s geometry is given in its own frame. World z is up and
gravity points along −z. Every torque is the generalized force exerted *by the environment on
the joint* (docs/model.md section 1), so drag satisfies ``q̇ · τ_drag ≤ 0``.

Joints and links are duck-typed: any objects with the attributes of :class:`uwml.model.Joint`
and :class:`uwml.model.Link` (``origin``, ``axis``; ``mass``, ``com``, ``volume``, ``cob``,
``segments``, at most one per link, each with ``start``, ``axis``, ``length``, ``normals``,
``widths``, ``area``) will do.
"""

# No ``from __future__ import annotations``: dataclasses with string annotations look their module
# up in sys.modules, which a standalone load (spec_from_file_location) need not provide.
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from ._inputs import _AXIS_TOLERANCE, Array, Vec3, _number, _states, _vector

__all__ = ["RefJoint", "RefLink", "RefSegment", "hydro", "paper_leg", "regressors"]

# The paper's leg (Table II of Liao et al.; docs/model.md section 2).
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
    """A rigid link: mass and COM, displaced volume and centre of buoyancy, and its segment
    (none or one)."""

    mass: float
    com: Vec3
    volume: float
    cob: Vec3
    segments: tuple[RefSegment, ...] = ()


def paper_leg() -> tuple[tuple[RefJoint, RefJoint, RefJoint], tuple[RefLink, RefLink, RefLink]]:
    """The paper's 3-DOF underwater leg (Table II), as joints and links.

    Joint 1 is the hip yaw about world z, joints 2 and 3 (hip and knee roll) turn about the local
    −y axis, so that with ``e_r = (cos q1, sin q1, 0)`` the thigh axis is
    ``u2 = cos q2 e_r + sin q2 z`` and the calf axis ``u3 = sin(q2+q3) e_r − cos(q2+q3) z``
    (docs/model.md section 2). The first normal of each segment is the out-of-plane direction (local
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
        RefLink(masses[1], thigh_com, masses[1] / PAPER_LINK_DENSITY, thigh_com, (thigh,)),
        RefLink(masses[2], calf_com, masses[2] / PAPER_LINK_DENSITY, calf_com, (calf,)),
    )
    return joints, links


# --------------------------------------------------------------------------------------------
# Input checking
# --------------------------------------------------------------------------------------------


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
    for i, link in enumerate(links):
        if len(tuple(link.segments)) > 1:
            raise ValueError(f"links[{i}] has {len(tuple(link.segments))} segments: a chain's link has at most one")
    segments = tuple(
        _segment(link.segments[0], f"links[{i}].segments[0]") if tuple(link.segments) else None for i, link in enumerate(links)
    )
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
    rotations: Array = np.eye(3) + s * k + (1.0 - c) * (k @ k)
    return rotations


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
        velocity: Array = np.einsum("mj,mjc->mc", self.qd[:, moved], np.cross(self.axes[:, moved], r))
        return velocity

    def acceleration(self, p: Array, v: Array, link: int) -> Array:
        """Acceleration (m, 3) of the point at ``p`` with velocity ``v`` fixed to ``link``.

        Time derivative of ``Σ_j q̇_j z_j × (p − o_j)``: ``d/dt z_j = ω_{j-1} × z_j`` and
        ``d/dt (p − o_j) = v − v(o_j)``.
        """
        moved = slice(0, link + 1)
        z = self.axes[:, moved]
        r = p[:, None, :] - self.origins[:, moved]
        dr = v[:, None, :] - self.origin_velocities[:, moved]
        terms: Array = self.qdd[:, moved, None] * np.cross(z, r) + self.qd[:, moved, None] * (
            np.cross(self.axis_rates[:, moved], r) + np.cross(z, dr)
        )
        acceleration: Array = terms.sum(axis=1)
        return acceleration


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
    """Hydrodynamic regressors of a serial chain (docs/model.md section 4).

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
    """Hydrodynamic joint torques of a serial chain by strip theory (docs/model.md section 3).

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
