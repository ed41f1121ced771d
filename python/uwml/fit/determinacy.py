"""What a linear identification's data determine, checked before it is fitted, and what its
result must respect after (docs/identification.md, "A hull from free-running logs"): a term
whose regressor is zero on every sample, or a group of terms whose columns are (nearly)
collinear, is refused by name; a coefficient that physics says is not negative (a damping, an
added mass, a drag coefficient, a loss level) and came out negative is named in a
:class:`uwml.PlausibilityWarning`.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Iterable, Mapping, Sequence

import numpy as np

from ..plausibility import PlausibilityWarning
from ._types import Array

__all__ = ["CONDITION_LIMIT", "ROUNDING", "check_determined", "row_normalized_gram", "warn_negative"]

#: The largest condition number of the regressor columns, each scaled to unit norm, that a fit
#: takes: beyond it a standard error can be ten thousand times what the same data would give
#: the term alone, and the terms involved are refused by name.
CONDITION_LIMIT = 1e4
#: A term is negative when it is below this fraction of its family's largest magnitude (less is
#: rounding: an exact fit of a zero term gives about ±1e-13).
ROUNDING = 1e-9
#: A term is named among the undetermined ones when its share of a near-null direction of the
#: scaled columns is at least this (of the largest share).
_SHARE = 0.1


def row_normalized_gram(grams: Array) -> Array:
    """``Σ_j XⱼᵀXⱼ / max diag(XⱼᵀXⱼ)`` of per-row Gram matrices ``(J, P, P)``: rows of different
    units (forces and moments, or joints) weighed alike before their weights are estimated."""
    peaks = np.max(np.diagonal(grams, axis1=1, axis2=2), axis=1)
    weights = np.where(peaks > 0.0, 1.0 / np.where(peaks > 0.0, peaks, 1.0), 0.0)
    total: Array = np.einsum("j,jab->ab", weights, grams)
    return total


def check_determined(gram: Array, names: Sequence[str], what: str, advice: str) -> None:
    """A ValueError naming the terms that the data do not determine (module docstring): those
    whose column is zero, else the groups of nearly collinear columns (condition number of the
    unit-norm columns above ``CONDITION_LIMIT``). ``what`` says whose data they are, ``advice``
    what to do."""
    diagonal = np.diag(gram)
    zero = [name for name, value in zip(names, diagonal, strict=True) if not value > 0.0]
    if zero:
        raise ValueError(
            f"{what}: the data do not determine {', '.join(zero)}: their regressors are zero on every sample "
            f"(the log never excites them); {advice}"
        )
    scale = np.sqrt(diagonal)
    eigenvalues, vectors = np.linalg.eigh(gram / np.outer(scale, scale))
    largest = float(eigenvalues[-1])
    limit = largest / CONDITION_LIMIT**2
    if eigenvalues[0] > limit:
        return
    weak: list[str] = []
    for k in np.flatnonzero(eigenvalues <= limit):
        share = np.abs(vectors[:, k])
        for i in np.argsort(-share):
            if share[i] >= _SHARE * share.max() and names[i] not in weak:
                weak.append(names[i])
    condition = math.sqrt(largest / eigenvalues[0]) if eigenvalues[0] > 0.0 else math.inf
    raise ValueError(
        f"{what}: the data do not determine {', '.join(weak)} apart: their regressor columns are nearly collinear "
        f"(condition number {condition:.3g} of the columns scaled to unit norm, above {CONDITION_LIMIT:g}); {advice}"
    )


def warn_negative(params: Mapping[str, float], stderr: Mapping[str, float | None], names: Iterable[str], what: str) -> tuple[str, ...]:
    """The terms of ``names`` that came out negative beyond rounding (below ``−ROUNDING`` times the
    largest magnitude of their family, the name before its first ``[``: a zero fitted exactly
    comes out as ±1e-13), each named with its value and standard error in one
    :class:`uwml.PlausibilityWarning` (``what``: what they are); empty if none."""
    names = list(names)
    largest: dict[str, float] = {}
    for name in names:
        family = name.split("[")[0]
        largest[family] = max(largest.get(family, 0.0), abs(params[name]))
    negative = tuple(name for name in names if params[name] < -ROUNDING * largest[name.split("[")[0]])
    if negative:
        shown = []
        for name in negative:
            error = stderr.get(name)
            shown.append(f"{name} = {params[name]:.4g}" + ("" if error is None else f" ± {error:.2g}"))
        warnings.warn(
            f"{what} came out negative, which is not physical: {'; '.join(shown)}. A value within a few standard errors "
            "of zero says the data hardly determine it (hold it at a known value); one far below zero, a model or log error "
            "(a sign, a unit, the thrust curve, the rigid-body inertia)",
            PlausibilityWarning,
            stacklevel=4,
        )
    return negative
