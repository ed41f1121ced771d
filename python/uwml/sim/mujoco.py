"""uwml's environment forces inside a MuJoCo simulation, with the added mass in the mass matrix
(docs/simulation.md, "Added mass in the mass matrix"; ``pip install "uwml[mujoco]"``).

:class:`Simulation` steps a MuJoCo model of a robot with the forces uwml computes for it: drag
and added mass along every segment, buoyancy with Froude-Krylov, joint losses at a depth and
temperature, in a current. MuJoCo's own fluid model is turned off (its lumped per-body model is
what uwml replaces), MuJoCo keeps everything else: the rigid bodies, gravity, contacts (a foot
on the seabed), joint limits, actuators.

**Added mass in the mass matrix.** The added-mass force is linear in the accelerations, so the
environment splits exactly into ``τ_env(q, q̇, q̈) = τ_env,0(q, q̇) − M_A(q) q̈``.
Each step evaluates ``τ_env,0`` (uwml at zero joint and base acceleration: drag, buoyancy,
Froude-Krylov and the velocity part of the added mass; the joint losses below) and ``M_A(q)``; ``M_A`` is added
to MuJoCo's joint-space inertia after its position stage (``mj_fwdPosition``), which is then
factored again (``mj_factorM``) and the constraints projected with it again
(``mj_projectConstraint``), so MuJoCo solves ``(M + M_A) q̈ = τ + τ_env,0`` with its
constraints: no acceleration is fed back from the last step, and a link lighter than the water
it drags along is as stable as any other. The rest is ``mj_forwardSkip`` from the velocity
stage. (Factoring twice costs less, for the robots of the benchmark, than calling the position
stage's functions one by one from Python.)
``scheme="lagged"`` instead applies ``−M_A q̈`` with the previous step's ``q̈`` as a force, as
gz-sim and UUV Simulator do: for comparison only (it diverges once ``M_A`` exceeds ``M``).

**Joint losses.** The seal's dry friction has a slope of ``S/ε`` at rest (about 2e4 N·m·s/rad
for the default seal at depth), which no explicit step of a light joint survives; the oil drag
is stiff too on a light wrist. So the losses are not forces here: each step sets every joint's
MuJoCo ``dof_frictionloss`` to the seal's dry-friction level at its speed,
``C(p) + (S(p) − C(p)) exp(−(ω/ω_s)²)`` (breakaway at rest, running friction in motion), which
MuJoCo solves as a friction constraint (stable at any step; it holds the joint at rest while the
load is below the level), and its ``dof_damping`` to the secant damping of the oil drag and the
seal's viscous term, ``−(τ_oil + D ω)/ω``, which MuJoCo's Euler integrator takes implicitly
(``LossState::dry_friction_split`` in the core; both added to the model's own values). The
friction is the hard sign's: the smooth sign's ``ε`` is a regularization for evaluation and
identification, not part of the simulated physics. MuJoCo's noslip solver is turned on (at least
``NOSLIP_ITERATIONS``, tolerance at most ``NOSLIP_TOLERANCE``) so that a held joint stays still
instead of creeping as soft constraints do. So ``data.qfrc_applied`` holds the hydrodynamics and
the motor torques, ``data.qfrc_constraint`` the seal's friction and ``data.qfrc_passive`` the
damping, while :meth:`Simulation.environment` returns uwml's whole environment, losses as forces,
for inspection. With ``mjDSBL_CONSTRAINT`` or ``mjDSBL_FRICTIONLOSS`` set, MuJoCo applies no
seal friction. ``integrator="rk4"`` takes the damping explicitly (each stage's forward pass):
for a stiff oil drag on light joints use Euler.

**Coordinates.** uwml's base twist is Fossen's ``ν`` (base frame); MuJoCo's free joint has the
world-frame velocity of the body origin and the body-frame angular velocity. With ``R`` the
base's orientation, ``ν = (Rᵀ v_world, ω_body)`` and ``ν̇ = (Rᵀ v̇_world − ω × v, ω̇)``: the
``−ω × v`` term is passed to uwml as the base's acceleration in ``τ_env,0``, ``M_A`` and the
forces are mapped to MuJoCo's degrees of freedom with the same ``Rᵀ``. Gravity is MuJoCo's
(``opt.gravity`` must be ``(0, 0, −g)`` with ``g`` the water's): uwml's gravity component is
not applied. ``opt.gravity`` is read each step and a change refused (the buoyancy is the
water's). Seal friction that MuJoCo's constraint memory cannot hold (it then drops every
constraint with a warning) is an error too. One thread at a time: a lock serializes steps.

**One native call per step.** The arithmetic between the position stage and ``mj_factorM`` (reading
the state from the data's arrays, the evaluation of ``τ_env,0`` and ``M_A``, the map, the writes
into ``data.M`` and ``data.qfrc_applied``) is done by ``uwml._core.MujocoCoupling``, which keeps
views of the data's arrays: a step costs MuJoCo's stages plus about one uwml evaluation and
``M_A`` (``benches/simulation.py``; docs/simulation.md).

**Integrators.** ``integrator="euler"``: MuJoCo's semi-implicit Euler (``mj_Euler``) after the
forward pass above, contacts included. ``"rk4"``: the classical Runge-Kutta method on that
forward pass (positions advanced with ``mj_integratePos``), for smooth motions without contacts,
where its order matters (the tests compare it with ``scipy.integrate.solve_ivp``): fourth order
for hinge and slide joints; a free joint's rotation, advanced with velocities averaged over the
stages as MuJoCo's own RK4 does, is second order.
"""

