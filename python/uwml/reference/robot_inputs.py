"""The inputs of the whole-robot reference (:mod:`uwml.reference.robot_hydro`), checked and packed into
arrays: the robot description (joints, bodies, segments, coefficients) and the base motion and
current of every sample. numpy and the standard library only, like the rest of the reference.
A body's lumped model (docs/model.md section 12.1) is packed beside its segments."""

# No ``from __future__ import annotations``: see uwml.reference.chain.
import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ._inputs import _AXIS_TOLERANCE, _LUMPED_EIGENVALUE_TOLERANCE, _LUMPED_SYMMETRY_TOLERANCE, Array, _lumped_tolerance, _number, _vector

BoolArray = NDArray[np.bool_]
IndexArray = NDArray[np.intp]

#: Tolerance on the norm of the base orientation quaternion.
_QUATERNION_TOLERANCE = 1e-6

_KINDS = ("revolute", "prismatic")
_SECTIONS = ("rectangular", "circular")


# --------------------------------------------------------------------------------------------
# The robot description, checked and packed into arrays
# --------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class _Robot:
    parents: tuple[int, ...]  # (N,) parent body of joint j: 0 = base, i + 1 = link i
    prismatic: BoolArray  # (N,)
    origins: Array  # (N, 3) joint origins in the parent's frame
    axes: Array  # (N, 3) joint axes in the parent's frame
    moves: BoolArray  # (B, N): joint j moves body b (b = 0 base, i + 1 link i)
    masses: Array  # (B,)
    coms: Array  # (B, 3) in body frames
    volumes: Array  # (B,)
    cobs: Array  # (B, 3) in body frames
    seg_body: IndexArray  # (S,) body index of each segment
    seg_start: Array  # (S, 3)
    seg_axis: Array  # (S, 3)
    seg_length: Array  # (S,)
    seg_normals: Array  # (S, 2, 3) (zeros for circular segments)
    seg_widths: Array  # (S, 2) (the diameter twice for circular segments)
    seg_area: Array  # (S,)
    seg_circular: BoolArray  # (S,)
    seg_cd: Array  # (S, 2), NaN where the segment has no coefficient of its own
    seg_cm: Array  # (S, 2)
    seg_cd_axial: Array  # (S,) axial drag coefficient (docs/model.md section 12.2), 0: none
    seg_axial_area: Array  # (S,) its reference area
    lumped_body: IndexArray  # (L,) body index of each lumped model (docs/model.md section 12.1)
    lumped_point: Array  # (L, 3) its reference point P in the body's frame
    lumped_axes: Array  # (L, 3, 3) the model's axes in the body's frame (body from model)
    lumped_mass: Array  # (L, 6, 6) M_A about P, body components
    lumped_linear: Array  # (L, 6, 6) D_L
    lumped_quadratic: Array  # (L, 6) d_i

    @property
    def n_joints(self) -> int:
        return len(self.parents)

    @property
    def n_bodies(self) -> int:
        return len(self.masses)


def _own_coefficient(value: Any, name: str, circular: bool) -> Array:
    if value is None:
        return np.full(2, np.nan)
    a = np.asarray(value, dtype=np.float64)
    if a.shape == ():
        a = np.full(2, float(a))
    if a.shape != (2,) or not np.all(np.isfinite(a)) or np.any(a < 0.0):
        raise ValueError(f"{name} must be one finite number >= 0 or a pair of them, got {value!r}")
    if circular and a[0] != a[1]:
        raise ValueError(f"{name} of a circular segment must be one number (equal pair), got {value!r}")
    return a


