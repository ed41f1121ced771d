"""The checks of a :class:`uwml.Robot`'s parts and of its arguments that are not conditions
(:mod:`uwml.robot.evaluation_conditions`): its joints, links and base, the water and joint losses
it holds, the threads of an evaluation; the keyword shortcuts of one call kept to compare with
the next's."""

from __future__ import annotations

import copy
import dataclasses
from collections.abc import Iterable, Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

from .._core import MAX_LUMPED_BODIES, MAX_ROBOT_JOINTS, MAX_SEGMENTS
from ..model.joint_losses import JointLosses
from ..model.parts import Joint, Link, Segment, Water

if TYPE_CHECKING:
    from .evaluation_conditions import ConditionFields


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


def kept_shortcut(value: object) -> object:
    """A shortcut's value as kept to compare the next call's with: a copy of what may change in
    place (lists, arrays), the object itself otherwise (numbers, tuples, frozen parts)."""
    if isinstance(value, np.ndarray):
        return value.copy()
    if isinstance(value, list):
        return copy.deepcopy(value)
    return value


def _same_value(kept: object, given: object) -> bool:
    """Whether a shortcut's value ``given`` is the one ``kept`` (:func:`kept_shortcut`): equal numbers,
    strings, tuples, lists or arrays, or the same object (frozen: a water, a base motion)."""
    kind = type(given)
    if kind is float or kind is int or kind is str:
        return type(kept) is kind and kept == given
    if isinstance(kept, np.ndarray):
        return isinstance(given, np.ndarray) and kept.shape == given.shape and kept.dtype == given.dtype and bool(np.all(kept == given))
    if kind is tuple or kind is list:
        try:
            return type(kept) is kind and bool(kept == given)
        except ValueError:  # sequences of arrays: no single truth value
            return False
    return kept is given


def same_shortcuts(kept: dict[str, Any], given: ConditionFields) -> bool:
    """Whether a call's keyword shortcuts ``given`` are those ``kept`` (each by :func:`kept_shortcut`)."""
    if kept.keys() != given.keys():
        return False
    return all(_same_value(kept[name], value) for name, value in given.items())
