"""The identification design of a whole :class:`uwml.Robot` (docs/model.md sections 4, 10 and
12): the whole-robot core's regressors (:meth:`uwml.Robot.hydro_regressors`) summed into the
coefficients fitted, on the selected rows (joints, and the base's wrench components), with the
target ``y = −Δ − buoyancy`` of each row (``Δ`` the motor torque's or the rig's wrench's
water-minus-land difference).

The coefficients:

* ``cd`` and ``cm`` per ``per`` (the robot, each body, each body and normal direction), named
  ``cd``, ``cd_<body>``, ``cd_<body>_n<d>``: bodies are the base (``base``, if it has segments)
  and every link (its name, else ``link<i>``); a circular segment counts in ``n0``;
* ``cd_axial`` (or ``cd_axial_<body>`` per body) where segments have an axial drag
  (docs/model.md section 12.2: ``cd_axial > 0``);
* each lumped model's entries (section 12.1), named ``<body>.added_mass[i][j]``,
  ``<body>.linear_damping[i][j]``, ``<body>.quadratic_damping[i]`` (in the model's own axes):
  its diagonals (``lumped="diagonal"``: ``M_A`` and ``D_L`` on their diagonal and the six
  quadratic dampings, Fossen's decoupled model), every entry (``"full"``: 63), or the entries
  that are not zero in the robot's model (``"given"``).

Where the columns are the segments' Cd and Cm alone on the joints of a robot on a fixed base (no
base rows, no segments on the base, no axial drag, no lumped model, no base twist in the log),
the core assembles them in one pass over the samples (``uwml._core.Robot.hydro_design``, four
states per evaluation), the same columns as the regressors give.
"""

from __future__ import annotations

import numpy as np

from ..io.logs import Log
from ..model.lumped import LUMPED_COEFFICIENTS
from ..model.parts import Water
from ..robot.base_motion import BaseMotion
from ..robot.evaluation_conditions import Conditions
from ..robot.tree import Robot
from . import design
from ._types import Array
from .design import _HydroDesign
from .log_set import LogSet

#: The base wrench's components, the rows ``0 … 5`` of the regressors.
BASE_ROWS = ("fx", "fy", "fz", "mx", "my", "mz")
#: The families of the base's lumped model a hull fit takes (their diagonals;
#: :func:`uwml.fit.hull_from_free_running`).
HULL_TERMS = ("added_mass", "linear_damping", "quadratic_damping")
#: The hydrostatic terms of a hull fit: ρV [kg], then ρV r_B [kg·m].
HYDROSTATIC_TERMS = ("base.rho_volume", "base.rho_volume_cob[0]", "base.rho_volume_cob[1]", "base.rho_volume_cob[2]")
#: The lumped columns of ``lumped="diagonal"``: M_A[i][i], D_L[i][i] and the quadratic dampings.
_DIAGONAL = tuple(
    index
    for index, name in enumerate(LUMPED_COEFFICIENTS)
    if name.startswith("quadratic") or name.split("[")[1].rstrip("]") == name.split("[")[2].rstrip("]")
)


