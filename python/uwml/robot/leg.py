"""The leg (any serial chain of revolute joints) and its hydrodynamic torques, computed by the Rust core."""

from __future__ import annotations

import operator
import os
from collections.abc import Sequence
from typing import Any, Literal, SupportsIndex

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .. import _core
from .._checks import real_array as _real_array
from ..model.joint_losses import JointLosses
from ..model.parts import FRESH_WATER, Joint, Link, Segment, Water
from ._arguments import _coefficients, joint_and_link_tuples
from .results import EnvironmentJacobians, HydroRegressors
from .tree import Robot

__all__ = ["MAX_JOINTS", "Leg"]

FloatArray = NDArray[np.float64]

#: Largest number of joints a chain may have.
MAX_JOINTS: int = _core.MAX_JOINTS


#: Why a Leg does not load descriptions.
_DESCRIPTIONS = (
    "a uwml.Leg is built from its Joints and Links (or Leg.paper()); a URDF, MJCF or MuJoCo model loads as a uwml.Robot "
    "(uwml.Robot.from_urdf, from_mjcf, from_mujoco)"
)


def _vec(values: Sequence[float]) -> tuple[float, float, float]:
    return (float(values[0]), float(values[1]), float(values[2]))


def _from_parts(joints: list[Any], links: list[Any], base: Any, segments: list[Any]) -> tuple[tuple[Joint, ...], tuple[Link, ...]]:
    """A leg's validated ``Joint``s and ``Link``s from its native robot's :meth:`parts` (a serial
    chain on a fixed base, each link with at most one rectangular segment; the segments'
    geometry, at the default coefficients as a leg's links have always been read)."""
    joint_list = tuple(Joint(origin=origin, axis=axis) for _parent, _kind, origin, axis in joints)
    by_link = {
        owner: (start, axis, length, area, normals, widths) for owner, start, axis, length, area, _section, normals, widths, *_ in segments
    }
    link_list = []
    for index, (mass, com, volume, cob) in enumerate(links):
        segment = None
        if index in by_link:
            start, axis, length, area, normals, widths = by_link[index]
            segment = Segment(start=start, axis=axis, length=length, normals=normals, widths=widths, area=area)
        link_list.append(Link(mass=mass, com=com, volume=volume, cob=cob, segment=segment))
    return joint_list, tuple(link_list)


