"""Input checking shared by the modules of :mod:`uwml.reference` (numpy and the standard library only)."""

import math
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

Array = NDArray[np.float64]
Vec3 = tuple[float, float, float]

#: Tolerance on unit length and orthogonality of axes and normals.
_AXIS_TOLERANCE = 1e-6

# A lumped model's tolerances (docs/model.md section 12.1; the core's and uwml.model.lumped's
# constants of the same names, restated here so that the reference stays numpy-only): the allowed
# asymmetry of the added mass and the allowed negative eigenvalue are the relative tolerance times
# the matrix's scale, but never more than the absolute floor, in the entries' units (a huge entry
# must not hide a wrong small one).
_LUMPED_SYMMETRY_TOLERANCE = 1e-9
_LUMPED_EIGENVALUE_TOLERANCE = 1e-10
_LUMPED_ABSOLUTE_TOLERANCE = 1e-2


def _lumped_tolerance(relative: float, scale: float) -> float:
    """``relative × scale``, at most ``_LUMPED_ABSOLUTE_TOLERANCE``."""
    return min(relative * scale, _LUMPED_ABSOLUTE_TOLERANCE)


def _vector(value: Any, name: str, *, unit: bool = False) -> Array:
    try:
        v = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{name} must be 3 numbers, got {value!r}") from exc
    if v.shape != (3,) or not np.all(np.isfinite(v)):
        raise ValueError(f"{name} must be 3 finite numbers, got {value!r}")
    if unit and abs(float(np.linalg.norm(v)) - 1.0) > _AXIS_TOLERANCE:
        raise ValueError(f"{name} must be a unit vector, got norm {np.linalg.norm(v)}")
    return v


def _number(value: Any, name: str, *, positive: bool) -> float:
    try:
        x = float(value)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{name} must be a number, got {value!r}") from exc
    if not math.isfinite(x) or (x <= 0.0 if positive else x < 0.0):
        raise ValueError(f"{name} must be finite and {'> 0' if positive else '>= 0'}, got {value!r}")
    return x


def _states(q: ArrayLike, qd: ArrayLike, qdd: ArrayLike, n: int) -> tuple[tuple[int, ...], Array, Array, Array]:
    """Check the joint states and flatten them to (samples, n)."""
    arrays = []
    for name, value in (("q", q), ("qd", qd), ("qdd", qdd)):
        try:
            a = np.asarray(value, dtype=np.float64)
        except (TypeError, ValueError) as exc:
            raise ValueError(f"{name} must be an array of numbers, got {value!r}") from exc
        if a.ndim == 0 or a.shape[-1] != n:
            raise ValueError(f"{name} must have shape (n,) or (m, n) with n = {n} joints, got shape {a.shape}")
        if not np.all(np.isfinite(a)):
            raise ValueError(f"{name} must be finite")
        arrays.append(a)
    if not arrays[0].shape == arrays[1].shape == arrays[2].shape:
        raise ValueError(f"q, qd and qdd must have the same shape, got {arrays[0].shape}, {arrays[1].shape}, {arrays[2].shape}")
    shape = arrays[0].shape
    q2, qd2, qdd2 = (a.reshape(-1, n) for a in arrays)
    return shape, q2, qd2, qdd2
