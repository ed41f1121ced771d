"""Shared by the tests of serial chains evaluated by the Rust core (``test_chain_*.py``,
``test_evaluation_inputs.py``): random chains built with ``uwml.Joint``, ``uwml.Link`` and
``uwml.Segment`` (a chain is a :class:`uwml.Robot` whose joints are in series), random states,
coefficients and water, and the comparison against expected values, whose expected values come
from elsewhere (``uwml.reference``, the paper, forward kinematics written here).

How "relative error" is measured (``assert_batch_close``): per sample, the largest absolute
difference over all entries of the sample (joints, and links and directions for regressors),
divided by the largest absolute expected entry of that sample. One sample's entries can all
be tiny while its terms are not (a one-joint chain whose centre of buoyancy lies almost on the
vertical through the joint axis; the added-mass torque of a slice whose moment arm changes sign
along the link): rounding errors scale with the terms, not with their sum. So the per-sample
scale is never taken below 1e-3 of the largest expected entry of the batch, nor below 1e-4 of
the sample's natural size (``natural_scales``: ρ Cd w L V² R for drag and so on, from the chain's
dimensions and the sample's speeds; it matters only on degenerate chains, e.g. a segment lying on
its joint's axis, whose whole batch is rounding noise), nor below 1e-300. This is stricter than
one relative error per batch, and does not blow up on entries that cancel to near zero.
"""

import math

import numpy as np
import uwml
from hypothesis import settings
from hypothesis import strategies as st

# docs/model.md sections 2 and 5 (Table II, and the reference values).
RHO, G = 1000.0, 9.81
RHO_M = 2700.0
L2, L3, L2C, L3C = 0.660, 0.714, 0.506, 0.560
D21, D22, D31, D32 = 0.131, 0.238, 0.131, 0.279
M2, M3 = 19.261, 10.375

#: Tolerance of the Rust core against the reference (relative, see the module docstring), on
#: random chains and on the paper's leg (measured worst: 2.5e-14).
RTOL_REFERENCE = 1e-10
RTOL_PAPER = 1e-12
#: Tolerance of exact algebraic relations evaluated twice by the core (rounding only).
RTOL_ROUNDING = 1e-12
#: Smallest scale of a relative error: below it an expected value counts as exactly zero.
TINY = 1e-300

PAPER = uwml.paper_leg()
seeds = st.integers(0, 2**32 - 1)


def scaled(fraction: float) -> settings:
    """A fraction of the profile's examples, for tests whose every example is a large batch."""
    return settings(max_examples=max(5, int(settings.default.max_examples * fraction)))


REFERENCE_EXAMPLES = scaled(1 / 4)  # 50 (fast) or 500 (slow) batches of 1000-3000 states
PROPERTY_EXAMPLES = scaled(1 / 4)  # 50 or 500 smaller batches


def random_unit(rng: np.random.Generator) -> np.ndarray:
    v = rng.normal(size=3)
    return v / np.linalg.norm(v)


def random_chain(rng: np.random.Generator, n: int | None = None) -> tuple[uwml.Robot, list, list]:
    """A random chain of 1-6 joints built with uwml.Joint/Link/Segment; returns the robot and the
    joints and links as the user built them (given to the reference, so that a mistake in
    passing them to Rust cannot cancel out).

    Random unit axes (sometimes an exact coordinate axis, sometimes the parent's axis, so
    parallel and intersecting axes occur), random origins (sometimes zero), random orthonormal
    normals, some links without a segment, the centre of buoyancy away from the centre of mass,
    any link density.
    """
    n = int(rng.integers(1, 7)) if n is None else n
    joints, links = [], []
    previous_axis = np.array([0.0, 0.0, 1.0])
    for i in range(n):
        r = rng.random()
        if r < 0.15:
            axis = np.eye(3)[rng.integers(3)] * rng.choice([-1.0, 1.0])
        elif r < 0.3:
            axis = previous_axis
        else:
            axis = random_unit(rng)
        origin = np.zeros(3) if rng.random() < 0.2 else rng.uniform(-0.5, 0.5, 3)
        joints.append(uwml.Joint(origin=tuple(origin), axis=tuple(axis)))
        previous_axis = axis
        segment = None
        if i == n - 1 or rng.random() < 0.7:
            seg_axis = axis if rng.random() < 0.1 else random_unit(rng)
            n1 = np.cross(seg_axis, random_unit(rng))
            n1 /= np.linalg.norm(n1)
            n2 = np.cross(seg_axis, n1)
            widths = rng.uniform(0.03, 0.3, 2)
            segment = uwml.Segment(
                start=tuple(np.zeros(3) if rng.random() < 0.2 else rng.uniform(-0.2, 0.2, 3)),
                axis=tuple(seg_axis),
                length=float(rng.uniform(0.1, 1.0)),
                normals=(tuple(n1), tuple(n2)),
                widths=tuple(widths),
                area=float(widths[0] * widths[1] * rng.uniform(0.6, 1.0)),
            )
        mass = float(rng.uniform(0.2, 20.0))
        com = rng.uniform(-0.4, 0.4, 3)
        links.append(
            uwml.Link(
                mass=mass,
                com=tuple(com),
                volume=mass / float(rng.uniform(1000.0, 8000.0)),
                cob=tuple(com + rng.uniform(-0.1, 0.1, 3)),
                segments=() if segment is None else (segment,),
            )
        )
    return uwml.Robot(joints, links), joints, links


