"""The ``uwml`` command line's argument types: each turns one argument's text into a value, or
raises ``argparse.ArgumentTypeError`` saying what is allowed and quoting (the start of) what was
given (argparse would otherwise print "invalid _positive value" for a word). Size-like
arguments are bounded, so that no argument asks for an absurd allocation."""

from __future__ import annotations

import argparse
import math

from ..domains import MAX_DEPTH, MAX_ROBOT_JOINTS
from ..paper.control_study import MAX_CYCLES

#: Most samples of ``uwml demo``'s printed table.
MAX_DEMO_SAMPLES = 10_000
#: Most depths of ``uwml simulate`` (each runs five simulations).
MAX_DEPTHS = 20


def _quoted(text: str) -> str:
    return repr(text) if len(text) <= 40 else repr(text[:40]) + "…"


def _number(text: str, allowed: str, low: float, high: float, low_open: bool = False) -> float:
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not (math.isfinite(value) and (low < value if low_open else low <= value) and value <= high):
        raise argparse.ArgumentTypeError(f"{allowed}, got {_quoted(text)}")
    return value


def _integer(text: str, low: int, high: int) -> int:
    try:
        value = int(text)
    except ValueError:  # not an integer, or one of more than 4300 digits
        value = low - 1
    if not low <= value <= high:
        raise argparse.ArgumentTypeError(f"must be an integer from {low} to {high}, got {_quoted(text)}")
    return value


def _positive(text: str) -> float:
    return _number(text, "must be a positive number", 0.0, math.inf, low_open=True)


def _non_negative(text: str) -> float:
    return _number(text, "must be a non-negative number", 0.0, math.inf)


def _finite(text: str) -> float:
    return _number(text, "must be a finite number", -math.inf, math.inf)


def _depth(text: str) -> float:
    return _number(text, f"must be a depth from 0 to {MAX_DEPTH:g} m", 0.0, MAX_DEPTH)


def _cycles(text: str) -> float:
    return _number(text, f"must be between 0 and {MAX_CYCLES} (gait cycles, more than 0)", 0.0, MAX_CYCLES, low_open=True)


def _count(text: str) -> int:
    return _integer(text, 2, MAX_DEMO_SAMPLES)


def _workers(text: str) -> int:
    return _integer(text, 1, 4096)


def _n_joints(text: str) -> int:
    return _integer(text, 1, MAX_ROBOT_JOINTS)


def _seed(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        value = -1
    if value < 0:
        raise argparse.ArgumentTypeError(f"must be a non-negative integer, got {_quoted(text)}")
    return value


def _joint_list(text: str) -> list[int]:
    allowed = f"must be distinct joint numbers from 1 to {MAX_ROBOT_JOINTS}, separated by commas, got {_quoted(text)}"
    try:
        joints = [int(item) for item in text.split(",") if item.strip()]
    except ValueError:  # not integers, or integers of more than 4300 digits
        raise argparse.ArgumentTypeError(allowed) from None
    if not joints or any(not 1 <= j <= MAX_ROBOT_JOINTS for j in joints) or len(set(joints)) != len(joints):
        raise argparse.ArgumentTypeError(allowed)
    return joints


def _depth_list(text: str) -> list[float]:
    try:
        depths = [float(item) for item in text.split(",") if item.strip()]
    except ValueError:
        raise argparse.ArgumentTypeError(f"must be depths in m separated by commas, got {_quoted(text)}") from None
    if not depths or any(not (math.isfinite(d) and 0.0 <= d <= MAX_DEPTH) for d in depths):
        raise argparse.ArgumentTypeError(f"must be depths from 0 to 11000 m, separated by commas, got {_quoted(text)}")
    if len(depths) > MAX_DEPTHS:
        raise argparse.ArgumentTypeError(f"must be at most {MAX_DEPTHS} depths (each runs five simulations), got {len(depths)}")
    return depths


def _joint_list_or_none(text: str) -> list[int]:
    """Joint numbers as :func:`_joint_list`, or ``none`` for no joint."""
    return [] if text.strip().lower() == "none" else _joint_list(text)


#: The base wrench's components as ``--base`` names them.
BASE_COMPONENTS = ("fx", "fy", "fz", "mx", "my", "mz")


def _base_rows(text: str) -> list[int]:
    """Base wrench components (``fx, fy, fz, mx, my, mz``, or ``all``) as indices 0 … 5."""
    if text.strip().lower() == "all":
        return list(range(6))
    names = [item.strip().lower() for item in text.split(",") if item.strip()]
    if not names or any(name not in BASE_COMPONENTS for name in names) or len(set(names)) != len(names):
        raise argparse.ArgumentTypeError(
            f"must be distinct components among fx, fy, fz, mx, my, mz separated by commas, or all; got {_quoted(text)}"
        )
    return [BASE_COMPONENTS.index(name) for name in names]
