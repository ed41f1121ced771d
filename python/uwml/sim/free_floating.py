"""A free-floating vehicle's hull and trim from pool trials, by output error with the replay in the
loop (:func:`vehicle_from_trials`, ``uwml fit vehicle``; docs/model.md section 13, "13.3
Identifying a vehicle"; docs/identification.md, "A vehicle from free-floating trials").

A trial is a log of the vehicle floating with its thrusters off while its arm moves: the joints
``q1 …`` and the vehicle's measured pose (``x, y, z`` and ``qw … qz`` or ``roll, pitch, yaw``),
in one file or in several streams, read as ``uwml replay`` reads them
(:mod:`uwml.sim.replay_inputs`). For parameters ``θ`` (names of
:data:`uwml.fit.vehicle_parameters.VEHICLE_PARAMETERS`: the hull's diagonal damping and added
mass, its centre of buoyancy's offset, its volume) put into the hull, each trial is replayed
(:mod:`uwml.sim.replay`): the joints follow the log exactly (docs/model.md section 12.4), the
vehicle responds, starting from a state estimated over the trial's first ``start_window``
seconds: the value and slope at the first sample of a cubic fitted to the window's poses (the
slope is the replay's start twist; the value replaces the first pose sample, so that the
measurement's noise on one sample does not set the whole replay's start). The residuals are the
simulated minus the measured roll and pitch at every sample but the first (where the replay
starts on the measurement), each trial's divided by its ``sigma``; they are fitted by
:func:`uwml.fit.output_error.output_error` (bounded least squares, a forward-difference Jacobian
whose columns are replays, standard errors from it at the optimum).

Trials held out (``test``) are replayed with the described and the fitted parameters: their RMS
says whether the fit carries over. With ``on_ray``, the replays of each batch (a residual: every
training trial; a Jacobian: every trial at every moved parameter) are shared out among Ray
actors, each holding the description and the trials (docs/scale.md); else they run one after
the other in this process. Still water unless ``options`` say otherwise (``current``, ...).
"""

from __future__ import annotations

import os
import warnings
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from ..errors import UwmlError
from ..fit._types import Array
from ..fit.inverse_dynamics import load_description
from ..fit.log_set import expand_patterns
from ..fit.output_error import DIFF_STEP, START_STATE, TrialRMS, VehicleFit, output_error, split_parameters
from ..fit.vehicle_parameters import check_bounds, check_parameters, described_values, typical_scale, with_parameters
from ..plausibility import PlausibilityWarning
from ..robot.tree import Robot
from .replay import MAX_TIMESTEP_S, _simulate
from .replay_inputs import (
    MAX_GAP_S,
    SMOOTHING_S,
    START_WINDOW_S,
    StartState,
    Streams,
    _euler,
    _seconds,
    check_joints,
    joint_motion,
    read_streams,
    start_fit,
    start_state,
)

__all__ = ["vehicle_from_trials"]


#: The bounds of a fitted start state's offsets from the window's estimate
#: (:data:`uwml.fit.output_error.START_STATE`): roll and pitch [rad], velocity [m/s], angular
#: velocity [rad/s].
START_OFFSET_BOUNDS = (0.2, 0.2, 0.5, 0.5, 0.5, 1.0, 1.0, 1.0)
#: The typical size of a start offset, for its finite-difference step [rad, rad/s].
START_OFFSET_SCALE = 0.01


@dataclass(frozen=True)
class _Trial:
    """One trial, read: its ``streams`` (the first pose sample replaced by the fitted start
    pose), its ``start`` (the twist fitted over the start window), the ``time`` [s] of the
    samples compared and their ``measured`` roll and pitch ``(n, 2)`` [rad]."""

    source: str
    streams: Streams
    start: StartState
    time: Array
    measured: Array