class Leg(Robot):
    """A serial chain of revolute joints with straight links: the paper's leg, or your own.

    A ``Leg`` is a :class:`uwml.Robot` (its joints in series on a fixed base, at most one
    rectangular segment per link), evaluated by the same code: :meth:`hydro`, :meth:`environment`
    and the rest are the robot's. What it adds: ``cd`` and ``cm`` per link (a scalar, an array
    ``(n_links,)`` per link, or ``(n_links, 2)`` per link and normal direction, column ``k`` with
    ``segment.normals[k]``; for the paper's leg 0 = out of the leg plane (yaw), 1 = in the plane
    (roll); links without a segment ignore theirs; None, the default: each segment's own, the
    paper's 2.2 and 0.5 unless a segment says otherwise), the leg's regressor and Jacobian layouts
    (joint space), and the chain's kinematics (:meth:`jacobian`, :meth:`forward_kinematics`).

    Build one from :class:`uwml.Joint` and :class:`uwml.Link` descriptions (see the module
    :mod:`uwml.model.parts` for the frame convention), or take :meth:`Leg.paper`. The parameters are
    validated once, here; evaluation is then done by the Rust core.

    Example: a single horizontal cylinder of 1 m, 0.1 m in diameter, turning about world z::

        import uwml
        rod = uwml.Leg(
            joints=[uwml.Joint(origin=(0, 0, 0), axis=(0, 0, 1))],
            links=[uwml.Link(mass=20.0, com=(0.5, 0, 0), volume=0.00785,
                             segment=uwml.Segment(start=(0, 0, 0), axis=(1, 0, 0), length=1.0,
                                                  normals=((0, 1, 0), (0, 0, 1)),
                                                  widths=(0.1, 0.1), area=0.00785))],
        )
        rod.hydro(q=[0.0], qd=[1.0], qdd=[0.0], cd=1.2, cm=1.0).drag
    """

    def __init__(self, joints: Sequence[Joint], links: Sequence[Link]) -> None:
        joints, links = joint_and_link_tuples(joints, links)
        if len(joints) != len(links) or not 1 <= len(joints) <= MAX_JOINTS:
            raise ValueError(f"a leg needs as many links as joints, 1 to {MAX_JOINTS}; got {len(joints)} joints and {len(links)} links")
        for index, joint in enumerate(joints):
            if joint.kind != "revolute" or joint.parent not in (None, index - 1):
                raise ValueError(
                    f"joints[{index}]: a uwml.Leg is a serial chain of revolute joints (parent = previous link); use uwml.Robot for trees and prismatic joints"
                )
        for index, link in enumerate(links):
            if len(link.segments) > 1 or (link.segment is not None and link.segment.section != "rectangular"):
                raise ValueError(
                    f"links[{index}]: a uwml.Leg link has at most one rectangular segment; use uwml.Robot for several segments or circular sections"
                )
            if any(segment.cd_axial != 0.0 for segment in link.segments):
                raise ValueError(f"links[{index}]: a uwml.Leg segment has no axial drag; use uwml.Robot for segments with cd_axial")
            if link.lumped is not None:
                raise ValueError(f"links[{index}]: a uwml.Leg link has no lumped model (uwml.LumpedModel); use uwml.Robot for bluff bodies")
        super().__init__(joints, links)  # validated by the core
        self._from_validated(*_from_parts(*self._core.parts()))

    def _from_validated(self, joints: tuple[Joint, ...], links: tuple[Link, ...]) -> None:
        """This leg from its parameters as the core validated them (axes normalized), and the
        robot they make."""
        self._leg_joints, self._leg_links = joints, links
        super().__init__(self._leg_joints, self._leg_links)
        #: The links that carry a segment, in segment order.
        self._owners = tuple(i for i, link in enumerate(self._leg_links) if link.segment is not None)

    @classmethod
    def paper(cls) -> Leg:
        """The 3-DOF leg of the paper (Table II): hip yaw, hip roll, knee roll."""
        leg = cls.__new__(cls)
        leg._from_validated(*_from_parts(*_core.Robot.paper_leg().parts()))
        return leg

    @property
    def joints(self) -> tuple[Joint, ...]:
        """The joints, as validated (axes normalized)."""
        return self._leg_joints

    @property
    def links(self) -> tuple[Link, ...]:
        """The links, as validated."""
        return self._leg_links

    def __repr__(self) -> str:
        return f"Leg(n_joints={self.n_joints})"

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Leg):
            return NotImplemented
        return (self._leg_joints, self._leg_links) == (other._leg_joints, other._leg_links)

    @classmethod
    def load(cls, path: str | os.PathLike[str]) -> Leg:
        """The leg of a uwml model file of a serial chain of revolute joints, each link with at
        most one rectangular segment (what :meth:`save` writes); other robots load with
        :meth:`uwml.Robot.load`."""
        robot = Robot.load(path)
        joints = [Joint(j.origin, j.axis, parent=None if j.parent == i - 1 else j.parent, kind=j.kind) for i, j in enumerate(robot.joints)]
        links = [Link(link.mass, link.com, link.volume, cob=link.cob, segments=link.segments) for link in robot.links]
        if robot.base is not None:
            raise ValueError(f"{path}: a uwml.Leg has no base body; load this file with uwml.Robot.load")
        if any(losses is not None for losses in robot.losses):
            raise ValueError(
                f"{path}: a uwml.Leg holds no joint losses (give them to Leg.environment); load this file with uwml.Robot.load"
            )
        if robot.water != FRESH_WATER:
            raise ValueError(
                f"{path}: a uwml.Leg holds no water of its own (give water= to its evaluations); load this file with uwml.Robot.load"
            )
        return cls(joints, links)

    @classmethod
    def from_urdf(cls, path: str | os.PathLike[str], hydro: str | os.PathLike[str] | None = None) -> Leg:
        """Not for a leg: a description loads as a :class:`uwml.Robot` (``uwml.Robot.from_urdf``)."""
        raise TypeError(_DESCRIPTIONS)

    @classmethod
    def from_mjcf(cls, path: str | os.PathLike[str], hydro: str | os.PathLike[str] | None = None) -> Leg:
        """Not for a leg: as :meth:`from_urdf`."""
        raise TypeError(_DESCRIPTIONS)

    @classmethod
    def from_mujoco(cls, model: Any, hydro: str | os.PathLike[str] | None = None) -> Leg:
        """Not for a leg: as :meth:`from_urdf`."""
        raise TypeError(_DESCRIPTIONS)

    _COEFFICIENTS_BY_LINK = True

    def _segment_values(self, value: ArrayLike | None, name: str) -> ArrayLike | None:
        """A leg's ``cd`` or ``cm`` (None, a scalar, per link or per link and direction) as the
        robot's (None, a scalar, or per segment and direction), for the robot's general path."""
        if value is None or (isinstance(value, (int, float)) and not isinstance(value, bool)):
            return value
        return _coefficients(value, name, self.n_joints)[list(self._owners)]

    def jacobians(  # type: ignore[override]  # the joint-space block of the robot's (a leg's base is fixed)
        self,
        q: ArrayLike,
        qd: ArrayLike,
        qdd: ArrayLike,
        depth: ArrayLike = 0.0,
        temperature_c: ArrayLike = 20.0,
        losses: JointLosses | Sequence[JointLosses | None] | None = None,
        cd: ArrayLike | None = None,
        cm: ArrayLike | None = None,
        water: Water | None = None,
        sea_density: float | None = None,
        added_mass: str = "morison",
    ) -> EnvironmentJacobians:
        """The environment torque of :meth:`environment` and its derivatives, for control: the
        joint-space block of :meth:`uwml.Robot.jacobians` (a leg's base is fixed).

        Arguments as for :meth:`environment`, but without ``threads`` (the batch runs on one
        thread). Returns an :class:`EnvironmentJacobians`: ``value`` (``τ_env``,
        ``environment(...).total`` to 1e-13 of the largest torque), ``d_q = ∂τ_env/∂q``,
        ``d_qd = ∂τ_env/∂q̇`` and ``added_mass_matrix = M_A(q)``, with
        ``added_mass(q, 0, q̈) = −M_A(q) q̈``. The derivatives are exact (forward-mode dual
        numbers through the same Rust code, not finite differences); at a joint speed of exactly
        zero with a hard sign (``epsilon=0``) the losses jump and their slope is not meaningful.
        """
        r = super().jacobians(
            q, qd, qdd, depth=depth, temperature_c=temperature_c, losses=losses,
            cd=cd, cm=cm, water=water, sea_density=sea_density, added_mass=added_mass,
        )  # fmt: skip
        return EnvironmentJacobians(
            value=r.value[..., 6:],
            d_q=r.d_q[..., 6:, :],
            d_qd=r.d_velocity[..., 6:, 6:],
            added_mass_matrix=r.added_mass_matrix[..., 6:, 6:],
        )

    def hydro_regressors(  # type: ignore[override]  # the leg's layouts (per leg, per link and direction)
        self,
        q: ArrayLike,
        qd: ArrayLike,
        qdd: ArrayLike,
        water: Water | None = None,
        per: Literal["leg", "direction"] = "leg",
        added_mass: str = "morison",
    ) -> HydroRegressors:
        """Regressors such that ``total = buoyancy + cd * drag + cm * added_mass``: the joint rows
        of :meth:`uwml.Robot.hydro_regressors`, by link.

        ``per="leg"`` gives one drag and one added-mass column (the paper's eq. 24);
        ``per="direction"`` one per link and normal direction (see :class:`HydroRegressors`).
        """
        if per not in ("leg", "direction"):
            raise ValueError(f"per must be 'leg' or 'direction', got {per!r}")
        r = super().hydro_regressors(q, qd, qdd, water=water, added_mass=added_mass)
        if per == "leg":
            drag, mass = r.drag.sum(axis=(-2, -1)), r.added_mass.sum(axis=(-2, -1))
        else:
            # Segments back to the links that carry them: (..., joints, links, 2).
            drag = np.zeros(r.drag.shape[:-2] + (self.n_joints, 2))
            mass = np.zeros_like(drag)
            drag[..., list(self._owners), :] = r.drag
            mass[..., list(self._owners), :] = r.added_mass
        return HydroRegressors(buoyancy=r.buoyancy, gravity=r.gravity, drag=drag, added_mass=mass, links_with_segments=self._owners)

    def _link_index(self, link: object) -> int:
        """``link`` as an index in ``0..n_joints`` (negative counts from the end)."""
        if isinstance(link, (bool, np.bool_)):
            raise TypeError(f"link must be an integer, got {link!r}")
        try:
            if not isinstance(link, SupportsIndex):
                raise TypeError(f"{type(link).__name__!r} object cannot be interpreted as an integer")
            index = operator.index(link)
        except TypeError:
            raise TypeError(f"link must be an integer, got {type(link).__name__}") from None
        n = self.n_joints
        if not -n <= index < n:
            raise ValueError(f"link must be in -{n}..{n - 1} (this leg has {n} links), got {index}")
        return index % n

    def _default_point(self, link: int) -> tuple[float, float, float]:
        segment = self._links[link].segment
        if segment is None:
            return (0.0, 0.0, 0.0)
        return _vec([s + segment.length * a for s, a in zip(segment.start, segment.axis)])

    def jacobian(self, q: ArrayLike, link: int = -1, point: ArrayLike | None = None) -> tuple[FloatArray, FloatArray]:
        """World position and geometric Jacobian of a point on a link.

        Parameters
        ----------
        q
            Joint angles [rad], shape ``(..., n_joints)`` (any number of leading axes).
        link
            The link carrying the point, ``0 .. n_joints - 1``; negative counts from the end
            (default ``-1``, the last link).
        point
            The point in the link's frame [m], shape ``(3,)``. ``None`` (default): the tip of the
            link's segment, ``start + length * axis``, if the link has one, else the link frame's
            origin (its joint). For :meth:`Leg.paper`, link ``-1``'s tip is the foot.

        Returns
        -------
        positions, jacobians
            Shapes ``(..., 3)`` and ``(..., 6, n_joints)``. Column ``j`` of a Jacobian maps
            ``qd[j]`` to the point's velocity (rows 0-2, ``z_j × (p − o_j)``) and to the link's
            angular velocity (rows 3-5, ``z_j``); joints after ``link`` have zero columns.

        The batch is evaluated in one call into Rust, with the GIL released.
        """
        index = self._link_index(link)
        if point is None:
            local = np.array(self._default_point(index))
        else:
            local = _real_array(point, "point", "three real numbers")
            if local.shape != (3,):
                raise ValueError(f"point must have shape (3,), got {local.shape}")
            if not np.all(np.isfinite(local)):
                raise ValueError(f"point must be finite, got {local.tolist()}")
        angles = _real_array(q, "q", "a rectangular array of real numbers")
        n = self.n_joints
        if angles.ndim < 1 or angles.shape[-1] != n:
            raise ValueError(f"q must have shape (..., {n}), got {angles.shape}")
        shape = angles.shape[:-1]
        positions, jacobians = self._core.point_jacobian(np.ascontiguousarray(angles.reshape(-1, n)), index, np.ascontiguousarray(local))
        return positions.reshape(shape + (3,)), jacobians.reshape(shape + (6, n))

    def forward_kinematics(self, q: ArrayLike, link: int = -1, point: ArrayLike | None = None) -> FloatArray:
        """World position of a point on a link, shape ``q.shape[:-1] + (3,)``.

        Arguments as for :meth:`jacobian`: by default the tip of the last link (the paper leg's
        foot, ``L2 u2 + L3 u3`` of docs/model.md section 2).
        """
        return self.jacobian(q, link, point)[0]
