"""A whole robot in moving water: a kinematic tree on a moving base, in a current (docs/model.md section 10).

:class:`Robot` takes :class:`uwml.Joint` (with ``parent`` and ``kind``), :class:`uwml.Link`
(any number of ``segments``, rectangular or circular) and an optional base body, and gives the
environment's generalized force on every joint *and* the wrench on the base, computed by the
Rust core. :class:`BaseMotion` says how the base moves; the current is a world-frame velocity.
"""

from __future__ import annotations

import operator
import os
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any, SupportsIndex

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .. import _core
from .._checks import real_array as _real_array
from ..io import descriptions, modelfile
from ..model.joint_losses import JointLosses, pack_leg_losses
from ..model.lumped import LumpedModel
from ..model.parts import FRESH_WATER, Joint, Link, Segment, Water
from ..model.thrusters import Thruster
from ..plausibility import check_efforts, check_states, joint_bounds
from ._arguments import _per_joint_losses, _threads, _water, kept_shortcut, robot_parts, same_shortcuts
from .evaluation_conditions import Conditions
from .results import Jacobians, Regressors, Torques
from .workspace import Workspace

if TYPE_CHECKING:
    from typing_extensions import Unpack

    from .evaluation_conditions import ConditionFields

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

    Examples
    --------
    A 2-joint arm of cylinders on an ROV that pitches and surges in a current:

    >>> import uwml
    >>> from scipy.spatial.transform import Rotation
    >>> arm = uwml.Robot(
    ...     joints=[uwml.Joint((0.5, 0, -0.3), (0, 0, 1)), uwml.Joint((0, 0, -0.4), (0, 1, 0))],
    ...     links=[uwml.Link(4.0, (0, 0, -0.2), 0.002, segments=[uwml.Segment((0, 0, 0), (0, 0, -1), 0.4, section="circular", diameter=0.08)]),
    ...            uwml.Link(3.0, (0.25, 0, 0), 0.0015, segments=[uwml.Segment((0, 0, 0), (1, 0, 0), 0.5, section="circular", diameter=0.06)])],
    ... )
    >>> motion = uwml.BaseMotion(orientation=Rotation.from_euler("y", 0.1), velocity=(0.5, 0, 0))
    >>> result = arm.hydro([0.3, -0.5], [0.2, 0.1], [0, 0], base_motion=motion, current=(0.2, 0, 0))
    >>> result.total.shape, result.base.total.shape   # joint torques; base force and moment
    ((2,), (6,))
    """

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
        #: The thrusters (body: -1 the base, else the link; thruster), base first: the allocation's columns.
        self._thrusters = tuple((b - 1, t) for b, body in enumerate((base_body, *links)) for t in body.thrusters)
        self._losses = _per_joint_losses(losses, len(self._joints))
        # The joints' own losses as an evaluation takes them: one object when they all share one.
        first = self._losses[0] if self._losses else None
        self._own_losses = first if all(item is first for item in self._losses) else self._losses
        self._water = FRESH_WATER if water is None else _water(water)
        #: The conditions of an evaluation given none (the robot's own water and losses).
        self._default_conditions = Conditions()
        #: The last keyword shortcuts of an evaluation (the conditions they replaced, a copy of
        #: them) and the conditions they made: a controller passing the same keywords every
        #: call has its conditions checked and read by the core once.
        self._last_shortcuts: tuple[Conditions | None, dict[str, Any], Conditions] | None = None

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
        regressors' order (:attr:`uwml.Regressors.lumped`)."""
        return self._lumped

    @property
    def thrusters(self) -> tuple[tuple[int, Thruster], ...]:
        """Every thruster with its body (-1 the base, else the link), base first: the order of
        :meth:`thruster_allocation`'s columns and of a simulation's commands."""
        return self._thrusters

    def thruster_allocation(self, q: ArrayLike | None = None) -> FloatArray:
        """The allocation matrix ``B`` ``(6, n_thrusters)`` (docs/model.md section 13.1): column
        ``k`` is the wrench on the base, force and moment about the base origin in base
        components, of thruster ``k`` (:attr:`thrusters`) pushing with 1 N, so that ``W = B T``.
        A thruster on the base gives ``(d, r × d)``; one on a link, the same of its position and
        direction carried into the base frame at the joint positions ``q`` ``(n_joints,)``, which
        such a thruster needs."""
        joints = None
        if any(body >= 0 for body, _ in self._thrusters):
            if q is None:
                raise ValueError("a thruster sits on a link: give the joint positions q (n_joints,) to place it")
            joints = _real_array(q, "q", "joint positions")
            if joints.shape != (self.n_joints,) or not np.all(np.isfinite(joints)):
                raise ValueError(f"q must be {self.n_joints} finite joint positions, got shape {joints.shape}")
        columns = np.zeros((6, len(self._thrusters)))
        for k, (body, thruster) in enumerate(self._thrusters):
            r, d = np.asarray(thruster.position), np.asarray(thruster.direction)
            if joints is not None and body >= 0:
                # Two points of the rigid link carried into the base frame: the direction is
                # their difference (the map is affine).
                start = self.forward_kinematics(joints, body, r)
                r, d = start, self.forward_kinematics(joints, body, r + d) - start
            columns[:3, k] = d
            columns[3:, k] = np.cross(r, d)
        return columns

    @property
    def n_joints(self) -> int:
        """Number of joints (and links)."""
        return len(self._joints)

    def __repr__(self) -> str:
        return f"Robot(n_joints={self.n_joints}, n_segments={len(self._segments)}, base={'body' if self._base is not None else None})"

    # --- evaluation: (q, qd, qdd, conditions) ------------------------------------------------

    def _conditions(self, conditions: Conditions | None, shortcuts: ConditionFields) -> Conditions:
        """The conditions of an evaluation: ``conditions`` (None: the defaults) with the fields
        ``shortcuts`` replaced (the same as the last call's: the same conditions)."""
        if conditions is not None and not isinstance(conditions, Conditions):
            raise TypeError(
                f"conditions must be a uwml.Conditions or None, got {type(conditions).__name__} "
                "(give cd=, cm=, water=, base_motion=, current=, ... as keywords)"
            )
        if not shortcuts:
            return self._default_conditions if conditions is None else conditions
        last = self._last_shortcuts
        if last is not None and last[0] is conditions and same_shortcuts(last[1], shortcuts):
            return last[2]
        made = Conditions(**shortcuts) if conditions is None else conditions.replace(**shortcuts)
        self._last_shortcuts = (conditions, {name: kept_shortcut(value) for name, value in shortcuts.items()}, made)
        return made

    def _native(self, conditions: Conditions) -> _core.Conditions:
        """``conditions`` as the core reads them for this robot (its own water and losses where
        they give none), made once and kept on them."""
        return self._kept(conditions)[1]

    def _kept(self, conditions: Conditions) -> tuple[_core.Robot, _core.Conditions, bool]:
        """What is kept on ``conditions`` for this robot: the robot's native object, the
        conditions as the core reads them (:meth:`_native`), and whether an evaluation gives the
        base wrench unless told (the robot has a base body, or the conditions move its base)."""
        kept: tuple[_core.Robot, _core.Conditions, bool] | None = conditions.__dict__.get("_native")
        if kept is not None and kept[0] is self._core:
            return kept
        water = self._water if conditions.water is None else conditions.water
        losses = self._own_losses if conditions.losses is None else conditions.losses
        native = _core.Conditions(self._core, conditions, water, pack_leg_losses(losses, self.n_joints))
        kept = (self._core, native, self._base is not None or conditions.base_motion is not None)
        object.__setattr__(conditions, "_native", kept)
        return kept

    def _states(self, q: ArrayLike, qd: ArrayLike, qdd: ArrayLike) -> tuple[FloatArray, FloatArray, FloatArray]:
        """The joint states checked, as C-contiguous float64 arrays ``(n_joints,)`` or
        ``(n_samples, n_joints)``, with a warning for states beyond the joints' plausible bounds
        (:mod:`uwml.plausibility`)."""
        n = self.n_joints
        arrays = []
        for name, value in (("q", q), ("qd", qd), ("qdd", qdd)):
            array = _real_array(value, name, "a rectangular array of real numbers")
            if array.ndim not in (1, 2) or array.shape[-1] != n:
                raise ValueError(f"{name} must have shape ({n},) or (n_samples, {n}), got {array.shape}")
            arrays.append(np.require(array, np.float64, ("C_CONTIGUOUS", "ALIGNED")))
        for name, array in zip(("qd", "qdd"), arrays[1:]):
            if array.shape != arrays[0].shape:
                raise ValueError(f"{name} must have the same shape as q {arrays[0].shape}, got {array.shape}")
        check_states(arrays[0], arrays[1], self._bounds, stacklevel=5)
        return arrays[0], arrays[1], arrays[2]

    def _forces(
        self,
        losses: bool,
        states: tuple[ArrayLike, ArrayLike, ArrayLike],
        conditions: Conditions | None,
        shortcuts: ConditionFields,
        threads: int,
        base: bool | None,
        workspace: Workspace | None,
        tried: bool = False,
    ) -> Torques:
        """:meth:`hydro` (``losses`` False) or :meth:`environment`: one native call for one
        plain state (lists, tuples or 1-D float64 arrays within the joints' bounds), else the
        states checked here first; the same evaluation either way, into ``workspace`` if given.
        ``tried``: the native call on the states as given was made already (it declined them)."""
        if workspace is not None:
            workspace._check(self._core)
        _, native, with_base = self._kept(self._conditions(conditions, shortcuts))
        if type(threads) is not int or threads < 1:
            threads = _threads(threads)
        with_base = with_base if base is None else bool(base)
        evaluate = self._core.environment if losses else self._core.hydro
        result: Torques | None = None if tried else evaluate(*states, native, threads, with_base)
        if result is None:
            result = evaluate(*self._states(*states), native, threads, with_base, True)
            assert result is not None
            check_efforts([result.drag, result.added_mass, result.buoyancy, result.visc, result.seal], self._bounds)
        return result if workspace is None else workspace._store(result)

    def hydro(
        self,
        q: ArrayLike,
        qd: ArrayLike,
        qdd: ArrayLike,
        conditions: Conditions | None = None,
        *,
        threads: int = 1,
        base: bool | None = None,
        workspace: Workspace | None = None,
        **shortcuts: Unpack[ConditionFields],
    ) -> Torques:
        """Drag, added mass, buoyancy (with Froude-Krylov) and gravity on every joint and on the
        base, each apart: ``total`` is the water's (drag, added mass and buoyancy), without the
        weight (``gravity``); the base's buoyancy is the gross ``ρ V g``, not net of the weight.

        Parameters
        ----------
        q, qd, qdd
            Joint positions, velocities, accelerations [rad or m]: ``(n_joints,)`` or
            ``(n_samples, n_joints)``, the same shape for all three.
        conditions
            The water, coefficients, added-mass form, base motion and current
            (:class:`uwml.Conditions`); None: the defaults (the robot's own water and the
            segments' own coefficients, a fixed base in still water).
        threads
            Threads to split a batch over (≥ 1).
        base
            Whether to evaluate the wrench on the base (``result.base``, a
            :class:`uwml.BaseWrench`; None where not evaluated). Default: where the robot has a
            base body or the conditions move its base.
        workspace
            A :class:`uwml.Workspace` of this robot (:meth:`workspace`) for one state: the
            forces are written into it and its result returned, the same object every call (no
            result objects made per call; copy what is to be kept).
        **shortcuts
            Fields of :class:`uwml.Conditions` (``cd=``, ``water=``, ``base_motion=``,
            ``current=``, ...): they replace those of ``conditions``.

        Notes
        -----
        Any input with a sample axis gives results with one; the others are broadcast. One state
        (lists, tuples or 1-D float64 arrays) is read and evaluated in one native call, with the
        same checks and the same bits as that state's row of a batch; made once and passed to
        every call, ``conditions`` are read by the core once.
        """
        # A Conditions kept for this robot, given alone (a controller's loop): one native call,
        # which takes one plain state (anything else: `_forces`).
        kept = conditions.__dict__.get("_native") if type(conditions) is Conditions and not shortcuts else None
        if kept is not None and kept[0] is self._core and type(threads) is int and threads == 1:
            with_base = kept[2] if base is None else bool(base)
            if workspace is None:
                result: Torques | None = self._core.hydro(q, qd, qdd, kept[1], 1, with_base)
                if result is not None:
                    return result
            elif workspace._core is self._core and self._core.evaluate_into(q, qd, qdd, kept[1], with_base, False, workspace._values):
                return workspace._with_base if with_base else workspace._without_base
            return self._forces(False, (q, qd, qdd), conditions, shortcuts, threads, base, workspace, tried=True)
        return self._forces(False, (q, qd, qdd), conditions, shortcuts, threads, base, workspace)

    def environment(
        self,
        q: ArrayLike,
        qd: ArrayLike,
        qdd: ArrayLike,
        conditions: Conditions | None = None,
        *,
        threads: int = 1,
        base: bool | None = None,
        workspace: Workspace | None = None,
        **shortcuts: Unpack[ConditionFields],
    ) -> Torques:
        """Hydrodynamics (as :meth:`hydro`) and the joint losses at depth, in one call: the
        result's ``visc``, ``seal`` and ``current`` (docs/losses.md), at the conditions'
        ``depth``, ``temperature_c`` and ``losses`` (the robot's own, :attr:`losses`, unless
        they give others; the pressure ``sea_density · g · depth``, ``sea_density`` the water's
        unless given, so that one water is used for both). Arguments as for :meth:`hydro`."""
        # As in `hydro`.
        kept = conditions.__dict__.get("_native") if type(conditions) is Conditions and not shortcuts else None
        if kept is not None and kept[0] is self._core and type(threads) is int and threads == 1:
            with_base = kept[2] if base is None else bool(base)
            if workspace is None:
                result: Torques | None = self._core.environment(q, qd, qdd, kept[1], 1, with_base)
                if result is not None:
                    return result
            elif workspace._core is self._core and self._core.evaluate_into(q, qd, qdd, kept[1], with_base, True, workspace._values):
                return workspace._with_base if with_base else workspace._without_base
            return self._forces(True, (q, qd, qdd), conditions, shortcuts, threads, base, workspace, tried=True)
        return self._forces(True, (q, qd, qdd), conditions, shortcuts, threads, base, workspace)

    def workspace(self) -> Workspace:
        """A reusable result for one state of this robot (:class:`uwml.Workspace`), given as
        ``workspace=`` to :meth:`hydro` or :meth:`environment`: each call writes its forces into
        it and returns its result, as Pinocchio's ``Data``; what a controller stepping one state
        at a time uses (docs/performance.md, "One state per call from Python")."""
        return Workspace(self)

    def jacobians(
        self,
        q: ArrayLike,
        qd: ArrayLike,
        qdd: ArrayLike,
        conditions: Conditions | None = None,
        **shortcuts: Unpack[ConditionFields],
    ) -> Jacobians:
        """The forces of :meth:`environment` on base and joints and their derivatives
        (:class:`uwml.Jacobians`): exact (forward-mode dual numbers through the same Rust code,
        not finite differences); at a joint speed of exactly zero with a hard sign
        (``epsilon=0``) the losses jump and their slope is not meaningful. The joint-space block
        (a fixed base) is ``[..., 6:, 6:]`` of the matrices. Arguments as for :meth:`hydro`."""
        native = self._native(self._conditions(conditions, shortcuts))
        result: Jacobians = self._core.jacobians(*self._states(q, qd, qdd), native)
        return result

    def hydro_regressors(
        self,
        q: ArrayLike,
        qd: ArrayLike,
        qdd: ArrayLike,
        conditions: Conditions | None = None,
        *,
        threads: int = 1,
        **shortcuts: Unpack[ConditionFields],
    ) -> Regressors:
        """Regressors of the hydrodynamic forces (:class:`uwml.Regressors`): a column per segment
        and normal direction (Cd and Cm), per segment for its axial drag, and per coefficient of
        each lumped model (:attr:`lumped_models`), on the joints and on the base. Arguments as
        for :meth:`hydro` (the conditions' coefficients are not used)."""
        native = self._native(self._conditions(conditions, shortcuts))
        result: Regressors = self._core.regressors(*self._states(q, qd, qdd), native, threads=_threads(threads))
        return result

    def link_wrenches(
        self,
        q: ArrayLike,
        qd: ArrayLike,
        qdd: ArrayLike,
        conditions: Conditions | None = None,
        *,
        threads: int = 1,
        **shortcuts: Unpack[ConditionFields],
    ) -> FloatArray:
        """The environment's wrench on every body, for coupling to a simulator.

        Arguments as for :meth:`hydro`. Returns ``(n_joints + 1, 6)`` (or ``(n_samples,
        n_joints + 1, 6)``): row 0 the base, row ``i + 1`` link ``i``; each the total force
        (drag, added mass, buoyancy with Froude-Krylov, and gravity) [N] and its moment about the
        body's centre of mass [N·m], in WORLD components.
        """
        native = self._native(self._conditions(conditions, shortcuts))
        wrenches: FloatArray = self._core.link_wrenches(*self._states(q, qd, qdd), native, threads=_threads(threads))
        return wrenches

    def added_mass_matrix(self, q: ArrayLike, conditions: Conditions | None = None, **shortcuts: Unpack[ConditionFields]) -> FloatArray:
        """The added-mass matrix over base and joints, ``M_A = −∂(W_am, τ_am)/∂(ν̇, q̈)``
        (docs/model.md section 10, "What is computed").

        ``(6 + n_joints)²`` (or one per sample of ``q``), base first (linear, then angular, base
        frame), then the joints: symmetric, positive semi-definite, independent of the base's
        orientation and motion. A simulator adds it to the rigid-body mass matrix; the added-mass
        forces are then ``−M_A (ν̇, q̈)`` plus terms in the velocities. Of the conditions, the
        water's density and ``cm`` are used.
        """
        n = self.n_joints
        array = _real_array(q, "q", "a rectangular array of real numbers")
        if array.ndim not in (1, 2) or array.shape[-1] != n:
            raise ValueError(f"q must have shape ({n},) or (n_samples, {n}), got {array.shape}")
        native = self._native(self._conditions(conditions, shortcuts))
        matrices: FloatArray = self._core.added_mass_matrix(np.require(array, np.float64, ("C_CONTIGUOUS", "ALIGNED")), native)
        return matrices

    # --- kinematics --------------------------------------------------------------------------

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
            raise ValueError(f"link must be in -{n}..{n - 1} (this robot has {n} links), got {index}")
        return index % n

    def point_jacobian(self, q: ArrayLike, link: int = -1, point: ArrayLike | None = None) -> tuple[FloatArray, FloatArray]:
        """Position and geometric Jacobian of a point on a link, in the base frame (a fixed,
        upright base: the world frame).

        The batch is evaluated in one call into Rust (``uwml_core::forward_kinematics`` and
        ``point_jacobian``), with the GIL released.

        Parameters
        ----------
        q
            Joint positions [rad or m], shape ``(..., n_joints)`` (any number of leading axes).
        link
            The link carrying the point, ``0 .. n_joints - 1``; negative counts from the end
            (default ``-1``, the last link).
        point
            The point in the link's frame [m], shape ``(3,)``. ``None`` (default): the far end
            of the link's first segment, ``start + length * axis``, if the link has one, else
            the link frame's origin (its joint). For :func:`uwml.paper_leg`, link ``-1``'s is
            the foot.

        Returns
        -------
        positions, jacobians
            Shapes ``(..., 3)`` and ``(..., 6, n_joints)``. Column ``j`` of a Jacobian maps
            ``qd[j]`` to the point's velocity (rows 0-2: ``z_j × (p − o_j)`` for a revolute
            joint, ``z_j`` for a prismatic one) and to the link's angular velocity (rows 3-5:
            ``z_j``, or zero); joints that do not carry the link have zero columns.
        """
        index = self._link_index(link)
        if point is None:
            segments = self._links[index].segments
            local = np.zeros(3) if not segments else np.array(segments[0].start) + segments[0].length * np.array(segments[0].axis)
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
        """Position of a point on a link in the base frame, shape ``q.shape[:-1] + (3,)``.

        Arguments as for :meth:`point_jacobian`: by default the far end of the last link's
        segment (the paper leg's foot, ``L2 u2 + L3 u3`` of docs/model.md section 2).
        """
        return self.point_jacobian(q, link, point)[0]
