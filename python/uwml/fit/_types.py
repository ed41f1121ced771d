"""Type aliases of the identification modules."""

from __future__ import annotations

import os
from typing import IO, Any

import numpy as np
from numpy.typing import NDArray

Array = NDArray[np.float64]
Columns = dict[str, NDArray[Any]]
PathOrFile = str | os.PathLike[str] | IO[str]
