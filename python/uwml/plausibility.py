"""Warnings for likely unit mistakes (:class:`PlausibilityWarning`): values that uwml can compute
with but that a robot in water hardly ever has, and that the usual mistakes give.

uwml warns, once per robot and cause (a joint's speed, angle or effort; a robot made anew warns
anew), when

* a revolute joint turns faster than ``PLAUSIBLE_ANGULAR_SPEED`` (30 rad/s, about 290 r/min:
  beyond any manipulator's or leg's joint; degrees per second are far above it), or a prismatic
  joint moves faster than ``PLAUSIBLE_LINEAR_SPEED`` (10 m/s); a joint with a velocity limit
  (:attr:`uwml.Joint.velocity_limit`, a URDF's ``<limit velocity>``) faster than
  ``LIMIT_MARGIN`` (1.5) times it instead (a speed estimated from a log of a joint at its limit
  overshoots it a little; one in the wrong unit by far);
* a revolute joint's angle is beyond ``PLAUSIBLE_ANGLE`` (±4π, two turns: degrees given as
  radians are far beyond; a continuous joint that has turned more is legitimate, and the
  warning can be silenced); for a joint with a range (:attr:`uwml.Joint.range`: a URDF revolute
  joint's ``lower``/``upper``, an MJCF hinge's ``range``), beyond ±2π or its range, whichever is
  wider (it cannot turn a full turn);
* a generalized force the water (and, in ``environment``, the joint losses) puts on a joint comes
  out beyond its effort limit (:attr:`uwml.Joint.effort_limit`, a URDF's ``<limit effort>``, an
  MJCF joint's ``actuatorfrcrange``): its motor could not hold it, and most likely a state is in
  the wrong unit;
* a water density is below 500 or above 1,100 kg/m³ (fresh water is 1,000, sea water about
  1,025; 1.025 is g/cm³);
* a log's median time step is 0.5 s or more (2 Hz or less: time stamps in milliseconds look like
  that).

The bounds of a robot's joints are worked out once, when it is built (:func:`joint_bounds`).
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
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

__all__ = [
    "CHECKED_ROWS",
    "LIMIT_MARGIN",
    "PLAUSIBLE_ANGLE",
    "PLAUSIBLE_ANGULAR_SPEED",
    "PLAUSIBLE_DENSITY",
    "PLAUSIBLE_LINEAR_SPEED",
    "PLAUSIBLE_TIME_STEP",
    "DescriptionWarning",
    "JointBounds",
    "PlausibilityWarning",
    "check_density",
    "check_efforts",
    "check_states",
    "check_time_step",
    "joint_bounds",
]

#: The largest plausible speed of a revolute joint [rad/s] (also the compiled core's, which a test
#: holds equal: its one-state path leaves a state beyond these to the general path, which warns).
PLAUSIBLE_ANGULAR_SPEED = 30.0
#: The largest plausible speed of a prismatic joint [m/s].
PLAUSIBLE_LINEAR_SPEED = 10.0
#: The largest plausible angle of a revolute joint [rad]: two turns either way.
PLAUSIBLE_ANGLE = 4.0 * math.pi
#: How far beyond a description's velocity limit a joint's speed may go before it warns.
LIMIT_MARGIN = 1.5
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


class DescriptionWarning(PlausibilityWarning):
    """A robot description with its hydro file that maps, but most likely not to what was meant:
    a link fused into a body with a lumped model adding its collision geometry's volume and
    strips beside that model (:mod:`uwml.io.hydrofile`). A :class:`PlausibilityWarning`, so one
    filter silences both."""


@dataclass(frozen=True)
class JointBounds:
    """The plausible bounds of a robot's joints (:func:`joint_bounds`), one entry per joint
    (``inf``: unbounded), with the joints they were worked out from (for the messages)."""

    joints: tuple[Any, ...]
    #: The largest plausible ``|q|`` [rad or m].
    angle: tuple[float, ...]
    #: The largest plausible ``|q̇|`` [rad/s or m/s].
    speed: tuple[float, ...]
    #: The largest plausible ``|τ|`` of the environment [N·m or N].
    effort: tuple[float, ...]
    #: The causes already warned of, ``(what, joint)``: each is warned of once.
    warned: set[tuple[str, int]] = field(default_factory=set, compare=False, repr=False)

    def first_time(self, what: str, joint: int) -> bool:
        """Whether ``what`` of ``joint`` has not been warned of yet (and now counts as warned)."""
        key = (what, joint)
        if key in self.warned:
            return False
        self.warned.add(key)
        return True

    def rows(self) -> list[tuple[float, float, float]]:
        """``(angle, speed, effort)`` per joint: the compiled core's one-state path takes a
        state within them, and leaves any other to the general path, which warns."""
        return list(zip(self.angle, self.speed, self.effort))


def joint_bounds(joints: Sequence[Any]) -> JointBounds:
    """The bounds of :class:`uwml.Joint`\\ s (module docstring)."""
    joints = tuple(joints)
    angle, speed = [], []
    for joint in joints:
        turns = joint.kind == "revolute"
        limit = joint.velocity_limit
        speed.append(LIMIT_MARGIN * limit if limit is not None else PLAUSIBLE_ANGULAR_SPEED if turns else PLAUSIBLE_LINEAR_SPEED)
        if turns and joint.range is not None:
            angle.append(max(2.0 * math.pi, abs(joint.range[0]), abs(joint.range[1])))
        else:
            angle.append(PLAUSIBLE_ANGLE if turns else math.inf)
    effort = tuple(math.inf if joint.effort_limit is None else joint.effort_limit for joint in joints)
    return JointBounds(joints, tuple(angle), tuple(speed), effort)


def _label(j: int, joint: Any) -> str:
    """Joint ``j`` as messages name it: ``joint 2 ('elbow')``."""
    return f"joint {j + 1}" + (f" ({joint.name!r})" if joint.name is not None else "")


def _checked_rows(values: NDArray[np.float64]) -> NDArray[np.float64]:
    """At most ``CHECKED_ROWS`` rows spread over ``values`` (1-D: one row)."""
    rows = np.atleast_2d(values)
    return rows[:: max(1, rows.shape[0] // CHECKED_ROWS)]


def _largest(values: NDArray[np.float64]) -> NDArray[np.float64]:
    """Per column, the largest finite ``|value|`` of the checked rows of ``values``; non-finite
    values are the evaluation's to refuse."""
    rows = _checked_rows(values)
    if rows.size == 0:
        return np.zeros(rows.shape[1])
    with np.errstate(invalid="ignore"):
        largest: NDArray[np.float64] = np.max(np.where(np.isfinite(rows), np.abs(rows), 0.0), axis=0)
    return largest


