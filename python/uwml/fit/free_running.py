"""A vehicle's hull from free-running logs (:func:`hull_from_free_running`; docs/model.md section
13, "13.3 Identifying a vehicle"; docs/identification.md, "A hull from free-running logs").

The thrusters' wrench ``B T`` (the commands ``u1 … un`` through each thruster's curve and the
allocation, :mod:`uwml.fit.thrust_wrench`) moves the vehicle against the water; with the base's
twist ``ν`` and rate ``ν̇`` (estimated by the Savitzky-Golay fit of :mod:`uwml.io.sampling` where
the log has no ``u_dot … r_dot``) and its orientation, Fossen's equations of the base,
``(M_RB + M_A) ν̇ + C_RB(ν) ν + C_A(ν) ν + D_L ν + D_Q(ν) ν + g(η) = B T + W_arm``, are linear in the
lumped model's entries and in the hydrostatic terms ``ρV`` and ``ρV r_B``. The rigid-body part
(``M_RB``, ``C_RB``, the weight, and the arm's motion's reaction: the description's masses,
inertias and centres of mass) is MuJoCo's inverse dynamics of the whole vehicle at the log's
states (:class:`uwml.fit.inverse_dynamics.RigidBodyInverse`); the water's wrench on the arm and
the terms not fitted are uwml's (:meth:`uwml.Robot.hydro`, the description's coefficients). So each
sample gives six equations (forces, then moments about the base's origin, base axes)

``ID_RB − B T − W_known = Σ θ_i R_i``

with ``R_i`` the base's regressor of term ``i`` (:meth:`uwml.Robot.hydro_regressors`: the
environment's wrench per unit coefficient, so a damping's column is minus its velocity term) and
``W_known`` the water's wrench with the fitted terms left out. It is a captive test
(docs/identification.md, "A hull from a captive test") whose rig is the thrusters and whose run
in air is the rigid-body model, and it is fitted as one: equation-error weighted least squares,
each of the six rows weighted by its σ (given, or estimated from the residuals), with the
statistics of :class:`uwml.fit.FitResult`.

The fitted terms are the diagonals of the base's lumped model (``terms``: ``added_mass``,
``linear_damping``, ``quadratic_damping``; Fossen's decoupled model), named
``base.added_mass[i][i]`` … ``base.quadratic_damping[i]`` in the model's axes, and optionally the
hydrostatic terms ``base.rho_volume`` [kg] and ``base.rho_volume_cob[k]`` [kg·m] (the base body's
own buoyancy, ``ρ V g`` upwards at ``r_B``: the force ``ρV g Rᵀe_z`` and the moment
``(ρV r_B) × g Rᵀe_z``). Any of them can be held at the description's value (``hold``). Terms the
data do not determine are refused by name before the fit (:mod:`uwml.fit.determinacy`); a
damping, an added mass or a volume that comes out negative is named in a
:class:`uwml.PlausibilityWarning` and in the result's ``negative``.

Still water: no current. The logs are read whole (in memory).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, replace
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from ..io.logs import Log
from ..io.sampling import WINDOW_S
from ..model.lumped import LUMPED_COEFFICIENTS, LumpedModel
from ..robot.base_motion import BaseMotion
from ..robot.tree import Robot
from ._types import Array, PathOrFile
from .design import DESIGN_CACHE_BYTES, _HydroDesign
from .equation_error import fit_design, read_whole
from .hydro import HydroFit
from .inverse_dynamics import RigidBodyInverse, load_description
from .log_set import LogSet, _Item, expand_patterns
from .robot_design import _DIAGONAL, BASE_ROWS, HULL_TERMS, HYDROSTATIC_TERMS
from .thrust_wrench import check_thruster_commands, thrust_wrench

__all__ = ["HullFit", "hull_from_free_running"]


def _diagonal(family: str) -> list[int]:
    """The entries of ``family`` on its diagonal, as indices of ``LUMPED_COEFFICIENTS``."""
    return [index for index in _DIAGONAL if LUMPED_COEFFICIENTS[index].startswith(f"{family}[")]


@dataclass(frozen=True, eq=False, kw_only=True)
class HullFit(HydroFit):
    """Result of :func:`hull_from_free_running`: the fitted terms (``params``, the held ones too,
    also in ``fixed``) with the statistics of :class:`uwml.fit.FitResult`. The data are
    ``ID_RB − B T − W_known`` of the six rows of the base's equations (``joint`` ``-1 … -6`` for
    ``fx … mz``), sample-major."""

    #: The base's lumped model in the description (the terms not fitted keep its values).
    described: LumpedModel
    #: The thrusters the commands drove.
    thrusters: int = 0
    #: Whether ρV and ρV r_B were fitted.
    hydrostatics: bool = False
    #: The damping, added-mass and volume terms that came out negative (warned of).
    negative: tuple[str, ...] = ()

    @property
    def squared_unit(self) -> str:
        """The unweighted χ²'s unit: the forces' rows in N², the moments' in (N·m)², summed."""
        return "N² or (N·m)²"

    def _report_statistics(self) -> list[str]:
        lines = [
            f"    equations          = base rows {', '.join(BASE_ROWS)} (forces N, moments N·m, base axes)",
            f"    thrusters          = {self.thrusters} (commands u1 … u{self.thrusters})",
        ]
        if self.fixed:
            lines.append(f"    held (described)   = {', '.join(self.fixed)}")
        if self.negative:
            lines.append(f"##  Warning: negative, not physical: {', '.join(self.negative)}")
        return lines

    def _summary_head(self) -> dict[str, Any]:
        return super()._summary_head() | {"model": "hull", "thrusters": self.thrusters, "negative": list(self.negative)}

    def lumped_model(self) -> LumpedModel:
        """The described lumped model with the fitted diagonal entries put in (its point, axes
        and other entries as described)."""
        values = self.described.coefficients()
        for index, name in enumerate(LUMPED_COEFFICIENTS):
            if f"base.{name}" in self.params:
                values[index] = self.params[f"base.{name}"]
        added = np.zeros((6, 6))
        added[np.triu_indices(6)] = values[:21]
        added = added + np.triu(added, 1).T
        return dataclasses.replace(
            self.described, added_mass=added, linear_damping=values[21:57].reshape(6, 6), quadratic_damping=values[57:]
        )