def _start_pose(streams: Streams, window: float) -> Streams:
    """``streams`` with the first pose sample replaced by the value at the first time of the
    polynomials fitted to the start window's poses (:func:`uwml.sim.replay_inputs.start_fit`)."""
    from scipy.spatial.transform import Rotation

    assert streams.pose is not None
    value = start_fit(streams, window)[0][0]
    reference = Rotation.from_quat(np.roll(streams.pose[1][0], -1))  # scipy's quaternions are scalar last
    return _started(streams, value[:3], (reference * Rotation.from_rotvec(value[3:])).as_quat())


def _started(streams: Streams, position: Array, quaternion: Array) -> Streams:
    """``streams`` whose first pose sample is ``position`` and ``quaternion`` (scalar last)."""
    assert streams.pose is not None
    positions, quaternions = streams.pose[0].copy(), streams.pose[1].copy()
    positions[0], quaternions[0] = position, np.roll(quaternion, 1)
    return replace(streams, pose=(positions, quaternions))


def _read_trial(entry: Any, robot: Robot, description: str, settings: dict[str, Any]) -> _Trial:
    """One trial, read and checked as a replay checks it (its joints' range and motion, warned of
    here once, and its start window), with its measured attitude (refused without one)."""
    streams = read_streams(entry, robot.n_joints, settings["max_gap"], settings["columns"])
    source = streams.joints.source
    if streams.pose is None:
        raise UwmlError(
            f"{source}: row 1 (header), column 'x': missing column (a vehicle fit compares the measured attitude: the trial "
            "needs the vehicle's pose, x, y, z and qw, qx, qy, qz or roll, pitch, yaw, in its file or a stream beside it)"
        )
    check_joints(streams.joints, robot.joints, streams.first_row, description)
    joint_motion(streams.joints, robot.joints, settings["smoothing"], streams.first_row)
    measured = _euler(streams.pose[1])[1:, :2]
    started = _start_pose(streams, settings["start_window"])
    return _Trial(source, started, start_state(started, settings["start_window"]), streams.joints.time[1:], measured)


#: One replay: the hull's parameters, the start state's offsets (roll, pitch, p, q), the trial.
Job = tuple[Array, Array, int]


class _Replayer:
    """The replays of the trials with given parameters (in this process or as a Ray actor)."""

    def __init__(
        self, model: Any, parts: tuple[Any, ...], trials: Sequence[_Trial], names: Sequence[str], settings: dict[str, Any]
    ) -> None:
        self._model, self._parts, self._trials, self._names, self._settings = model, parts, list(trials), list(names), settings

    def simulation(self, x: Array) -> Any:
        """The floating simulation of the vehicle with the parameters ``x`` in its hull."""
        from .mujoco import Simulation

        joints, links, base, losses, water = self._parts
        robot = Robot(joints, links, base=with_parameters(base, self._names, x), losses=losses, water=water)
        s = self._settings
        sim = Simulation(self._model, robot, integrator=s["integrator"], **s["options"])
        if s["timestep"] is not None:
            sim.model.opt.timestep = s["timestep"]
        return sim

    def angles(self, x: Array, offset: Array, k: int) -> Array:
        """The simulated roll and pitch of trial ``k`` with the parameters ``x``, started at the
        window's estimate turned by ``offset``'s roll and pitch (about the body's x and y axes),
        its twist plus the offset's (:data:`uwml.fit.output_error.START_STATE`), at the trial's
        compared samples, each within half a turn of the
        measured one, sample-major ``(2 n,)``."""
        trial, s = self._trials[k], self._settings
        streams, start = trial.streams, trial.start
        if np.any(offset):
            from scipy.spatial.transform import Rotation

            assert streams.pose is not None
            turned = Rotation.from_quat(np.roll(streams.pose[1][0], -1)) * Rotation.from_rotvec([offset[0], offset[1], 0.0])
            streams = _started(streams, streams.pose[0][0], turned.as_quat())
            start = replace(start, twist=start.twist + offset[2:])
        sim = self.simulation(x)
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", PlausibilityWarning)  # warned of once, when the trial was read
                replayed = _simulate(sim, streams, s["description"], False, s["smoothing"], s["start_window"], False, start)
        except UwmlError as error:
            chosen = ", ".join(f"{name} = {value:.6g}" for name, value in zip(self._names, x, strict=True))
            raise UwmlError(f"{error} (replayed with {chosen}: narrow the bounds?)") from None
        euler = _euler(replayed.quaternion)
        simulated = np.column_stack([np.interp(trial.time, replayed.time, euler[:, j]) for j in range(2)])
        wrapped = (simulated - trial.measured + np.pi) % (2.0 * np.pi) - np.pi
        return np.asarray((trial.measured + wrapped).ravel(), dtype=np.float64)

    def run(self, jobs: Sequence[Job]) -> list[Array]:
        """:meth:`angles` of each job."""
        return [self.angles(*job) for job in jobs]


