"""A free-floating vehicle's hull and trim from pool trials by gradients through MJX
(:func:`vehicle_by_gradients`; docs/batched.md, "A fit by gradients through MJX"; docs/model.md
section 13, "13.3 Identifying a vehicle").

The fit of :func:`uwml.sim.free_floating.vehicle_from_trials`, with the replays in
:mod:`uwml.sim.mjx` and an exact Jacobian: the same trials, read and cleaned the same way (the
joints' smoothing fit, the start window's pose and twist), the same parameters by name
(:data:`uwml.fit.vehicle_parameters.VEHICLE_PARAMETERS`: ``linear_damping[3]``, ``cob_z``, ...)
and bounds, each training trial's start offsets fitted with them by default, the same residuals
(simulated minus measured roll and pitch at every sample but the first, each trial's over its
``sigma``), the same bounded least squares (:func:`uwml.fit.output_error.output_error`) and the
same result (:class:`uwml.fit.output_error.VehicleFit`, lmfit-style statistics, standard errors
``s² (JᵀJ)⁻¹`` at the optimum). Where the CPU fit replays each trial once more per parameter for
a forward difference, here the replays' derivatives with respect to the parameters and the start
offsets are carried through every MJX step in forward mode (``jax.jacfwd``: the added mass in
the mass matrix, the prescribed arm's imposing torque, the constraint solver's iterations).

A replay in MJX (:func:`replay_simulation`: the vehicle floating, every joint prescribed,
contacts off, float64): the joints on the cubics of the trial's smoothing fit, the vehicle from
the window's pose and twist (turned by the start offsets' roll and pitch about its own x and y
axes, the offsets' twist added), thrusters idle, steps of the simulation's timestep on the grid
from the first sample; the simulated roll and pitch interpolated linearly at the samples. The
CPU replay shortens its last step to end on the last sample; here the grid runs on past it, so
the two agree to rounding where a trial spans a whole number of steps and differ slightly on the
last interval elsewhere. A trial with thruster commands is refused (the fit is of a vehicle with
its thrusters off). Every trial, held-out ones included, is padded to the longest (its motion
held after its end), so that a fit compiles once for its parameters' names and its trials'
padded length (about 25 s on a CPU for the BlueROV2 example), kept for the simulation's next fit
with the same names and length.
"""

from __future__ import annotations

import copy
import math
import os
import warnings
import weakref
from collections.abc import Callable, Mapping, Sequence
from typing import Any, NamedTuple

import jax
import jax.numpy as jnp
import numpy as np

from ..errors import UwmlError
from ..fit._types import Array
from ..fit.output_error import START_STATE, VehicleFit, output_error, split_parameters
from ..fit.vehicle_parameters import _lumped, check_parameters
from ..plausibility import PlausibilityWarning
from .free_floating import _check_floats, _Problem, _read_trial, _sigmas, _start, _Trial, _trial_entries, _vehicle
from .mjx import Parameters, Simulation, Spline
from .prescribed import Trajectory
from .replay_inputs import MAX_GAP_S, SMOOTHING_S, START_WINDOW_S, joint_motion

__all__ = ["JACOBIAN", "replay_simulation", "vehicle_by_gradients"]

#: :attr:`uwml.fit.output_error.VehicleFit.jacobian` of a fit by gradients through MJX.
JACOBIAN = "forward-mode derivatives through uwml.sim.mjx (jax.jacfwd): exact"
#: A padded motion's knots after its last sample, this far apart [s].
PAD_S = 1.0


class _Padded(NamedTuple):
    """A trial of a fit, padded to the longest: the joints' motion (its times from the trial's
    first sample; None without joints), the start position and quaternion (w first) of the
    vehicle, its start twist (MuJoCo's free joint), the measured roll and pitch ``(S, 2)`` and,
    for each sample, the grid point before it and the fraction of the step to it."""

    motion: Spline | None
    position: Any
    quaternion: Any
    twist: Any
    measured: Any
    index: Any
    weight: Any


