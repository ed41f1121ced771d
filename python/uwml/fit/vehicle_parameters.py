"""The parameters an output-error fit of a free-floating vehicle may choose (docs/model.md section
13, "13.3 Identifying a vehicle"; docs/identification.md, "A vehicle from free-floating
trials"): entries of the hull's lumped model and its trim, by name, with their bounds and how
they change the vehicle. The hull is the robot's base body with a lumped model (docs/model.md
section 12.1).

=========================  ==============================================================
name                       meaning
=========================  ==============================================================
``added_mass[i]``          ``M_A[i][i]`` of the hull's lumped model, ``i`` 0 … 5 for x, y,
                           z, roll, pitch, yaw (the model's axes) [kg, kg·m²]
``linear_damping[i]``      ``D_L[i][i]`` [N·s/m, N·m·s]
``quadratic_damping[i]``   ``d_i`` [kg/m, kg·m²]
``cob_x``, ``cob_y``,      the offset of the hull's centre of buoyancy from the
``cob_z``                  description's, in the base's frame [m] (trim: the buoyancy's
                           point moves; the lumped model's reference point stays where the
                           description put it)
``volume``                 the hull's displaced volume [m³] (its buoyancy ``ρ V g``)
=========================  ==============================================================

Default bounds: the lumped entries and the volume at least 0, unbounded above (a lumped model
refuses a negative diagonal; a lower bound below 0 is refused); the centre of buoyancy within
``±COB_OFFSET_BOUND`` of the description's. Everything not chosen keeps the description's value.

This module imports neither scipy nor MuJoCo (the command line's parser takes its names).
"""

from __future__ import annotations

import dataclasses
import math
import re
from collections.abc import Iterable, Mapping, Sequence

import numpy as np

from ..model.lumped import LumpedModel
from ..model.parts import Link

__all__ = [
    "COB_OFFSET_BOUND",
    "LUMPED_PARAMETERS",
    "TRIM_PARAMETERS",
    "VEHICLE_PARAMETERS",
    "check_bounds",
    "check_parameters",
    "described_values",
    "typical_scale",
    "with_parameters",
]

#: The lumped model's families whose diagonal entries may be fitted, each ``family[i]``.
LUMPED_PARAMETERS = ("added_mass", "linear_damping", "quadratic_damping")
#: The trim's parameters: the centre of buoyancy's offset [m], the displaced volume [m³].
TRIM_PARAMETERS = ("cob_x", "cob_y", "cob_z", "volume")
#: Every parameter name an output-error fit of a vehicle takes (the module's table).
VEHICLE_PARAMETERS: tuple[str, ...] = (*(f"{family}[{i}]" for family in LUMPED_PARAMETERS for i in range(6)), *TRIM_PARAMETERS)
#: The default bounds of a centre of buoyancy's offset: ± this [m] from the description's.
COB_OFFSET_BOUND = 0.1

_LUMPED_NAME = re.compile(r"(added_mass|linear_damping|quadratic_damping)\[([0-5])\]")


def check_parameters(names: Iterable[str]) -> list[str]:
    """``names`` as a list, each one of :data:`VEHICLE_PARAMETERS` and none twice; else a
    ValueError that lists the allowed names."""
    if isinstance(names, str):
        names = [names]
    chosen = list(names)
    unknown = [name for name in chosen if name not in VEHICLE_PARAMETERS]
    if unknown or not chosen:
        what = f"unknown parameter{'s' if len(unknown) > 1 else ''} {', '.join(map(repr, unknown))}" if unknown else "no parameter"
        raise ValueError(
            f"{what}: choose from {', '.join(VEHICLE_PARAMETERS)} (the hull's diagonal entries, i = 0 … 5 for x, y, z, roll, "
            "pitch, yaw; the centre of buoyancy's offset [m]; the displaced volume [m³])"
        )
    twice = sorted({name for name in chosen if chosen.count(name) > 1})
    if twice:
        raise ValueError(f"parameters must be distinct; {', '.join(map(repr, twice))} given more than once")
    return chosen


def _lumped(name: str) -> tuple[str, int] | None:
    """``(family, i)`` of a lumped parameter's name, None for a trim parameter."""
    match = _LUMPED_NAME.fullmatch(name)
    return None if match is None else (match.group(1), int(match.group(2)))