class _HullDesign(_HydroDesign):
    """The six base rows of every sample (module docstring): the fitted terms' regressors and the
    target ``ID_RB − B T − W_known``, from a log whose ``wrench_land`` holds ``ID_RB`` and whose
    ``wrench_water`` holds ``B T`` (:func:`_prepared`)."""

    def __init__(self, robot: Robot, log: LogSet, model: int, entries: list[int], hydrostatics: bool, cache_bytes: int) -> None:
        self._robot, self._model, self._entries, self._hydrostatics = robot, model, entries, hydrostatics
        self._described = robot.lumped_models[model][1].coefficients()[entries]
        base = robot.base
        assert base is not None
        rho = robot.water.density
        self._buoyancy = np.array([rho * base.volume, *(rho * base.volume * np.asarray(base.cob))])
        names = [f"base.{LUMPED_COEFFICIENTS[i]}" for i in entries] + (list(HYDROSTATIC_TERMS) if hydrostatics else [])
        self._setup(log, robot.water, "lumped", list(range(6)), cache_bytes, names)

    def _compute(self, log: Log) -> Array:
        robot = self._robot
        assert log.wrench_land is not None and log.wrench_water is not None and log.qd is not None and log.qdd is not None
        fields = log.base_motion()
        motion = BaseMotion(**fields)
        states: tuple[Array, Array, Array] = (log.q, log.qd, log.qdd)
        regressors = robot.hydro_regressors(*states, water=robot.water, base_motion=motion)
        water = robot.hydro(*states, water=robot.water, base_motion=motion, base=True).base
        assert water is not None
        columns = regressors.base_lumped[:, :, self._model, self._entries]
        known = water.total - columns @ self._described
        if self._hydrostatics:
            up = robot.water.gravity * _body_up(fields["orientation"], log.n_samples)
            statics = np.zeros((log.n_samples, 6, 4))
            statics[:, :3, 0] = up
            for k in range(3):
                statics[:, 3:, 1 + k] = np.cross(np.eye(3)[k], up)
            columns = np.concatenate([columns, statics], axis=2)
            known = known - statics @ self._buoyancy
        target = log.wrench_land - log.wrench_water - known
        return np.ascontiguousarray(np.concatenate([columns, target[:, :, None]], axis=2).transpose(1, 0, 2))


