"""Shared by the tests of the whole-robot numpy reference (``test_reference_robot*.py``): the
reference package loaded standalone, duck-typed descriptions and random robots built here, and
rotations written here (quaternions), independent of the reference."""

import math
from types import SimpleNamespace
from typing import Any

import numpy as np
from pure import load_reference

NS = SimpleNamespace
RHO, G = 1000.0, 9.81


ref = load_reference()

PARTS = ("drag", "added_mass", "buoyancy", "gravity")
KEYS = PARTS + tuple(f"base_{p}" for p in PARTS)


def assert_close(got: Any, expected: Any, rtol: float, what: str = "", atol: float = 0.0) -> None:
    """``|got − expected| <= rtol · max|expected| + atol`` elementwise (one scale per array)."""
    got, expected = np.asarray(got, dtype=float), np.asarray(expected, dtype=float)
    assert got.shape == expected.shape, f"{what}: shape {got.shape} != {expected.shape}"
    scale = float(np.max(np.abs(expected))) if expected.size else 0.0
    err = float(np.max(np.abs(got - expected))) if expected.size else 0.0
    message = f"{what}: max error {err:.3e} > {rtol:.0e} × scale {scale:.3e} + {atol:.0e}\ngot {got}\nexpected {expected}"
    assert err <= rtol * scale + atol, message


# --------------------------------------------------------------------------------------------
# Descriptions (duck-typed, built here) and random robots
# --------------------------------------------------------------------------------------------


def unit(v: Any) -> np.ndarray:
    v = np.asarray(v, dtype=float)
    return v / np.linalg.norm(v)


def random_unit(rng: np.random.Generator) -> np.ndarray:
    return unit(rng.normal(size=3))


def cylinder(start: Any, axis: Any, length: float, diameter: float, cd: float = 1.2, cm: float = 1.0) -> NS:
    area = math.pi * diameter**2 / 4
    axis = tuple(unit(axis))
    return NS(start=tuple(start), axis=axis, length=length, section="circular", diameter=diameter, area=area, cd=(cd, cd), cm=(cm, cm))


def box(start: Any, axis: Any, length: float, normals: Any, widths: Any, area: float, cd: Any = (2.2, 2.2), cm: Any = (0.5, 0.5)) -> NS:
    return NS(
        start=tuple(start),
        axis=tuple(unit(axis)),
        length=length,
        section="rectangular",
        normals=tuple(map(tuple, normals)),
        widths=tuple(widths),
        area=area,
        cd=tuple(cd),
        cm=tuple(cm),
    )


def body(mass: float = 0.0, com: Any = (0, 0, 0), volume: float = 0.0, cob: Any = None, segments: tuple = ()) -> NS:
    return NS(mass=mass, com=tuple(com), volume=volume, cob=None if cob is None else tuple(cob), segments=tuple(segments))


def joint(origin: Any, axis: Any, parent: int | None = None, kind: str = "revolute") -> NS:
    return NS(origin=tuple(origin), axis=tuple(unit(axis)), parent=parent, kind=kind)


def random_segment(rng: np.random.Generator) -> NS:
    axis = random_unit(rng) if rng.random() < 0.8 else np.eye(3)[rng.integers(3)]
    start = rng.uniform(-0.3, 0.3, 3)
    length = float(rng.uniform(0.1, 0.9))
    if rng.random() < 0.5:
        d = float(rng.uniform(0.02, 0.3))
        return cylinder(start, axis, length, d, cd=float(rng.uniform(0.5, 2.0)), cm=float(rng.uniform(0.5, 1.5)))
    n1 = unit(np.cross(axis, random_unit(rng)))
    n2 = np.cross(axis, n1)
    widths = rng.uniform(0.03, 0.3, 2)
    area = float(widths.prod() * rng.uniform(0.6, 1.0))
    return box(start, axis, length, (n1, n2), widths, area, cd=rng.uniform(0.5, 3.0, 2), cm=rng.uniform(0.2, 1.5, 2))


def random_body(rng: np.random.Generator, segments: int | None = None) -> NS:
    count = int(rng.integers(0, 3)) if segments is None else segments
    mass = float(rng.uniform(0.2, 20.0))
    com = rng.uniform(-0.4, 0.4, 3)
    segments = tuple(random_segment(rng) for _ in range(count))
    return body(mass, com, mass / float(rng.uniform(1000.0, 8000.0)), com + rng.uniform(-0.1, 0.1, 3), segments)