def described_values(base: Link, names: Sequence[str]) -> np.ndarray:
    """The description's value of each parameter of ``names`` on the hull ``base`` (a
    :class:`uwml.Link` with a lumped model): its diagonal entries, 0 for the offsets, its volume."""
    assert base.lumped is not None
    values = []
    for name in names:
        lumped = _lumped(name)
        if lumped is None:
            values.append(float(base.volume) if name == "volume" else 0.0)
            continue
        family, i = lumped
        entry = getattr(base.lumped, family)
        values.append(float(entry[i]) if family == "quadratic_damping" else float(entry[i][i]))
    return np.array(values, dtype=np.float64)


def typical_scale(name: str) -> float:
    """The size below which a parameter's finite-difference step stops shrinking with its
    value: 1 (kg, N·s/m, …) for a lumped entry, 0.01 m for an offset, 1e-3 m³ for a volume."""
    if _lumped(name) is not None:
        return 1.0
    return 1e-3 if name == "volume" else 0.01


def check_bounds(
    names: Sequence[str], start: np.ndarray, bounds: Mapping[str, tuple[float, float]] | None
) -> tuple[np.ndarray, np.ndarray]:
    """``(lower, upper)`` of the parameters ``names`` (the module's defaults, replaced by
    ``bounds``' entries), checked: numbers, ``lower < upper``, no negative lower bound of a lumped
    entry or a volume, and the start ``start`` within them (each refused by name)."""
    given = dict(bounds or {})
    strangers = [name for name in given if name not in names]
    if strangers:
        raise ValueError(f"bounds: {', '.join(map(repr, strangers))} not among the parameters fitted ({', '.join(names)})")
    lower, upper = np.empty(len(names)), np.empty(len(names))
    for k, name in enumerate(names):
        default = (-COB_OFFSET_BOUND, COB_OFFSET_BOUND) if name.startswith("cob_") else (0.0, math.inf)
        pair = given.get(name, default)
        try:
            low, high = (float(x) for x in pair)
        except (TypeError, ValueError):
            raise ValueError(f"bounds[{name!r}] must be two numbers (lower, upper), got {pair!r}") from None
        if math.isnan(low) or math.isnan(high) or not low < high:
            raise ValueError(f"bounds[{name!r}] must be (lower, upper) with lower < upper, got {pair!r}")
        if not name.startswith("cob_") and low < 0.0:
            raise ValueError(
                f"bounds[{name!r}]: the lower bound {low:g} is below 0; a hull's diagonal damping, added mass or volume is not "
                "negative (a lumped model refuses it)"
            )
        if not low <= start[k] <= high:
            raise ValueError(f"bounds[{name!r}] = ({low:g}, {high:g}) does not contain the start {start[k]:g}: widen them or start inside")
        lower[k], upper[k] = low, high
    return lower, upper


def with_parameters(base: Link, names: Sequence[str], values: Sequence[float] | np.ndarray) -> Link:
    """The hull ``base`` with the parameters ``names`` set to ``values`` (the module's table;
    an offset moves the centre of buoyancy from ``base``'s by that much)."""
    assert base.lumped is not None and base.cob is not None
    added = np.array(base.lumped.added_mass, dtype=np.float64)
    linear = np.array(base.lumped.linear_damping, dtype=np.float64)
    quadratic = np.array(base.lumped.quadratic_damping, dtype=np.float64)
    cob, volume = np.array(base.cob, dtype=np.float64), float(base.volume)
    for name, value in zip(names, values, strict=True):
        lumped = _lumped(name)
        if lumped is not None:
            family, i = lumped
            if family == "quadratic_damping":
                quadratic[i] = value
            else:
                (added if family == "added_mass" else linear)[i, i] = value
        elif name == "volume":
            volume = float(value)
        else:
            cob["xyz".index(name[-1])] += value
    model: LumpedModel = dataclasses.replace(base.lumped, added_mass=added, linear_damping=linear, quadratic_damping=quadratic)
    point = (float(cob[0]), float(cob[1]), float(cob[2]))
    return dataclasses.replace(base, lumped=model, cob=point, volume=volume)