def _body_up(orientation: Array, n: int) -> Array:
    """``Rᵀ e_z`` ``(n, 3)``: the world's up in body axes, of unit quaternions (world from body)."""
    w, x, y, z = np.broadcast_to(orientation, (n, 4)).T
    return np.stack([2.0 * (x * z - w * y), 2.0 * (y * z + w * x), 1.0 - 2.0 * (x * x + y * y)], axis=1)


def _prepared(entry: Any, inverse: RigidBodyInverse, columns: Any, window_s: float) -> _Item:
    """One free-running log, read and checked (orientation, twist, one command per thruster), its
    rates estimated where absent, with ``ID_RB`` as ``wrench_land`` and ``B T`` as
    ``wrench_water``."""
    robot = inverse.robot
    log = read_whole(entry, robot.n_joints, columns)
    for field, column, what in (
        ("base_twist", "u", "the vehicle's twist u, v, w, p, q, r"),
        ("base_orientation", "qw", "its orientation qw, qx, qy, qz or roll, pitch, yaw"),
    ):
        if getattr(log, field) is None:
            raise ValueError(f"{log.source}: row 1 (header), column {column!r}: missing column (a free-running fit needs {what})")
    check_thruster_commands(log, robot)
    log = log.with_derivatives(window_s)
    rigid = inverse(log)[:, :6]
    log = replace(log, wrench_land=rigid, wrench_water=thrust_wrench(log, robot), wrench=None, tau_land=None, tau_water=None)
    return _Item(log.source, log.n_samples, log=log)