def random_tree(
    rng: np.random.Generator, n: int | None = None, *, base: bool | None = None, prismatic: float = 0.35
) -> tuple[list, list, NS | None]:
    """Random parents (default, the base, or any earlier link), kinds, axes, origins; links with
    0-2 random rectangular or circular segments; a random base body or none."""
    n = int(rng.integers(1, 6)) if n is None else n
    joints, links = [], []
    for i in range(n):
        r = rng.random()
        parent = None if r < 0.4 else (-1 if r < 0.55 else int(rng.integers(-1, i)))
        kind = "prismatic" if rng.random() < prismatic else "revolute"
        axis = random_unit(rng) if rng.random() < 0.8 else np.eye(3)[rng.integers(3)] * rng.choice([-1.0, 1.0])
        origin = np.zeros(3) if rng.random() < 0.15 else rng.uniform(-0.5, 0.5, 3)
        joints.append(joint(origin, axis, parent, kind))
        links.append(random_body(rng, segments=1 if i == n - 1 else None))
    has_base = rng.random() < 0.7 if base is None else base
    return joints, links, (random_body(rng) if has_base else None)


def random_quaternion(rng: np.random.Generator, m: int | None = None) -> np.ndarray:
    shape = (4,) if m is None else (m, 4)
    q = rng.normal(size=shape)
    return q / np.linalg.norm(q, axis=-1, keepdims=True)


def random_motion(rng: np.random.Generator, m: int, n: int) -> dict[str, np.ndarray]:
    """States and base motion and current, one per sample (some exact zeros)."""
    qd = rng.uniform(-2.0, 2.0, (m, n))
    qd[rng.random((m, n)) < 0.15] = 0.0
    return {
        "q": rng.uniform(-math.pi, math.pi, (m, n)),
        "qd": qd,
        "qdd": rng.uniform(-5.0, 5.0, (m, n)),
        "orientation": random_quaternion(rng, m),
        "velocity": rng.uniform(-1.0, 1.0, (m, 3)),
        "angular_velocity": rng.uniform(-1.0, 1.0, (m, 3)),
        "acceleration": rng.uniform(-2.0, 2.0, (m, 3)),
        "angular_acceleration": rng.uniform(-2.0, 2.0, (m, 3)),
        "current": rng.uniform(-0.8, 0.8, (m, 3)),
        "current_acceleration": rng.uniform(-1.0, 1.0, (m, 3)),
    }


def hydro(joints: Any, links: Any, base: Any, motion: dict, **kwargs: Any) -> dict[str, np.ndarray]:
    m = dict(motion)
    return ref.robot_hydro(joints, links, base, m.pop("q"), m.pop("qd"), m.pop("qdd"), **m, **kwargs)


# --------------------------------------------------------------------------------------------
# Rotations written here (quaternions), independent of the reference
# --------------------------------------------------------------------------------------------


def quat_mul(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    w1, x1, y1, z1 = a
    w2, x2, y2, z2 = b
    return np.array(
        [
            w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2,
            w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
            w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2,
            w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2,
        ]
    )


def quat_axis_angle(axis: Any, angle: Any) -> np.ndarray:
    """The quaternion ``(cos θ/2, sin θ/2 · axis)``; a complex angle is allowed."""
    axis = np.asarray(axis, dtype=float)
    return np.concatenate([[np.cos(angle / 2)], np.sin(angle / 2) * axis])


def quat_matrix(q: np.ndarray) -> np.ndarray:
    """Rotation matrix of a unit quaternion (w, x, y, z) (complex entries allowed)."""
    w, x, y, z = q
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
        ]
    )


def rotation_vector_matrix(phi: np.ndarray) -> np.ndarray:
    """``exp([φ]×)`` for a real rotation vector, via its quaternion."""
    angle = float(np.linalg.norm(phi))
    if angle == 0.0:
        return np.eye(3)
    return quat_matrix(quat_axis_angle(phi / angle, angle))


def skew(v: Any) -> np.ndarray:
    return np.array([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]])