def _segment_arrays(segment: Any, name: str) -> dict[str, Any]:
    section = getattr(segment, "section", "rectangular")
    if section not in _SECTIONS:
        raise ValueError(f"{name}.section must be one of {_SECTIONS}, got {section!r}")
    axis = _vector(segment.axis, f"{name}.axis", unit=True)
    axis = axis / np.linalg.norm(axis)
    length = _number(segment.length, f"{name}.length", positive=True)
    circular = section == "circular"
    if circular:
        diameter = _number(segment.diameter, f"{name}.diameter", positive=True)
        area_value = getattr(segment, "area", None)
        area = math.pi * diameter * diameter / 4.0 if area_value is None else _number(area_value, f"{name}.area", positive=True)
        normals = np.zeros((2, 3))
        widths = np.array([diameter, diameter])
    else:
        normals = np.array([_vector(n, f"{name}.normals[{k}]", unit=True) for k, n in enumerate(segment.normals)])
        if normals.shape != (2, 3):
            raise ValueError(f"{name}.normals must hold 2 vectors, got {len(normals)}")
        normals = normals / np.linalg.norm(normals, axis=1, keepdims=True)
        pairs = (
            ("normals[0]·axis", normals[0], axis),
            ("normals[1]·axis", normals[1], axis),
            ("normals[0]·normals[1]", normals[0], normals[1]),
        )
        for label, a, b in pairs:
            if abs(float(a @ b)) > _AXIS_TOLERANCE:
                raise ValueError(f"{name}.{label} must be 0 (orthonormal normals perpendicular to the axis), got {a @ b}")
        pair = tuple(segment.widths)
        if len(pair) != 2:
            raise ValueError(f"{name}.widths must hold 2 numbers, got {len(pair)}")
        widths = np.array([_number(w, f"{name}.widths[{k}]", positive=True) for k, w in enumerate(pair)])
        area = _number(segment.area, f"{name}.area", positive=True)
    return {
        "start": _vector(segment.start, f"{name}.start"),
        "axis": axis,
        "length": length,
        "normals": normals,
        "widths": widths,
        "area": area,
        "circular": circular,
        "cd": _own_coefficient(getattr(segment, "cd", None), f"{name}.cd", circular),
        "cm": _own_coefficient(getattr(segment, "cm", None), f"{name}.cm", circular),
        # Axial drag (docs/model.md section 12.2): none unless given; its area defaults to the section's.
        "cd_axial": _number(getattr(segment, "cd_axial", 0.0) or 0.0, f"{name}.cd_axial", positive=False),
        "axial_area": area
        if getattr(segment, "axial_area", None) is None
        else _number(segment.axial_area, f"{name}.axial_area", positive=False),
    }


def _lumped_arrays(lumped: Any, name: str, cob: Array) -> dict[str, Array]:
    """A body's lumped model (docs/model.md section 12.1), duck-typed: ``point`` (None: the body's
    centre of buoyancy), ``axes`` (a 3×3 rotation, body from model; None or missing: the
    identity), ``added_mass`` (6×6, symmetric), ``linear_damping`` (6×6), ``quadratic_damping``
    (6, each ≥ 0), the last three in the model's axes; a missing field is zero."""
    point = getattr(lumped, "point", None)
    out = {"point": cob if point is None else _vector(point, f"{name}.point")}
    axes = getattr(lumped, "axes", None)
    rotation = np.eye(3) if axes is None else np.asarray(axes, dtype=np.float64)
    if rotation.shape != (3, 3) or not np.all(np.isfinite(rotation)) or np.max(np.abs(rotation.T @ rotation - np.eye(3))) > 1e-6:
        raise ValueError(f"{name}.axes must be a 3×3 rotation, got {axes!r}")
    out["axes"] = rotation
    for key, shape in (("added_mass", (6, 6)), ("linear_damping", (6, 6)), ("quadratic_damping", (6,))):
        value = getattr(lumped, key, None)
        try:
            a = np.zeros(shape) if value is None else np.asarray(value, dtype=np.float64)
        except (TypeError, ValueError) as exc:
            raise ValueError(f"{name}.{key} must be an array of numbers, got {value!r}") from exc
        if a.shape != shape or not np.all(np.isfinite(a)):
            raise ValueError(f"{name}.{key} must be finite, of shape {shape}, got {value!r}")
        out[key] = a
    mass = out["added_mass"]
    allowed = _lumped_tolerance(_LUMPED_SYMMETRY_TOLERANCE, float(np.max(np.abs(mass))))
    if np.any(np.abs(mass - mass.T) > allowed):
        raise ValueError(f"{name}.added_mass must be symmetric within {allowed:g}, got {mass.tolist()}")
    for key, what in (("added_mass", "be positive semi-definite"), ("linear_damping", "have a positive semi-definite symmetric part")):
        symmetric = 0.5 * (out[key] + out[key].T)
        smallest = float(np.linalg.eigvalsh(symmetric)[0])
        allowed = _lumped_tolerance(_LUMPED_EIGENVALUE_TOLERANCE, float(np.max(np.abs(np.diag(symmetric)))))
        if smallest < -allowed:
            raise ValueError(f"{name}.{key} must {what}: its smallest eigenvalue is {smallest:.6g}, below the allowed {-allowed:g}")
    for index, d in enumerate(out["quadratic_damping"]):
        if d < 0.0:
            raise ValueError(f"{name}.quadratic_damping[{index}] must be >= 0, got {d}")
    return out