from __future__ import annotations

import copy
import threading
from collections.abc import Mapping, Sequence
from typing import Any, Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .. import _core
from .._checks import shown
from ..model.joint_losses import JointLosses
from ..model.parts import Water
from ..robot._arguments import _per_joint_losses
from ..robot.base_motion import BaseMotion, _trusted_motion
from ..robot.evaluation_conditions import Conditions
from ..robot.files import model_and_robot
from ..robot.tree import Robot
from ..sea.conditions import check_depths, check_temperatures
from ._dof_map import body_id, map_degrees_of_freedom, sparse_inertia_entries
from .mjcf import mjcf_of
from .prescribed import PrescribedJoints, Trajectory
from .thrust import SimulatedThrusters

__all__ = ["SCHEMES", "Simulation", "mjcf_of"]

FloatArray = NDArray[np.float64]

#: How the added mass enters the equations of motion.
SCHEMES = ("matrix", "lagged")
INTEGRATORS = ("euler", "rk4")
#: The fractions of a step at which the classical Runge-Kutta method evaluates.
_RK4_FRACTIONS = (0.0, 0.5, 0.5, 1.0)
#: MuJoCo's noslip solver with joint losses (at least these iterations, at most this tolerance):
#: a friction constraint then holds a joint at rest (to about 1e-8 rad/s) instead of creeping.
NOSLIP_ITERATIONS = 50
NOSLIP_TOLERANCE = 1e-10


def _mujoco() -> Any:
    try:
        import mujoco
    except ImportError:
        raise ImportError('uwml.sim.mujoco needs MuJoCo: pip install "uwml[mujoco]" (or pip install mujoco)') from None
    return mujoco


def _vector3(value: ArrayLike, name: str) -> FloatArray:
    try:
        array = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError):
        array = np.full(0, np.nan)
    if array.shape != (3,) or not np.all(np.isfinite(array)):
        raise ValueError(f"{name} must be 3 finite numbers [world frame], got {shown(value)}")
    return array


def _number(value: Any, name: str) -> float:
    """``value`` as one float (a number, or a 0-d array), or a ValueError naming ``name``."""
    if isinstance(value, (bool, np.bool_)) or value is None or np.ndim(value) != 0:
        raise ValueError(f"{name} must be one number, got {shown(value)}")
    try:
        return float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be one number, got {shown(value)}") from None


