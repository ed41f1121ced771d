"""A hydro file's masses (docs/model.md section 13): a link's mass override (``mass``, ``com``,
``inertia`` on ``[links.NAME]``) and its point items (``[[links.NAME.items]]``: lead, foam, a
DVL, a battery), read and checked for :mod:`uwml.io.hydrofile`. Every vector is in the link's
description frame; errors name the file, the table and the key."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from .._checks import Vec3, shown
from ..domains import MAX_LENGTH, MAX_MASS, MAX_VOLUME
from ._description_io import DescriptionError
from ._model_tables import _float, _Reader, _vec3

__all__ = ["MAX_ITEMS", "HydroItem", "read_items", "read_override"]

#: The most point items a link takes (a hydro file's ``[[links.NAME.items]]``).
MAX_ITEMS = 64
#: The largest moment of inertia taken [kg·m²]: the largest mass at the largest distance.
MAX_INERTIA = MAX_MASS * MAX_LENGTH * MAX_LENGTH
_ITEM_KEYS = ("name", "mass", "volume", "position", "inertia")
#: The longest item name (a label in messages and in ``uwml describe``, never code).
_MAX_NAME = 60


@dataclass(frozen=True)
class HydroItem:
    """A point item on a link (docs/model.md section 13): its mass [kg] and displaced volume [m³]
    at ``position`` [m] (the link's description frame), and its own principal moments of inertia
    about that point along the frame's axes [kg·m²] (None: a point, none of its own)."""

    mass: float
    volume: float
    position: Vec3
    name: str | None = None
    inertia: Vec3 | None = None


def _bounded(value: Any, high: float, unit: str) -> float:
    x = _float(value)
    if not (math.isfinite(x) and 0.0 <= x <= high):
        raise ValueError(f"between 0 and {high:g} {unit}")
    return x


def _mass(value: Any) -> float:
    return _bounded(value, MAX_MASS, "kg")


def _positive_mass(value: Any) -> float:
    x = _mass(value)
    if x <= 0.0:
        raise ValueError("positive: a link's mass (give the link no override to keep the description's)")
    return x


def _volume(value: Any) -> float:
    return _bounded(value, MAX_VOLUME, "m³")


def _point(value: Any) -> Vec3:
    """A point [m]: finite coordinates within ``MAX_LENGTH``."""
    point = _vec3(value)
    if not all(math.isfinite(x) and abs(x) <= MAX_LENGTH for x in point):
        raise ValueError(f"each coordinate finite, at most {MAX_LENGTH:g} m in magnitude")
    return point


def _moments(value: Any, positive: bool) -> Vec3:
    """Three principal moments [kg·m²]: finite, at least 0 (above 0 if ``positive``), each at most
    the sum of the other two (a real body's: the triangle inequality)."""
    moments = _vec3(value)
    low = "above 0" if positive else "at least 0"
    if not all(math.isfinite(x) and (x > 0.0 if positive else x >= 0.0) and x <= MAX_INERTIA for x in moments):
        raise ValueError(f"each moment finite, {low}, at most {MAX_INERTIA:g} kg·m²")
    a, b, c = moments
    slack = 1e-12 * max(moments)
    for name, one, others in (("ixx", a, b + c), ("iyy", b, a + c), ("izz", c, a + b)):
        if one > others + slack:
            raise ValueError(f"{name} at most the sum of the other two (a real body's moments obey the triangle inequality)")
    return moments


def _name(value: Any) -> str:
    if not isinstance(value, str):
        raise TypeError("not a string")
    if not value or len(value) > _MAX_NAME or not value.isprintable():
        raise ValueError(f"1 to {_MAX_NAME} printable characters")
    return value


def read_override(r: _Reader) -> tuple[float | None, Vec3 | None, Vec3 | None]:
    """A link table's ``mass``, ``com`` and ``inertia`` (None where not given): the link's
    inertial in place of the description's (``com`` and ``inertia`` need ``mass``)."""
    mass = r.get("mass", _positive_mass, f"a mass [kg], above 0, at most {MAX_MASS:g}", required=False)
    com = r.get("com", _point, "an array of 3 numbers [m]", required=False)
    inertia = r.get("inertia", lambda v: _moments(v, positive=True), "[ixx, iyy, izz] [kg·m²] about the centre of mass", required=False)
    for key, value in (("com", com), ("inertia", inertia)):
        if value is not None and mass is None:
            r.fail(key, "needs mass (a mass override gives the link's mass, then optionally its com and inertia)")
    return mass, com, inertia


def read_items(r: _Reader, source: str, where: str) -> tuple[HydroItem, ...]:
    """A link table's ``[[...items]]``: at most :data:`MAX_ITEMS`, each with ``mass`` and
    ``volume`` (both required, at least 0), ``position``, and optionally ``name`` and ``inertia``
    (which needs a mass)."""
    raw = r.table.get("items", [])
    if isinstance(raw, list) and len(raw) > MAX_ITEMS:  # refused before reading a thousand of them
        r.fail("items", f"has {len(raw)} entries; a link takes at most {MAX_ITEMS} items (uwml.io.hydrofile.MAX_ITEMS)")
    if not isinstance(raw, list) or not all(isinstance(t, dict) for t in raw):
        r.fail("items", f"must be an array of tables ([[{where.strip('[]')}.items]]), got {shown(raw)}")
    items = []
    for index, table in enumerate(raw):
        item = _Reader(source, f"{where}, items[{index}]", table, DescriptionError)
        item.check_keys(_ITEM_KEYS)
        mass = item.get("mass", _mass, f"a mass [kg], 0 to {MAX_MASS:g}")
        inertia = item.get("inertia", lambda v: _moments(v, positive=False), "[ixx, iyy, izz] [kg·m²] about its position", required=False)
        if inertia is not None and mass <= 0.0:
            item.fail("inertia", "needs a mass above 0 (moments of inertia without mass are no body's)")
        items.append(
            HydroItem(
                mass=mass,
                volume=item.get("volume", _volume, f"a volume [m³], 0 to {MAX_VOLUME:g} (0 for none)"),
                position=item.get("position", _point, "an array of 3 numbers [m], in the link's description frame"),
                name=item.get("name", _name, f"a name, 1 to {_MAX_NAME} printable characters", required=False),
                inertia=inertia,
            )
        )
    return tuple(items)