def chain_or_paper(kind: str, rng: np.random.Generator) -> tuple[uwml.Robot, tuple, tuple]:
    if kind == "paper":
        return PAPER, PAPER.joints, PAPER.links
    return random_chain(rng)


def drawn(
    kind: str, seed: int, m: int | None = None
) -> tuple[np.random.Generator, uwml.Robot, tuple, tuple, tuple[np.ndarray, np.ndarray, np.ndarray]]:
    """A test's draw: the random generator of ``seed``, the chain of ``kind`` (``"paper"`` or a
    random ``"chain"``) with its joints and links, and ``m`` random states of it (None: 1000 to
    3000)."""
    rng = np.random.default_rng(seed)
    leg, joints, links = chain_or_paper(kind, rng)
    m = int(rng.integers(1000, 3001)) if m is None else m
    return rng, leg, tuple(joints), tuple(links), random_states(rng, m, leg.n_joints)


def random_states(rng: np.random.Generator, m: int, n: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """q in [-π, π], q̇ in [-3, 3], q̈ in [-10, 10]; exact zeros in single q̇ entries, whole rows
    at rest (q̇ = 0) and rows without acceleration."""
    q = rng.uniform(-math.pi, math.pi, (m, n))
    qd = rng.uniform(-3.0, 3.0, (m, n))
    qdd = rng.uniform(-10.0, 10.0, (m, n))
    qd[rng.random((m, n)) < 0.15] = 0.0
    qd[rng.random(m) < 0.03] = 0.0
    qdd[rng.random(m) < 0.03] = 0.0
    return q, qd, qdd


LAYOUTS = ("scalar", "per link", "per direction")
layouts = st.sampled_from(LAYOUTS)


def random_coefficients(rng: np.random.Generator, n: int, layout: str | None = None) -> tuple[object, object]:
    """Cd and Cm as a scalar, per link (n,) or per link and direction (n, 2), as the chain
    reference takes them; some zeros (:func:`per_segment` gives them as a robot takes them)."""
    layout = LAYOUTS[int(rng.integers(3))] if layout is None else layout
    if layout == "scalar":
        return float(rng.uniform(0.5, 3.0)), float(rng.uniform(0.1, 1.5))
    shape = (n,) if layout == "per link" else (n, 2)
    cd, cm = rng.uniform(0.5, 3.0, shape), rng.uniform(0.1, 1.5, shape)
    cd[rng.random(shape) < 0.1] = 0.0
    cm[rng.random(shape) < 0.1] = 0.0
    return cd, cm


def segment_coefficients(rng: np.random.Generator, links, layout: str | None = None) -> tuple[object, object]:
    """:func:`random_coefficients` as the robot takes them (:func:`per_segment`)."""
    cd, cm = random_coefficients(rng, len(links), layout)
    return per_segment(links, cd), per_segment(links, cm)


def per_segment(links, value: object) -> object:
    """A coefficient per link (``(n,)`` or ``(n, 2)``) as the robot takes it: the entries of the
    links that carry a segment, in segment order; a scalar as it is."""
    if np.ndim(value) == 0:
        return value
    return np.asarray(value)[[i for i, link in enumerate(links) if link.segments]]


def random_water(rng: np.random.Generator) -> tuple[float, float]:
    if rng.random() < 0.5:
        return RHO, G
    return float(rng.uniform(900.0, 1100.0)), float(rng.choice([0.0, rng.uniform(1.0, 12.0)]))


def natural_scales(joints, links, qd: np.ndarray, qdd: np.ndarray, density: float = RHO, gravity: float = G, cd=1.0, cm=1.0) -> dict:
    """The natural size (m,) of each torque of every sample, from the chain's dimensions alone:
    R = reach of the chain, V = R Σ|q̇_j| (bound on any point's speed), A = R (Σ|q̈_j| + (Σ|q̇_j|)²);
    drag ~ ½ρ Cd Σ w L V² R, added mass ~ ρ Cm Σ A L A R, buoyancy ~ ρ g Σ V R, gravity ~ g Σ m R."""
    reach = sum(float(np.linalg.norm(j.origin)) for j in joints)
    extent = [max(np.linalg.norm(link.com), np.linalg.norm(link.cob)) for link in links]
    segments = [segment for link in links for segment in link.segments]
    extent += [np.linalg.norm(s.start) + s.length for s in segments]
    reach += float(max(extent))
    qd, qdd = np.atleast_2d(qd), np.atleast_2d(qdd)
    rate = np.abs(qd).sum(axis=1)
    speed, acceleration = reach * rate, reach * (np.abs(qdd).sum(axis=1) + rate**2)
    drag = 0.5 * density * float(np.max(cd)) * sum(max(s.widths) * s.length for s in segments) * speed**2 * reach
    added_mass = density * float(np.max(cm)) * sum(s.area * s.length for s in segments) * acceleration * reach
    ones = np.ones_like(rate)
    buoyancy = density * gravity * sum(link.volume for link in links) * reach * ones
    weight = gravity * sum(link.mass for link in links) * reach * ones
    return {"drag": drag, "added_mass": added_mass, "buoyancy": buoyancy, "gravity": weight, "total": drag + added_mass + buoyancy}


def relative_errors(actual: np.ndarray, expected: np.ndarray, natural=0.0) -> np.ndarray:
    """Per-sample relative error (see the module docstring); leading axis = samples."""
    actual, expected = np.asarray(actual), np.asarray(expected)
    assert actual.shape == expected.shape, f"shape {actual.shape}, expected {expected.shape}"
    m = expected.shape[0] if expected.ndim > 1 else 1
    a, e = actual.reshape(m, -1), expected.reshape(m, -1)
    row = np.abs(e).max(axis=1, initial=0.0)
    floor = np.maximum(max(1e-3 * float(row.max(initial=0.0)), TINY), 1e-4 * np.asarray(natural))
    return np.abs(a - e).max(axis=1, initial=0.0) / np.maximum(row, floor)


def assert_batch_close(actual: np.ndarray, expected: np.ndarray, rtol: float, what: str, natural=0.0) -> None:
    err = relative_errors(actual, expected, natural)
    if err.size == 0:
        return
    worst = int(np.nanargmax(err)) if not np.all(np.isnan(err)) else 0
    a = np.asarray(actual).reshape(err.size, -1)[worst]
    e = np.asarray(expected).reshape(err.size, -1)[worst]
    assert np.all(np.isfinite(actual)), f"{what}: non-finite values"
    assert err[worst] <= rtol, f"{what}: relative error {err[worst]:.3g} > {rtol:g} at sample {worst}:\n got      {a}\n expected {e}"


def rodrigues(axis: np.ndarray, angle: np.ndarray) -> np.ndarray:
    """Rotation matrices (m, 3, 3) by ``angle`` (m,) about the unit ``axis``."""
    x, y, z = axis
    k = np.array([[0.0, -z, y], [z, 0.0, -x], [-y, x, 0.0]])
    s, c = np.sin(angle)[:, None, None], np.cos(angle)[:, None, None]
    return np.eye(3) + s * k + (1.0 - c) * (k @ k)


def link_frames(joints, q: np.ndarray) -> list[tuple[np.ndarray, np.ndarray]]:
    """World (rotation (m, 3, 3), origin (m, 3)) of every link frame, by the frame convention of
    uwml.model: joint i at ``origin`` in link i-1's frame, turning link i about ``axis`` by q_i."""
    m = q.shape[0]
    rotation, origin = np.broadcast_to(np.eye(3), (m, 3, 3)), np.zeros((m, 3))
    frames = []
    for j, joint in enumerate(joints):
        origin = origin + rotation @ np.asarray(joint.origin, dtype=float)
        rotation = rotation @ rodrigues(np.asarray(joint.axis, dtype=float), q[:, j])
        frames.append((rotation, origin))
    return frames


def potential_heights(joints, links, q: np.ndarray, point: str, weight: str) -> np.ndarray:
    """``Σ_i weight_i · z(point_i)`` (m,): e.g. Σ V_i c_i,z for buoyancy, Σ m_i com_i,z for weight."""
    total = np.zeros(q.shape[0])
    for link, (rotation, origin) in zip(links, link_frames(joints, q)):
        local = np.asarray(getattr(link, point), dtype=float)
        total += float(getattr(link, weight)) * (origin + rotation @ local)[:, 2]
    return total


def gradient(fun, q: np.ndarray, step: float = 1e-3) -> np.ndarray:
    """∂fun/∂q (m, n) by the 4th-order central difference (error ~ step⁴ and eps/step)."""
    grad = np.empty_like(q)
    for j in range(q.shape[1]):
        e = np.zeros(q.shape[1])
        e[j] = step
        grad[:, j] = (8.0 * (fun(q + e) - fun(q - e)) - (fun(q + 2 * e) - fun(q - 2 * e))) / (12.0 * step)
    return grad
