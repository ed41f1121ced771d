"""uwml's forces in MuJoCo MJX, the added mass in the mass matrix, for batches of environments
under ``jax.jit`` and ``jax.vmap`` (docs/batched.md, "Simulating with MJX"; ``pip install
"uwml[jax]"``).

:class:`Simulation` is the JAX counterpart of :class:`uwml.sim.mujoco.Simulation`: the same
robot, the same physics and the same step (docs/model.md section 11: MJX solves
``(M + M_A) q̈ = τ + τ_env,0`` with its constraints, ``M_A`` added after the composite-rigid-body
stage and before the factorization; joint losses as MJX friction constraints and implicit
damping; thrusters through their curves and lags; prescribed joint motion; floating bases and
currents: :mod:`uwml.sim.mjx_forward`), written as pure functions of a state pytree:

- :meth:`Simulation.reset` ``(params) -> State`` and :meth:`Simulation.step`
  ``(params, state, action) -> State`` for ONE environment; a batch is ``jax.vmap``'s, each
  environment with its own :class:`Parameters` (drag and added-mass coefficients, per segment or
  scaled, the lumped models' entries, the bodies' centres of buoyancy and volumes, the current, a
  payload, the depth and temperature of the joint losses, a prescribed motion), so domain
  randomization is a batch of parameters, and a gradient may be taken with respect to any of
  them (:mod:`uwml.sim.mjx_fit`). Any RL library that takes pure
  ``reset``/``step`` functions of JAX arrays can drive them.
- :class:`Action`: the thrusters' commands (in each curve's units, through the thrust curves)
  and motor torques on the joints; a flat array ``(n_thrusters + n_joints,)`` is read the same.
- :meth:`Simulation.rollout`: ``step`` under ``jax.lax.scan`` over a sequence of actions.

Contacts are off by default (open water; MJX refuses some collision pairs, which
``contacts=True`` reports). Euler steps only (the model's timestep). MJX has no noslip solver:
a seal's friction constraint is soft, so a joint held by it creeps slowly where the CPU
simulation's noslip keeps it still (docs/batched.md). Float64 needs
``jax.config.update("jax_enable_x64", True)`` before the simulation is made; it then agrees
with :class:`uwml.sim.mujoco.Simulation` to rounding (tests/test_mjx_agreement.py).
"""

from __future__ import annotations

import contextlib
import copy
import io
from collections.abc import Callable, Iterator, Sequence
from typing import Any, Literal, NamedTuple

import jax
import jax.numpy as jnp
import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..jax.compiled_robot import compile_robot
from ..model.joint_losses import JointLosses
from ..model.parts import Water
from ..robot._arguments import _per_joint_losses
from ..robot.evaluation_conditions import Conditions
from ..robot.files import model_and_robot
from ..robot.tree import Robot
from ..sea.conditions import check_depths, check_temperatures
from ._dof_map import body_id, map_degrees_of_freedom
from .mjx_forward import Inputs, Layout, robot_model_for, step_dynamics
from .mjx_inputs import MotionFunction, Spline, ThrusterArrays, evaluate, spline
from .mujoco import _robot_and_water
from .prescribed import Trajectory, joint_index

__all__ = ["Action", "Parameters", "Simulation", "Spline", "State", "benchmark_steps", "spline"]

Array = jax.Array
FloatArray = NDArray[np.float64]


def _modules() -> tuple[Any, Any]:
    """``mujoco`` and ``mujoco.mjx`` (MJX prints a note about its optional Warp backend when it
    is first imported; that note is kept out of the caller's output)."""
    try:
        import mujoco

        with contextlib.redirect_stdout(io.StringIO()):
            from mujoco import mjx
    except ImportError:
        raise ImportError('uwml.sim.mjx needs MuJoCo MJX: pip install "uwml[jax]" (or pip install mujoco-mjx)') from None
    return mujoco, mjx