def _segments_of(body: Any) -> tuple[Any, ...]:
    return tuple(getattr(body, "segments", ()))


def _robot(joints: Sequence[Any], links: Sequence[Any], base: Any | None) -> _Robot:
    joints, links = list(joints), list(links)
    if len(joints) != len(links):
        raise ValueError(f"joints and links must have equal length, got {len(joints)} joints and {len(links)} links")
    n = len(joints)
    parents, prismatic = [], []
    moves = np.zeros((n + 1, n), dtype=bool)
    for i, joint in enumerate(joints):
        parent = getattr(joint, "parent", None)
        parent = i - 1 if parent is None else parent
        if isinstance(parent, bool) or not isinstance(parent, (int, np.integer)) or not -1 <= parent < i:
            raise ValueError(f"joints[{i}].parent must be -1 (the base), None, or a link index < {i}, got {parent!r}")
        kind = getattr(joint, "kind", "revolute")
        if kind not in _KINDS:
            raise ValueError(f"joints[{i}].kind must be one of {_KINDS}, got {kind!r}")
        parents.append(int(parent) + 1)
        prismatic.append(kind == "prismatic")
        moves[i + 1] = moves[int(parent) + 1]
        moves[i + 1, i] = True
    origins = np.array([_vector(j.origin, f"joints[{i}].origin") for i, j in enumerate(joints)]).reshape(n, 3)
    axes = np.array([_vector(j.axis, f"joints[{i}].axis", unit=True) for i, j in enumerate(joints)]).reshape(n, 3)
    axes = axes / np.linalg.norm(axes, axis=1, keepdims=True) if n else axes

    bodies: list[tuple[str, Any]] = [("base", base)] + [(f"links[{i}]", link) for i, link in enumerate(links)]
    masses, coms, volumes, cobs, segments = [], [], [], [], []
    lumped: list[tuple[int, dict[str, Array]]] = []
    for b, (name, body) in enumerate(bodies):
        if body is None:
            if b > 0:
                raise ValueError(f"{name} must be a link description, got None")
            masses.append(0.0)
            coms.append(np.zeros(3))
            volumes.append(0.0)
            cobs.append(np.zeros(3))
            continue
        masses.append(_number(body.mass, f"{name}.mass", positive=False))
        com = _vector(body.com, f"{name}.com")
        coms.append(com)
        volumes.append(_number(body.volume, f"{name}.volume", positive=False))
        cob = getattr(body, "cob", None)
        cobs.append(com if cob is None else _vector(cob, f"{name}.cob"))
        model = getattr(body, "lumped", None)
        if model is not None:
            lumped.append((b, _lumped_arrays(model, f"{name}.lumped", cobs[-1])))
        for k, segment in enumerate(_segments_of(body)):
            segments.append((b, _segment_arrays(segment, f"{name}.segments[{k}]")))

    def stack(key: str, shape: tuple[int, ...]) -> Array:
        return np.array([s[key] for _, s in segments], dtype=np.float64).reshape((len(segments), *shape))

    return _Robot(
        parents=tuple(parents),
        prismatic=np.array(prismatic, dtype=bool),
        origins=origins,
        axes=axes,
        moves=moves,
        masses=np.array(masses),
        coms=np.array(coms),
        volumes=np.array(volumes),
        cobs=np.array(cobs),
        seg_body=np.array([b for b, _ in segments], dtype=np.intp),
        seg_start=stack("start", (3,)),
        seg_axis=stack("axis", (3,)),
        seg_length=stack("length", ()),
        seg_normals=stack("normals", (2, 3)),
        seg_widths=stack("widths", (2,)),
        seg_area=stack("area", ()),
        seg_circular=np.array([s["circular"] for _, s in segments], dtype=bool),
        seg_cd=stack("cd", (2,)),
        seg_cm=stack("cm", (2,)),
        seg_cd_axial=stack("cd_axial", ()),
        seg_axial_area=stack("axial_area", ()),
        lumped_body=np.array([b for b, _ in lumped], dtype=np.intp),
        lumped_point=np.array([m["point"] for _, m in lumped], dtype=np.float64).reshape(len(lumped), 3),
        lumped_axes=np.array([m["axes"] for _, m in lumped], dtype=np.float64).reshape(len(lumped), 3, 3),
        lumped_mass=np.array([m["added_mass"] for _, m in lumped], dtype=np.float64).reshape(len(lumped), 6, 6),
        lumped_linear=np.array([m["linear_damping"] for _, m in lumped], dtype=np.float64).reshape(len(lumped), 6, 6),
        lumped_quadratic=np.array([m["quadratic_damping"] for _, m in lumped], dtype=np.float64).reshape(len(lumped), 6),
    )


