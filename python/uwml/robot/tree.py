"""A whole robot in moving water: a kinematic tree on a moving base, in a current (docs/model.md section 10).

:class:`Robot` takes :class:`uwml.Joint` (with ``parent`` and ``kind``), :class:`uwml.Link`
(any number of ``segments``, rectangular or circular) and an optional base body, and gives the
environment's generalized force on every joint *and* the wrench on the base, computed by the
Rust core. :class:`BaseMotion` says how the base moves; the current is a world-frame velocity.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .. import _core
from .._checks import check_overflow
from .._checks import real_array as _real_array
from ..io import descriptions, modelfile
from ..model.joint_losses import JointLosses, pack_leg_losses
from ..model.lumped import LumpedModel
from ..model.parts import FRESH_WATER, Joint, Link, Segment, Water
from ..plausibility import check_efforts, check_states, joint_bounds
from ..sea.conditions import loss_conditions
from ._arguments import (
    _Inputs,
    _kirchhoff,
    _per_joint_losses,
    _short_path,
    _threads,
    _water,
    one_state_losses,
    robot_inputs,
    robot_parts,
    segment_coefficients,
)
from .base_motion import BaseMotion
from .results import BaseWrench, RobotEnvironment, RobotJacobians, RobotRegressors, RobotTorques

__all__ = [
    "MAX_LUMPED_BODIES",
    "MAX_ROBOT_JOINTS",
    "MAX_SEGMENTS",
    "Robot",
]

FloatArray = NDArray[np.float64]

#: Largest number of joints of a :class:`Robot`.
MAX_ROBOT_JOINTS: int = _core.MAX_ROBOT_JOINTS
#: Largest number of segments (all bodies together) of a :class:`Robot`.
MAX_SEGMENTS: int = _core.MAX_SEGMENTS
#: The most lumped models (:class:`uwml.LumpedModel`) a robot may carry, on all its bodies.
MAX_LUMPED_BODIES: int = _core.MAX_LUMPED_BODIES


def _base_wrench(out: Sequence[FloatArray], lead: tuple[int, ...]) -> BaseWrench:
    """The base wrench of a native ``hydro`` result (items 4 to 7), shaped ``(*lead, 6)``."""
    drag, mass, buoyancy, gravity = (a.reshape(*lead, 6) for a in out[4:8])
    return BaseWrench(drag=drag, added_mass=mass, buoyancy=buoyancy, gravity=gravity)


class Robot:
    """A robot: joints in a tree, the links they move, and optionally the base's own body.

    Joints come in topological order: a joint's ``parent`` is an earlier link, or ``-1`` for the
    base (``None``, the default, means the previous link: a list of joints is a serial chain).
    Frames, kinds and segments are described in :mod:`uwml.model.parts`. ``base`` is a
    :class:`uwml.Link` in the base frame (a vehicle's hull, a walking robot's body), or ``None``
    for a base without volume, mass or segments of its own. ``losses``: the joints' own losses
    (one :class:`uwml.JointLosses` for all, or one or None per joint), used by
    :meth:`environment` unless it is given others. ``water``: the robot's water
    (:class:`uwml.Water`, default fresh), used by every evaluation unless it is given another.

    Segments are numbered base first, then link 0's, link 1's, ...: the order of per-segment
    coefficients and of :attr:`segments`.

    Example: a 2-joint arm of cylinders on an ROV that pitches and surges in a current::

        import uwml
        from scipy.spatial.transform import Rotation
        arm = uwml.Robot(
            joints=[uwml.Joint((0.5, 0, -0.3), (0, 0, 1)), uwml.Joint((0, 0, -0.4), (0, 1, 0))],
            links=[uwml.Link(4.0, (0, 0, -0.2), 0.002, segments=[uwml.Segment((0, 0, 0), (0, 0, -1), 0.4, section="circular", diameter=0.08)]),
                   uwml.Link(3.0, (0.25, 0, 0), 0.0015, segments=[uwml.Segment((0, 0, 0), (1, 0, 0), 0.5, section="circular", diameter=0.06)])],
        )
        motion = uwml.BaseMotion(orientation=Rotation.from_euler("y", 0.1), velocity=(0.5, 0, 0))
        result = arm.hydro([0.3, -0.5], [0.2, 0.1], [0, 0], base_motion=motion, current=(0.2, 0, 0))
        result.total, result.base.total   # joint torques; base force and moment
    """

    #: The last ``JointLosses`` of a one-state call, and the core's reading of it.
    _losses_cache: tuple[JointLosses, _core.Losses] | None = None

    def __init__(
        self,
        joints: Sequence[Joint],
        links: Sequence[Link],
        base: Link | None = None,
        losses: JointLosses | Sequence[JointLosses | None] | None = None,
        water: Water | None = None,
    ) -> None:
        # The checked tuples from here on (``joints`` and ``links`` may be any iterables).
        self._joints, links, base_body, owned = robot_parts(joints, links, base)
        for what, items in (("joint", self._joints), ("link", links)):
            names = [item.name for item in items if item.name is not None]
            repeated = sorted({name for name in names if names.count(name) > 1})
            if repeated:
                raise ValueError(f"{what} names must be unique; {repeated[0]!r} is given more than once")
        self._bounds = joint_bounds(self._joints)
        self._core = _core.Robot(self._joints, links, base_body, owned, self._bounds.rows())
        self._links = links
        self._base = base
        self._segments = tuple(s for _, s in owned)
        #: The lumped models (body: -1 the base, else the link; model), in the regressors' order.
        self._lumped = tuple((b - 1, body.lumped) for b, body in enumerate((base_body, *links)) if body.lumped is not None)
        self._losses = _per_joint_losses(losses, len(self._joints))
        # The joints' own losses as an evaluation takes them: one object when they all share one.
        first = self._losses[0] if self._losses else None
        self._own_losses = first if all(item is first for item in self._losses) else self._losses
        self._water = FRESH_WATER if water is None else _water(water)
        self._circular = np.array([s.section == "circular" for s in self._segments], dtype=bool)
        #: The segments' own coefficients, ``(S, 2)`` each: for an evaluation given only one of them.
        self._own_cd = np.array([s.cd for s in self._segments], dtype=np.float64).reshape(-1, 2)
        self._own_cm = np.array([s.cm for s in self._segments], dtype=np.float64).reshape(-1, 2)

    @classmethod
    def from_leg(cls, leg: Any) -> Robot:
        """The serial chain of a :class:`uwml.Leg` as a robot on a fixed base."""
        return cls(leg.joints, leg.links)

    @property
    def joints(self) -> tuple[Joint, ...]:
        """The joints, with every ``parent`` explicit (``-1`` for the base)."""
        return self._joints

    @property
    def links(self) -> tuple[Link, ...]:
        """The links, link ``i`` moved by joint ``i``."""
        return self._links

    @property
    def base(self) -> Link | None:
        """The base's own body, if any."""
        return self._base

    @property
    def joint_names(self) -> tuple[str, ...]:
        """The joints' names in the order of ``q`` (``"joint{i}"`` where a joint has none)."""
        return tuple(j.name if j.name is not None else f"joint{i}" for i, j in enumerate(self._joints))

    @property
    def link_names(self) -> tuple[str, ...]:
        """The links' names in order (``"link{i}"`` where a link has none)."""
        return tuple(link.name if link.name is not None else f"link{i}" for i, link in enumerate(self._links))

    @property
    def losses(self) -> tuple[JointLosses | None, ...]:
        """Each joint's own losses (None: none), used by :meth:`environment` and
        :meth:`jacobians` unless they are given others."""
        return self._losses

    @property
    def water(self) -> Water:
        """The robot's water (density, gravity): what every evaluation uses unless given
        ``water=``. Default fresh water (1000 kg/m³, 9.81 m/s²); a hydro file's or model file's
        ``[water]`` sets it."""
        return self._water

    def _the_water(self, water: Water | None) -> Water:
        return self._water if water is None else _water(water)

    def _effective_losses(
        self, losses: JointLosses | Sequence[JointLosses | None] | None
    ) -> JointLosses | Sequence[JointLosses | None] | None:
        """``losses`` if given, else the joints' own: one object when they all share one."""
        return self._own_losses if losses is None else losses

    def _loss_inputs(
        self,
        losses: JointLosses | Sequence[JointLosses | None] | None,
        depth: ArrayLike,
        temperature_c: ArrayLike,
        water: Water | None,
        sea_density: float | None,
        n_samples: int,
    ) -> tuple[Any, FloatArray, FloatArray]:
        """The native losses arguments of a batch: the joints' losses packed, and the pressure [Pa]
        and temperature [°C] per sample (hydrostatic, over ``sea_density`` or the water's)."""
        water = self._the_water(water)
        column = water.density if sea_density is None else sea_density
        pressure, temperature = loss_conditions(depth, temperature_c, column, water.gravity, n_samples)
        return pack_leg_losses(losses, self.n_joints), pressure, temperature

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Robot):
            return NotImplemented
        mine = (self._joints, self._links, self._base, self._losses, self._water)
        return mine == (other._joints, other._links, other._base, other._losses, other._water)

    __hash__ = None  # type: ignore[assignment]  # unhashable on purpose; typeshed types object.__hash__ as a method

    def save(self, path: str | os.PathLike[str]) -> None:
        """Writes the whole validated model to a uwml model file (TOML, :mod:`uwml.io.modelfile`),
        which :meth:`load` reads back equal to this robot."""
        modelfile.save(self, path)

    @classmethod
    def load(cls, path: str | os.PathLike[str]) -> Robot:
        """The robot of a uwml model file (:meth:`save`); errors name the file, the table and the key."""
        return modelfile.read(path).build(cls)

    @classmethod
    def from_urdf(cls, path: str | os.PathLike[str], hydro: str | os.PathLike[str] | None = None) -> Robot:
        """The robot of a URDF file, with an optional hydro file (:mod:`uwml.io.descriptions`;
        needs ``uwml[mujoco]``)."""
        return descriptions.urdf_parts(path, hydro).build(cls)

    @classmethod
    def from_mjcf(cls, path: str | os.PathLike[str], hydro: str | os.PathLike[str] | None = None) -> Robot:
        """The robot of an MJCF file, with an optional hydro file (:mod:`uwml.io.descriptions`;
        needs ``uwml[mujoco]``)."""
        return descriptions.mjcf_parts(path, hydro).build(cls)

    @classmethod
    def from_mujoco(cls, model: Any, hydro: str | os.PathLike[str] | None = None) -> Robot:
        """The robot of a compiled ``mujoco.MjModel``, with an optional hydro file
        (:mod:`uwml.io.descriptions`)."""
        return descriptions.mujoco_parts(model, hydro).build(cls)

    @property
    def segments(self) -> tuple[Segment, ...]:
        """Every segment, base first, then link by link: the order of per-segment coefficients."""
        return self._segments

    @property
    def lumped_models(self) -> tuple[tuple[int, LumpedModel], ...]:
        """Every lumped model with its body (-1 the base, else the link), base first: the
        regressors' order (:attr:`RobotRegressors.lumped`)."""
        return self._lumped

    @property
    def n_joints(self) -> int:
        """Number of joints (and links)."""
        return len(self._joints)

    def __repr__(self) -> str:
        return f"Robot(n_joints={self.n_joints}, n_segments={len(self._segments)}, base={'body' if self._base is not None else None})"

    # Whether ``cd`` and ``cm`` arrays are per link (each segment taking its link's), not per
    # segment: a :class:`uwml.Leg`'s layout (see :meth:`_segment_values`).
    _COEFFICIENTS_BY_LINK = False

    def _segment_values(self, value: ArrayLike | None, name: str) -> ArrayLike | None:
        """``cd`` or ``cm`` as an evaluation was given it, in the robot's layout (None, a scalar,
        per segment or per segment and direction): as given here; a :class:`uwml.Leg` takes them
        per link."""
        return value

    def _coefficients(self, value: ArrayLike | None, name: str) -> FloatArray:
        """``(S, 2)`` per segment and direction, or ``(0, 2)`` for the segments' own."""
        return segment_coefficients(self._segment_values(value, name), name, self._circular)

    def _evaluation(
        self,
        q: ArrayLike,
        qd: ArrayLike,
        qdd: ArrayLike,
        cd: ArrayLike | None,
        cm: ArrayLike | None,
        water: Water | None,
        base_motion: BaseMotion | None,
        current: ArrayLike,
        current_acceleration: ArrayLike,
    ) -> tuple[_Inputs, bool, int]:
        """The native ``Robot.hydro`` arguments (before ``threads``), whether the inputs had a
        sample axis, and the number of samples (:func:`uwml.robot._arguments.robot_inputs`)."""
        the_water = self._the_water(water)
        cd, cm = self._segment_values(cd, "cd"), self._segment_values(cm, "cm")
        if (cd is None) != (cm is None):
            # One given: the other is the segments' own.
            cd, cm = (self._own_cd, cm) if cd is None else (cd, self._own_cm)
        inputs = robot_inputs(self.n_joints, self._circular, the_water, q, qd, qdd, cd, cm, base_motion, current, current_acceleration)
        check_states(inputs[0][0], inputs[0][1], self._bounds, stacklevel=4)
        return inputs

    def hydro(
        self,
        q: ArrayLike,
        qd: ArrayLike,
        qdd: ArrayLike,
        cd: ArrayLike | None = None,
        cm: ArrayLike | None = None,
        water: Water | None = None,
        base_motion: BaseMotion | None = None,
        current: ArrayLike = (0.0, 0.0, 0.0),
        current_acceleration: ArrayLike = (0.0, 0.0, 0.0),
        threads: int = 1,
        added_mass: str = "morison",
    ) -> RobotTorques:
        """Drag, added mass, buoyancy (with Froude-Krylov) and gravity on every joint and on the
        base, each apart: ``total`` is the water's (drag, added mass and buoyancy), without the
        weight (``gravity``); the base's buoyancy is the gross ``ρ V g``, not net of the weight.

        Parameters
        ----------
        q, qd, qdd
            Joint positions, velocities, accelerations [rad or m]: ``(n_joints,)`` or
            ``(n_samples, n_joints)``, the same shape for all three.
        cd, cm
            ``None`` (default): each segment's own coefficients. Otherwise a scalar for all, an
            array ``(n_segments,)`` per segment or ``(n_segments, 2)`` per segment and normal
            direction (a circular segment takes one: its two entries must be equal).
        water
            Density and gravity; default the robot's own (:attr:`water`: fresh water,
            1000 kg/m³ and 9.81 m/s², unless its hydro or model file says otherwise).
        base_motion
            How the base moves (:class:`BaseMotion`); default a fixed, upright base.
        current, current_acceleration
            The water's velocity [m/s] and acceleration [m/s²], WORLD frame: ``(3,)`` or
            ``(n_samples, 3)``. Drag acts on the velocity relative to the water, added mass on
            the acceleration relative to it, and every body's centre of buoyancy carries
            ``ρ V (current_acceleration − g)``.
        threads
            Threads to split a batch over (≥ 1).
        added_mass
            ``"morison"`` (default): the paper's form, added mass on the normal components of
            each slice's acceleration. ``"kirchhoff"``: the form derived from the water's kinetic
            energy (docs/simulation.md, "Energy-consistent added mass"; the core's
            ``AddedMassForm``): the same added-mass matrix, other velocity terms,
            energy-consistent. Also taken by :meth:`environment`, :meth:`link_wrenches`,
            :meth:`hydro_regressors` and :meth:`jacobians`.

        Notes
        -----
        Any argument with a sample axis gives results with one; the others are broadcast. One
        state (lists, tuples or 1-D float64 arrays; ``cd``, ``cm`` None or numbers; a base motion
        of single values) is read, checked and evaluated in one short native call, with the same
        checks and the same bits as that state's row of a batch.
        """
        water = self._the_water(water)
        kirchhoff = _kirchhoff(added_mass)
        short, motion = _short_path(water, base_motion)
        if short:
            one: RobotTorques | None = self._core.hydro_one(
                RobotTorques,
                BaseWrench,
                q,
                qd,
                qdd,
                cd,
                cm,
                water.density,
                water.gravity,
                motion,
                current,
                current_acceleration,
                threads,
                kirchhoff,
                per_link=self._COEFFICIENTS_BY_LINK,
            )
            if one is not None:
                return one
        threads = _threads(threads)
        arguments, batched, n_samples = self._evaluation(q, qd, qdd, cd, cm, water, base_motion, current, current_acceleration)
        out = self._core.hydro(*arguments, threads, False, kirchhoff=kirchhoff)
        check_overflow((out[0], out[1], out[4], out[5]), n_samples, arguments[1], arguments[2])
        lead = (n_samples,) if batched else ()
        drag, mass, buoyancy, gravity = (a.reshape(*lead, self.n_joints) for a in out[:4])
        result = RobotTorques(drag=drag, added_mass=mass, buoyancy=buoyancy, gravity=gravity, base=_base_wrench(out, lead))
        check_efforts((drag, mass, buoyancy), self._bounds)
        return result

    def environment(
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
        base_motion: BaseMotion | None = None,
        current: ArrayLike = (0.0, 0.0, 0.0),
        current_acceleration: ArrayLike = (0.0, 0.0, 0.0),
        sea_density: float | None = None,
        threads: int = 1,
        added_mass: str = "morison",
    ) -> RobotEnvironment:
        """Hydrodynamics (as :meth:`hydro`) and the joint losses at depth, in one call.

        ``depth`` [m], 0 to 11000, and ``temperature_c`` [°C]: a scalar or one per sample (the
        pressure is the hydrostatic ``sea_density · g · depth``, as for
        :meth:`uwml.Leg.environment`; ``sea_density`` defaults to the water's, the robot's own
        unless ``water`` is given, so that one water is used for both).
        ``losses``: one :class:`uwml.JointLosses` for every joint, a sequence with one (or None)
        per joint, or None for the joints' own (:attr:`losses`; ``[None] * n_joints`` for none). The other arguments as for :meth:`hydro`; one state (with scalar
        ``depth``, ``temperature_c``, ``sea_density`` and ``losses`` None or one
        :class:`uwml.JointLosses`) takes the short path of :meth:`hydro`.
        """
        losses = self._effective_losses(losses)
        water = self._the_water(water)
        kirchhoff = _kirchhoff(added_mass)
        short, motion = _short_path(water, base_motion)
        if short:
            one: RobotEnvironment | None = self._core.environment_one(
                RobotEnvironment,
                BaseWrench,
                q,
                qd,
                qdd,
                depth,
                temperature_c,
                None if losses is None else one_state_losses(self, losses, self.n_joints),
                cd,
                cm,
                water.density,
                water.gravity,
                water.density if sea_density is None else sea_density,
                motion,
                current,
                current_acceleration,
                threads,
                kirchhoff,
                per_link=self._COEFFICIENTS_BY_LINK,
            )
            if one is not None:
                return one
        threads = _threads(threads)
        arguments, batched, n_samples = self._evaluation(q, qd, qdd, cd, cm, water, base_motion, current, current_acceleration)
        loss_inputs = self._loss_inputs(losses, depth, temperature_c, water, sea_density, n_samples)
        out = self._core.hydro(*arguments, threads, False, *loss_inputs, kirchhoff=kirchhoff)
        check_overflow((out[0], out[1], out[4], out[5], out[9], out[10], out[11]), n_samples, arguments[1], arguments[2])
        lead = (n_samples,) if batched else ()
        drag, mass, buoyancy, gravity, visc, seal, current_a = (out[i].reshape(*lead, self.n_joints) for i in (0, 1, 2, 3, 9, 10, 11))
        result = RobotEnvironment(
            drag=drag,
            added_mass=mass,
            buoyancy=buoyancy,
            gravity=gravity,
            visc=visc,
            seal=seal,
            current=current_a,
            base=_base_wrench(out, lead),
        )
        check_efforts((drag, mass, buoyancy, visc, seal), self._bounds)
        return result

    def jacobians(
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
        base_motion: BaseMotion | None = None,
        current: ArrayLike = (0.0, 0.0, 0.0),
        current_acceleration: ArrayLike = (0.0, 0.0, 0.0),
        sea_density: float | None = None,
        added_mass: str = "morison",
    ) -> RobotJacobians:
        """The forces of :meth:`environment` on base and joints and their derivatives
        (:class:`RobotJacobians`); arguments as for :meth:`environment`."""
        kirchhoff = _kirchhoff(added_mass)
        losses = self._effective_losses(losses)
        arguments, batched, n_samples = self._evaluation(q, qd, qdd, cd, cm, water, base_motion, current, current_acceleration)
        loss_inputs = self._loss_inputs(losses, depth, temperature_c, water, sea_density, n_samples)
        value, d_q, d_velocity, matrix = self._core.jacobians(*arguments, *loss_inputs, kirchhoff=kirchhoff)
        check_overflow((value, d_q, d_velocity), n_samples, arguments[1], arguments[2])
        n = self.n_joints
        m = 6 + n
        lead = (n_samples,) if batched else ()
        return RobotJacobians(
            value=value.reshape(*lead, m),
            d_q=d_q.reshape(*lead, m, n),
            d_velocity=d_velocity.reshape(*lead, m, m),
            added_mass_matrix=matrix.reshape(*lead, m, m),
        )

    def hydro_regressors(
        self,
        q: ArrayLike,
        qd: ArrayLike,
        qdd: ArrayLike,
        water: Water | None = None,
        base_motion: BaseMotion | None = None,
        current: ArrayLike = (0.0, 0.0, 0.0),
        current_acceleration: ArrayLike = (0.0, 0.0, 0.0),
        threads: int = 1,
        added_mass: str = "morison",
    ) -> RobotRegressors:
        """Regressors of the hydrodynamic forces (:class:`RobotRegressors`): a column per segment
        and normal direction (Cd and Cm), per segment for its axial drag, and per coefficient of
        each lumped model (:attr:`lumped_models`), on the joints and on the base. Arguments as
        for :meth:`hydro`."""
        kirchhoff = _kirchhoff(added_mass)
        threads = _threads(threads)
        arguments, batched, n_samples = self._evaluation(q, qd, qdd, None, None, water, base_motion, current, current_acceleration)
        states, (density, gravity), motion = arguments[:3], arguments[5:7], arguments[7:]
        out = self._core.regressors(*states, density, gravity, *motion, threads, kirchhoff=kirchhoff)
        check_overflow((out[4], out[5]), n_samples, arguments[1], arguments[2])
        n, s, m = self.n_joints, len(self._segments), len(self._lumped)
        lead = (n_samples,) if batched else ()
        drag, added = (a.reshape(*lead, 6 + n, 3 * s + 63 * m) for a in (out[4], out[5]))
        segments = [a[..., : 2 * s].reshape(*lead, 6 + n, s, 2) for a in (drag, added)]
        axial = drag[..., 2 * s : 3 * s]
        # A lumped coefficient's column is in one of the two tables and zero in the other.
        lumped = (drag[..., 3 * s :] + added[..., 3 * s :]).reshape(*lead, 6 + n, m, 63)
        return RobotRegressors(
            buoyancy=out[0].reshape(*lead, n),
            gravity=out[1].reshape(*lead, n),
            drag=segments[0][..., 6:, :, :],
            added_mass=segments[1][..., 6:, :, :],
            base_buoyancy=out[2].reshape(*lead, 6),
            base_gravity=out[3].reshape(*lead, 6),
            base_drag=segments[0][..., :6, :, :],
            base_added_mass=segments[1][..., :6, :, :],
            axial_drag=axial[..., 6:, :],
            base_axial_drag=axial[..., :6, :],
            lumped=lumped[..., 6:, :, :],
            base_lumped=lumped[..., :6, :, :],
        )

    def link_wrenches(
        self,
        q: ArrayLike,
        qd: ArrayLike,
        qdd: ArrayLike,
        cd: ArrayLike | None = None,
        cm: ArrayLike | None = None,
        water: Water | None = None,
        base_motion: BaseMotion | None = None,
        current: ArrayLike = (0.0, 0.0, 0.0),
        current_acceleration: ArrayLike = (0.0, 0.0, 0.0),
        threads: int = 1,
        added_mass: str = "morison",
    ) -> FloatArray:
        """The environment's wrench on every body, for coupling to a simulator.

        Arguments as for :meth:`hydro`. Returns ``(n_joints + 1, 6)`` (or ``(n_samples,
        n_joints + 1, 6)``): row 0 the base, row ``i + 1`` link ``i``; each the total force
        (drag, added mass, buoyancy with Froude-Krylov, and gravity) [N] and its moment about the
        body's centre of mass [N·m], in WORLD components.
        """
        threads = _threads(threads)
        arguments, batched, n_samples = self._evaluation(q, qd, qdd, cd, cm, water, base_motion, current, current_acceleration)
        wrenches = self._core.hydro(*arguments, threads, True, kirchhoff=_kirchhoff(added_mass))[8]
        check_overflow((wrenches,), n_samples, arguments[1], arguments[2])
        shape = (n_samples, self.n_joints + 1, 6) if batched else (self.n_joints + 1, 6)
        return wrenches.reshape(shape)

    def added_mass_matrix(self, q: ArrayLike, cm: ArrayLike | None = None, water: Water | None = None) -> FloatArray:
        """The added-mass matrix over base and joints, ``M_A = −∂(W_am, τ_am)/∂(ν̇, q̈)``
        (docs/model.md section 10, "What is computed").

        ``(6 + n_joints)²`` (or one per sample of ``q``), base first (linear, then angular, base
        frame), then the joints: symmetric, positive semi-definite, independent of the base's
        orientation and motion. A simulator adds it to the rigid-body mass matrix; the added-mass
        forces are then ``−M_A (ν̇, q̈)`` plus terms in the velocities. ``cm`` as for :meth:`hydro`.
        """
        water = self._the_water(water)
        n = self.n_joints
        array = _real_array(q, "q", "a rectangular array of real numbers")
        if array.ndim not in (1, 2) or array.shape[-1] != n:
            raise ValueError(f"q must have shape ({n},) or (n_samples, {n}), got {array.shape}")
        rows = np.ascontiguousarray(array.reshape(-1, n), dtype=np.float64)
        matrices = self._core.added_mass_matrix(rows, self._coefficients(cm, "cm"), water.density)
        check_overflow((matrices,), len(rows), np.zeros_like(rows), np.zeros_like(rows))
        size = 6 + n
        return matrices.reshape((len(rows), size, size) if array.ndim == 2 else (size, size))