class _Runner:
    """Runs batches of replays, here or shared out among Ray actors, each replay once: a batch's
    replays are kept for the next (a Jacobian after the residual at its point; a start offset's
    column replays its own trial alone)."""

    def __init__(self, replayer: _Replayer, ray: Any = None, spec: tuple[Any, ...] = ()) -> None:
        self._replayer, self._ray, self._actors = replayer, ray, []
        self._kept: dict[bytes, Array] = {}
        if ray is not None:
            actor = ray.remote(num_cpus=1)(_Replayer)
            cpus = max(1, int(ray.cluster_resources().get("CPU", 1)))
            self._actors = [actor.remote(*spec) for _ in range(cpus)]

    def __call__(self, jobs: list[Job]) -> list[Array]:
        keys = [x.tobytes() + offset.tobytes() + k.to_bytes(4, "little") for x, offset, k in jobs]
        todo = {key: job for key, job in zip(keys, jobs, strict=True) if key not in self._kept}
        answers = self._run(list(todo.values()))
        done = dict(zip(todo, answers, strict=True))
        results = [done[key] if key in done else self._kept[key] for key in keys]
        self._kept = dict(zip(keys, results, strict=True))
        return results

    def _run(self, jobs: list[Job]) -> list[Array]:
        if not self._actors or not jobs:
            return self._replayer.run(jobs)
        n = min(len(self._actors), len(jobs))
        answers = self._ray.get([self._actors[k].run.remote(jobs[k::n]) for k in range(n)])
        ordered: list[Array] = [np.empty(0)] * len(jobs)
        for k, answer in enumerate(answers):
            ordered[k::n] = answer
        return ordered

    def close(self) -> None:
        for actor in self._actors:
            self._ray.kill(actor)


def _vehicle(description: Any, hydro: Any, timestep: float | None) -> tuple[Any, Robot, str]:
    """The MuJoCo model and robot of a vehicle fit's ``description`` (floated) and its label for
    messages, ``timestep`` checked (at most ``MAX_TIMESTEP_S``) and the base's lumped model (the
    hull, what is fitted) required."""
    if timestep is not None and _seconds(timestep, "timestep") > MAX_TIMESTEP_S:
        raise ValueError(f"timestep must be at most {MAX_TIMESTEP_S:g} s (replays take longer steps badly), got {timestep!r}")
    model, robot = load_description(description, hydro, True)
    label = "the description" if isinstance(description, tuple) else os.fspath(description)
    if robot.base is None or robot.base.lumped is None:
        raise ValueError(
            f"{label}: the base has no lumped model (a hydro file's [links.NAME.lumped] on the base link, the hull): nothing to fit"
        )
    return model, robot, label


def _check_floats(label: str, free_dof: int | None) -> None:
    """A vehicle fit's simulation, whose free joint's first degree of freedom is ``free_dof``
    (None: the base does not float), refused unless it floats."""
    if free_dof is None:
        raise ValueError(f"{label}: the robot's base did not float (its root hangs from the world by a joint): a vehicle fit needs it to")


def _trial_entries(trials: Any, what: str) -> list[Any]:
    """The trials of ``trials``: one path (a glob pattern: its files, each a trial), or a list of
    them, a list or tuple in it being one trial's streams."""
    given = [trials] if isinstance(trials, str | os.PathLike) else list(trials)
    entries = [one for entry in given for one in (expand_patterns([entry]) if isinstance(entry, str | os.PathLike) else [list(entry)])]
    if not entries and what == "trials":
        raise ValueError("trials: give at least one trial to fit")
    return entries


