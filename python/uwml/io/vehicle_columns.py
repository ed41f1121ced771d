"""The vehicle in a log: its columns, named once (docs/logs.md; docs/model.md, "The vehicle in a
log"), and how a header's vehicle columns are checked and read.

==========================================  ================================================
columns                                     meaning
==========================================  ================================================
``x``, ``y``, ``z``                         position of the body origin [m], world frame, z up
``qw``, ``qx``, ``qy``, ``qz``              orientation, world from body, scalar first
``roll``, ``pitch``, ``yaw``                or the same as z-y-x Euler angles [rad]
``u``, ``v``, ``w``, ``p``, ``q``, ``r``    body-frame twist ν (Fossen): [m/s], then [rad/s]
``u_dot`` … ``r_dot``                       its time derivative ν̇ (optional: else estimated)
``fx`` … ``mz``                             measured wrench on the body: force [N], moment
                                            [N·m] about the body origin, body components
``fx_land`` … ``mz_land``, ``fx_water`` …   the same in each run of a land/water experiment
``u1`` … ``un``                             thruster commands (as the vehicle's logger writes them)
==========================================  ================================================

Each group is complete or absent: ``x`` without ``z``, or a twist without ``r``, is an error naming
the missing column. An orientation is a quaternion or Euler angles, not both. ``u`` (surge) and
``u1`` (the first thruster's command) are different columns: a thruster command always has its
number. A quaternion must be of norm 1 within ``ORIENTATION_TOLERANCE`` (1e-3, a quaternion
recorded to a few digits); :meth:`uwml.io.logs.Log.base_motion` normalizes it.
"""

from __future__ import annotations

import re
from collections.abc import Sequence

import numpy as np
from numpy.typing import NDArray

from .._checks import shown

__all__ = [
    "EULER",
    "FIELDS",
    "MAX_THRUSTERS",
    "ORIENTATION_TOLERANCE",
    "POSITION",
    "QUATERNION",
    "TWIST",
    "TWIST_DOT",
    "VEHICLE_COLUMNS",
    "WRENCH",
    "check_orientation",
    "is_vehicle_column",
    "orientation",
    "quaternion_from_euler",
    "thruster_columns",
    "vehicle_layout",
]

Array = NDArray[np.float64]

POSITION = ("x", "y", "z")
QUATERNION = ("qw", "qx", "qy", "qz")
EULER = ("roll", "pitch", "yaw")
TWIST = ("u", "v", "w", "p", "q", "r")
TWIST_DOT = tuple(f"{name}_dot" for name in TWIST)
WRENCH = ("fx", "fy", "fz", "mx", "my", "mz")
#: The most thruster command columns (``u1`` … ``u64``) a log has.
MAX_THRUSTERS = 64
#: How far from 1 a log's quaternion's norm may be.
ORIENTATION_TOLERANCE = 1e-3

#: The :class:`uwml.io.logs.Log` fields of the vehicle and their columns, in the order written.
FIELDS: dict[str, tuple[str, ...]] = {
    "base_position": POSITION,
    "base_orientation": QUATERNION,
    "base_twist": TWIST,
    "base_twist_dot": TWIST_DOT,
    "wrench_land": tuple(f"{name}_land" for name in WRENCH),
    "wrench_water": tuple(f"{name}_water" for name in WRENCH),
    "wrench": WRENCH,
}
#: What each group of columns is, for the messages.
_WHAT = {
    "base_position": "the vehicle's position",
    "base_orientation": "the vehicle's orientation (a quaternion)",
    "euler": "the vehicle's orientation (Euler angles)",
    "base_twist": "the vehicle's twist",
    "base_twist_dot": "the vehicle's twist rate",
    "wrench_land": "the wrench on the vehicle on land",
    "wrench_water": "the wrench on the vehicle in water",
    "wrench": "the wrench on the vehicle",
}
#: Every vehicle column of the schema but the thruster commands.
VEHICLE_COLUMNS = frozenset(name for columns in (*FIELDS.values(), EULER) for name in columns)
_THRUSTER = re.compile(r"^u(\d+)$")


def is_vehicle_column(name: str) -> bool:
    """Whether ``name`` is a column of the vehicle's (a thruster command's included)."""
    return name in VEHICLE_COLUMNS or _THRUSTER.match(name) is not None


