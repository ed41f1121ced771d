"""Fossen's lumped hydrodynamic model of a bluff body: a vehicle's hull, a battery can, a gripper
(docs/model.md section 12.1).

Strip theory (segments) is for slender parts and has no force along a segment's axis. A body that
is not slender carries a :class:`LumpedModel` instead, or beside its strips: an added-mass matrix,
a linear damping matrix and quadratic damping about a reference point ``P``, all in the body's
frame and relative to the water. With ``ν_r = (v_P − Rᵀc, ω)`` the body's twist relative to the
water at ``P`` in the body's components, the body feels at ``P``

    W = −M_A ν̇_r − C_A(ν_r) ν_r − D_L ν_r − D_Q(ν_r) ν_r,

``C_A`` Fossen's added-mass Coriolis-centripetal matrix, ``D_Q(ν) ν = (d_i |ν_i| ν_i)``.

**Signs.** uwml takes magnitudes as they act: the added mass and damping on the diagonal are
positive numbers. SNAME's hydrodynamic derivatives are their negatives: ``X_u̇ = −M_A[0, 0]``,
``X_u = −D_L[0, 0]``, ``X_u|u| = −d_0``. Entries are ordered ``(x, y, z, roll, pitch, yaw)``,
linear first; units kg, kg·m and kg·m² for ``M_A``, N·s/m, N·s and N·m·s for ``D_L``, kg/m and
kg·m² for the quadratic damping.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike

Vec3 = tuple[float, float, float]

__all__ = [
    "LUMPED_ABSOLUTE_TOLERANCE",
    "LUMPED_COEFFICIENTS",
    "LUMPED_EIGENVALUE_TOLERANCE",
    "LUMPED_SYMMETRY_TOLERANCE",
    "MAX_LUMPED",
    "LumpedModel",
]

#: The largest magnitude of an entry of a lumped model (the core's ``MAX_LUMPED``).
MAX_LUMPED = 1e12

# The tolerances of the checks (docs/model.md section 12.1), the core's constants of the same
# names: an allowed asymmetry of the added mass and an allowed negative eigenvalue are relative to
# the matrix's scale (rounding grows with it) but never more than LUMPED_ABSOLUTE_TOLERANCE, in
# the entries' own units, so that a huge entry cannot hide a wrong small one (at the 1e12 cap, a
# −99 eigenvalue and an asymmetry of 900 passed the relative rule alone). 1e-2 is ten times
# float64's rounding at the cap and far below any physical entry.
#: The allowed asymmetry of the added mass, relative to its largest entry in magnitude.
LUMPED_SYMMETRY_TOLERANCE = 1e-9
#: The allowed negative eigenvalue, relative to the matrix's largest diagonal entry in magnitude.
LUMPED_EIGENVALUE_TOLERANCE = 1e-10
#: The most either tolerance allows, in the entries' units.
LUMPED_ABSOLUTE_TOLERANCE = 1e-2

Matrix6 = tuple[tuple[float, ...], ...]

#: The names of a lumped model's 63 coefficients, in the order of its regressor columns
#: (:attr:`uwml.Regressors.lumped`, :meth:`LumpedModel.coefficients`): the added mass's 21
#: independent entries (upper triangle, row by row: ``added_mass[0][0]``, ``added_mass[0][1]``,
#: …, ``added_mass[5][5]``; an off-diagonal one stands for both of its symmetric entries), the
#: linear damping's 36 (row by row), the quadratic damping's 6. Every entry is in the model's own
#: axes: the forces are linear in each (docs/model.md section 12.1).
LUMPED_COEFFICIENTS: tuple[str, ...] = (
    *(f"added_mass[{i}][{j}]" for i in range(6) for j in range(i, 6)),
    *(f"linear_damping[{i}][{j}]" for i in range(6) for j in range(6)),
    *(f"quadratic_damping[{i}]" for i in range(6)),
)

#: How many of :data:`LUMPED_COEFFICIENTS` are the added mass's (the others are damping).
LUMPED_ADDED_MASS_COEFFICIENTS = 21


def _matrix6(value: object, name: str) -> Matrix6:
    try:
        array = np.array(value, dtype=np.float64)
    except (TypeError, ValueError):
        raise TypeError(f"{name} must be a 6×6 matrix of numbers, got {value!r}") from None
    if array.shape != (6, 6):
        raise ValueError(f"{name} must be a 6×6 matrix, got shape {array.shape}")
    bad = np.argwhere(~np.isfinite(array))
    if bad.size:
        r, c = bad[0]
        raise ValueError(f"{name}[{r}][{c}] must be finite, got {array[r, c]}")
    big = np.argwhere(np.abs(array) > MAX_LUMPED)
    if big.size:
        r, c = big[0]
        raise ValueError(f"{name}[{r}][{c}] must be at most {MAX_LUMPED:g} in magnitude, got {array[r, c]}")
    return tuple(tuple(float(x) for x in row) for row in array)


def _rotation(value: object) -> tuple[tuple[float, ...], ...]:
    """A rotation matrix within 1e-6 (unit, perpendicular, right-handed columns), kept as given."""
    try:
        array = np.array(value, dtype=np.float64)
    except (TypeError, ValueError):
        raise TypeError(f"lumped.axes must be a 3×3 rotation matrix, got {value!r}") from None
    if array.shape != (3, 3) or not np.all(np.isfinite(array)):
        raise ValueError(f"lumped.axes must be a 3×3 rotation matrix of finite numbers, got {value!r}")
    if np.max(np.abs(array.T @ array - np.eye(3))) > 1e-6 or np.linalg.det(array) < 0.0:
        raise ValueError(f"lumped.axes must be a rotation (orthonormal columns, right-handed, within 1e-6), got {array.tolist()}")
    return tuple(tuple(float(x) for x in row) for row in array)


def _tolerance(relative: float, scale: float) -> float:
    """The rule of docs/model.md section 12.1: ``relative × scale``, at most the absolute floor."""
    return min(relative * scale, LUMPED_ABSOLUTE_TOLERANCE)


def _rule(relative: float, scale: float, of: str) -> str:
    return f"min({relative:g} × {scale:g} {of}, {LUMPED_ABSOLUTE_TOLERANCE:g})"


def _check_semidefinite(matrix: np.ndarray, name: str, what: str) -> None:
    """Refuses a symmetric ``matrix`` whose smallest eigenvalue is below the allowed
    ``−min(LUMPED_EIGENVALUE_TOLERANCE × scale, LUMPED_ABSOLUTE_TOLERANCE)``, ``scale`` its largest
    diagonal entry in magnitude."""
    smallest = float(np.linalg.eigvalsh(matrix)[0])
    scale = float(np.max(np.abs(np.diag(matrix))))
    allowed = _tolerance(LUMPED_EIGENVALUE_TOLERANCE, scale)
    if smallest < -allowed:
        raise ValueError(
            f"{name} must {what}; its smallest eigenvalue is {smallest:.6g}, below the allowed {-allowed:g} "
            f"(-{_rule(LUMPED_EIGENVALUE_TOLERANCE, scale, 'its largest diagonal entry')})"
        )


@dataclass(frozen=True)
class LumpedModel:
    """Fossen's lumped model of one body (see the module), in the body's frame.

    ``point``: the reference point ``P`` [m] (None: the body's centre of buoyancy, resolved when
    the model is given to a :class:`uwml.Link`). ``axes``: the model's axes in the body's frame,
    a 3×3 rotation whose columns are its x, y, z (default the identity: the body's own axes); the
    matrices and the quadratic damping are in these axes. ``added_mass``: ``M_A`` about ``P``, 6×6,
    symmetric and positive semi-definite. ``linear_damping``: ``D_L`` about ``P``, 6×6, its
    symmetric part positive semi-definite. ``quadratic_damping``: the six ``d_i ≥ 0``. Each
    defaults to zero.
    """

    point: Vec3 | None = None
    added_mass: ArrayLike = field(default_factory=lambda: np.zeros((6, 6)))
    linear_damping: ArrayLike = field(default_factory=lambda: np.zeros((6, 6)))
    quadratic_damping: ArrayLike = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    axes: ArrayLike = ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))

    def __post_init__(self) -> None:
        if self.point is not None:
            try:
                point = np.array(self.point, dtype=np.float64)
            except (TypeError, ValueError):
                raise TypeError(f"lumped.point must be 3 numbers, got {self.point!r}") from None
            if point.shape != (3,) or not np.all(np.isfinite(point)):
                raise ValueError(f"lumped.point must be 3 finite numbers, got {self.point!r}")
            object.__setattr__(self, "point", (float(point[0]), float(point[1]), float(point[2])))
        object.__setattr__(self, "axes", _rotation(self.axes))
        added_mass = _matrix6(self.added_mass, "lumped.added_mass")
        array = np.array(added_mass)
        asymmetry = np.abs(array - array.T)
        scale = float(np.max(np.abs(array)))
        allowed = _tolerance(LUMPED_SYMMETRY_TOLERANCE, scale)
        if np.any(asymmetry > allowed):
            r, c = np.unravel_index(int(np.argmax(asymmetry)), asymmetry.shape)
            raise ValueError(
                f"lumped.added_mass must be symmetric within {allowed:g} ({_rule(LUMPED_SYMMETRY_TOLERANCE, scale, 'its largest entry')}): "
                f"[{r}][{c}] = {array[r, c]} but [{c}][{r}] = {array[c, r]}"
            )
        symmetric = 0.5 * (array + array.T)
        _check_semidefinite(symmetric, "lumped.added_mass", "be positive semi-definite (no direction of negative energy)")
        object.__setattr__(self, "added_mass", tuple(tuple(float(x) for x in row) for row in symmetric))
        damping = _matrix6(self.linear_damping, "lumped.linear_damping")
        array = np.array(damping)
        _check_semidefinite(
            0.5 * (array + array.T),
            "lumped.linear_damping",
            "have a positive semi-definite symmetric part (no direction in which it feeds energy in)",
        )
        object.__setattr__(self, "linear_damping", damping)
        try:
            quadratic = tuple(float(x) for x in np.asarray(self.quadratic_damping, dtype=np.float64).reshape(-1))
        except (TypeError, ValueError):
            raise TypeError(f"lumped.quadratic_damping must be 6 numbers, got {self.quadratic_damping!r}") from None
        if len(quadratic) != 6:
            raise ValueError(f"lumped.quadratic_damping must be 6 numbers, got {len(quadratic)}")
        for index, d in enumerate(quadratic):
            if not math.isfinite(d) or d < 0.0:
                raise ValueError(f"lumped.quadratic_damping[{index}] must be finite and non-negative, got {d}")
            if d > MAX_LUMPED:
                raise ValueError(f"lumped.quadratic_damping[{index}] must be at most {MAX_LUMPED:g}, got {d}")
        object.__setattr__(self, "quadratic_damping", quadratic)

    def coefficients(self) -> np.ndarray:
        """The model's 63 coefficients in the order of :data:`LUMPED_COEFFICIENTS`: with the
        regressors' lumped columns, ``Σ columns × coefficients`` is the model's forces."""
        upper = np.triu_indices(6)
        return np.concatenate(
            [np.asarray(self.added_mass)[upper], np.asarray(self.linear_damping).reshape(-1), np.asarray(self.quadratic_damping)]
        )

    def at(self, point: Vec3) -> LumpedModel:
        """This model with ``point`` as its reference point where it has none."""
        return self if self.point is not None else dataclasses.replace(self, point=point)