def _sigmas(sigma: Any, trials: Sequence[_Trial]) -> tuple[Array, bool]:
    """Each compared point's standard error [rad] (``sigma``: one, or one per training trial;
    None: 1, to be estimated from the residuals) and whether it was given."""
    if sigma is None:
        return np.ones(sum(2 * t.time.size for t in trials)), False
    values = (
        np.broadcast_to(np.asarray(sigma, dtype=np.float64), (len(trials),)) if np.ndim(sigma) == 0 else np.asarray(sigma, dtype=np.float64)
    )
    if values.shape != (len(trials),) or not np.all(np.isfinite(values) & (values > 0.0)):
        raise ValueError(f"sigma must be a number > 0 [rad] or one per training trial ({len(trials)}), got {sigma!r}")
    return np.concatenate([np.full(2 * t.time.size, s) for s, t in zip(values, trials, strict=True)]), True


def _start(
    base: Any, names: Sequence[str], start: Mapping[str, float] | None, bounds: Mapping[str, tuple[float, float]] | None
) -> tuple[Array, Array, Array, Array]:
    """The parameters' values in the hull ``base``, where the fit starts (``start``'s values
    replacing them) and their bounds (checked: :func:`uwml.fit.vehicle_parameters.check_bounds`)."""
    described = described_values(base, names)
    begin = described.copy()
    for name, value in (start or {}).items():
        if name not in names:
            raise ValueError(f"start: {name!r} not among the parameters fitted ({', '.join(names)})")
        begin[list(names).index(name)] = float(value)
    lower, upper = check_bounds(names, begin, bounds)
    return described, begin, lower, upper


def _rms(values: Array, trial: _Trial) -> tuple[float, float]:
    """The RMS of roll and pitch of a trial's simulated ``values`` against its measured angles."""
    error = values.reshape(-1, 2) - trial.measured
    return float(np.sqrt(np.mean(error[:, 0] ** 2))), float(np.sqrt(np.mean(error[:, 1] ** 2)))