def vehicle_layout(header: Sequence[str], source: str) -> dict[str, tuple[str, ...]]:
    """The vehicle's fields a header holds, each with the columns it is read from (the
    orientation: the quaternion's four, or ``roll, pitch, yaw``), in :data:`FIELDS` order; a
    ValueError naming the first column of a group given in part, or an orientation given twice."""
    present = set(header)
    out: dict[str, tuple[str, ...]] = {}
    for group, columns in (*FIELDS.items(), ("euler", EULER)):
        given = [name for name in columns if name in present]
        if not given:
            continue
        missing = [name for name in columns if name not in present]
        if missing:
            raise ValueError(
                f"{source}: row 1 (header), column {missing[0]!r}: missing column ({_WHAT[group]} is {', '.join(columns)}; "
                f"the header has {', '.join(given)})"
            )
        if group == "euler" and "base_orientation" in out:
            raise ValueError(
                f"{source}: row 1 (header), column 'roll': the orientation is given twice (qw, qx, qy, qz and roll, pitch, yaw); "
                "give one (a column map can pick one: docs/logs.md)"
            )
        out["base_orientation" if group == "euler" else group] = columns
    return {field: out[field] for field in FIELDS if field in out}


def thruster_columns(header: Sequence[str], source: str) -> tuple[str, ...]:
    """The thruster commands' columns ``u1`` … ``un`` of a header (none: empty), checked: numbered
    from 1 without a gap or a leading zero, at most ``MAX_THRUSTERS``."""
    numbers: dict[int, str] = {}
    for name in header:
        match = _THRUSTER.match(name)
        if not match:
            continue
        digits = match.group(1)
        if digits.startswith("0"):
            why = "thrusters are numbered from 1" if digits.strip("0") == "" else "thruster numbers have no leading zero"
            raise ValueError(f"{source}: row 1 (header), column {shown(name)}: {why} (u1, u2, …)")
        number = int(digits) if len(digits) <= 6 else 10**6
        if number > MAX_THRUSTERS:
            raise ValueError(f"{source}: row 1 (header), column {shown(name)}: a log has at most {MAX_THRUSTERS} thruster commands")
        numbers[number] = name
    if not numbers:
        return ()
    for k in range(1, max(numbers) + 1):
        if k not in numbers:
            raise ValueError(
                f"{source}: row 1 (header), column 'u{k}': missing column (thruster commands u1 … u{max(numbers)}, numbered without a gap)"
            )
    return tuple(f"u{k}" for k in range(1, max(numbers) + 1))


def quaternion_from_euler(euler: Array) -> Array:
    """Unit quaternions ``(w, x, y, z)``, world from body, of z-y-x Euler angles ``(roll,
    pitch, yaw)`` [rad], ``(n, 3)``: ``R = Rz(yaw) Ry(pitch) Rx(roll)``."""
    roll, pitch, yaw = (np.asarray(euler, dtype=np.float64)[:, k] / 2.0 for k in range(3))
    cr, sr, cp, sp, cy, sy = np.cos(roll), np.sin(roll), np.cos(pitch), np.sin(pitch), np.cos(yaw), np.sin(yaw)
    return np.stack(
        [cr * cp * cy + sr * sp * sy, sr * cp * cy - cr * sp * sy, cr * sp * cy + sr * cp * sy, cr * cp * sy - sr * sp * cy], axis=1
    )


def check_orientation(quaternion: Array, source: str, first_row: int) -> None:
    """The rows of an orientation ``(n, 4)`` (its first row ``first_row`` of the file) quaternions
    of norm 1 within ``ORIENTATION_TOLERANCE``, or a ValueError naming the first other row."""
    with np.errstate(over="ignore"):  # a huge quaternion's norm overflows: not a unit one
        norms = np.linalg.norm(quaternion, axis=1)
    bad = np.flatnonzero(~(np.abs(norms - 1.0) <= ORIENTATION_TOLERANCE))
    if bad.size:
        k = int(bad[0])
        raise ValueError(
            f"{source}: row {first_row + k}, column 'qw': the vehicle's orientation (qw, qx, qy, qz, world from body) must be "
            f"of norm 1 within {ORIENTATION_TOLERANCE:g}, got {norms[k]:.6g}"
        )


def orientation(values: Array, columns: Sequence[str], source: str, first_row: int) -> Array:
    """The orientation read from ``columns`` (the quaternion's or Euler angles, ``(n, 4)`` or
    ``(n, 3)``) as quaternions ``(n, 4)``: Euler angles converted, a quaternion checked."""
    if tuple(columns) == EULER:
        return quaternion_from_euler(values)
    check_orientation(values, source, first_row)
    return values