def replay_simulation(description: Any, hydro: Any = None, *, timestep: float | None = None, **options: Any) -> Simulation:
    """The :class:`uwml.sim.mjx.Simulation` :func:`vehicle_by_gradients` replays trials on: the
    vehicle of ``description`` (a URDF or MJCF path with its ``hydro`` file, or a
    ``(mujoco.MjModel, uwml.Robot)`` pair) floating, every joint prescribed (its motion each
    trial's), contacts off, steps of ``timestep`` [s] (None: the description's; at most
    ``MAX_TIMESTEP_S``); ``options`` as for the simulation (``current``, ``depth``, ...). Make it
    once and give it to every fit: its compilations are kept with it. Needs float64
    (``jax.config.update("jax_enable_x64", True)`` first)."""
    if jax.dtypes.canonicalize_dtype(np.float64) != np.float64:
        raise ValueError('a fit by gradients replays in float64: call jax.config.update("jax_enable_x64", True) first')
    model, robot, label = _vehicle(description, hydro, timestep)
    model = copy.deepcopy(model)  # the caller's is left as it is
    if timestep is not None:
        model.opt.timestep = float(timestep)
    sim = Simulation(model, robot, prescribed=list(range(robot.n_joints)), **options)
    _check_floats(label, sim._layout.free_dof)
    return sim


def _check_simulation(sim: Simulation) -> None:
    layout = sim._layout
    if layout.free_dof is None or len(layout.prescribed_dofs) != sim.n_joints:
        raise ValueError("the simulation must float with every joint prescribed: make it with uwml.sim.mjx_fit.replay_simulation")
    if sim._data.qpos.dtype != np.float64:
        raise ValueError('the simulation is float32: call jax.config.update("jax_enable_x64", True) before making it')
    base = sim.robot.base
    if base is None or base.lumped is None or not sim.robot.lumped_models or sim.robot.lumped_models[0][0] != -1:
        raise ValueError("the simulation's base has no lumped model (the hull): nothing to fit")


def _with_parameters(params: Parameters, names: Sequence[str], x: Any) -> Parameters:
    """``params`` with the hull's parameters ``names`` at ``x`` (as
    :func:`uwml.fit.vehicle_parameters.with_parameters` puts them in the hull: the base's lumped
    model is the first, the base body row 0), differentiably."""
    added, linear, quadratic = (
        jnp.asarray(f) for f in (params.lumped_added_mass, params.lumped_linear_damping, params.lumped_quadratic_damping)
    )
    cob, volume = jnp.asarray(params.cob), jnp.asarray(params.volume)
    for k, name in enumerate(names):
        lumped = _lumped(name)
        if lumped is None:
            if name == "volume":
                volume = volume.at[0].set(x[k])
            else:
                cob = cob.at[0, "xyz".index(name[-1])].add(x[k])
            continue
        family, i = lumped
        if family == "quadratic_damping":
            quadratic = quadratic.at[0, i].set(x[k])
        elif family == "added_mass":
            added = added.at[0, i, i].set(x[k])
        else:
            linear = linear.at[0, i, i].set(x[k])
    return params._replace(
        lumped_added_mass=added, lumped_linear_damping=linear, lumped_quadratic_damping=quadratic, cob=cob, volume=volume
    )


def _turned(quaternion: Any, roll: Any, pitch: Any) -> Any:
    """``quaternion`` (w first) turned by the rotation vector ``(roll, pitch, 0)`` in its own
    frame (scipy's ``q * from_rotvec``), with finite derivatives at no turn."""
    square = roll * roll + pitch * pitch
    turning = square > 0.0
    angle = jnp.sqrt(jnp.where(turning, square, 1.0))
    scale = jnp.where(turning, jnp.sin(angle / 2) / angle, 0.5 - square / 48.0)
    w, v = jnp.where(turning, jnp.cos(angle / 2), 1.0 - square / 8.0), scale * jnp.stack([roll, pitch, jnp.zeros_like(roll)])
    q0, q = quaternion[0], quaternion[1:]
    return jnp.concatenate([jnp.array([q0 * w - q @ v]), q0 * v + w * q + jnp.cross(q, v)])


