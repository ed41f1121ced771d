"""Cd, Cm and the joint losses of an arm from logs of the water run alone
(:func:`hydro_from_water_logs`; docs/model.md section 13, "13.3 Identifying a vehicle";
docs/identification.md, "Cd and Cm from water-only logs").

Without a run on land, the land torque of the land/water experiment (docs/model.md section 4) is
what the description says it is: the rigid-body inverse dynamics ``ID_RB(q, q̇, q̈)`` of its masses
and inertias with gravity (MuJoCo's ``mj_inverse``, :mod:`uwml.fit.inverse_dynamics`). The motor
then supplies ``τ_motor = ID_RB − τ_env(q, q̇, q̈; θ)``, the environment's torque being the water's
(drag, added mass, buoyancy) and the joint losses', so that

``ID_RB − τ_motor − τ_buoy − τ_loss,held = Cd R_d + Cm R_m (+ axial drag, lumped models) + Σ ℓ_k L_k``

linear in the coefficients of :func:`uwml.fit.hydro_coefficients` (``per``, its regressors of
:mod:`uwml.fit.robot_design`) and in the loss levels ``ℓ_k`` of the selected joints
(:mod:`uwml.fit.loss_regressors`: ``<joint>.k_oil``, ``.c0``, ``.s0``, ``.d0`` at the given depth
and temperature). The fit is that of :func:`uwml.fit.hydro_coefficients` (weights per joint,
Huber's loss, its statistics) on the land/water log whose land torque is ``ID_RB − τ_loss,held``
and whose water torque is the logged ``τ_motor``; terms the data do not determine are refused
by name (:mod:`uwml.fit.determinacy`); coefficients without a regressor on the selected joints
are dropped and named, as there. Any error in the description's masses, inertias or centres of
mass goes into the coefficients: the land run is what measures them otherwise.

A log holds ``time``, ``q1 …`` (with ``qd``, ``qdd`` or estimated) and the water run's motor
torques ``tau1 …`` (or ``tau_water1 …`` of a land/water log, its land run ignored); a floating
base moves as its vehicle columns say (docs/logs.md). Logs are read whole (in memory).
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass, replace
from typing import Any, Literal

import numpy as np
from numpy.typing import ArrayLike

from ..io.logs import Log
from ..model.joint_losses import JointLosses
from ..robot._arguments import _per_joint_losses
from ..sea.conditions import check_depths, check_temperatures, hydrostatic_pressure
from ._types import Array, PathOrFile
from .design import DESIGN_CACHE_BYTES
from .equation_error import fit_design, read_whole
from .hydro import HydroFit
from .inverse_dynamics import RigidBodyInverse, load_description
from .log_set import LogSet, _Item, expand_patterns
from .loss_regressors import DEFAULT_LOSS_TERMS, LossColumns
from .robot_design import _RobotHydroDesign

__all__ = ["WaterOnlyFit", "hydro_from_water_logs"]


@dataclass(frozen=True, eq=False, kw_only=True)
class WaterOnlyFit(HydroFit):
    """Result of :func:`hydro_from_water_logs`: :class:`uwml.fit.HydroFit`'s, the data being
    ``ID_RB − τ_motor − τ_buoy − τ_loss,held`` [N·m]."""

    #: The loss terms fitted (``<joint>.k_oil`` …).
    losses: tuple[str, ...] = ()
    #: Where the losses were evaluated [m, °C].
    depth: float = 0.0
    temperature_c: float = 20.0
    #: The coefficients and loss levels that came out negative (warned of).
    negative: tuple[str, ...] = ()

    def _report_statistics(self) -> list[str]:
        lines = super()._report_statistics()
        lines.append("    land run           = none: the description's rigid-body inverse dynamics (mj_inverse)")
        if self.losses:
            lines.append(f"    losses at          = {self.depth:g} m, {self.temperature_c:g} °C")
        if self.negative:
            lines.append(f"##  Warning: negative, not physical: {', '.join(self.negative)}")
        return lines

    def _summary_head(self) -> dict[str, Any]:
        return super()._summary_head() | {
            "model": "water_only",
            "losses": list(self.losses),
            "depth": self.depth,
            "temperature_c": self.temperature_c,
            "negative": list(self.negative),
        }


class _WaterOnlyDesign(_RobotHydroDesign):
    """The robot's design (:class:`uwml.fit.robot_design._RobotHydroDesign`) of a log whose land
    torque is ``ID_RB − τ_loss,held``, with the loss columns after its own (module docstring)."""

    def __init__(
        self, inverse: RigidBodyInverse, log: LogSet, per: str, rows: list[int], cache_bytes: int, lumped: str, losses: LossColumns
    ) -> None:
        super().__init__(inverse.robot, log, inverse.robot.water, per, rows, cache_bytes, lumped)
        self._inverse, self._losses = inverse, losses
        self.names = self.names + losses.names

    def _compute(self, log: Log) -> Array:
        assert log.qd is not None
        rigid = self._inverse(log)[:, 6:]
        columns, known = self._losses(log.qd)
        problem = super()._compute(replace(log, tau_land=rigid - known, tau_water=log.tau, tau=None))
        joints = [row - 6 for row in self._joints]
        loss = columns[:, joints, :].transpose(1, 0, 2)
        return np.ascontiguousarray(np.concatenate([problem[:, :, :-1], loss, problem[:, :, -1:]], axis=2))


def _water_log(entry: Any, inverse: RigidBodyInverse, columns: Any) -> _Item:
    """One water log, read and checked, its derivatives estimated where absent."""
    n_joints = inverse.robot.n_joints
    log = read_whole(entry, n_joints, columns)
    torque = log.tau if log.tau is not None else log.tau_water
    if torque is None:
        raise ValueError(
            f"{log.source}: row 1 (header), column 'tau1': missing column (a water-only fit reads the water run's motor torques "
            f"tau1 … tau{n_joints})"
        )
    log = replace(log, tau=torque, tau_land=None, tau_water=None).with_derivatives()
    return _Item(log.source, log.n_samples, log=log)


def hydro_from_water_logs(
    log_or_path: Log | PathOrFile | Sequence[Log | PathOrFile],
    description: Any,
    hydro: Any = None,
    joints: ArrayLike | None = None,
    per: Literal["leg", "link", "direction"] = "leg",
    *,
    losses: bool | Iterable[str] = False,
    joint_losses: JointLosses | Sequence[JointLosses | None] | None = None,
    depth: float = 0.0,
    temperature_c: float = 20.0,
    lumped: Literal["diagonal", "full", "given"] = "diagonal",
    robust: bool = False,
    sigma: ArrayLike | None = None,
    scale_covar: bool = True,
    columns: Any = None,
    floating: bool | None = None,
    cache_bytes: int = DESIGN_CACHE_BYTES,
) -> WaterOnlyFit:
    """Fit Cd and Cm (and the joint losses) to logs of the water run alone (module docstring).

    Parameters
    ----------
    log_or_path : Log, file, glob pattern, or a list of them
        Water logs (``tau1 …``), fitted together.
    description : path or (mujoco.MjModel, uwml.Robot)
        The robot's URDF or MJCF, with ``hydro`` its hydro file (``floating``: its root on a free
        joint, None: as the hydro file says); or the compiled model with its robot.
    joints : sequence of int, optional
        The joints whose torques are fitted (0-based); default all.
    per, lumped, robust, sigma, scale_covar, columns, cache_bytes
        As for :func:`uwml.fit.hydro_coefficients`.
    losses : bool or iterable of str
        The loss terms fitted on each selected joint (``LOSS_TERMS``: ``k_oil``, ``c0``, ``s0``,
        ``d0``); True: ``DEFAULT_LOSS_TERMS``; False: none (the losses held, as ``joint_losses``
        says).
    joint_losses : JointLosses or one per joint, optional
        The joints' loss models: the shapes of the fitted terms and the values of the held ones;
        default the robot's own.
    depth, temperature_c : float
        Where the losses are evaluated [m, °C] (the pressure of the robot's water at that depth).

    Raises
    ------
    ValueError
        A log without ``tau`` columns (naming the column) or with another number of joints; bad
        joints or terms; terms the data do not determine (named).
    """
    model, robot = load_description(description, hydro, floating)
    inverse = RigidBodyInverse(model, robot)
    selected = list(range(robot.n_joints)) if joints is None else [int(j) for j in np.atleast_1d(np.asarray(joints))]
    if not selected or len(set(selected)) != len(selected) or any(not 0 <= j < robot.n_joints for j in selected):
        raise ValueError(f"joints must be distinct indices in 0..{robot.n_joints - 1} (at least one), got {joints!r}")
    if per not in ("leg", "link", "direction"):
        raise ValueError(f"per must be 'leg', 'link' or 'direction', got {per!r}")
    terms = list(DEFAULT_LOSS_TERMS) if losses is True else [] if losses is False else list(losses)
    check_depths(np.asarray(float(depth)))
    check_temperatures(np.asarray(float(temperature_c)))
    models = _per_joint_losses(robot.losses if joint_losses is None else joint_losses, robot.n_joints)
    labels = [joint.name or f"joint{j}" for j, joint in enumerate(robot.joints)]
    pressure = float(hydrostatic_pressure(np.asarray(float(depth)), robot.water.density, robot.water.gravity)) / 1e6
    loss_columns = LossColumns(models, selected, terms, labels, pressure, float(temperature_c))
    given = list(log_or_path) if isinstance(log_or_path, list | tuple) else [log_or_path]
    logs = LogSet([_water_log(entry, inverse, columns) for entry in expand_patterns(given)])
    rows = [6 + j for j in selected]
    design = _WaterOnlyDesign(inverse, logs, per, rows, cache_bytes, lumped, loss_columns)
    state, negative = fit_design(
        design, logs, selected, per=per, robust=robust, sigma=sigma, scale_covar=scale_covar, drop_zero=True,
        advice="hold some (fewer loss terms, or per='leg'), or log motions that excite them apart",
        physical=lambda name: not _off_diagonal(name), what="coefficients and loss levels",
    )  # fmt: skip
    state |= {"unit": "N·m (ID_RB − τ_motor − τ_buoy − τ_loss,held)"}
    fitted_losses = tuple(name for name in loss_columns.names if name in state["params"])
    return WaterOnlyFit(**state, losses=fitted_losses, depth=float(depth), temperature_c=float(temperature_c), negative=negative)


def _off_diagonal(name: str) -> bool:
    """Whether ``name`` is an off-diagonal entry of a lumped matrix (its sign is free)."""
    indices = name.replace("]", "").split("[")[1:]
    return len(indices) == 2 and indices[0] != indices[1]
