"""What the two equation-error fits without a land run share (:mod:`uwml.fit.water_only`,
:mod:`uwml.fit.free_running`): a log read whole with its joints checked, and the fit of a design
(:class:`uwml.fit.design._HydroDesign`) with the checks around it: the terms the data do not
determine refused by name before (:mod:`uwml.fit.determinacy`), the weighted least squares of
:func:`uwml.fit.hydro_coefficients` (:func:`uwml.fit.hydro._fit`), the terms that came out
negative named after.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from ..io.logs import Log, read_log
from .design import _HydroDesign
from .determinacy import check_determined, row_normalized_gram, warn_negative
from .hydro import HydroFit, _fit
from .log_set import LogSet, _check_joints

__all__ = ["fit_design", "read_whole"]


def read_whole(entry: Any, n_joints: int, columns: Any) -> Log:
    """A :class:`uwml.io.logs.Log` as it is, or a file read whole (through the column map
    ``columns``), with ``n_joints`` joints (else a ValueError naming the column)."""
    log = entry if isinstance(entry, Log) else read_log(entry, n_joints, columns=columns)
    _check_joints(log.source, log.n_joints, n_joints, "the description")
    return log


def fit_design(
    design: _HydroDesign,
    logs: LogSet,
    selected: list[int],
    *,
    per: str,
    robust: bool,
    sigma: ArrayLike | None,
    scale_covar: bool,
    drop_zero: bool,
    advice: str,
    physical: Callable[[str], bool],
    what: str,
) -> tuple[dict[str, Any], tuple[str, ...]]:
    """The fit of ``design`` on the rows ``selected`` (``j ≥ 0`` joint ``j``, ``-1 … -6`` the base's
    ``fx … mz``), as the fields of a :class:`uwml.fit.HydroFit`, and the terms of ``physical``
    that came out negative (``what`` they are, for the warning). Columns that are zero on every
    sample are dropped (``drop_zero``) or refused with the others the data do not determine
    (``advice``: what to do then)."""
    gram = design.moments().gram
    keep = np.diag(gram.sum(axis=0)) > 0.0 if drop_zero else np.ones(len(design.names), dtype=bool)
    kept = [name for name, k in zip(design.names, keep, strict=True) if k]
    check_determined(row_normalized_gram(gram[:, keep][:, :, keep]), kept, logs.source, advice)
    given: Any = None
    if sigma is not None:
        given = np.broadcast_to(np.asarray(sigma, dtype=np.float64), (len(selected),)) if np.ndim(sigma) <= 1 else None
        if given is None or not np.all(np.isfinite(given)) or np.any(given <= 0.0):
            raise ValueError(f"sigma must be a positive number or one per fitted row ({len(selected)}), got {sigma!r}")
    joints = [j for j in selected if j >= 0]
    components = [-1 - j for j in selected if j < 0]
    result = _fit(design, logs, selected, joints, components, per, robust, sigma is not None, given, scale_covar)
    negative = warn_negative(result.params, result.stderr, [name for name in result.var_names if physical(name)], what)
    return {field.name: getattr(result, field.name) for field in dataclasses.fields(HydroFit)}, negative