def _roll_pitch(quaternion: Any) -> Any:
    """Roll and pitch [rad] (z-y-x Euler angles) of quaternions ``(n, 4)``, w first."""
    w, x, y, z = quaternion.T
    roll = jnp.arctan2(2.0 * (w * x + y * z), 1.0 - 2.0 * (x * x + y * y))
    pitch = jnp.arcsin(jnp.clip(2.0 * (w * y - z * x), -1.0, 1.0))
    return jnp.stack([roll, pitch], axis=1)


def _replays(sim: Simulation, names: tuple[str, ...]) -> Callable[..., tuple[Any, Any]]:
    """The jitted replay of one trial (padded) and its Jacobian: ``(z, trial, steps) ->
    (angles (S, 2), ∂angles/∂z (S, 2, p + 8))``, ``z`` ``(p + 8,)`` the parameters and the
    trial's start offsets (:data:`uwml.fit.output_error.START_STATE`). One trial a call: a
    ``jax.vmap`` over trials would take about twice as long to compile (its batching of the
    scan's derivatives), for little gain on a CPU."""
    defaults = sim.parameters()
    layout = sim._layout
    free, dof, qpos0, count = layout.free_qpos, layout.free_dof, np.asarray(sim.model.qpos0, dtype=np.float64), len(names)
    assert free is not None and dof is not None

    def angles(z: Any, trial: _Padded, steps: int) -> Any:
        params = _with_parameters(defaults, names, z[:count])._replace(motion=trial.motion)
        offset = z[count:]
        start = _turned(trial.quaternion, offset[0], offset[1])
        qpos = jnp.asarray(qpos0).at[free : free + 3].set(trial.position).at[free + 3 : free + 7].set(start)
        qvel = jnp.zeros(sim.model.nv).at[dof : dof + 6].set(trial.twist + offset[2:])
        _, poses = sim.rollout(params, sim.reset(params, qpos, qvel), jnp.zeros((steps, sim.action_size)), lambda s: sim.base_pose(s)[1])
        euler = _roll_pitch(jnp.concatenate([start[None], poses]))
        w = trial.weight[:, None]
        simulated = (1.0 - w) * euler[trial.index] + w * euler[trial.index + 1]
        return trial.measured + jnp.mod(simulated - trial.measured + jnp.pi, 2.0 * jnp.pi) - jnp.pi

    def twice(z: Any, trial: _Padded, steps: int) -> tuple[Any, Any]:
        values = angles(z, trial, steps)
        return values, values  # the derivatives of the first, the second the values themselves

    def with_jacobian(z: Any, trial: _Padded, steps: int) -> tuple[Any, Any]:
        jacobian, values = jax.jacfwd(twice, has_aux=True)(z, trial, steps)
        return values, jacobian

    return jax.jit(with_jacobian, static_argnums=2)


#: Each simulation's compiled replays, by the names of the parameters fitted.
_COMPILED: weakref.WeakKeyDictionary[Simulation, dict[tuple[str, ...], Callable[..., tuple[Any, Any]]]] = weakref.WeakKeyDictionary()


def _compiled(sim: Simulation, names: tuple[str, ...]) -> Callable[..., tuple[Any, Any]]:
    kept = _COMPILED.setdefault(sim, {})
    if names not in kept:
        kept[names] = _replays(sim, names)
    return kept[names]


def _motion(trial: _Trial, sim: Simulation, smoothing: float, t0: float, knots: int) -> Spline:
    """The trial's joint motion as the CPU replay makes it (its cubics), its times from ``t0``,
    padded to ``knots`` knots by holding its last angles."""
    streams = trial.streams
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", PlausibilityWarning)  # warned of once, when the trial was read
        motion = joint_motion(streams.joints, sim.robot.joints, smoothing, streams.first_row)
    spline = Spline.of(Trajectory(motion.time, motion.q, motion.qd, motion.qdd))
    own = np.asarray(spline.knots) - t0
    extra = knots - own.size
    c = np.asarray(spline.q)[:, -1, :]
    dt = own[-1] - own[-2]
    end = ((c[0] * dt + c[1]) * dt + c[2]) * dt + c[3]
    held = np.zeros((4, extra, c.shape[-1]))
    held[3] = end
    none = np.zeros_like(held)
    return Spline(
        np.concatenate([own, own[-1] + PAD_S * np.arange(1, extra + 1)]),
        np.concatenate([spline.q, held], axis=1),
        np.concatenate([spline.qd, none], axis=1),
        np.concatenate([spline.qdd, none], axis=1),
    )