def _robot_and_water(model: Any, robot: Robot | None, hydro: Any, water: Water | None) -> tuple[Robot, Water]:
    """The simulation's robot (``robot``, default ``Robot.from_mujoco(model, hydro)``) and water
    (``water``, default the robot's), checked: ``model.opt.gravity`` must be ``(0, 0, −g)`` of the
    water, for uwml's buoyancy (:class:`Simulation`, :class:`uwml.sim.mjx.Simulation`)."""
    if robot is None:
        robot = Robot.from_mujoco(model, hydro)
    elif not isinstance(robot, Robot):
        raise TypeError(f"robot must be a uwml.Robot or None, got {type(robot).__name__}")
    chosen = robot.water if water is None else water
    if not isinstance(chosen, Water):
        raise TypeError(f"water must be a uwml.Water or None, got {type(water).__name__}")
    gravity = np.asarray(model.opt.gravity, dtype=np.float64)
    if not np.allclose(gravity, (0.0, 0.0, -chosen.gravity), rtol=1e-12, atol=0.0):
        raise ValueError(f"the model's gravity {gravity.tolist()} must be (0, 0, -{chosen.gravity:g}), the water's, for uwml's buoyancy")
    return robot, chosen


class Simulation:
    """A MuJoCo model stepped with uwml's environment forces (module docstring).

    Parameters
    ----------
    model : mujoco.MjModel
        The robot's MuJoCo model (copied: the caller's model is not changed). Its world holds
        exactly one root body, the robot's base (a free joint: a floating base), as for
        :func:`uwml.robot.files.from_mujoco`.
    robot : uwml.Robot, optional
        The same robot for uwml (default ``uwml.Robot.from_mujoco(model, hydro)``); its joints
        must be the model's hinge and slide joints in model order.
    hydro : path, optional
        A hydro file, when ``robot`` is taken from the model.
    depth, temperature_c
        Where the joint losses are evaluated [m, °C] (``Robot.environment``).
    losses
        Joint losses (``Robot.environment``'s ``losses``): None for the robot's own.
    current, current_acceleration
        The water's velocity [m/s] and acceleration [m/s²], world frame.
    water
        Density and gravity; default the robot's. ``model.opt.gravity`` must be ``(0, 0, −g)``.
    scheme : {"matrix", "lagged"}
        ``"matrix"``: ``M_A`` in the mass matrix (the default; exact and stable). ``"lagged"``:
        ``−M_A q̈_previous`` as a force, for comparison.
    integrator : {"euler", "rk4"}
        See the module docstring.
    added_mass : {"morison", "kirchhoff"}
        The added mass's velocity terms (``Robot.hydro``): the paper's Morison form, or
        Kirchhoff's, which conserves the energy ``T_rigid + T_A + V`` without drag and losses.

    Attributes
    ----------
    model, data
        The MuJoCo model (fluid model off) and data; set ``data.qpos``, ``data.qvel`` and
        ``data.ctrl`` as usual (in place: the simulation keeps views of this data's arrays, so
        both attributes are read-only).
    robot, water, depth, temperature_c, losses, current, current_acceleration, scheme, integrator, added_mass
        As given (read-only: each step uses what the simulation was made with; make a new
        :class:`Simulation` for other conditions).
    """

    def __init__(
        self,
        model: Any,
        robot: Robot | None = None,
        hydro: Any = None,
        *,
        depth: float = 0.0,
        temperature_c: float = 20.0,
        losses: JointLosses | Sequence[JointLosses | None] | None = None,
        current: ArrayLike = (0.0, 0.0, 0.0),
        current_acceleration: ArrayLike = (0.0, 0.0, 0.0),
        water: Water | None = None,
        scheme: str = "matrix",
        integrator: str = "euler",
        added_mass: Literal["morison", "kirchhoff"] = "morison",
    ) -> None:
        mujoco = _mujoco()
        if not isinstance(model, mujoco.MjModel):
            raise TypeError(f"model must be a mujoco.MjModel, got {type(model).__name__}")
        if scheme not in SCHEMES:
            raise ValueError(f"scheme must be one of {', '.join(SCHEMES)}, got {scheme!r}")
        if integrator not in INTEGRATORS:
            raise ValueError(f"integrator must be one of {', '.join(INTEGRATORS)}, got {integrator!r}")
        robot, self._water = _robot_and_water(model, robot, hydro, water)
        self._mj = mujoco
        #: Held by every step, forward pass and read of the state: one thread at a time (MuJoCo's
        #: functions release the GIL, and the native coupling keeps one step's arrays).
        self._lock = threading.Lock()
        self._model = copy.deepcopy(model)
        self._model.opt.density = 0.0  # MuJoCo's own fluid model off: uwml is the water
        self._model.opt.viscosity = 0.0
        self._data = mujoco.MjData(self._model)
        self._robot = robot
        self._depth, self._temperature_c = _number(depth, "depth"), _number(temperature_c, "temperature_c")
        check_depths(np.asarray(self._depth))
        check_temperatures(np.asarray(self._temperature_c))
        self._current = _vector3(current, "current")
        self._current_acceleration = _vector3(current_acceleration, "current_acceleration")
        if added_mass not in ("morison", "kirchhoff"):
            raise ValueError(f"added_mass must be one of morison, kirchhoff, got {added_mass!r}")
        self._scheme, self._integrator, self._added_mass = scheme, integrator, added_mass
        self._euler, self._lagged = integrator == "euler", scheme == "lagged"
        self._position_stage = mujoco.mjtStage.mjSTAGE_POS  # looked up once: a step's own cost is small
        # The joint losses (the robot's own unless given), read by the core once.
        self._losses = robot.losses if losses is None else losses
        self._joint_losses = _per_joint_losses(self._losses, robot.n_joints)
        #: The conditions of :meth:`environment` but the base's motion (the water column above
        #: is the robot's water, as in Robot.environment).
        self._conditions = Conditions(
            water=self._water, added_mass=added_mass, current=self._current, current_acceleration=self._current_acceleration,
            depth=self._depth, temperature_c=self._temperature_c, losses=self._losses,
        )  # fmt: skip
        if any(loss is not None and loss.seal is not None for loss in self._joint_losses):
            # The seal's friction is a MuJoCo friction constraint (module docstring): the noslip
            # solver removes the creep of soft constraints, so that a held joint stays at rest.
            opt = self._model.opt
            opt.noslip_iterations = max(int(opt.noslip_iterations), NOSLIP_ITERATIONS)
            opt.noslip_tolerance = min(float(opt.noslip_tolerance), NOSLIP_TOLERANCE)
        #: The friction constraints the seals need each step: fewer means MuJoCo dropped them.
        self._seal_rows = sum(loss is not None and loss.seal is not None for loss in self._joint_losses)
        dofs = map_degrees_of_freedom(mujoco, self.model, robot)
        self._root, self._free_dof, self._free_qpos = dofs.root, dofs.free_dof, dofs.free_qpos
        self._joint_dofs, self._joint_qpos = dofs.joint_dofs, dofs.joint_qpos
        self._base_is_world, self._floating = dofs.base_is_world, dofs.floating
        #: During a step with thrust: the pushed bodies' rows of ``xfrc_applied`` without it.
        self._under_thrust: FloatArray | None = None
        self._thrusters = SimulatedThrusters(mujoco, self._model, robot, None if self._base_is_world else self._root, self._joint_dofs)
        inertia_entries = sparse_inertia_entries(mujoco, self.model, self.data)
        # The per-step arithmetic, native: it keeps views of the data's arrays (module docstring).
        d = self.data
        self._coupling = _core.MujocoCoupling(
            robot._core, d.qpos, d.qvel, d.qacc, d.xquat, d.xmat, d.M, d.qfrc_applied,
            self.model.dof_damping, self.model.dof_frictionloss, self.model.opt.gravity,
            None if self._base_is_world else self._root, self._joint_qpos.tolist(), self._joint_dofs.tolist(),
            self._free_dof, inertia_entries, robot._native(self._conditions), scheme == "lagged",
        )  # fmt: skip
        mujoco.mj_forward(self.model, self.data)
        #: The joints on a prescribed motion (:meth:`prescribe`), if any.
        self._prescribed: PrescribedJoints | None = None
        try:  # a current so strong that the water's forces overflow is outside the physics
            self.environment()
        except ValueError as error:
            raise ValueError(f"the water's forces at the model's initial state are not finite numbers: {error}") from None

    # Read-only: the native coupling took them at construction, so that a change would be
    # honoured by environment() and not by step(). Make a new Simulation for other conditions.
    @property
    def robot(self) -> Robot:
        """The uwml robot."""
        return self._robot

    @property
    def water(self) -> Water:
        """The water's density and gravity."""
        return self._water

    @property
    def depth(self) -> float:
        """Where the joint losses are evaluated [m]."""
        return self._depth

    @property
    def temperature_c(self) -> float:
        """The joints' oil temperature [°C]."""
        return self._temperature_c

    @property
    def losses(self) -> tuple[JointLosses | None, ...]:
        """Each joint's losses (None: none), the robot's own unless given others."""
        return self._joint_losses

    @property
    def current(self) -> FloatArray:
        """The water's velocity [m/s], world frame (a copy)."""
        return self._current.copy()

    @property
    def current_acceleration(self) -> FloatArray:
        """The water's acceleration [m/s²], world frame (a copy)."""
        return self._current_acceleration.copy()

    @property
    def scheme(self) -> str:
        """How the added mass enters: ``"matrix"`` or ``"lagged"``."""
        return self._scheme

    @property
    def integrator(self) -> str:
        """``"euler"`` or ``"rk4"``."""
        return self._integrator

    @property
    def added_mass(self) -> str:
        """The added mass's velocity terms: ``"morison"`` or ``"kirchhoff"``."""
        return self._added_mass

    @property
    def model(self) -> Any:
        """The MuJoCo model stepped (a copy of the one given, its fluid model off)."""
        return self._model

    @property
    def data(self) -> Any:
        """The MuJoCo data stepped."""
        return self._data

    @classmethod
    def from_file(cls, path: Any, hydro: Any = None, *, floating: bool | None = None, **options: Any) -> Simulation:
        """The simulation of a URDF or MJCF file (with its hydro file), read as
        :func:`uwml.robot.files.model_and_robot` reads it: the description's own masses and
        inertias; visual geoms dropped (absent visual meshes do not matter), and a collision mesh
        dropped too where the hydro file describes its link's geometry (``volume`` or ``dry``)
        and the link's mass comes from its inertial (always in a URDF), so no mesh file is needed
        then (the link has no contacts). ``floating``: the root
        body on a free joint, a vehicle floating freely (None: the hydro file's ``[base]
        floating``, default false). ``options`` as for the constructor."""
        model, robot = model_and_robot(path, hydro, floating)
        return cls(model, robot, **options)

    # --- the base's motion in uwml's coordinates ----------------------------------------------

    def _base_motion(self) -> BaseMotion:
        zero = np.zeros(3)
        if self._base_is_world:
            return _trusted_motion(np.array([1.0, 0.0, 0.0, 0.0]), zero, zero, zero, zero)
        orientation = np.array(self.data.xquat[self._root])
        if not self._floating:
            return _trusted_motion(orientation, zero, zero, zero, zero)
        assert self._free_dof is not None
        rotation = self.data.xmat[self._root].reshape(3, 3)
        v = rotation.T @ self.data.qvel[self._free_dof : self._free_dof + 3]
        w = np.array(self.data.qvel[self._free_dof + 3 : self._free_dof + 6])
        # ν̇ = Rᵀ v̇_world − ω × v: the second term is what zero MuJoCo acceleration means to uwml.
        minus_w_cross_v = np.array([w[2] * v[1] - w[1] * v[2], w[0] * v[2] - w[2] * v[0], w[1] * v[0] - w[0] * v[1]])
        return _trusted_motion(orientation, v, w, minus_w_cross_v, zero)

    # --- one forward pass ------------------------------------------------------------------

    def environment(self) -> tuple[FloatArray, FloatArray]:
        """``(τ_env,0 without gravity, M_A)`` in uwml's coordinates at the data's state: the
        generalized forces (base wrench, then joints) at zero MuJoCo acceleration, and the
        added-mass matrix: :meth:`uwml.Robot.environment` and :meth:`uwml.Robot.added_mass_matrix`
        in the simulation's conditions.
        Waits for a step under way in another thread."""
        with self._lock:
            return self._environment()

    def _environment(self) -> tuple[FloatArray, FloatArray]:
        q = np.array(self.data.qpos[self._joint_qpos])
        qd = np.array(self.data.qvel[self._joint_dofs])
        motion = self._base_motion()
        result = self.robot.environment(q, qd, np.zeros_like(q), self._conditions._moved(motion), base=True)
        assert result.base is not None
        # ``total`` is drag + added mass + buoyancy (+ losses on the joints): no gravity.
        forces = np.concatenate([result.base.total, result.total])
        return forces, self.robot.added_mass_matrix(q, self._conditions)

    def forward(self, torque: ArrayLike | None = None, qfrc: ArrayLike | None = None) -> None:
        """MuJoCo's forward dynamics at the data's state with uwml's forces: fills
        ``data.qacc`` (and everything ``mj_forward`` fills). ``torque``: motor torques on the
        robot's joints [N·m or N], added to ``data.qfrc_applied``'s uwml part; ``qfrc``: any
        generalized forces in MuJoCo's coordinates (``(nv,)``, as ``qvel``), added too (thrusters
        on a free joint: the force in world components, the moment in the body's). A state that
        is no longer finite (a diverged simulation) raises ``FloatingPointError``; a
        ``model.opt.gravity`` changed since the simulation was made raises ``ValueError`` (uwml's
        buoyancy is the water's, for the gravity it was made with); constraint memory too small
        for the seals' friction raises :class:`uwml.UwmlError`. One thread at a time: calls from
        several threads wait for each other."""
        with self._lock:
            self._forward(torque, qfrc)

    def _forward(self, torque: ArrayLike | None, qfrc: ArrayLike | None) -> None:
        mj, m, d, coupling = self._mj, self._model, self._data, self._coupling
        coupling.write_joint_losses()  # the friction constraints take the levels (nothing without losses)
        mj.mj_fwdPosition(m, d)
        if self._under_thrust is not None:
            self._thrusters.push(d.xfrc_applied, d.xmat, self._under_thrust)
        if self._seal_rows and d.nefc < self._seal_rows:
            self._check_constraint_memory()
        status = coupling.apply(torque)
        if status == 2:  # a torque the native reader does not take as it is: convert, or refuse
            motor = np.asarray(torque, dtype=np.float64)
            if motor.shape != (self.robot.n_joints,) or not np.all(np.isfinite(motor)):
                raise ValueError(f"torque must be {self.robot.n_joints} finite numbers (one per joint), got {torque!r}")
            status = coupling.apply(np.ascontiguousarray(motor))
        if status == 1:
            raise FloatingPointError(f"the simulation diverged at t = {d.time:.6g} s: its state is no longer finite")
        if status == 3:
            raise ValueError(
                f"model.opt.gravity changed to {[float(g) for g in m.opt.gravity]} after the Simulation was made: uwml's buoyancy "
                f"is for the water's gravity (0, 0, -{self.water.gravity:g}); put it back, or make a new Simulation "
                "(with water=uwml.Water(density, gravity) for another gravity)"
            )
        if qfrc is not None:
            extra = np.asarray(qfrc, dtype=np.float64)
            if extra.shape != (m.nv,) or not np.all(np.isfinite(extra)):
                raise ValueError(f"qfrc must be {m.nv} finite numbers (one per degree of freedom), got shape {extra.shape}")
            d.qfrc_applied[:] += extra
        mj.mj_factorM(m, d)
        mj.mj_projectConstraint(m, d)
        mj.mj_forwardSkip(m, d, self._position_stage, 0)
        if self._prescribed is not None:
            # The prescribed joints' accelerations imposed by the torque that gives them, added to
            # the applied forces and the pass run again, so that every stage (constraints,
            # MuJoCo's implicit damping) sees it (sim/prescribed.py).
            self._prescribed.impose(mj, m, d)
            mj.mj_forwardSkip(m, d, self._position_stage, 0)

    def _check_constraint_memory(self) -> None:
        """Refuses a step whose seal friction MuJoCo dropped (its constraint memory full), unless
        the model's flags turned constraints or friction off (the module docstring)."""
        mj, m, d = self._mj, self._model, self._data
        off = int(mj.mjtDisableBit.mjDSBL_CONSTRAINT) | int(mj.mjtDisableBit.mjDSBL_FRICTIONLOSS)
        if int(m.opt.disableflags) & off:
            return
        from ..errors import UwmlError

        raise UwmlError(
            f"MuJoCo's constraint memory ({m.narena / 2**20:.3g} MiB) cannot hold the constraints at t = {d.time:.6g} s "
            f"({d.ncon} contacts, and the seal friction of {self._seal_rows} joints): MuJoCo dropped them all, the seal friction "
            'with them. Give the model more memory (MJCF <size memory="..."/>, say four times as much) or fewer contacts '
            "(contype/conaffinity of geoms that need not touch)"
        )

    def step(self, torque: ArrayLike | None = None, qfrc: ArrayLike | None = None, wrenches: Mapping[str, ArrayLike] | None = None) -> None:
        """One time step (``model.opt.timestep``) with motor ``torque`` on the joints and
        generalized forces ``qfrc`` (as :meth:`forward`), and ``wrenches`` on bodies by name
        (thrusters, a tether): each six numbers, a force [N] and a moment [N·m] in world
        components at the body's centre of mass (MuJoCo's ``data.xfrc_applied``), held for this
        step only: those bodies' rows of ``xfrc_applied`` are restored after it. Errors as
        :meth:`forward`'s; one thread at a time."""
        with self._lock:
            if wrenches is None and self._thrusters.idle:
                if self._prescribed is None:  # the common step: no motion to put the joints back on
                    self._integrate(torque, qfrc)
                else:
                    self._step(torque, qfrc)
                return
            self._step_with_wrenches(torque, qfrc, wrenches)

    def _step_with_wrenches(self, torque: ArrayLike | None, qfrc: ArrayLike | None, wrenches: Mapping[str, ArrayLike] | None) -> None:
        """A step with ``wrenches`` set on their bodies and the thrusters' added (module
        :mod:`uwml.sim.thrust`), every row touched restored after it."""
        d, thrusters = self.data, self._thrusters
        if wrenches is None:  # thrust alone: the thrusters' rows (a slice, usually)
            touched: slice | NDArray[np.int64] = thrusters.rows
            rows: dict[int, FloatArray] = {}
        else:
            rows = self._wrench_rows(wrenches)
            touched = np.array(sorted(set(rows) | ({*thrusters.bodies.tolist()} if not thrusters.idle else set())), dtype=np.int64)
        kept = d.xfrc_applied[touched].copy()
        try:
            for body, wrench in rows.items():
                d.xfrc_applied[body] = wrench
            if not thrusters.idle:  # added in each forward pass, at the pose of its position stage
                # Thrust alone: its rows as kept (the copy made above); else with the wrenches set.
                self._under_thrust = kept if not rows else d.xfrc_applied[thrusters.rows].copy()
            self._step(torque, qfrc)
        finally:
            self._under_thrust = None
            d.xfrc_applied[touched] = kept
        thrusters.advance(self._model.opt.timestep)

    def command_thrusters(self, command: ArrayLike) -> None:
        """Hold ``command`` (one number per thruster of ``robot.thrusters``, in its curve's
        units) from the next step on, as an ESC holds it: each thruster's thrust lags its
        steady value by its time constant (:mod:`uwml.sim.thrust`)."""
        with self._lock:
            self._thrusters.set_command(command)

    @property
    def thrust(self) -> FloatArray:
        """Each thruster's thrust [N] now (``robot.thrusters``' order)."""
        with self._lock:
            return self._thrusters.thrust

    def _wrench_rows(self, wrenches: Mapping[str, ArrayLike]) -> dict[int, FloatArray]:
        """``wrenches`` by body id, checked."""
        if not isinstance(wrenches, Mapping):
            raise TypeError(f"wrenches must map body names to 6 numbers, got {type(wrenches).__name__}")
        rows: dict[int, FloatArray] = {}
        m = self.model
        for name, value in wrenches.items():
            body = body_id(self._mj, m, name, "wrenches")
            wrench = np.asarray(value, dtype=np.float64)
            if wrench.shape != (6,) or not np.all(np.isfinite(wrench)):
                raise ValueError(f"wrenches[{name!r}] must be 6 finite numbers (force [N], moment [N·m], world components), got {value!r}")
            rows[body] = wrench
        return rows

    def prescribe(self, joints: Sequence[str | int], motion: Trajectory | None) -> None:
        """Make ``joints`` (names or indices of the robot's joints) follow ``motion`` (a
        :class:`uwml.sim.prescribed.Trajectory` of as many joints) exactly from now on, their
        accelerations imposed while the rest of the robot, the floating base above all,
        responds through ``M + M_A`` (docs/model.md section 12.4); ``None`` frees them again. The
        joints are set on the motion at the data's time at once, and after every step; the
        torque that imposed it is :attr:`prescribed_torque`."""
        if motion is None:
            with self._lock:
                self._prescribed = None
                self._coupling.prescribe([], [], np.zeros(0))
            return
        names = [joint.name for joint in self.robot.joints]
        with self._lock:
            prescribed = PrescribedJoints(joints, motion, names, self._joint_dofs, self._joint_qpos, self.model.nv, self._coupling)
            q, qd, _ = motion(float(self.data.time))  # refused here if the data's time is outside the motion
            self._prescribed = prescribed
            self.data.qpos[prescribed.qpos], self.data.qvel[prescribed.dofs] = q, qd

    @property
    def prescribed_torque(self) -> FloatArray:
        """The generalized force that imposed the prescribed joints' accelerations at the last
        forward pass, one per prescribed joint [N·m or N] (empty without a prescribed motion):
        what their motors deliver, beyond the other forces on those joints."""
        with self._lock:
            torque: FloatArray = self._coupling.prescribed_torque()
        return torque

    def _step(self, torque: ArrayLike | None, qfrc: ArrayLike | None) -> None:
        self._integrate(torque, qfrc)
        if self._prescribed is not None:
            # On the motion, exactly (the integration of imposed accelerations drifts by its error).
            self._prescribed.put_on_motion(float(self.data.time))

    def _integrate(self, torque: ArrayLike | None, qfrc: ArrayLike | None) -> None:
        mj, m, d = self._mj, self._model, self._data
        if self._euler:
            self._forward(torque, qfrc)
            if self._lagged:
                self._coupling.remember_acceleration()
            mj.mj_Euler(m, d)
            return
        # The classical Runge-Kutta method; the stages' velocities, accelerations and averages are
        # kept by the native coupling (the same operations as the numpy code they replace).
        h, time0, coupling = m.opt.timestep, d.time, self._coupling
        coupling.rk4_begin()
        for stage, fraction in enumerate(_RK4_FRACTIONS):
            offset = fraction * h
            # qpos back to the start, qvel the stage's; the previous stage's velocity.
            previous = coupling.rk4_stage(stage, offset)
            if previous is not None:
                mj.mj_integratePos(m, d.qpos, previous, offset)
            d.time = time0 + offset
            self._forward(torque, qfrc)
            coupling.rk4_keep(stage)
        mj.mj_integratePos(m, d.qpos, coupling.rk4_finish(h), h)
        d.time = time0 + h
