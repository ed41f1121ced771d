"""The checks and layouts of the robots' arguments, shared by :class:`uwml.Leg` and
:class:`uwml.Robot`: joint states, coefficients, threads, the water, the added-mass form, the
joint losses (per joint, and read by the core once for a one-state call)."""

from __future__ import annotations

import dataclasses
from collections.abc import Iterable, Sequence
from typing import Any, NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .. import _core
from .._checks import real_array as _real_array
from .._core import MAX_LUMPED_BODIES, MAX_ROBOT_JOINTS, MAX_SEGMENTS
from ..model.joint_losses import JointLosses, pack_leg_losses
from ..model.parts import Joint, Link, Segment, Water
from .base_motion import BaseMotion

FloatArray = NDArray[np.float64]


#: The forms of the added-mass forces: the paper's Morison form, and Kirchhoff's
#: (docs/simulation.md, "Energy-consistent added mass").
ADDED_MASS_FORMS = ("morison", "kirchhoff")


def _kirchhoff(added_mass: object) -> bool:
    if added_mass not in ADDED_MASS_FORMS:
        raise ValueError(f"added_mass must be one of {', '.join(ADDED_MASS_FORMS)}, got {added_mass!r}")
    return added_mass == "kirchhoff"


def _coefficients(value: ArrayLike, name: str, n_links: int) -> FloatArray:
    """A coefficient given as a scalar, per link ``(n_links,)`` or per link and direction ``(n_links, 2)``."""
    array = _real_array(value, name, "a real number or a rectangular array of real numbers")
    if array.ndim == 0:
        table = np.full((n_links, 2), float(array))
    elif array.shape == (n_links,):
        table = np.repeat(array[:, None], 2, axis=1)
    elif array.shape == (n_links, 2):
        table = np.array(array)
    else:
        raise ValueError(
            f"{name} must be a scalar, shape ({n_links},) per link, or ({n_links}, 2) per link and direction; got shape {array.shape}"
        )
    if not np.all(np.isfinite(table)) or np.any(table < 0.0):
        raise ValueError(f"{name} must be finite and non-negative, got {array.tolist()}")
    return np.ascontiguousarray(table)


def _states(q: ArrayLike, qd: ArrayLike, qdd: ArrayLike, n_joints: int) -> tuple[tuple[int, ...], FloatArray, FloatArray, FloatArray]:
    """The three joint-state arrays as C-contiguous ``(n_samples, n_joints)`` float64 (no copy if already so)."""
    arrays = []
    for name, value in (("q", q), ("qd", qd), ("qdd", qdd)):
        array = _real_array(value, name, "a rectangular array of real numbers")
        if array.ndim not in (1, 2) or array.shape[-1] != n_joints:
            raise ValueError(f"{name} must have shape ({n_joints},) or (n_samples, {n_joints}), got {array.shape}")
        arrays.append(array)
    shape = arrays[0].shape
    for name, array in zip(("qd", "qdd"), arrays[1:]):
        if array.shape != shape:
            raise ValueError(f"{name} must have the same shape as q {shape}, got {array.shape}")
    flat = [np.ascontiguousarray(a.reshape(-1, n_joints)) for a in arrays]
    return shape, flat[0], flat[1], flat[2]


def _threads(threads: object) -> int:
    """``threads`` as a count of threads ≥ 1, or a ValueError."""
    if isinstance(threads, bool) or not isinstance(threads, int | np.integer) or threads < 1:
        raise ValueError(f"threads must be an integer >= 1, got {threads!r}")
    return int(threads)


def _water(water: Water) -> Water:
    if not isinstance(water, Water):
        raise TypeError(f"water must be a uwml.Water, got {type(water).__name__}")
    return water


def _per_joint_losses(losses: object, n_joints: int) -> tuple[JointLosses | None, ...]:
    """``losses`` (None, one :class:`JointLosses` for every joint, or one or None per joint) as a
    tuple with one entry per joint."""
    if losses is None or isinstance(losses, JointLosses):
        return (losses,) * n_joints
    if not isinstance(losses, Iterable):
        raise TypeError(f"losses must be a uwml.JointLosses, a sequence of them (or None), or None; got {type(losses).__name__}")
    items = tuple(losses)
    if len(items) != n_joints:
        raise ValueError(f"losses must have one entry per joint ({n_joints}), got {len(items)}")
    checked: list[JointLosses | None] = []
    for index, item in enumerate(items):
        if item is not None and not isinstance(item, JointLosses):
            raise TypeError(f"losses[{index}] must be a uwml.JointLosses or None, got {type(item).__name__}")
        checked.append(item)
    return tuple(checked)