def _padded(trials: Sequence[_Trial], sim: Simulation, smoothing: float) -> tuple[list[_Padded], int]:
    """Every trial padded to the longest (:class:`_Padded`), and the steps of the longest
    replay."""
    h = sim.timestep
    starts = [float(t.streams.joints.time[0]) for t in trials]
    steps = max(max(1, math.ceil((float(t.time[-1]) - t0) / h - 1e-6)) for t, t0 in zip(trials, starts, strict=True))
    samples = max(t.time.size for t in trials)
    knots = max(t.streams.joints.time.size for t in trials) + 1
    out = []
    for t, t0 in zip(trials, starts, strict=True):
        if t.streams.thrusters is not None:
            raise UwmlError(
                f"{t.streams.thruster_source}: the trial has thruster commands; a fit by gradients through MJX replays the "
                "vehicle with its thrusters off (fit it with uwml.sim.free_floating.vehicle_from_trials)"
            )
        assert t.streams.pose is not None
        pad = samples - t.time.size
        at = (t.time - t0) / h
        index = np.clip(np.floor(at).astype(np.int64), 0, steps - 1)
        padded = _Padded(
            motion=_motion(t, sim, smoothing, t0, knots) if sim.n_joints else None,
            position=t.streams.pose[0][0], quaternion=t.streams.pose[1][0], twist=t.start.twist,
            measured=np.concatenate([t.measured, np.zeros((pad, 2))]),
            index=np.concatenate([index, np.zeros(pad, dtype=np.int64)]), weight=np.concatenate([at - index, np.zeros(pad)]),
        )  # fmt: skip
        out.append(jax.tree_util.tree_map(jnp.asarray, padded))
    return out, steps