def vehicle_from_trials(
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
    integrator: str = "euler",
    columns: Any = None,
    diff_step: float = DIFF_STEP,
    max_nfev: int | None = None,
    on_ray: bool = False,
    address: str | None = None,
    workers: int | None = None,
    **options: Any,
) -> VehicleFit:
    """Fit the hull's ``parameters`` to free-floating trials by output error (module docstring).

    Parameters
    ----------
    trials : path, glob pattern, or a list of them
        The training trials (a list or tuple inside the list: one trial's streams, as
        :func:`uwml.sim.replay.replay` takes them).
    description : path or (mujoco.MjModel, uwml.Robot)
        The vehicle's URDF or MJCF with ``hydro``, its hydro file (floated), or the compiled
        model with its robot: its base must float and carry a lumped model (the hull).
    parameters : sequence of str
        The parameters fitted (:data:`uwml.fit.vehicle_parameters.VEHICLE_PARAMETERS`, e.g.
        ``"linear_damping[3]"``, ``"cob_z"``); the rest keep the description's values.
    bounds : mapping, optional
        ``name: (lower, upper)`` replacing the default bounds (:mod:`uwml.fit.vehicle_parameters`).
    start : mapping, optional
        ``name: value`` replacing the description's value as the start.
    test : path, glob pattern, or a list of them
        Trials held out: replayed with the described and the fitted parameters (from the
        window's start state), not fitted.
    fit_start : bool
        Fit each training trial's start roll, pitch and twist too, as offsets from the window's
        estimate within ``START_OFFSET_BOUNDS`` (eight parameters a trial, each column of the
        Jacobian one replay of its trial): the window's estimate is off by the pose noise, and a
        replay carries its start's error along. False: replay from the window's estimate.
    sigma : float or one per training trial, optional
        The standard error of a measured angle [rad]; None: estimated from the residuals.
    scale_covar : bool
        Scale the covariance by the reduced χ² where ``sigma`` is given (always without it).
    start_window, smoothing, max_gap, timestep, integrator, columns
        As for :func:`uwml.sim.replay.replay` (``timestep`` None: the description's).
    diff_step : float
        The forward differences' relative step (:mod:`uwml.fit.output_error`).
    max_nfev : int, optional
        At most this many least-squares iterations' residuals (scipy's ``max_nfev``).
    on_ray, address, workers
        Replay on Ray (a cluster at ``address``, else a local Ray of ``workers`` CPUs).
    options
        As for :class:`uwml.sim.mujoco.Simulation` (``current``, ``depth``, ...).

    Raises
    ------
    ValueError
        Unknown or repeated parameter names (listing the allowed ones); a base that does not
        float or has no lumped model; a trial without a measured pose (naming its column) or
        that a replay refuses; bounds that do not contain the start, or a negative lower bound
        of a lumped entry or volume; a replay that diverges (naming the parameters).
    """
    names = check_parameters(parameters)
    model, robot, label = _vehicle(description, hydro, timestep)
    base = robot.base
    assert base is not None
    settings = {
        "max_gap": max_gap, "columns": columns, "smoothing": smoothing, "start_window": start_window, "timestep": timestep,
        "integrator": integrator, "options": options, "description": label,
    }  # fmt: skip
    described, begin, lower, upper = _start(base, names, start, bounds)
    fitted = [_read_trial(entry, robot, label, settings) for entry in _trial_entries(trials, "trials")]
    held = [_read_trial(entry, robot, label, settings) for entry in _trial_entries(test, "test")]
    parts = (robot.joints, robot.links, base, robot.losses, robot.water)
    replayer = _Replayer(model, parts, fitted + held, names, settings)
    first_simulation = replayer.simulation(begin)
    _check_floats(label, first_simulation._free_dof)
    problem = _Problem(fitted, held, names, fit_start)
    sigma_points, given = _sigmas(sigma, fitted)
    x0, lower, upper, scales = problem.extended(begin, lower, upper)
    arguments = (sigma_points, x0, lower, upper, scales, given, scale_covar, diff_step, max_nfev)
    if on_ray or address is not None:
        from .._ray import ray_session

        with ray_session(address, workers) as ray:
            runner = _Runner(replayer, ray, (model, parts, fitted + held, names, settings))
            try:
                state, trial_rms = problem.solve(runner, *arguments)
            finally:
                runner.close()
    else:
        state, trial_rms = problem.solve(_Runner(replayer), *arguments)
    how = {"timestep": float(first_simulation.model.opt.timestep), "integrator": integrator, "diff_step": float(diff_step)}
    return problem.result(state, trial_rms, lower, upper, described, base, **how)