class Parameters(NamedTuple):
    """One environment's parameters (:meth:`Simulation.parameters`); a batch has a leading axis
    on every field. Each a JAX or numpy array."""

    #: Each segment's drag and added-mass coefficients, ``(S, 2)`` (:attr:`uwml.Robot.segments`'
    #: order, per normal direction; a circular segment uses column 0).
    cd: Any
    cm: Any
    #: Multiplies every drag coefficient (the segments' ``cd`` and axial ``cd``, the lumped
    #: models' linear and quadratic damping) and every added-mass one (``cm``, the lumped ``M_A``).
    drag_scale: Any
    added_mass_scale: Any
    #: The water's velocity [m/s] and acceleration [m/s²], world frame, ``(3,)``.
    current: Any
    current_acceleration: Any
    #: Where the joint losses are evaluated [m, °C] (unchecked inside a step: keep them in their domains).
    depth: Any
    temperature_c: Any
    #: A mass [kg] at the centre of mass of the simulation's ``payload_body`` (no volume).
    payload: Any
    #: Each lumped model's ``M_A``, ``D_L`` ``(L, 6, 6)`` and quadratic damping ``d`` ``(L, 6)``
    #: (:attr:`uwml.Robot.lumped_models`' order, in each model's axes; the scales multiply them).
    lumped_added_mass: Any
    lumped_linear_damping: Any
    lumped_quadratic_damping: Any
    #: Each body's centre of buoyancy ``(B, 3)`` [m] in its frame and displaced volume ``(B,)``
    #: [m³]: the base (row 0; zeros without a base body), then link by link.
    cob: Any
    volume: Any
    #: The prescribed joints' motion from samples (None: none, or a motion function).
    motion: Spline | None


class Action(NamedTuple):
    """One step's inputs: each thruster's command ``(n_thrusters,)`` (robot.thrusters' order, in
    its curve's units), held for the step, and the motor torques on the joints ``(n_joints,)``
    [N·m or N]."""

    thrusters: Any
    torque: Any


class State(NamedTuple):
    """One environment's state: MJX's data (``data.qpos``, ``data.qvel``, ``data.time``, ...),
    each thruster's thrust [N] (it lags its command by the thruster's time constant), and the
    torque that imposed the prescribed joints' motion at the last step (empty without one)."""

    data: Any
    thrust: Any
    prescribed_torque: Any


def _vector3(value: ArrayLike, name: str) -> FloatArray:
    array = np.asarray(value, dtype=np.float64)
    if array.shape != (3,) or not np.all(np.isfinite(array)):
        raise ValueError(f"{name} must be 3 finite numbers [world frame], got {value!r}")
    return array


def _shaped(value: Any, shape: tuple[int, ...], name: str) -> Array:
    """``value`` as an array of ``shape``, or a ValueError naming it (shapes are static: under
    ``jit`` this is raised while tracing)."""
    array = jnp.asarray(value)
    if array.shape != shape:
        raise ValueError(f"{name} must have shape {shape}, got {array.shape}")
    return array