def vehicle_by_gradients(
    trials: Any,
    description: Any,
    hydro: Any = None,
    *,
    parameters: Sequence[str],
    bounds: Mapping[str, tuple[float, float]] | None = None,
    start: Mapping[str, float] | None = None,
    test: Any = (),
    fit_start: bool = True,
    sigma: Any = None,
    scale_covar: bool = True,
    start_window: float = START_WINDOW_S,
    smoothing: float = SMOOTHING_S,
    max_gap: float = MAX_GAP_S,
    timestep: float | None = None,
    columns: Any = None,
    max_nfev: int | None = None,
    **options: Any,
) -> VehicleFit:
    """Fit the hull's ``parameters`` to free-floating trials by output error, the replays in MJX
    and the Jacobian exact (module docstring).

    ``description``: a :class:`uwml.sim.mjx.Simulation` made by :func:`replay_simulation` (it
    keeps its compilations from fit to fit; then ``hydro``, ``timestep`` and ``options`` are its
    own), or what :func:`replay_simulation` takes, with ``hydro``, ``timestep`` and ``options``.
    Everything else as for :func:`uwml.sim.free_floating.vehicle_from_trials`: ``trials`` and
    ``test`` (held out), ``parameters`` by name, ``bounds``, ``start``, ``fit_start``, ``sigma``,
    ``scale_covar``, ``start_window``, ``smoothing``, ``max_gap``, ``columns``, ``max_nfev``.
    Returns its :class:`uwml.fit.output_error.VehicleFit` (``integrator`` ``"euler (MJX)"``,
    ``jacobian`` :data:`JACOBIAN`).

    Raises
    ------
    ValueError
        As :func:`uwml.sim.free_floating.vehicle_from_trials` does; without float64; a
        simulation that does not float with every joint prescribed.
    UwmlError
        A trial that a replay refuses, or with thruster commands; a replay that is no longer
        finite (naming the parameters).
    """
    names = check_parameters(parameters)
    if isinstance(description, Simulation):
        if hydro is not None or timestep is not None or options:
            raise ValueError("hydro, timestep and simulation options are the simulation's own when it is given")
        sim, label = description, "the simulation's description"
    else:
        sim = replay_simulation(description, hydro, timestep=timestep, **options)
        label = "the description" if isinstance(description, tuple) else os.fspath(description)
    _check_simulation(sim)
    base = sim.robot.base
    assert base is not None
    described, begin, lower, upper = _start(base, names, start, bounds)
    settings = {"max_gap": max_gap, "columns": columns, "smoothing": smoothing, "start_window": start_window}
    fitted = [_read_trial(entry, sim.robot, label, settings) for entry in _trial_entries(trials, "trials")]
    held = [_read_trial(entry, sim.robot, label, settings) for entry in _trial_entries(test, "test")]
    problem = _Problem(fitted, held, names, fit_start)
    sigma_points, given = _sigmas(sigma, fitted)
    x0, lower, upper, _ = problem.extended(begin, lower, upper)
    padded, steps = _padded(fitted + held, sim, smoothing)
    replays = _compiled(sim, tuple(names))
    p, count, offsets = len(names), len(fitted), len(START_STATE)
    kept: dict[bytes, tuple[Array, Array]] = {}

    def replayed(x: Array) -> tuple[Array, Array]:
        """Every trial's angles ``(T, S, 2)`` and their derivatives at the parameters ``x``."""
        key = x.tobytes()
        if key not in kept:
            z = np.zeros((len(fitted) + len(held), p + offsets))
            z[:, :p] = x[:p]
            for k in range(count):
                z[k, p:] = problem.offset(x, k)
            answers = [replays(jnp.asarray(z[k]), trial, steps) for k, trial in enumerate(padded)]
            values, jacobian = (np.stack([np.asarray(a[i], dtype=np.float64) for a in answers]) for i in range(2))
            if not np.all(np.isfinite(values)):
                chosen = ", ".join(f"{name} = {value:.6g}" for name, value in zip(names, x, strict=True))
                raise UwmlError(f"a replay in MJX is no longer finite (replayed with {chosen}: narrow the bounds?)")
            kept.clear()  # a Jacobian is asked for where the residual was last evaluated
            kept[key] = values, jacobian
        return kept[key]

    def evaluate(points: Sequence[Array]) -> list[Array]:
        return [np.concatenate([replayed(x)[0][k, : t.time.size].ravel() for k, t in enumerate(fitted)]) for x in points]

    def jacobian(x: Array) -> Array:
        derivatives = replayed(x)[1]
        out = np.zeros((problem.data.size, len(problem.all_names)))
        row = 0
        for k, t in enumerate(fitted):
            block = derivatives[k, : t.time.size].reshape(2 * t.time.size, p + offsets)
            out[row : row + block.shape[0], :p] = block[:, :p]
            if fit_start:
                out[row : row + block.shape[0], p + offsets * k : p + offsets * (k + 1)] = block[:, p:]
            row += block.shape[0]
        return out

    scales = np.ones(len(problem.all_names))  # unused: the Jacobian is exact
    state, first, best = output_error(
        evaluate, problem.data, sigma_points, problem.all_names, x0, lower, upper, scales, sigma_given=given,
        scale_covar=scale_covar, max_nfev=max_nfev, jacobian=jacobian,
    )  # fmt: skip
    state, found = split_parameters(state, p)
    x = np.concatenate([[state["params"][name] for name in names], np.zeros(x0.size - p)])
    at_start, at_optimum = replayed(x0)[0], replayed(x)[0]
    pairs = [(at_start[count + k, : t.time.size].ravel(), at_optimum[count + k, : t.time.size].ravel()) for k, t in enumerate(held)]
    trial_rms = problem.trial_rms(first, best, found, pairs)
    how = {"timestep": sim.timestep, "integrator": "euler (MJX)", "diff_step": 0.0, "jacobian": JACOBIAN}
    return problem.result(state, trial_rms, lower[:p], upper[:p], described, base, **how)