def one_state_losses(owner: Any, losses: object, n_joints: int) -> _core.Losses | bool:
    """``losses`` (not None) for a one-state native call: one :class:`JointLosses` for every
    joint, read by the core once and kept on ``owner`` (its ``_losses_cache``) for the next call
    with the same object (it is frozen), or ``False`` (which the native calls do not take) for
    anything else, left to the general path."""
    cached: tuple[JointLosses, _core.Losses] | None = owner._losses_cache
    if cached is not None and cached[0] is losses:
        return cached[1]
    if type(losses) is not JointLosses:
        return False
    compiled = pack_leg_losses(losses, n_joints)
    owner._losses_cache = (losses, compiled)
    return compiled


def _short_path(water: object, base_motion: object) -> tuple[bool, tuple[FloatArray, ...] | None]:
    """Whether a call may try the one-state native path (a :class:`Water`, and no base motion or
    one of single values), and the base motion's arrays for it (None: a fixed base)."""
    if not isinstance(water, Water):
        return False, None
    if base_motion is None:
        return True, None
    if not isinstance(base_motion, BaseMotion):
        return False, None
    motion = base_motion._single()
    return motion is not None, motion


class _Inputs(NamedTuple):
    """The arguments of the native evaluations before ``threads``, checked and laid out."""

    q: FloatArray
    qd: FloatArray
    qdd: FloatArray
    cd: FloatArray
    cm: FloatArray
    density: float
    gravity: float
    orientation: FloatArray
    velocity: FloatArray
    angular_velocity: FloatArray
    acceleration: FloatArray
    angular_acceleration: FloatArray
    current: FloatArray
    current_acceleration: FloatArray


def segment_coefficients(value: ArrayLike | None, name: str, circular: NDArray[np.bool_]) -> FloatArray:
    """A robot's ``cd`` or ``cm``: ``(S, 2)`` per segment and direction (``circular``: which of the
    S segments are), or ``(0, 2)`` for the segments' own."""
    n = len(circular)
    if value is None:
        return np.zeros((0, 2))
    array = _real_array(value, name, "None, a real number, or an array per segment")
    if array.ndim == 0:
        table = np.full((n, 2), float(array))
    elif array.shape == (n,):
        table = np.repeat(array[:, None], 2, axis=1)
    elif array.shape == (n, 2):
        table = np.array(array)
    else:
        raise ValueError(
            f"{name} must be None, a scalar, shape ({n},) per segment, or ({n}, 2) per segment and direction; got shape {array.shape}"
        )
    if not np.all(np.isfinite(table)) or np.any(table < 0.0):
        raise ValueError(f"{name} must be finite and non-negative, got {array.tolist()}")
    unequal = np.flatnonzero(circular & (table[:, 0] != table[:, 1]))
    if unequal.size:
        raise ValueError(f"{name}: segment {unequal[0]} is circular and takes one coefficient; got {table[unequal[0]].tolist()}")
    return np.ascontiguousarray(table)