class _Problem:
    """The fit's parameters (the hull's, then each training trial's start offsets with
    ``fit_start``), its data, and the replays that answer them."""

    def __init__(self, fitted: Sequence[_Trial], held: Sequence[_Trial], names: Sequence[str], fit_start: bool) -> None:
        self.fitted, self.held, self.names, self.fit_start = list(fitted), list(held), list(names), fit_start
        self.data = np.concatenate([t.measured.ravel() for t in fitted])
        states = len(START_STATE) * len(fitted) if fit_start else 0
        self.all_names = self.names + [f"start{k}.{name}" for k in range(len(fitted)) for name in START_STATE][:states]

    def extended(self, begin: Array, lower: Array, upper: Array) -> tuple[Array, Array, Array, Array]:
        """Start, bounds and typical scales of every parameter fitted."""
        extra = len(self.all_names) - len(self.names)
        offsets = np.tile(START_OFFSET_BOUNDS, len(self.fitted))[:extra]
        scales = [typical_scale(name) for name in self.names] + [START_OFFSET_SCALE] * extra
        return (
            np.concatenate([begin, np.zeros(extra)]),
            np.concatenate([lower, -offsets]),
            np.concatenate([upper, offsets]),
            np.array(scales),
        )

    def result(
        self, state: dict[str, Any], trial_rms: tuple[TrialRMS, ...], lower: Array, upper: Array, described: Array, base: Any, **how: Any
    ) -> VehicleFit:
        """The fit's :class:`VehicleFit` from :func:`uwml.fit.output_error.output_error`'s
        ``state`` (the start offsets split off) and each trial's RMS; ``how``: the replays'
        ``timestep`` and ``integrator``, how the Jacobian was taken."""
        fitted, names = self.fitted, self.names
        return VehicleFit(
            **state,
            time=np.concatenate([np.repeat(t.time, 2) for t in fitted]),
            trial=np.concatenate([np.full(2 * t.time.size, k, dtype=np.int64) for k, t in enumerate(fitted)]),
            angle=np.tile(np.array([0, 1], dtype=np.int64), self.data.size // 2),
            trials=trial_rms, bounds={name: (float(lower[k]), float(upper[k])) for k, name in enumerate(names)},
            described=dict(zip(names, described.tolist(), strict=True)), described_base=base,
            source=fitted[0].source if len(fitted) == 1 else f"{fitted[0].source} and {len(fitted) - 1} more trials",
            start_fitted=self.fit_start, **how,
        )  # fmt: skip

    def offset(self, x: Array, k: int) -> Array:
        """Trial ``k``'s start offsets in the parameters ``x`` (zero without ``fit_start``)."""
        if not self.fit_start or k >= len(self.fitted):
            return np.zeros(len(START_STATE))
        at = len(self.names) + len(START_STATE) * k
        return np.asarray(x[at : at + len(START_STATE)], dtype=np.float64)

    def solve(
        self, runner: _Runner, sigma: Array, x0: Array, lower: Array, upper: Array, scales: Array, given: bool, scale_covar: bool,
        diff_step: float, max_nfev: int | None,
    ) -> tuple[dict[str, Any], tuple[TrialRMS, ...]]:  # fmt: skip
        """The output-error fit with ``runner``'s replays; each trial's RMS, the held-out ones
        replayed (from the window's start) at the start and at the optimum."""
        count, p = len(self.fitted), len(self.names)

        def evaluate(points: Sequence[Array]) -> list[Array]:
            answers = runner([(x[:p], self.offset(x, k), k) for x in points for k in range(count)])
            return [np.concatenate(answers[i * count : (i + 1) * count]) for i in range(len(points))]

        state, first, best = output_error(
            evaluate, self.data, sigma, self.all_names, x0, lower, upper, scales, sigma_given=given, scale_covar=scale_covar,
            diff_step=diff_step, max_nfev=max_nfev,
        )  # fmt: skip
        state, offsets = split_parameters(state, p)
        x = np.array([state["params"][name] for name in self.names])
        zero = np.zeros(len(START_STATE))
        answers = runner([(point, zero, count + k) for k in range(len(self.held)) for point in (x0[:p], x)])
        return state, self.trial_rms(first, best, offsets, [(answers[2 * k], answers[2 * k + 1]) for k in range(len(self.held))])

    def trial_rms(
        self, first: Array, best: Array, offsets: Mapping[str, tuple[float, float | None]], held: Sequence[tuple[Array, Array]]
    ) -> tuple[TrialRMS, ...]:
        """Each trial's RMS: the training trials' of the model values at the start (``first``)
        and at the optimum (``best``), with their fitted start ``offsets``; the held-out ones' of
        their replays with the described and the fitted parameters (``held``, one pair a trial)."""
        sizes = np.cumsum([0] + [2 * t.time.size for t in self.fitted])
        rms = []
        for k, t in enumerate(self.fitted):
            start = tuple(offsets[f"start{k}.{name}"] for name in START_STATE) if self.fit_start else None
            a, b = sizes[k], sizes[k + 1]
            rms.append(TrialRMS(t.source, "train", t.time.size, _rms(first[a:b], t), _rms(best[a:b], t), start))
        for t, (described, fitted) in zip(self.held, held, strict=True):
            rms.append(TrialRMS(t.source, "test", t.time.size, _rms(described, t), _rms(fitted, t)))
        return tuple(rms)
