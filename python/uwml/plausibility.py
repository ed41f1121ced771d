"""Warnings for likely unit mistakes (:class:`PlausibilityWarning`): values that uwml can compute
with but that a robot in water hardly ever has, and that the usual mistakes give.

uwml warns, once per call, when

* a revolute joint turns faster than ``PLAUSIBLE_ANGULAR_SPEED`` (30 rad/s, about 290 r/min:
  beyond any manipulator's or leg's joint; degrees per second are far above it), or a prismatic
  joint moves faster than ``PLAUSIBLE_LINEAR_SPEED`` (10 m/s);
* a revolute joint's angle is beyond ``PLAUSIBLE_ANGLE`` (±4π, two turns: degrees given as
  radians are far beyond; a continuous joint that has turned more is legitimate, and the
  warning can be silenced);
* a water density is below 500 or above 1,100 kg/m³ (fresh water is 1,000, sea water about
  1,025; 1.025 is g/cm³);
* a log's median time step is 0.5 s or more (2 Hz or less: time stamps in milliseconds look like
  that).

A batch of states is checked on at most ``CHECKED_ROWS`` rows spread over it (a unit mistake
shows in nearly every row), so the check costs nothing measurable; one state from the one-state
path goes to the general path, which checks it, only when it is out of bounds. Silence the
warnings with ``warnings.filterwarnings("ignore", category=uwml.PlausibilityWarning)``, or make
them errors with ``"error"``.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Sequence

import numpy as np
from numpy.typing import NDArray

__all__ = [
    "CHECKED_ROWS",
    "PLAUSIBLE_ANGLE",
    "PLAUSIBLE_ANGULAR_SPEED",
    "PLAUSIBLE_DENSITY",
    "PLAUSIBLE_LINEAR_SPEED",
    "PLAUSIBLE_TIME_STEP",
    "PlausibilityWarning",
    "check_density",
    "check_states",
    "check_time_step",
]

#: The largest plausible speed of a revolute joint [rad/s] (also the compiled core's, which a test
#: holds equal: its one-state path leaves a state beyond these to the general path, which warns).
PLAUSIBLE_ANGULAR_SPEED = 30.0
#: The largest plausible speed of a prismatic joint [m/s].
PLAUSIBLE_LINEAR_SPEED = 10.0
#: The largest plausible angle of a revolute joint [rad]: two turns either way.
PLAUSIBLE_ANGLE = 4.0 * math.pi
#: The plausible water densities [kg/m³].
PLAUSIBLE_DENSITY = (500.0, 1100.0)
#: The longest plausible median time step of a log [s].
PLAUSIBLE_TIME_STEP = 0.5
#: The most rows of a batch that are checked.
CHECKED_ROWS = 1024

_SILENCE = 'silence with warnings.filterwarnings("ignore", category=uwml.PlausibilityWarning)'


class PlausibilityWarning(UserWarning):
    """A value that is computable but hardly ever right: most likely a unit mistake (module
    docstring)."""


def check_states(q: NDArray[np.float64], qd: NDArray[np.float64], revolute: Sequence[bool], stacklevel: int = 3) -> None:
    """Warn about joint angles and speeds beyond the plausible bounds: ``q`` and ``qd`` of shape
    ``(n_joints,)`` or ``(n_samples, n_joints)``, ``revolute`` per joint."""
    q2, qd2 = np.atleast_2d(q), np.atleast_2d(qd)
    step = max(1, q2.shape[0] // CHECKED_ROWS)
    rows_q, rows_qd = q2[::step], qd2[::step]
    if rows_q.size == 0:
        return
    # Non-finite values are refused by the evaluation itself, with its own message.
    with np.errstate(invalid="ignore"):
        speeds = np.max(np.where(np.isfinite(rows_qd), np.abs(rows_qd), 0.0), axis=0)
        angles = np.max(np.where(np.isfinite(rows_q), np.abs(rows_q), 0.0), axis=0)
    for j, turns in enumerate(revolute):
        if turns and speeds[j] > PLAUSIBLE_ANGULAR_SPEED:
            _warn(
                f"joint {j + 1}'s speed reaches {speeds[j]:.4g} rad/s, above {PLAUSIBLE_ANGULAR_SPEED:g} rad/s (about 290 r/min): "
                f"are the speeds in degrees per second? uwml takes rad/s; {_SILENCE} if they are right",
                stacklevel,
            )
            return
        if turns and angles[j] > PLAUSIBLE_ANGLE:
            _warn(
                f"joint {j + 1}'s angle reaches {angles[j]:.4g} rad, {angles[j] / (2 * math.pi):.3g} turns: are the angles in "
                f"degrees? uwml takes radians; {_SILENCE} if the joint has turned that far",
                stacklevel,
            )
            return
        if not turns and speeds[j] > PLAUSIBLE_LINEAR_SPEED:
            _warn(
                f"joint {j + 1} (prismatic) moves at up to {speeds[j]:.4g} m/s, above {PLAUSIBLE_LINEAR_SPEED:g} m/s: "
                f"are the speeds in mm/s? uwml takes m/s; {_SILENCE} if they are right",
                stacklevel,
            )
            return


def check_density(density: float, stacklevel: int = 3) -> None:
    """Warn about a water density outside ``PLAUSIBLE_DENSITY``."""
    low, high = PLAUSIBLE_DENSITY
    if not low <= density <= high:
        hint = " (1.025 is sea water in g/cm³)" if density < 10.0 else ""
        _warn(
            f"a water density of {density:g} kg/m³ is outside {low:g} to {high:g} kg/m³ (fresh water 1000, sea water about 1025){hint}: "
            f"uwml takes kg/m³; {_SILENCE} if the fluid is right",
            stacklevel,
        )


def check_time_step(dt: float, source: str, stacklevel: int = 3) -> None:
    """Warn about a log whose median time step ``dt`` is ``PLAUSIBLE_TIME_STEP`` or more."""
    if dt >= PLAUSIBLE_TIME_STEP:
        _warn(
            f"{source}: the median time step is {dt:g} s ({1.0 / dt:.3g} Hz): is time in milliseconds? "
            f"uwml takes seconds; {_SILENCE} if the log is that slow",
            stacklevel,
        )


def _warn(message: str, stacklevel: int) -> None:
    warnings.warn(message, PlausibilityWarning, stacklevel=stacklevel + 1)