def robot_inputs(
    n: int,
    circular: NDArray[np.bool_],
    the_water: Water,
    q: ArrayLike,
    qd: ArrayLike,
    qdd: ArrayLike,
    cd: ArrayLike | None,
    cm: ArrayLike | None,
    base_motion: BaseMotion | None,
    current: ArrayLike,
    current_acceleration: ArrayLike,
) -> tuple[_Inputs, bool, int]:
    """The native ``Robot.hydro`` arguments (before ``threads``) of a robot of ``n`` joints and
    segments ``circular`` or not, in ``the_water``: checked and laid out; whether the inputs had
    a sample axis, and the number of samples."""
    motion = base_motion if base_motion is not None else BaseMotion()
    if not isinstance(motion, BaseMotion):
        raise TypeError(f"base_motion must be a uwml.BaseMotion or None, got {type(motion).__name__}")
    states = []
    for name, value in (("q", q), ("qd", qd), ("qdd", qdd)):
        array = _real_array(value, name, "a rectangular array of real numbers")
        if array.ndim not in (1, 2) or array.shape[-1] != n:
            raise ValueError(f"{name} must have shape ({n},) or (n_samples, {n}), got {array.shape}")
        states.append(array)
    for name, array in zip(("qd", "qdd"), states[1:]):
        if array.shape != states[0].shape:
            raise ValueError(f"{name} must have the same shape as q {states[0].shape}, got {array.shape}")
    flows = []
    for name, value in (("current", current), ("current_acceleration", current_acceleration)):
        array = _real_array(value, name, "a 3-vector or an (n, 3) array")
        if array.ndim not in (1, 2) or array.shape[-1] != 3:
            raise ValueError(f"{name} must have shape (3,) or (n_samples, 3), got {array.shape}")
        if not np.all(np.isfinite(array)):
            raise ValueError(f"{name} must be finite, got {array.tolist()}")
        flows.append(array)
    per_sample = {
        name: array
        for name, array in (
            ("q", states[0]),
            ("base_motion.orientation", motion.orientation),
            ("base_motion.velocity", motion.velocity),
            ("base_motion.angular_velocity", motion.angular_velocity),
            ("base_motion.acceleration", motion.acceleration),
            ("base_motion.angular_acceleration", motion.angular_acceleration),
            ("current", flows[0]),
            ("current_acceleration", flows[1]),
        )
        if array.ndim == 2
    }
    counts = {len(a) for a in per_sample.values()}
    if len(counts) > 1:
        sizes = ", ".join(f"{k}: {len(v)}" for k, v in per_sample.items())
        raise ValueError(f"arguments given per sample must agree on the number of samples; got {sizes}")
    n_samples = counts.pop() if counts else 1

    def rows(array: FloatArray, width: int) -> FloatArray:
        return np.ascontiguousarray(array.reshape(-1, width), dtype=np.float64)

    def joint_rows(array: FloatArray) -> FloatArray:
        return np.ascontiguousarray(np.broadcast_to(array.reshape(-1, n), (n_samples, n)), dtype=np.float64)

    arguments = _Inputs(
        joint_rows(states[0]),
        joint_rows(states[1]),
        joint_rows(states[2]),
        segment_coefficients(cd, "cd", circular),
        segment_coefficients(cm, "cm", circular),
        the_water.density,
        the_water.gravity,
        rows(motion.orientation, 4),
        rows(motion.velocity, 3),
        rows(motion.angular_velocity, 3),
        rows(motion.acceleration, 3),
        rows(motion.angular_acceleration, 3),
        rows(flows[0], 3),
        rows(flows[1], 3),
    )
    return arguments, bool(per_sample), n_samples


def joint_and_link_tuples(joints: Sequence[Joint], links: Sequence[Link]) -> tuple[tuple[Joint, ...], tuple[Link, ...]]:
    """``joints`` and ``links`` as tuples, each item checked to be a :class:`uwml.Joint` or a
    :class:`uwml.Link` (a TypeError naming the first that is not)."""
    try:
        joints, links = tuple(joints), tuple(links)
    except TypeError:
        raise TypeError(
            f"joints and links must be sequences of uwml.Joint and uwml.Link, got {type(joints).__name__} and {type(links).__name__}"
        ) from None
    for name, items, kind in (("joints", joints, Joint), ("links", links, Link)):
        for index, item in enumerate(items):
            if not isinstance(item, kind):
                raise TypeError(f"{name}[{index}] must be a uwml.{kind.__name__}, got {type(item).__name__}")
    return joints, links


def robot_parts(
    joints: Sequence[Joint], links: Sequence[Link], base: Link | None
) -> tuple[tuple[Joint, ...], tuple[Link, ...], Link, list[tuple[int, Segment]]]:
    """A :class:`uwml.Robot`'s parts checked: its joints with every ``parent`` resolved, its
    links, the base's body (a body without mass, volume or segments for ``None``) and every
    segment with its owner (``-1`` the base), base first."""
    joints, links = joint_and_link_tuples(joints, links)
    if base is not None and not isinstance(base, Link):
        raise TypeError(f"base must be a uwml.Link or None, got {type(base).__name__}")
    if len(joints) != len(links) or not 1 <= len(joints) <= MAX_ROBOT_JOINTS:
        raise ValueError(f"a robot needs as many links as joints, 1 to {MAX_ROBOT_JOINTS}; got {len(joints)} joints and {len(links)} links")
    parents = []
    for index, joint in enumerate(joints):
        parent = index - 1 if joint.parent is None else joint.parent
        if parent >= index:
            raise ValueError(f"joints[{index}].parent must be -1 (the base) or an earlier link (< {index}), got {parent}")
        parents.append(parent)
    base_body = base if base is not None else Link(mass=0.0, com=(0.0, 0.0, 0.0), volume=0.0)
    owned = [(-1, s) for s in base_body.segments] + [(i, s) for i, link in enumerate(links) for s in link.segments]
    if len(owned) > MAX_SEGMENTS:
        raise ValueError(f"a robot may have up to {MAX_SEGMENTS} segments, got {len(owned)}")
    lumped = sum(body.lumped is not None for body in (base_body, *links))
    if lumped > MAX_LUMPED_BODIES:
        raise ValueError(f"a robot may carry up to {MAX_LUMPED_BODIES} lumped models (one per body), got {lumped}")
    return tuple(dataclasses.replace(j, parent=p) for p, j in zip(parents, joints)), links, base_body, owned