def _coefficients(value: ArrayLike | None, name: str, own: Array, circular: BoolArray) -> Array:
    """Coefficients per segment and direction, (S, 2): the segments' own (``None``), one number,
    one per segment (S,) or one per segment and direction (S, 2)."""
    count = len(own)
    if value is None:
        if np.any(np.isnan(own)):
            missing = int(np.flatnonzero(np.isnan(own[:, 0]))[0])
            raise ValueError(f"segment {missing} (in the order base, link 0, link 1, ...) has no {name} of its own: pass {name}=")
        return own
    try:
        c = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{name} must be a number or an array of numbers, got {value!r}") from exc
    if c.shape == ():
        c = np.full((count, 2), float(c))
    elif c.shape == (count,):
        c = np.repeat(c[:, None], 2, axis=1)
    elif c.shape != (count, 2):
        raise ValueError(
            f"{name} must be a scalar, shape ({count},) (per segment) or ({count}, 2) (per segment and direction), got shape {c.shape}"
        )
    if not np.all(np.isfinite(c)) or np.any(c < 0.0):
        raise ValueError(f"{name} must be finite and non-negative, got {value!r}")
    if np.any(circular & (c[:, 0] != c[:, 1])):
        bad = int(np.flatnonzero(circular & (c[:, 0] != c[:, 1]))[0])
        raise ValueError(f"{name} of circular segment {bad} must be equal in both directions (cross-flow principle), got {c[bad]}")
    return c


# --------------------------------------------------------------------------------------------
# Samples
# --------------------------------------------------------------------------------------------


def _sampled(value: ArrayLike, name: str, width: int) -> tuple[Array, int | None]:
    """One value ``(width,)`` or one per sample ``(n, width)``, as ``(n or 1, width)``, and n."""
    try:
        a = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{name} must be an array of numbers, got {value!r}") from exc
    if a.shape == (width,):
        count = None
        a = a[None, :]
    elif a.ndim == 2 and a.shape[1] == width:
        count = a.shape[0]
    else:
        raise ValueError(f"{name} must have shape ({width},) or (n, {width}), got shape {a.shape}")
    if not np.all(np.isfinite(a)):
        raise ValueError(f"{name} must be finite")
    return a, count


@dataclass(frozen=True)
class _Motion:
    q: Array  # (n, N)
    qd: Array
    qdd: Array
    rotation: Array  # (n, 3, 3) world from base
    velocity: Array  # (n, 3) base components
    angular_velocity: Array
    acceleration: Array
    angular_acceleration: Array
    current: Array  # (n, 3) world
    current_acceleration: Array
    batched: bool


def _quaternion_rotation(quaternion: Array) -> Array:
    norm = np.linalg.norm(quaternion, axis=1)
    if np.any(np.abs(norm - 1.0) > _QUATERNION_TOLERANCE):
        worst = norm[np.argmax(np.abs(norm - 1.0))]
        raise ValueError(f"orientation must be a unit quaternion (w, x, y, z) (norm 1 within {_QUATERNION_TOLERANCE}), got norm {worst}")
    w, x, y, z = (quaternion / norm[:, None]).T
    return np.stack(
        [
            np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)], axis=-1),
            np.stack([2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)], axis=-1),
            np.stack([2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)], axis=-1),
        ],
        axis=-2,
    )


def _motion(n_joints: int, **values: ArrayLike) -> _Motion:
    widths = {"q": n_joints, "qd": n_joints, "qdd": n_joints, "orientation": 4}
    arrays, counts = {}, {}
    for name, value in values.items():
        arrays[name], count = _sampled(value, name, widths.get(name, 3))
        if count is not None:
            counts[name] = count
    if len(set(counts.values())) > 1:
        raise ValueError(f"inputs with a sample axis must agree on the number of samples, got {counts}")
    n = next(iter(counts.values())) if counts else 1
    full = {name: np.broadcast_to(a, (n, a.shape[1])) for name, a in arrays.items()}
    return _Motion(
        q=full["q"],
        qd=full["qd"],
        qdd=full["qdd"],
        rotation=_quaternion_rotation(full["orientation"]),
        velocity=full["velocity"],
        angular_velocity=full["angular_velocity"],
        acceleration=full["acceleration"],
        angular_acceleration=full["angular_acceleration"],
        current=full["current"],
        current_acceleration=full["current_acceleration"],
        batched=bool(counts),
    )