class _RobotHydroDesign(_HydroDesign):
    """The design of a :class:`uwml.Robot` (module docstring) on the rows ``rows`` of its
    regressors (``0 … 5`` the base wrench's components, ``6 + j`` joint ``j``), its base moving as
    the log says (``base_twist``; fixed and upright without one)."""

    #: Bytes of regressors (all rows and columns, drag and added mass) per chunk.
    REGRESSOR_BYTES = 1 << 26

    def __init__(
        self, robot: Robot, log: LogSet, water: Water, per: str, rows: list[int], cache_bytes: int, lumped: str = "diagonal"
    ) -> None:
        self._robot = robot
        owners = [-1] * (len(robot.base.segments) if robot.base is not None else 0)
        owners += [i for i, link in enumerate(robot.links) for _ in link.segments]
        bodies = ([-1] if owners and owners[0] == -1 else []) + list(range(robot.n_joints))
        labels = {b: _label(robot, b) for b in range(-1, robot.n_joints)}
        n_segments = len(owners)
        if per == "leg":
            columns = [(k, d, 0) for k in range(n_segments) for d in range(2)]
            half = [""]
        elif per == "link":
            columns = [(k, d, bodies.index(o)) for k, o in enumerate(owners) for d in range(2)]
            half = [f"_{labels[b]}" for b in bodies]
        else:
            columns = [(k, d, 2 * bodies.index(o) + d) for k, o in enumerate(owners) for d in range(2)]
            half = [f"_{labels[b]}_n{d}" for b in bodies for d in range(2)]
        # (segment, direction) -> column of one half (the Cd half or the Cm half).
        self._map = np.zeros((n_segments * 2, len(half)))
        for k, d, column in columns:
            self._map[2 * k + d, column] = 1.0
        names = [f"{prefix}{suffix}" for prefix in ("cd", "cm") for suffix in half]
        # The axial drag: segments that have one, summed as the Cd of `per` (never per direction).
        axial_owners = [o for o, segment in zip(owners, robot.segments, strict=True) if segment.cd_axial > 0.0]
        axial_bodies = sorted(set(axial_owners), key=lambda b: bodies.index(b)) if per != "leg" else ([0] if axial_owners else [])
        self._axial_map = np.zeros((n_segments, len(axial_bodies)))
        for k, (o, segment) in enumerate(zip(owners, robot.segments, strict=True)):
            if segment.cd_axial > 0.0:
                self._axial_map[k, 0 if per == "leg" else axial_bodies.index(o)] = 1.0
        names += ["cd_axial"] if per == "leg" and axial_bodies else [f"cd_axial_{labels[b]}" for b in axial_bodies]
        # The lumped models' selected entries: (model, entry) per column.
        self._lumped_columns = [
            (m, i) for m, (_, model) in enumerate(robot.lumped_models) for i in _lumped_entries(model.coefficients(), lumped)
        ]
        names += [f"{labels[robot.lumped_models[m][0]]}.{LUMPED_COEFFICIENTS[i]}" for m, i in self._lumped_columns]
        self._setup(log, water, per, rows, cache_bytes, names)
        width = 3 * n_segments + 63 * len(robot.lumped_models)
        self._rows = max(64, self.REGRESSOR_BYTES // (2 * (6 + robot.n_joints) * max(width, 1) * 8))
        #: Whether the core's one-pass design gives these columns (module docstring).
        self._one_pass = not names[2 * len(half) :] and owners[:1] != [-1] and all(r >= 6 for r in rows)
        self._conditions = Conditions(water=water)

    def _chunk_samples(self) -> int:
        return design.CHUNK_SAMPLES if self._one_pass else min(design.CHUNK_SAMPLES, self._rows)

    def _compute(self, log: Log) -> Array:
        robot = self._robot
        assert log.qd is not None and log.qdd is not None
        if self._one_pass and log.base_twist is None:
            assert log.tau_land is not None and log.tau_water is not None
            q, qd, qdd = (np.ascontiguousarray(a, dtype=np.float64) for a in (log.q, log.qd, log.qdd))
            delta = np.ascontiguousarray(log.tau_water - log.tau_land, dtype=np.float64)
            joints = [row - 6 for row in self._joints]
            one_pass: Array = robot._core.hydro_design(q, qd, qdd, delta, robot._native(self._conditions), joints, self._per)
            return one_pass
        motion = None if log.base_twist is None else BaseMotion(**log.base_motion())
        regressors = robot.hydro_regressors(log.q, log.qd, log.qdd, water=self._water, base_motion=motion)
        n = log.n_samples
        selected = self._joints

        def every_row(base: Array, joints: Array) -> Array:
            """The base's rows and the joints', then the selected ones: ``(n, rows, ...)``."""
            both: Array = np.concatenate([base, joints], axis=1)
            return both[:, selected]

        def summed(base: Array, joints: Array, mapping: Array) -> Array:
            return every_row(base, joints).reshape(n, len(selected), -1) @ mapping

        lumped = every_row(regressors.base_lumped, regressors.lumped)
        picked = (
            np.stack([lumped[:, :, m, i] for m, i in self._lumped_columns], axis=2)
            if self._lumped_columns
            else np.zeros((n, len(selected), 0))
        )
        delta = np.zeros((n, 6 + robot.n_joints))
        for offset, land, water in ((0, log.wrench_land, log.wrench_water), (6, log.tau_land, log.tau_water)):
            if land is not None and water is not None:
                delta[:, offset : offset + land.shape[1]] = water - land
        buoyancy = np.concatenate([regressors.base_buoyancy, regressors.buoyancy], axis=1)
        target = (-delta - buoyancy)[:, selected]
        problem = np.concatenate(
            [
                summed(regressors.base_drag, regressors.drag, self._map),
                summed(regressors.base_added_mass, regressors.added_mass, self._map),
                every_row(regressors.base_axial_drag, regressors.axial_drag) @ self._axial_map,
                picked,
                target[:, :, None],
            ],
            axis=2,
        )
        return np.ascontiguousarray(problem.transpose(1, 0, 2))


def _label(robot: Robot, body: int) -> str:
    """A body's name in the coefficients' names: ``base``, else the link's name or ``link<i>``."""
    return "base" if body < 0 else (robot.links[body].name or f"link{body}")


def _lumped_entries(coefficients: Array, lumped: str) -> list[int]:
    """The lumped columns fitted (module docstring)."""
    if lumped == "full":
        return list(range(len(LUMPED_COEFFICIENTS)))
    if lumped == "given":
        return [int(i) for i in np.flatnonzero(coefficients)]
    return list(_DIAGONAL)