class Simulation:
    """A robot in MJX with uwml's forces (the module docstring): pure ``reset`` and ``step``
    functions of one environment, each with its own :class:`Parameters`. For float64, call
    ``jax.config.update("jax_enable_x64", True)`` before making it (the data's dtype is fixed
    then).

    Parameters
    ----------
    model : mujoco.MjModel
        The robot's MuJoCo model (copied), as for :class:`uwml.sim.mujoco.Simulation`: one root
        body, the base (a free joint: floating); ``opt.gravity`` ``(0, 0, −g)`` of the water.
    robot, hydro
        The same robot for uwml (default ``uwml.Robot.from_mujoco(model, hydro)``).
    depth, temperature_c, current, current_acceleration
        The default :class:`Parameters` (per environment in a batch).
    losses
        Joint losses (None: the robot's own), compiled in: which joints have them is structure.
    water
        Density and gravity; default the robot's.
    added_mass : {"morison", "kirchhoff"}
        The added mass's velocity terms.
    prescribed
        Joints (names or indices) that follow a motion exactly, their accelerations imposed.
    motion
        Their motion: a :class:`uwml.sim.prescribed.Trajectory` from samples or a
        :class:`Spline` (the default :attr:`Parameters.motion`, per environment in a batch), or
        a JAX function ``t -> (q, q̇, q̈)`` (the same for every environment).
    payload_body
        The MuJoCo body that carries :attr:`Parameters.payload` (default the base's).
    contacts
        Whether geoms collide (default False: open water; every geom's ``contype`` and
        ``conaffinity`` are cleared). MJX does not collide every pair of shapes: a model with one
        it cannot is refused (``ValueError``).
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
        added_mass: Literal["morison", "kirchhoff"] = "morison",
        prescribed: Sequence[str | int] = (),
        motion: Trajectory | Spline | MotionFunction | None = None,
        payload_body: str | None = None,
        contacts: bool = False,
    ) -> None:
        mujoco, mjx = _modules()
        if not isinstance(model, mujoco.MjModel):
            raise TypeError(f"model must be a mujoco.MjModel, got {type(model).__name__}")
        robot, self._water = _robot_and_water(model, robot, hydro, water)
        if added_mass not in ("morison", "kirchhoff"):
            raise ValueError(f"added_mass must be one of morison, kirchhoff, got {added_mass!r}")
        self._mj, self._mjx, self._robot = mujoco, mjx, robot
        m = copy.deepcopy(model)
        m.opt.density, m.opt.viscosity = 0.0, 0.0  # MuJoCo's fluid model off: uwml is the water
        m.opt.integrator = int(mujoco.mjtIntegrator.mjINT_EULER)
        m.opt.jacobian = int(mujoco.mjtJacobian.mjJAC_DENSE)  # M_A is added to MJX's dense M
        if not contacts:
            m.geom_contype[:], m.geom_conaffinity[:] = 0, 0
            m.opt.disableflags |= int(mujoco.mjtDisableBit.mjDSBL_CONTACT)
        dofs = map_degrees_of_freedom(mujoco, m, robot)
        depth_value, temperature = float(depth), float(temperature_c)
        check_depths(np.asarray(depth_value))
        check_temperatures(np.asarray(temperature))
        per_joint = _per_joint_losses(robot.losses if losses is None else losses, robot.n_joints)
        joint_dofs = dofs.joint_dofs
        own_damping, own_friction = m.dof_damping[joint_dofs].copy(), m.dof_frictionloss[joint_dofs].copy()
        sealed = np.array([loss is not None and loss.seal is not None for loss in per_joint], dtype=bool)
        # MJX decides which friction rows exist from the model it is given: a sealed joint gets one.
        m.dof_frictionloss[joint_dofs[sealed]] = np.where(own_friction[sealed] > 0.0, own_friction[sealed], 1.0)
        self._model = m
        try:
            mjx_model = mjx.put_model(m)
        except NotImplementedError as error:
            hint = " (contacts=True: give those geoms contype = conaffinity = 0, or simulate without contacts)" if contacts else ""
            raise ValueError(f"MJX cannot simulate this model: {error}{hint}") from None
        m.dof_frictionloss[joint_dofs] = own_friction  # each step adds the seals' levels to the model's own
        self._mjx_model = mjx_model.replace(dof_frictionloss=jnp.asarray(m.dof_frictionloss))
        body = dofs.root if payload_body is None else body_id(mujoco, m, payload_body, "payload_body")
        joint_names = [joint.name for joint in robot.joints]
        chosen = [joint_index(joint, joint_names) for joint in prescribed]
        if len(set(chosen)) != len(chosen):
            raise ValueError(f"prescribed must name each joint once, got {list(prescribed)!r}")
        self._layout = Layout(
            root=dofs.root, base_is_world=dofs.base_is_world, free_dof=dofs.free_dof, free_qpos=dofs.free_qpos,
            joint_dofs=joint_dofs, joint_qpos=dofs.joint_qpos,
            prescribed_dofs=joint_dofs[chosen], prescribed_qpos=dofs.joint_qpos[chosen],
            own_damping=own_damping, own_frictionloss=own_friction,
            losses=any(loss is not None for loss in per_joint), payload_body=body,
        )  # fmt: skip
        self._motion_function: MotionFunction | None = None
        default_motion = self._motion(motion, len(chosen))
        self._thrusters = ThrusterArrays(mujoco, m, robot, None if dofs.base_is_world else dofs.root, joint_dofs)
        conditions = Conditions(water=self._water, added_mass=added_mass, losses=losses)
        self._robot_model = compile_robot(robot, conditions)
        self._timestep = float(m.opt.timestep)
        self._data = mjx.make_data(self._mjx_model)
        self._jitted_reset = jax.jit(self._reset)
        self._jitted_step = jax.jit(self._step)
        lumped = self._robot_model.lumped
        self._defaults = Parameters(
            cd=np.asarray(self._robot_model.segments.cd), cm=np.asarray(self._robot_model.segments.cm),
            drag_scale=np.array(1.0), added_mass_scale=np.array(1.0),
            current=_vector3(current, "current"), current_acceleration=_vector3(current_acceleration, "current_acceleration"),
            depth=np.array(depth_value), temperature_c=np.array(temperature), payload=np.array(0.0),
            lumped_added_mass=np.asarray(lumped.added_mass), lumped_linear_damping=np.asarray(lumped.linear_damping),
            lumped_quadratic_damping=np.asarray(lumped.quadratic_damping),
            cob=np.asarray(self._robot_model.bodies.cob), volume=np.asarray(self._robot_model.bodies.volume), motion=default_motion,
        )  # fmt: skip

    @classmethod
    def from_file(cls, path: Any, hydro: Any = None, *, floating: bool | None = None, **options: Any) -> Simulation:
        """The simulation of a URDF or MJCF file with its hydro file, read as
        :meth:`uwml.sim.mujoco.Simulation.from_file` reads it; ``options`` as for the constructor."""
        model, robot = model_and_robot(path, hydro, floating)
        return cls(model, robot, **options)

    def _motion(self, motion: Any, joints: int) -> Spline | None:
        """The default motion from ``motion`` (a motion function is kept as structure)."""
        if motion is None:
            return None
        if not joints:
            raise ValueError("a motion was given without prescribed joints: name them (prescribed=...)")
        if isinstance(motion, Trajectory):
            motion = Spline.of(motion)
        if isinstance(motion, Spline):
            if motion.joints != joints:
                raise ValueError(f"the motion is of {motion.joints} joints, {joints} are prescribed")
            return motion
        if callable(motion):
            self._motion_function = motion
            return None
        raise TypeError(f"motion must be a uwml.sim.prescribed.Trajectory, a Spline or a JAX function of time, got {type(motion).__name__}")

    # --- what the simulation is -------------------------------------------------------------

    @property
    def robot(self) -> Robot:
        """The uwml robot."""
        return self._robot

    @property
    def water(self) -> Water:
        """The water's density and gravity."""
        return self._water

    @property
    def model(self) -> Any:
        """The MuJoCo model simulated (a copy of the one given: fluid model off, dense Jacobians,
        Euler, contacts as asked)."""
        return self._model

    @property
    def mjx_model(self) -> Any:
        """The MJX model."""
        return self._mjx_model

    @property
    def timestep(self) -> float:
        """The step [s] (the model's)."""
        return self._timestep

    @property
    def n_thrusters(self) -> int:
        """The robot's thrusters (an action's commands)."""
        return len(self._thrusters)

    @property
    def n_joints(self) -> int:
        """The robot's joints (an action's torques)."""
        return self._robot.n_joints

    @property
    def action_size(self) -> int:
        """The length of a flat action: the thrusters' commands, then the joints' torques."""
        return self.n_thrusters + self.n_joints

    # --- parameters, reset, step ---------------------------------------------------------------

    def parameters(self, batch: int | None = None, **changes: Any) -> Parameters:
        """The default :class:`Parameters` (the constructor's), with ``changes`` by field name;
        with ``batch``, every field with a leading axis of that many environments (a change
        given for one environment is repeated, one given per environment kept). Shapes are
        checked (``ValueError``)."""
        unknown = set(changes) - set(Parameters._fields)
        if unknown:
            raise TypeError(f"no parameter {', '.join(sorted(unknown))} (the parameters: {', '.join(Parameters._fields)})")
        if batch is not None and (isinstance(batch, bool) or not isinstance(batch, int) or batch < 1):
            raise ValueError(f"batch must be a positive integer, got {batch!r}")
        fields = self._defaults._asdict()
        if changes.get("motion") is not None and not isinstance(changes["motion"], Spline):
            changes["motion"] = self._motion(changes["motion"], len(self._layout.prescribed_dofs))
        out: dict[str, Any] = {}
        for name, default in fields.items():
            value = changes.get(name, default)
            if name == "motion":
                out[name] = self._check_motion(value, batch)
                continue
            shape = np.shape(default)
            array = np.asarray(value, dtype=np.float64) if not isinstance(value, jax.Array) else value
            batched = batch is not None and array.shape == (batch, *shape)
            if array.shape != shape and not batched:
                expected = f"{shape} or {(batch, *shape)}" if batch is not None else f"{shape}"
                raise ValueError(f"parameter {name} must have shape {expected}, got {array.shape}")
            out[name] = array if batch is None or batched else np.broadcast_to(array, (batch, *shape)).copy()
        return Parameters(**out)

    def _check_motion(self, motion: Spline | None, batch: int | None) -> Spline | None:
        if motion is None:
            return None
        if not isinstance(motion, Spline):
            raise TypeError(f"motion must be a Spline, got {type(motion).__name__}")
        knots = np.shape(motion.knots)
        if len(knots) == 2:  # a batch of motions
            if batch is None or knots[0] != batch:
                raise ValueError(f"a batch of {knots[0]} motions for {batch} environments")
            return motion
        if batch is None:
            return motion
        return Spline(*(np.broadcast_to(np.asarray(f), (batch, *np.shape(f))).copy() for f in motion))

    def reset(self, params: Parameters, qpos: ArrayLike | None = None, qvel: ArrayLike | None = None) -> State:
        """One environment's state at time 0: ``qpos`` (default the model's ``qpos0``) and
        ``qvel`` (default zero), the prescribed joints on their motion, the thrust that of zero
        commands, the bodies' poses computed (``data.xpos``, ``data.xquat``). Pure and jitted
        (compiled on its first call): vmap it over a batch of parameters (and states)."""
        state: State = self._jitted_reset(params, qpos, qvel)
        return state

    def _reset(self, params: Parameters, qpos: ArrayLike | None, qvel: ArrayLike | None) -> State:
        d, m, layout = self._data, self._mjx_model, self._layout
        dtype = d.qpos.dtype
        positions = jnp.asarray(m.qpos0, dtype) if qpos is None else _shaped(qpos, (m.nq,), "qpos").astype(dtype)
        velocities = jnp.zeros(m.nv, dtype) if qvel is None else _shaped(qvel, (m.nv,), "qvel").astype(dtype)
        d = d.replace(qpos=positions, qvel=velocities, time=jnp.zeros((), dtype))
        if len(layout.prescribed_dofs):
            q, qd, _ = self._prescribed_motion(params, d.time, dtype)
            d = d.replace(qpos=d.qpos.at[layout.prescribed_qpos].set(q), qvel=d.qvel.at[layout.prescribed_dofs].set(qd))
        d = self._mjx.kinematics(m, d)
        thrust = self._thrusters.steady(jnp.zeros(self.n_thrusters, dtype))
        return State(d, thrust, jnp.zeros(len(layout.prescribed_dofs), dtype))

    def _prescribed_motion(self, params: Parameters, t: Array, dtype: Any) -> tuple[Array, Array, Array]:
        if self._motion_function is not None:
            values = self._motion_function(t)
        elif params.motion is not None:
            values = evaluate(Spline(*(jnp.asarray(f, dtype) for f in params.motion)), t)
        else:
            raise ValueError("the prescribed joints have no motion: give one (motion=... here or in the parameters)")
        k = len(self._layout.prescribed_dofs)
        q, qd, qdd = (
            _shaped(v, (k,), f"the prescribed motion's {n}").astype(dtype) for v, n in zip(values, ("q", "qd", "qdd"), strict=True)
        )
        return q, qd, qdd

    def _action(self, action: Any, dtype: Any) -> tuple[Array, Array]:
        n, joints = self.n_thrusters, self.n_joints
        if isinstance(action, Action):
            commands = _shaped(action.thrusters, (n,), "action.thrusters")
            torque = _shaped(action.torque, (joints,), "action.torque")
        else:
            flat = _shaped(action, (n + joints,), f"a flat action ({n} thruster commands, then {joints} torques)")
            commands, torque = flat[:n], flat[n:]
        return commands.astype(dtype), torque.astype(dtype)

    def step(self, params: Parameters, state: State, action: Action | ArrayLike) -> State:
        """One Euler step of one environment (:mod:`uwml.sim.mjx_forward`): pure and jitted
        (compiled on its first call for each kind of argument), for ``jit``, ``vmap`` and
        ``lax.scan``. ``action``: an :class:`Action` or a flat array. Bad shapes raise
        ``ValueError`` (while tracing)."""
        after: State = self._jitted_step(params, state, action)
        return after

    def _step(self, params: Parameters, state: State, action: Action | ArrayLike) -> State:
        d, layout = state.data, self._layout
        dtype = d.qpos.dtype
        p = self._cast(params, dtype)
        commands, torque = self._action(action, dtype)
        _shaped(state.thrust, (self.n_thrusters,), "state.thrust")
        lumped = (p.lumped_added_mass, p.lumped_linear_damping, p.lumped_quadratic_damping)
        robot = robot_model_for(self._robot_model, p.cd, p.cm, p.drag_scale, p.added_mass_scale, lumped, (p.cob, p.volume))
        steady = self._thrusters.steady(commands)
        acting = self._thrusters.acting(state.thrust.astype(dtype), steady)
        inputs = Inputs(robot, p.current, p.current_acceleration, p.depth, p.temperature_c, p.payload, torque, acting)
        target = None
        if len(layout.prescribed_dofs):
            target = self._prescribed_motion(params, d.time, dtype)[2]
        d, imposed = step_dynamics(self._mjx, self._mjx_model, d, layout, inputs, self._thrusters, target)
        if len(layout.prescribed_dofs):  # on the motion, exactly (integrated accelerations drift)
            q, qd, _ = self._prescribed_motion(params, d.time, dtype)
            d = d.replace(qpos=d.qpos.at[layout.prescribed_qpos].set(q), qvel=d.qvel.at[layout.prescribed_dofs].set(qd))
        thrust = self._thrusters.advance(acting, steady, jnp.asarray(self._timestep, dtype))
        return State(d, thrust, imposed)

    def _cast(self, params: Parameters, dtype: Any) -> Parameters:
        if not isinstance(params, Parameters):
            raise TypeError(f"params must be a uwml.sim.mjx.Parameters, got {type(params).__name__}")
        fields = {}
        for name, default in self._defaults._asdict().items():
            if name != "motion":
                fields[name] = _shaped(getattr(params, name), np.shape(default), f"parameter {name}").astype(dtype)
        return Parameters(**fields, motion=params.motion)

    def rollout(self, params: Parameters, state: State, actions: Any, observe: Callable[[State], Any] | None = None) -> tuple[State, Any]:
        """:meth:`step` over ``actions`` (an :class:`Action` or flat actions with a leading time
        axis) under ``jax.lax.scan``: the last state and ``observe(state)`` after each step
        stacked (default ``(qpos, qvel)``)."""
        look = observe if observe is not None else (lambda s: (s.data.qpos, s.data.qvel))

        def one(carry: State, action: Any) -> tuple[State, Any]:
            after = self.step(params, carry, action)
            return after, look(after)

        return jax.lax.scan(one, state, actions)

    # --- reading a state ------------------------------------------------------------------------

    def joint_state(self, state: State) -> tuple[Array, Array]:
        """The robot's joint angles and speeds ``(q, q̇)``, each ``(n_joints,)`` (any batch axes
        leading)."""
        layout = self._layout
        return state.data.qpos[..., layout.joint_qpos], state.data.qvel[..., layout.joint_dofs]

    def base_pose(self, state: State) -> tuple[Array, Array]:
        """The base's position [m] and orientation (a quaternion ``w, x, y, z``) in the world,
        from the state's ``qpos`` on a floating base (else the root body's pose at the last
        position stage)."""
        layout = self._layout
        if layout.free_qpos is None:
            return state.data.xpos[..., layout.root, :], state.data.xquat[..., layout.root, :]
        at = layout.free_qpos
        return state.data.qpos[..., at : at + 3], state.data.qpos[..., at + 3 : at + 7]


def benchmark_steps(sizes: Sequence[int], repeats: int = 5) -> Iterator[tuple[str, int, float, float]]:
    """Steps a second of the BlueROV2 example with its arm at each batch size of ``sizes``, bare
    MJX against uwml's step: ``(what, environments, compile seconds, steps per second)`` rows
    (:func:`uwml.sim.mjx_bench.benchmark_steps`; ``benches/accelerated.py --mjx``)."""
    from .mjx_bench import benchmark_steps as run

    return run(sizes, repeats)
