"""Input checks shared by the pure-Python modules."""

import numpy as np
from numpy.typing import ArrayLike, NDArray


def finite_array(value: ArrayLike, name: str) -> NDArray[np.float64]:
    """``value`` as a float64 array of finite numbers, or a ValueError naming ``name``."""
    try:
        a = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{name} must be a number or an array of numbers, got {value!r}") from exc
    if not np.all(np.isfinite(a)):
        raise ValueError(f"{name} must be finite")
    return a