def hull_from_free_running(
    log_or_path: Log | PathOrFile | Sequence[Log | PathOrFile],
    description: Any,
    hydro: Any = None,
    *,
    terms: Iterable[str] = HULL_TERMS,
    hydrostatics: bool = False,
    hold: Iterable[str] = (),
    sigma: ArrayLike | None = None,
    robust: bool = False,
    scale_covar: bool = True,
    columns: Any = None,
    window_s: float = WINDOW_S,
    cache_bytes: int = DESIGN_CACHE_BYTES,
) -> HullFit:
    """Fit the base's lumped model (and its buoyancy) to free-running logs (module docstring).

    Parameters
    ----------
    log_or_path : Log, file, glob pattern, or a list of them
        Logs of the vehicle running free (docs/logs.md): ``time``, the joints ``q1 …`` (the arm,
        still or moving; its ``qd``, ``qdd`` estimated where absent), the orientation (``qw … qz``
        or ``roll, pitch, yaw``), the twist ``u … r`` (its rate ``u_dot … r_dot`` estimated where
        absent) and one command ``u1 … un`` per thruster of the description, fitted together.
    description : path or (mujoco.MjModel, uwml.Robot)
        The vehicle's URDF or MJCF (with ``hydro``, its hydro file, which gives the thrusters and
        the lumped model), floating; or the compiled model with its robot.
    terms : iterable of str
        The families of the base's lumped model whose diagonals are fitted (``HULL_TERMS``).
    hydrostatics : bool
        Fit ``ρV`` and ``ρV r_B`` of the base body too (else the description's).
    hold : iterable of str
        Terms (``base.linear_damping[1][1]``, ``base.rho_volume`` …) held at the description's values.
    sigma : float or 6 floats, optional
        Standard error of each row's data (``fx … mz``) [N, N·m]; None: estimated.
    robust, scale_covar, cache_bytes
        As for :func:`uwml.fit.hydro_coefficients`.
    columns : path, dict or ColumnMap, optional
        A column map every file is read through (:mod:`uwml.io.column_map`).
    window_s : float
        The smoothing fit's window [s] for the rates the logs lack (:mod:`uwml.io.sampling`):
        shorter for fast motions (its bias grows as the window's fourth power), longer for noisy ones.

    Raises
    ------
    ValueError
        A log without the columns the fit needs, or with another number of thruster commands than
        the description has thrusters (naming the column); a description whose base does not
        float or has no lumped model; unknown terms; terms the data do not determine (named).
    """
    model, robot = load_description(description, hydro, floating=True if not isinstance(description, tuple) else None)
    inverse = RigidBodyInverse(model, robot)
    if not inverse.floating:
        raise ValueError("the description's base does not float (its root on a free joint): a free-running vehicle needs it to")
    where = [m for m, (body, _) in enumerate(robot.lumped_models) if body == -1]
    if not where:
        raise ValueError("the description's base has no lumped model (a hydro file's [links.NAME.lumped] on the base): nothing to fit")
    families = list(terms)
    unknown = [family for family in families if family not in HULL_TERMS]
    if unknown or not families:
        raise ValueError(f"terms must be some of {', '.join(HULL_TERMS)}, got {families!r}")
    entries = [i for family in families for i in _diagonal(family)]
    candidates = [f"base.{LUMPED_COEFFICIENTS[i]}" for i in entries] + (list(HYDROSTATIC_TERMS) if hydrostatics else [])
    held = list(hold)
    strangers = [name for name in held if name not in candidates]
    if strangers:
        raise ValueError(f"hold: {', '.join(map(repr, strangers))} not among the terms fitted ({', '.join(candidates)})")
    entries = [i for i in entries if f"base.{LUMPED_COEFFICIENTS[i]}" not in held]
    statics = hydrostatics and not any(name in held for name in HYDROSTATIC_TERMS)
    if hydrostatics and not statics and not all(name in held for name in HYDROSTATIC_TERMS):
        raise ValueError("hold: the hydrostatic terms are held all together or fitted all together")
    if not entries and not statics:
        raise ValueError("every term is held: nothing to fit")
    given = list(log_or_path) if isinstance(log_or_path, list | tuple) else [log_or_path]
    logs = LogSet([_prepared(entry, inverse, columns, window_s) for entry in expand_patterns(given)])
    design = _HullDesign(robot, logs, where[0], entries, statics, cache_bytes)
    state, negative = fit_design(
        design, logs, [-1 - c for c in range(6)], per="lumped", robust=robust, sigma=sigma, scale_covar=scale_covar,
        drop_zero=False, advice="hold them at the description's values (hold=…, --hold) or log motions that excite them",
        physical=lambda name: name == HYDROSTATIC_TERMS[0] or name not in HYDROSTATIC_TERMS, what="hull terms",
    )  # fmt: skip
    described = robot.lumped_models[where[0]][1]
    values = dict(zip([f"base.{n}" for n in LUMPED_COEFFICIENTS], described.coefficients().tolist(), strict=True))
    buoyancy = design._buoyancy.tolist()
    values |= dict(zip(HYDROSTATIC_TERMS, buoyancy, strict=True))
    fixed = {name: values[name] for name in candidates if name not in state["params"]}
    state |= {"params": {name: state["params"].get(name, values[name]) for name in candidates}, "fixed": fixed}
    state |= {"unit": "N or N·m (ID_RB − B T − W_known: forces, then moments)", "per": "lumped"}
    return HullFit(**state, described=described, thrusters=len(robot.thrusters), hydrostatics=statics, negative=negative)