def check_states(q: NDArray[np.float64], qd: NDArray[np.float64], bounds: JointBounds, stacklevel: int = 3) -> None:
    """Warn about joint angles and speeds beyond ``bounds``: ``q`` and ``qd`` of shape
    ``(n_joints,)`` or ``(n_samples, n_joints)``."""
    speeds, angles = _largest(qd), _largest(q)
    for j, joint in enumerate(bounds.joints):
        label, turns = _label(j, joint), joint.kind == "revolute"
        if speeds[j] > bounds.speed[j]:
            if bounds.first_time("speed", j):
                _warn(_speed_message(label, joint, speeds[j], bounds.speed[j], turns), stacklevel)
            return
        if angles[j] > bounds.angle[j] and bounds.first_time("angle", j):
            ranged = " (beyond ±2π and its range)" if joint.range is not None else ""
            _warn(
                f"{label}'s angle reaches {angles[j]:.4g} rad, {angles[j] / (2 * math.pi):.3g} turns{ranged}: are the angles in "
                f"degrees? uwml takes radians; {_SILENCE} if the joint has turned that far",
                stacklevel,
            )
            return


def _speed_message(label: str, joint: Any, speed: float, bound: float, turns: bool) -> str:
    """The warning of a joint moving at ``speed`` beyond its ``bound``: its own velocity limit
    (a noisy estimate, or a limit that is wrong) unless the speed is beyond any joint's too (a
    unit: degrees, mm)."""
    unit, generic = ("rad/s", PLAUSIBLE_ANGULAR_SPEED) if turns else ("m/s", PLAUSIBLE_LINEAR_SPEED)
    seen = f"{label}'s speed reaches {speed:.4g} {unit}" if turns else f"{label} (prismatic) moves at up to {speed:.4g} m/s"
    unit_hint = "degrees per second? uwml takes rad/s" if turns else "mm/s? uwml takes m/s"
    if joint.velocity_limit is not None:
        above = f"above {LIMIT_MARGIN:g} times its own velocity limit of {joint.velocity_limit:.4g} {unit}"
        if speed <= generic:
            return (
                f"{seen}, {above}, faster than the joint can turn: is the speed estimated from a noisy log, or the "
                f"description's limit wrong? {_SILENCE} if it is right"
            )
        return f"{seen}, {above} and beyond any joint's {generic:g} {unit}: are the speeds in {unit_hint}; {_SILENCE} if they are right"
    above = f"above {bound:g} {unit}" + (" (about 290 r/min)" if turns else "")
    return f"{seen}, {above}: are the speeds in {unit_hint}; {_SILENCE} if they are right"


def check_efforts(parts: Sequence[NDArray[np.float64]], bounds: JointBounds, stacklevel: int = 3) -> None:
    """Warn about a joint whose environment force is beyond its effort limit: the force the sum
    of ``parts`` (each ``(n_joints,)`` or ``(n_samples, n_joints)``: a result's ``total`` is
    the sum of its parts), added on the checked rows only, and only for a robot with an effort
    limit."""
    if all(math.isinf(x) for x in bounds.effort):
        return
    force = np.sum([_checked_rows(part) for part in parts], axis=0)
    largest = _largest(force)
    for j, joint in enumerate(bounds.joints):
        if largest[j] > bounds.effort[j]:
            if not bounds.first_time("effort", j):
                return
            unit = "N·m" if joint.kind == "revolute" else "N"
            _warn(
                f"the environment puts up to {largest[j]:.4g} {unit} on {_label(j, joint)}, beyond its effort limit of "
                f"{bounds.effort[j]:.4g} {unit}: its motor could not hold that; is a state in the wrong unit (degrees, mm)? "
                f"{_SILENCE} if it is right",
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
