"""The Rust path (``uwml.Leg.hydro``, ``uwml.Leg.hydro_regressors``) held against the numpy
reference, the paper's printed equations, the reference values and the properties of
docs/model.md section 5.

Nothing expected here is produced by the code under test: the expected values come from
``uwml.reference`` (an independent numpy implementation), from numbers typed from docs/model.md and
the paper (Table II, eqs. 8, 9, 17, 21), from forward kinematics written in this file, or from
relations between two evaluations (homogeneity, linearity, symmetry, conservation).

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
import threading

import numpy as np
import pytest
import uwml
from hypothesis import given, settings
from hypothesis import strategies as st
from uwml import reference as ref

# docs/model.md sections 2 and 5 (Table II, and the reference values).
RHO, G = 1000.0, 9.81
RHO_M = 2700.0
L2, L3, L2C, L3C = 0.660, 0.714, 0.506, 0.560
D21, D22, D31, D32 = 0.131, 0.238, 0.131, 0.279
M2, M3 = 19.261, 10.375

#: Tolerance of the Rust core against the reference (relative, see the module docstring).
RTOL_REFERENCE = 1e-10
#: Tolerance of exact algebraic relations evaluated twice by the core (rounding only).
RTOL_ROUNDING = 1e-12
#: Smallest scale of a relative error: below it an expected value counts as exactly zero.
TINY = 1e-300

PAPER = uwml.Leg.paper()
seeds = st.integers(0, 2**32 - 1)


def scaled(fraction: float) -> settings:
    """A fraction of the profile's examples, for tests whose every example is a large batch."""
    return settings(max_examples=max(5, int(settings.default.max_examples * fraction)))


REFERENCE_EXAMPLES = scaled(1 / 4)  # 50 (fast) or 500 (slow) batches of 1000-3000 states
PROPERTY_EXAMPLES = scaled(1 / 4)  # 50 or 500 smaller batches


# --------------------------------------------------------------------------------------------
# Helpers: random chains and states, comparison
# --------------------------------------------------------------------------------------------


def random_unit(rng: np.random.Generator) -> np.ndarray:
    v = rng.normal(size=3)
    return v / np.linalg.norm(v)


def random_chain(rng: np.random.Generator, n: int | None = None) -> tuple[uwml.Leg, list, list]:
    """A random chain of 1-6 joints built with uwml.Joint/Link/Segment; returns the leg and the
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
                segment=segment,
            )
        )
    return uwml.Leg(joints, links), joints, links


def chain_or_paper(kind: str, rng: np.random.Generator) -> tuple[uwml.Leg, tuple, tuple]:
    if kind == "paper":
        return PAPER, PAPER.joints, PAPER.links
    return random_chain(rng)


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
    """Cd and Cm as a scalar, per link (n,) or per link and direction (n, 2); some zeros."""
    layout = LAYOUTS[int(rng.integers(3))] if layout is None else layout
    if layout == "scalar":
        return float(rng.uniform(0.5, 3.0)), float(rng.uniform(0.1, 1.5))
    shape = (n,) if layout == "per link" else (n, 2)
    cd, cm = rng.uniform(0.5, 3.0, shape), rng.uniform(0.1, 1.5, shape)
    cd[rng.random(shape) < 0.1] = 0.0
    cm[rng.random(shape) < 0.1] = 0.0
    return cd, cm


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
    extent += [np.linalg.norm(link.segment.start) + link.segment.length for link in links if link.segment is not None]
    reach += float(max(extent))
    segments = [link.segment for link in links if link.segment is not None]
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


# --------------------------------------------------------------------------------------------
# 1. The Rust core against the numpy reference
# --------------------------------------------------------------------------------------------


@pytest.mark.parametrize("kind", ["paper", "chain"])
@REFERENCE_EXAMPLES
@given(seed=seeds, layout=layouts)
def test_hydro_matches_reference(kind: str, seed: int, layout: str) -> None:
    rng = np.random.default_rng(seed)
    leg, joints, links = chain_or_paper(kind, rng)
    q, qd, qdd = random_states(rng, int(rng.integers(1000, 3001)), leg.n_joints)
    cd, cm = random_coefficients(rng, leg.n_joints, layout)
    density, gravity = random_water(rng)
    out = leg.hydro(q, qd, qdd, cd=cd, cm=cm, water=uwml.Water(density=density, gravity=gravity))
    expected = ref.hydro(joints, links, q, qd, qdd, cd=cd, cm=cm, density=density, gravity=gravity)
    natural = natural_scales(joints, links, qd, qdd, density, gravity, cd, cm)
    for key in ("drag", "added_mass", "buoyancy", "gravity", "total"):
        assert_batch_close(getattr(out, key), expected[key], RTOL_REFERENCE, f"{kind} {key}", natural[key])
    if kind == "paper":
        # The preset against the reference's own Table II leg (catches preset mistakes that
        # leg.joints/leg.links would carry over to the reference).
        preset = ref.hydro(*ref.paper_leg(), q, qd, qdd, cd=cd, cm=cm, density=density, gravity=gravity)
        for key in ("drag", "added_mass", "buoyancy", "gravity", "total"):
            assert_batch_close(getattr(out, key), preset[key], RTOL_REFERENCE, f"paper preset {key}", natural[key])


@pytest.mark.parametrize("kind", ["paper", "chain"])
@REFERENCE_EXAMPLES
@given(seed=seeds, layout=layouts)
def test_regressors_match_reference(kind: str, seed: int, layout: str) -> None:
    rng = np.random.default_rng(seed)
    leg, joints, links = chain_or_paper(kind, rng)
    n = leg.n_joints
    m = int(rng.integers(1000, 3001))
    q, qd, qdd = random_states(rng, m, n)
    density, gravity = random_water(rng)
    water = uwml.Water(density=density, gravity=gravity)
    expected = ref.regressors(joints, links, q, qd, qdd, density=density, gravity=gravity)
    unit = natural_scales(joints, links, qd, qdd, density, gravity)  # at Cd = Cm = 1

    per_direction = leg.hydro_regressors(q, qd, qdd, water=water, per="direction")
    assert per_direction.drag.shape == per_direction.added_mass.shape == (m, n, n, 2)
    assert per_direction.buoyancy.shape == per_direction.gravity.shape == (m, n)
    assert_batch_close(per_direction.drag, expected["drag"], RTOL_REFERENCE, f"{kind} drag regressor per direction", unit["drag"])
    assert_batch_close(
        per_direction.added_mass, expected["added_mass"], RTOL_REFERENCE, f"{kind} added-mass regressor per direction", unit["added_mass"]
    )
    assert_batch_close(per_direction.buoyancy, expected["buoyancy"], RTOL_REFERENCE, f"{kind} buoyancy", unit["buoyancy"])

    per_leg = leg.hydro_regressors(q, qd, qdd, water=water, per="leg")
    assert per_leg.drag.shape == per_leg.added_mass.shape == (m, n)
    assert_batch_close(per_leg.drag, expected["drag"].sum(axis=(-2, -1)), RTOL_REFERENCE, f"{kind} drag regressor per leg", unit["drag"])
    assert_batch_close(
        per_leg.added_mass,
        expected["added_mass"].sum(axis=(-2, -1)),
        RTOL_REFERENCE,
        f"{kind} added-mass regressor per leg",
        unit["added_mass"],
    )
    assert_batch_close(per_leg.buoyancy, expected["buoyancy"], RTOL_REFERENCE, f"{kind} buoyancy (per leg)", unit["buoyancy"])

    # HydroRegressors.torques(cd, cm) equals Leg.hydro, in every coefficient layout.
    cd, cm = random_coefficients(rng, n, layout)
    direct = leg.hydro(q, qd, qdd, cd=cd, cm=cm, water=water)
    natural = natural_scales(joints, links, qd, qdd, density, gravity, cd, cm)
    for key, value in vars(per_direction.torques(cd, cm)).items():
        assert_batch_close(value, getattr(direct, key), RTOL_ROUNDING, f"{kind} per-direction torques().{key}", natural[key])
    cd_s, cm_s = float(rng.uniform(0.5, 3.0)), float(rng.uniform(0.1, 1.5))
    direct = leg.hydro(q, qd, qdd, cd=cd_s, cm=cm_s, water=water)
    natural = natural_scales(joints, links, qd, qdd, density, gravity, cd_s, cm_s)
    for regressors in (per_leg, per_direction):
        torques = regressors.torques(cd_s, cm_s)
        for key in ("drag", "added_mass", "buoyancy", "gravity", "total"):
            assert_batch_close(
                getattr(torques, key), getattr(direct, key), RTOL_ROUNDING, f"{kind} torques({cd_s}, {cm_s}).{key}", natural[key]
            )


# --------------------------------------------------------------------------------------------
# 2. docs/model.md section 5 (typed from it)
# --------------------------------------------------------------------------------------------

SECTION5_STATE = ([0.3, -0.4, 0.6], [0.8, 0.5, -0.7], [1.0, -2.0, 0.5])
SECTION5 = {
    "drag": [-24.24084, -5.060505, -0.7383118],
    "added_mass": [-8.525438, 21.77596, 9.484545],
    "buoyancy": [0.0, 59.72457, 4.193843],
}


def test_model_section5_reference_values() -> None:
    out = PAPER.hydro(*SECTION5_STATE, cd=2.2, cm=0.5, water=uwml.Water(density=1000.0, gravity=9.81))
    for key, values in SECTION5.items():
        np.testing.assert_allclose(getattr(out, key), values, rtol=1e-6, atol=0.0, err_msg=key)
    np.testing.assert_allclose(out.total, np.sum(list(SECTION5.values()), axis=0), rtol=1e-6)
    # Defaults are the paper's coefficients and water.
    default = PAPER.hydro(*SECTION5_STATE)
    for key, values in SECTION5.items():
        np.testing.assert_allclose(getattr(default, key), values, rtol=1e-6, atol=0.0, err_msg=key)
    # The regressor path: total = buoyancy + Cd R_d + Cm R_m (docs/model.md section 4).
    reg = PAPER.hydro_regressors(*SECTION5_STATE)
    np.testing.assert_allclose(2.2 * reg.drag, SECTION5["drag"], rtol=1e-6)
    np.testing.assert_allclose(0.5 * reg.added_mass, SECTION5["added_mass"], rtol=1e-6)
    np.testing.assert_allclose(reg.buoyancy, SECTION5["buoyancy"], rtol=1e-6, atol=0.0)


# --------------------------------------------------------------------------------------------
# 3. The paper's printed equations
# --------------------------------------------------------------------------------------------


def eq8_joint1_drag(q: np.ndarray, qd: np.ndarray, cd: float, rho: float) -> np.ndarray:
    """Eq. (8) with the calf arm's typo fixed (``x sin(q2+q3)``, docs/model.md section 6 item 1), in
    uwml's sign (−τ_d1), written out here: ``v21 = q̇1 x c2``, ``v31 = q̇1 (L2 c2 + x s23)``.

    Thigh: ``∫₀^L2 x c2 v21|v21| dx = q̇1|q̇1| c2²|c2| L2⁴/4``. Calf: ``q̇1|q̇1| ∫₀^L3 |a(x)|³ dx``
    with ``a = L2 c2 + x s23``, a cubic on each side of its root, integrated exactly by 3-point
    Gauss-Legendre on each piece.
    """
    w1, c2, s23 = qd[:, 0], np.cos(q[:, 1]), np.sin(q[:, 1] + q[:, 2])
    thigh = c2 * c2 * np.abs(c2) * L2**4 / 4.0
    with np.errstate(divide="ignore", invalid="ignore"):
        root = np.where(s23 != 0.0, -L2 * c2 / s23, L3)
    root = np.clip(np.nan_to_num(root, nan=L3, posinf=L3, neginf=L3), 0.0, L3)
    t, w = np.polynomial.legendre.leggauss(3)
    calf = np.zeros_like(w1)
    for lo, hi in ((np.zeros_like(root), root), (root, np.full_like(root, L3))):
        half = 0.5 * (hi - lo)
        x = lo[:, None] + half[:, None] * (t + 1.0)
        calf += half * np.sum(w * np.abs(L2 * c2[:, None] + x * s23[:, None]) ** 3, axis=1)
    return -0.5 * rho * cd * w1 * np.abs(w1) * (D21 * thigh + D31 * calf)


def eq9_pure_yaw_joint1_added_mass(q: np.ndarray, qdd: np.ndarray, cm: float, rho: float) -> np.ndarray:
    """Eq. (9) for pure yaw (``v̇21 = q̈1 x c2``, ``v̇31 = q̈1 (L2 c2 + x s23)``), uwml's sign:
    ``−ρ Cm q̈1 [A2 c2² L2³/3 + A3 ∫₀^L3 (L2 c2 + x s23)² dx]``, the last in closed form."""
    c2, s23 = np.cos(q[:, 1]), np.sin(q[:, 1] + q[:, 2])
    alpha, beta = L2 * c2, s23
    calf = alpha**2 * L3 + alpha * beta * L3**2 + beta**2 * L3**3 / 3.0
    return -rho * cm * qdd[:, 0] * (D21 * D22 * c2**2 * L2**3 / 3.0 + D31 * D32 * calf)


@PROPERTY_EXAMPLES
@given(seed=seeds, cd=st.floats(0.0, 4.0), cm=st.floats(0.0, 2.0))
def test_pure_yaw_joint1_equals_paper_equations(seed: int, cd: float, cm: float) -> None:
    """For q̇2 = q̇3 = q̈2 = q̈3 = 0 joint 1's drag and added mass are the printed eqs. (8), (9)."""
    rng = np.random.default_rng(seed)
    m = 200
    q = rng.uniform(-math.pi, math.pi, (m, 3))
    qd, qdd = np.zeros((m, 3)), np.zeros((m, 3))
    qd[:, 0], qdd[:, 0] = rng.uniform(-3.0, 3.0, m), rng.uniform(-10.0, 10.0, m)
    qd[:10, 0], qdd[10:20, 0] = 0.0, 0.0
    out = PAPER.hydro(q, qd, qdd, cd=cd, cm=cm)
    paper = ref.paper_equations(q, qd, qdd, cd=cd, cm=cm)
    # Joint 1's drag and added mass have no cancellation for pure yaw (∫ arm·v|v| = q̇1|q̇1| ∫ |arm|³,
    # ∫ arm·v̇ = q̈1 ∫ arm²), so each sample is compared relative to its own value; but not below
    # 1e-3 ρ C (q̇1² + |q̈1|) [N·m], 1e-3 of the terms the core adds up (the slice acceleration has
    # a centripetal part ~q̇1² whose out-of-plane component is zero only up to rounding).
    for key, typed, coefficient in (
        ("drag", eq8_joint1_drag(q, qd, cd, RHO), cd),
        ("added_mass", eq9_pure_yaw_joint1_added_mass(q, qdd, cm, RHO), cm),
    ):
        actual = getattr(out, key)[:, 0]
        floor = 1e-3 * RHO * coefficient * (qd[:, 0] ** 2 + np.abs(qdd[:, 0])) + TINY
        for expected, source in ((paper[key][:, 0], "reference.paper_equations"), (typed, "written out")):
            err = np.abs(actual - expected) / np.maximum(np.abs(expected), floor)
            assert err.max() <= 1e-9, f"joint-1 {key} vs {source}: relative error {err.max():.3g} at {q[err.argmax()]}"


@PROPERTY_EXAMPLES
@given(seed=seeds, cd=st.floats(0.0, 4.0))
def test_joint1_drag_equals_eq8_for_any_motion(seed: int, cd: float) -> None:
    """Roll motions are in the leg plane, so joint 1's drag is eq. (8) (typo fixed) for every state."""
    rng = np.random.default_rng(seed)
    q, qd, qdd = random_states(rng, 200, 3)
    drag = PAPER.hydro(q, qd, qdd, cd=cd, cm=0.5).drag[:, 0]
    paper_all = ref.paper_equations(q, qd, qdd, cd=cd, cm=0.5)["drag"]
    paper = paper_all[:, 0]
    typed = eq8_joint1_drag(q, qd, cd, RHO)
    # Relative to each sample's own value (no cancellation: joint 1's drag is −½ρCd q̇1|q̇1| times a
    # positive integral), but not below 1e-4 of the sample's largest drag torque (the printed
    # equations' joints 2-3 give its size): the moment arm of joint 1 along the in-plane normals is
    # zero only up to rounding, and times the in-plane drag of a rolling leg that is ~1e-16 of it.
    floor = 1e-4 * np.abs(paper_all).max(axis=1) + TINY
    for expected, source in ((paper, "reference.paper_equations"), (typed, "written out")):
        err = np.abs(drag - expected) / np.maximum(np.abs(expected), floor)
        assert err.max() <= 1e-9, f"joint-1 drag vs eq. (8) {source}: relative error {err.max():.3g} at sample {err.argmax()}"


@pytest.mark.filterwarnings("ignore::uwml.PlausibilityWarning")  # values beyond plausible on purpose
@given(seed=seeds, density=st.floats(500.0, 1500.0), gravity=st.floats(0.0, 20.0))
def test_buoyancy_equals_eqs_17_and_21(seed: int, density: float, gravity: float) -> None:
    """τ_f2 = {m2 g Lc2 c2 + m3 g [L2 c2 + Lc3 s23]} ρ/ρm, τ_f3 = m3 g Lc3 s23 ρ/ρm, τ_f1 = 0 exactly."""
    rng = np.random.default_rng(seed)
    q, qd, qdd = random_states(rng, 500, 3)
    q[:5, 1:] = [[0.0, 0.0], [math.pi / 2, 0.0], [-math.pi / 2, math.pi], [math.pi, -math.pi / 2], [0.0, math.pi / 2]]
    out = PAPER.hydro(q, qd, qdd, water=uwml.Water(density=density, gravity=gravity))
    c2, s23 = np.cos(q[:, 1]), np.sin(q[:, 1] + q[:, 2])
    eq17 = (M2 * gravity * L2C * c2 + M3 * gravity * (L2 * c2 + L3C * s23)) * density / RHO_M
    eq21 = M3 * gravity * L3C * s23 * density / RHO_M
    assert np.all(out.buoyancy[:, 0] == 0.0), "joint 1 (yaw about world z) must get exactly no buoyancy torque"
    scale = (M2 + M3) * gravity * (L2 + L3) * density / RHO_M + TINY  # the largest possible value
    np.testing.assert_allclose(out.buoyancy[:, 1], eq17, rtol=1e-12, atol=1e-13 * scale)
    np.testing.assert_allclose(out.buoyancy[:, 2], eq21, rtol=1e-12, atol=1e-13 * scale)


# --------------------------------------------------------------------------------------------
# 4. Properties of docs/model.md section 5 on the Rust path
# --------------------------------------------------------------------------------------------


@pytest.mark.parametrize("kind", ["paper", "chain"])
@PROPERTY_EXAMPLES
@given(seed=seeds, scale=st.one_of(st.sampled_from([0.0, 1.0, -1.0]), st.floats(-5.0, 5.0)))
def test_drag_dissipative_and_homogeneous(kind: str, seed: int, scale: float) -> None:
    rng = np.random.default_rng(seed)
    leg, joints, links = chain_or_paper(kind, rng)
    q, qd, qdd = random_states(rng, 500, leg.n_joints)
    cd, cm = random_coefficients(rng, leg.n_joints)
    drag = leg.hydro(q, qd, qdd, cd=cd, cm=cm).drag
    natural = natural_scales(joints, links, qd, qdd, cd=cd)["drag"]
    # Dissipative: q̇ · τ_drag = −½ρ Σ Cd w ∫|v_k|³ ≤ 0, up to rounding: of the sum (first term),
    # and of the normal velocities themselves (second term): a normal velocity that is zero in
    # exact arithmetic (e.g. the out-of-plane velocity when only the knee turns) is ~1e-16 V of
    # noise, whose drag (~1e-32 of its natural size) does a power of either sign.
    power = np.einsum("mj,mj->m", qd, drag)
    bound = 1e-12 * np.einsum("mj,mj->m", np.abs(qd), np.abs(drag)) + 1e-28 * natural * np.abs(qd).sum(axis=1)
    assert np.all(power <= bound), f"drag does work on the leg: q̇·τ = {power.max()} at sample {power.argmax()}"
    # Homogeneous of degree 2: τ(λ q̇) = λ|λ| τ(q̇), whatever q̈.
    scaled = leg.hydro(q, scale * qd, rng.permutation(qdd), cd=cd, cm=cm).drag
    assert_batch_close(scaled, scale * abs(scale) * drag, RTOL_ROUNDING, f"drag at {scale} q̇", scale * scale * natural)


@pytest.mark.parametrize("kind", ["paper", "chain"])
@PROPERTY_EXAMPLES
@given(seed=seeds)
def test_added_mass_linear_with_symmetric_psd_matrix(kind: str, seed: int) -> None:
    rng = np.random.default_rng(seed)
    leg, joints, links = chain_or_paper(kind, rng)
    n, m = leg.n_joints, 100
    q, qd, qdd = random_states(rng, m, n)
    cd, cm = random_coefficients(rng, n)
    # Natural size of M_A entries, ρ Cm Σ A L R² (the added mass per unit q̈ of R), for degenerate
    # chains whose M_A is all rounding noise (a segment on its joint's axis).
    natural = natural_scales(joints, links, np.zeros(n), np.ones(n) / n, cm=cm)["added_mass"][0]
    # M_A(q) = −∂τ_am/∂q̈, column by column from unit q̈ at q̇ = 0: one batch of m·n samples.
    columns = leg.hydro(np.repeat(q, n, axis=0), np.zeros((m * n, n)), np.tile(np.eye(n), (m, 1)), cd=cd, cm=cm).added_mass
    matrix = -columns.reshape(m, n, n).transpose(0, 2, 1)  # matrix[s, :, l] = −τ_am(q̈ = e_l)
    size = np.maximum(np.abs(matrix).max(axis=(1, 2)), 1e-4 * natural)[:, None, None] + TINY
    asymmetry = np.abs(matrix - matrix.transpose(0, 2, 1)) / size
    assert asymmetry.max() <= RTOL_ROUNDING, f"M_A not symmetric: {asymmetry.max():.3g}"
    eigenvalues = np.linalg.eigvalsh(0.5 * (matrix + matrix.transpose(0, 2, 1)))
    assert np.all(eigenvalues >= -RTOL_ROUNDING * size[:, 0]), f"M_A not positive semi-definite: {eigenvalues.min()}"
    # Linear in q̈ at any q̇: τ_am(q, q̇, q̈) − τ_am(q, q̇, 0) = −M_A(q) q̈ (the rest is velocity terms).
    full = leg.hydro(q, qd, qdd, cd=cd, cm=cm)
    rest = leg.hydro(q, qd, np.zeros_like(qdd), cd=cd, cm=cm)
    difference = full.added_mass - rest.added_mass
    expected = -np.einsum("mjl,ml->mj", matrix, qdd)
    error = np.abs(difference - expected).max(axis=1)
    bound = RTOL_ROUNDING * size[:, 0, 0] * (np.abs(qdd).sum(axis=1) + (qd**2).sum(axis=1) + 1.0)
    assert np.all(error <= 10 * bound), f"added mass not linear in q̈: error {error.max():.3g}"
    # Drag and buoyancy do not depend on q̈ at all.
    np.testing.assert_array_equal(full.drag, rest.drag)
    np.testing.assert_array_equal(full.buoyancy, rest.buoyancy)


@pytest.mark.parametrize("kind", ["paper", "chain"])
@PROPERTY_EXAMPLES
@given(seed=seeds)
def test_buoyancy_and_gravity_are_gradients_of_potentials(kind: str, seed: int) -> None:
    """τ_buoy = ∂/∂q (ρ g Σ V_i c_i,z) and τ_grav = −∂/∂q (g Σ m_i com_i,z), with the heights
    from forward kinematics written in this file and the gradient by finite differences."""
    rng = np.random.default_rng(seed)
    leg, joints, links = chain_or_paper(kind, rng)
    density, gravity = float(rng.uniform(900.0, 1100.0)), float(rng.uniform(1.0, 12.0))
    q, qd, qdd = random_states(rng, 50, leg.n_joints)
    out = leg.hydro(q, qd, qdd, water=uwml.Water(density=density, gravity=gravity))
    reach = sum(np.linalg.norm(j.origin) for j in joints) + max(max(np.linalg.norm(link.com), np.linalg.norm(link.cob)) for link in links)
    for name, point, weight, factor in (("buoyancy", "cob", "volume", density * gravity), ("gravity", "com", "mass", -gravity)):
        expected = factor * gradient(lambda qq, point=point, weight=weight: potential_heights(joints, links, qq, point, weight), q)
        scale = abs(factor) * sum(getattr(link, weight) for link in links) * reach + TINY
        error = np.abs(getattr(out, name) - expected).max()
        assert error <= 1e-9 * scale, f"{name} is not the gradient of its potential: error {error:.3g}, scale {scale:.3g}"


def test_paper_leg_potential_matches_model_section2() -> None:
    """The forward kinematics of this file on the paper leg give docs/model.md section 2's heights
    (thigh COM at Lc2 u2, calf COM at L2 u2 + Lc3 u3), so the gradient check above is a check
    of the documented geometry, and its gradient is eqs. (17) and (21)."""
    rng = np.random.default_rng(5)
    q = rng.uniform(-math.pi, math.pi, (200, 3))
    v2, v3 = M2 / RHO_M, M3 / RHO_M
    typed = v2 * L2C * np.sin(q[:, 1]) + v3 * (L2 * np.sin(q[:, 1]) - L3C * np.cos(q[:, 1] + q[:, 2]))
    np.testing.assert_allclose(potential_heights(PAPER.joints, PAPER.links, q, "cob", "volume"), typed, rtol=0, atol=1e-15)
    np.testing.assert_allclose(potential_heights(*ref.paper_leg(), q, "cob", "volume"), typed, rtol=0, atol=1e-15)


@pytest.mark.parametrize("kind", ["paper", "chain"])
@PROPERTY_EXAMPLES
@given(seed=seeds)
def test_buoyancy_does_no_work_around_a_closed_loop(kind: str, seed: int) -> None:
    """∮ τ_buoy · dq = 0 along q(t) = q0 + a cos t + b sin t (trapezoid rule: exponentially
    accurate for a smooth periodic integrand)."""
    rng = np.random.default_rng(seed)
    leg, _, _ = chain_or_paper(kind, rng)
    n, loops, points = leg.n_joints, 8, 128
    t = 2.0 * math.pi * np.arange(points) / points
    q0 = rng.uniform(-math.pi, math.pi, (loops, 1, n))
    a, b = rng.uniform(-1.0, 1.0, (2, loops, 1, n))
    q = q0 + a * np.cos(t)[:, None] + b * np.sin(t)[:, None]  # (loops, points, n)
    dq = -a * np.sin(t)[:, None] + b * np.cos(t)[:, None]
    tau = leg.hydro(q.reshape(-1, n), dq.reshape(-1, n), np.zeros((loops * points, n))).buoyancy.reshape(loops, points, n)
    power = np.einsum("lpj,lpj->lp", tau, dq)
    work = power.sum(axis=1) * (2.0 * math.pi / points)
    gross = np.abs(power).sum(axis=1) * (2.0 * math.pi / points)
    assert np.all(np.abs(work) <= 1e-10 * gross + TINY), f"buoyancy work around a loop: {work}, gross {gross}"


@pytest.mark.parametrize("kind", ["paper", "chain"])
@PROPERTY_EXAMPLES
@given(seed=seeds, factor=st.floats(0.0, 10.0))
def test_every_term_is_linear_in_its_coefficient(kind: str, seed: int, factor: float) -> None:
    rng = np.random.default_rng(seed)
    leg, joints, links = chain_or_paper(kind, rng)
    n = leg.n_joints
    q, qd, qdd = random_states(rng, 300, n)
    natural = natural_scales(joints, links, qd, qdd, cd=4.0 * max(factor, 1.0), cm=2.0 * max(factor, 1.0))
    cd1, cm1 = rng.uniform(0.0, 3.0, (n, 2)), rng.uniform(0.0, 1.5, (n, 2))
    cd2, cm2 = rng.uniform(0.0, 3.0, (n, 2)), rng.uniform(0.0, 1.5, (n, 2))
    one = leg.hydro(q, qd, qdd, cd=cd1, cm=cm1)
    scaled = leg.hydro(q, qd, qdd, cd=factor * cd1, cm=factor * cm1)
    assert_batch_close(scaled.drag, factor * one.drag, RTOL_ROUNDING, f"drag at {factor} cd", natural["drag"])
    assert_batch_close(scaled.added_mass, factor * one.added_mass, RTOL_ROUNDING, f"added mass at {factor} cm", natural["added_mass"])
    np.testing.assert_array_equal(scaled.buoyancy, one.buoyancy)
    np.testing.assert_array_equal(scaled.gravity, one.gravity)
    two = leg.hydro(q, qd, qdd, cd=cd2, cm=cm2)
    both = leg.hydro(q, qd, qdd, cd=cd1 + cd2, cm=cm1 + cm2)
    assert_batch_close(both.drag, one.drag + two.drag, RTOL_ROUNDING, "drag additive in cd", natural["drag"])
    assert_batch_close(both.added_mass, one.added_mass + two.added_mass, RTOL_ROUNDING, "added mass additive in cm", natural["added_mass"])
    zero = leg.hydro(q, qd, qdd, cd=0.0, cm=0.0)
    assert np.all(zero.drag == 0.0) and np.all(zero.added_mass == 0.0)
    np.testing.assert_array_equal(zero.total, zero.buoyancy)


@pytest.mark.filterwarnings("ignore::uwml.PlausibilityWarning")  # values beyond plausible on purpose
@pytest.mark.parametrize("kind", ["paper", "chain"])
@PROPERTY_EXAMPLES
@given(seed=seeds, density=st.floats(1.0, 2000.0), gravity=st.floats(0.0, 30.0))
def test_water_scaling(kind: str, seed: int, density: float, gravity: float) -> None:
    """Drag and added mass ∝ ρ and independent of g; buoyancy ∝ ρ g; gravity ∝ g, independent of ρ."""
    rng = np.random.default_rng(seed)
    leg, joints, links = chain_or_paper(kind, rng)
    q, qd, qdd = random_states(rng, 300, leg.n_joints)
    natural = natural_scales(joints, links, qd, qdd, density, gravity, 2.2, 0.5)
    base = leg.hydro(q, qd, qdd, water=uwml.Water(density=1.0, gravity=1.0))
    out = leg.hydro(q, qd, qdd, water=uwml.Water(density=density, gravity=gravity))
    for key, factor in (("drag", density), ("added_mass", density), ("buoyancy", density * gravity), ("gravity", gravity)):
        assert_batch_close(
            getattr(out, key), factor * getattr(base, key), RTOL_ROUNDING, f"{key} at ρ={density}, g={gravity}", natural[key]
        )


@pytest.mark.filterwarnings("ignore::uwml.PlausibilityWarning")  # values beyond plausible on purpose
@given(seed=seeds, density=st.floats(500.0, 1500.0), gravity=st.floats(0.0, 20.0))
def test_paper_leg_gravity_is_minus_density_ratio_times_buoyancy(seed: int, density: float, gravity: float) -> None:
    """COM = COB and V = m/ρm on the paper leg: the weight −m g at the COM and the buoyancy
    ρ V g at the same point give τ_gravity = −(ρm/ρ) τ_buoy."""
    rng = np.random.default_rng(seed)
    q, qd, qdd = random_states(rng, 200, 3)
    out = PAPER.hydro(q, qd, qdd, water=uwml.Water(density=density, gravity=gravity))
    scale = (M2 + M3) * gravity * (L2 + L3) + TINY
    np.testing.assert_allclose(out.gravity, -(RHO_M / density) * out.buoyancy, rtol=1e-12, atol=1e-13 * scale)
    assert np.all(out.gravity[:, 0] == 0.0)


# --------------------------------------------------------------------------------------------
# 5, 6. Shapes, layouts and dtypes
# --------------------------------------------------------------------------------------------

KEYS = ("drag", "added_mass", "buoyancy", "gravity")


@pytest.mark.parametrize("kind", ["paper", "chain"])
@settings(max_examples=max(5, settings.default.max_examples // 20))
@given(seed=seeds)
def test_single_samples_and_batches_agree(kind: str, seed: int) -> None:
    rng = np.random.default_rng(seed)
    leg, _, _ = chain_or_paper(kind, rng)
    n, m = leg.n_joints, 12
    q, qd, qdd = random_states(rng, m, n)
    cd, cm = random_coefficients(rng, n)
    batch = leg.hydro(q, qd, qdd, cd=cd, cm=cm)
    per_direction = leg.hydro_regressors(q, qd, qdd, per="direction")
    per_leg = leg.hydro_regressors(q, qd, qdd)
    for key in KEYS:
        assert getattr(batch, key).shape == (m, n)
        assert getattr(batch, key).dtype == np.float64
    assert batch.total.shape == (m, n)
    assert per_direction.drag.shape == per_direction.added_mass.shape == (m, n, n, 2)
    assert per_leg.drag.shape == per_leg.added_mass.shape == per_leg.buoyancy.shape == (m, n)
    for s in range(m):
        one = leg.hydro(q[s], qd[s], qdd[s], cd=cd, cm=cm)
        one_direction = leg.hydro_regressors(q[s], qd[s], qdd[s], per="direction")
        one_leg = leg.hydro_regressors(q[s], qd[s], qdd[s], per="leg")
        for key in KEYS:
            assert getattr(one, key).shape == (n,)
            assert_batch_close(getattr(one, key), getattr(batch, key)[s], 1e-14, f"sample {s} {key}")
        assert one.total.shape == (n,)
        assert one_direction.drag.shape == one_direction.added_mass.shape == (n, n, 2)
        assert one_direction.buoyancy.shape == one_leg.drag.shape == one_leg.added_mass.shape == (n,)
        assert_batch_close(one_direction.drag, per_direction.drag[s], 1e-14, f"sample {s} drag regressor")
        assert_batch_close(one_direction.added_mass, per_direction.added_mass[s], 1e-14, f"sample {s} added-mass regressor")
        assert_batch_close(one_leg.drag, per_leg.drag[s], 1e-14, f"sample {s} drag regressor per leg")
        # torques() keeps the single-sample layout.
        assert one_direction.torques(cd, cm).drag.shape == (n,)


def _layouts(q: np.ndarray) -> dict[str, object]:
    """The same float64 values in other memory layouts and containers."""
    m, n = q.shape
    wide = np.zeros((m, 2 * n))
    wide[:, ::2] = q
    tall = np.zeros((3 * m, n))
    tall[::3] = q
    read_only = q.copy()
    read_only.flags.writeable = False
    return {
        "fortran": np.asfortranarray(q),
        "strided columns": wide[:, ::2],
        "strided rows": tall[::3],
        "transposed view": np.ascontiguousarray(q.T).T,
        "big-endian": q.astype(">f8"),
        "read-only": read_only,
        "nested lists": q.tolist(),
    }


@pytest.mark.parametrize("kind", ["paper", "chain"])
@settings(max_examples=max(5, settings.default.max_examples // 10))
@given(seed=seeds)
def test_memory_layouts_give_the_same_numbers(kind: str, seed: int) -> None:
    rng = np.random.default_rng(seed)
    leg, _, _ = chain_or_paper(kind, rng)
    q, qd, qdd = random_states(rng, 40, leg.n_joints)
    expected = leg.hydro(q, qd, qdd)
    expected_reg = leg.hydro_regressors(q, qd, qdd, per="direction")
    layouts = [_layouts(x) for x in (q, qd, qdd)]
    for name in layouts[0]:
        args = [layout[name] for layout in layouts]
        before = [np.array(a, copy=True) for a in args]
        out = leg.hydro(*args)
        reg = leg.hydro_regressors(*args, per="direction")
        for key in KEYS:
            np.testing.assert_array_equal(getattr(out, key), getattr(expected, key), err_msg=f"{name} {key}")
        np.testing.assert_array_equal(reg.drag, expected_reg.drag, err_msg=f"{name} drag regressor")
        np.testing.assert_array_equal(reg.added_mass, expected_reg.added_mass, err_msg=f"{name} added-mass regressor")
        for a, b in zip(args, before):
            np.testing.assert_array_equal(np.asarray(a), b, err_msg=f"{name}: input modified")
    # Mixed layouts in one call.
    out = leg.hydro(layouts[0]["fortran"], layouts[1]["strided rows"], layouts[2]["nested lists"])
    for key in KEYS:
        np.testing.assert_array_equal(getattr(out, key), getattr(expected, key), err_msg=f"mixed {key}")


@pytest.mark.parametrize("dtype", [np.int8, np.int32, np.int64, np.uint16, np.float16, np.float32, np.longdouble])
def test_other_dtypes_are_converted_to_float64(dtype: type) -> None:
    """Integer and other float inputs give the numbers of the same values in float64."""
    rng = np.random.default_rng(3)
    for leg in (PAPER, random_chain(rng, 5)[0]):
        n = leg.n_joints
        q, qd, qdd = (rng.uniform(-3.0, 3.0, (50, n)) for _ in range(3))
        if np.issubdtype(dtype, np.unsignedinteger):
            q, qd, qdd = np.abs(q), np.abs(qd), np.abs(qdd)
        args = [x.astype(dtype) for x in (q, qd, qdd)]
        as_float64 = [a.astype(np.float64) for a in args]
        out, expected = leg.hydro(*args), leg.hydro(*as_float64)
        reg, expected_reg = leg.hydro_regressors(*args, per="direction"), leg.hydro_regressors(*as_float64, per="direction")
        for key in KEYS:
            assert getattr(out, key).dtype == np.float64
            np.testing.assert_array_equal(getattr(out, key), getattr(expected, key), err_msg=f"{dtype.__name__} {key}")
        np.testing.assert_array_equal(reg.drag, expected_reg.drag)
        np.testing.assert_array_equal(reg.added_mass, expected_reg.added_mass)
        # One dtype mixed with float64 contiguous arrays.
        mixed = leg.hydro(args[0], as_float64[1], as_float64[2])
        np.testing.assert_array_equal(mixed.drag, expected.drag)


def test_float32_inputs_match_float64_closely() -> None:
    """Float32 states are converted exactly: their results are the float64 results of the same
    values, and differ from the unrounded float64 states only as much as the rounding of q, q̇, q̈."""
    rng = np.random.default_rng(4)
    q, qd, qdd = random_states(rng, 500, 3)
    out32 = PAPER.hydro(q.astype(np.float32), qd.astype(np.float32), qdd.astype(np.float32))
    out64 = PAPER.hydro(q, qd, qdd)
    for key in KEYS:
        assert getattr(out32, key).dtype == np.float64
        assert_batch_close(getattr(out32, key), getattr(out64, key), 1e-5, f"float32 {key}")
    expected = ref.hydro(PAPER.joints, PAPER.links, q.astype(np.float32), qd.astype(np.float32), qdd.astype(np.float32))
    for key in KEYS:
        assert_batch_close(getattr(out32, key), expected[key], RTOL_REFERENCE, f"float32 {key} vs reference")


def test_empty_batch() -> None:
    out = PAPER.hydro(np.zeros((0, 3)), np.zeros((0, 3)), np.zeros((0, 3)))
    for key in KEYS:
        assert getattr(out, key).shape == (0, 3)
    reg = PAPER.hydro_regressors(np.zeros((0, 3)), np.zeros((0, 3)), np.zeros((0, 3)), per="direction")
    assert reg.drag.shape == (0, 3, 3, 2) and reg.buoyancy.shape == (0, 3)


def test_concurrent_calls_agree() -> None:
    """The batch loop runs without the GIL: calls from several threads give the serial results."""
    rng = np.random.default_rng(8)
    leg = random_chain(rng, 6)[0]
    batches = [random_states(rng, 5000, 6) for _ in range(4)]
    expected = [leg.hydro(*b).total for b in batches]
    results: list = [None] * len(batches)

    def work(i: int) -> None:
        for _ in range(3):
            results[i] = leg.hydro(*batches[i]).total

    threads = [threading.Thread(target=work, args=(i,)) for i in range(len(batches))]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    for got, want in zip(results, expected):
        np.testing.assert_array_equal(got, want)


def test_normals_within_the_tolerance_become_an_exact_frame() -> None:
    """Normals accepted within AXIS_TOLERANCE (1e-6) of an orthonormal frame are made an exact
    one on input (Gram-Schmidt; the second normal on the side it was given), in Python and in
    the core: the strip integrals' identities assume an exact frame. A two-link chain whose
    second segment's normals are tilted by 5e-7 (the first towards the axis, the second towards
    the first) evaluates, on the chain path and on the whole-robot path, as the reference does
    with the exact frame the tilt came from (they differed by 3e-7 in drag and 1.2e-6 in added
    mass when the normals were only renormalized)."""
    rng = np.random.default_rng(5)
    axis = random_unit(rng)
    n1 = np.cross(axis, random_unit(rng))
    n1 /= np.linalg.norm(n1)
    n2 = np.cross(axis, n1)
    tilted1, tilted2 = n1 + 5e-7 * axis, n2 + 5e-7 * n1
    tilted1, tilted2 = tilted1 / np.linalg.norm(tilted1), tilted2 / np.linalg.norm(tilted2)

    def chain(normals: tuple) -> tuple[list, list]:
        segment = uwml.Segment(start=(0.05, 0.0, 0.0), axis=tuple(axis), length=0.6, normals=normals, widths=(0.2, 0.05), area=0.01)
        joints = [uwml.Joint(origin=(0.0, 0.0, 0.0), axis=(0.0, 0.0, 1.0)), uwml.Joint(origin=(0.4, 0.0, 0.0), axis=(0.0, 1.0, 0.0))]
        first = uwml.Segment(
            start=(0.0, 0.0, 0.0), axis=(1.0, 0.0, 0.0), length=0.4, normals=((0, 1, 0), (0, 0, 1)), widths=(0.1, 0.1), area=0.008
        )
        links = [uwml.Link(2.0, (0.2, 0, 0), 1e-3, segment=first), uwml.Link(3.0, (0.3, 0, 0), 2e-3, segment=segment)]
        return joints, links

    joints, links = chain((tuple(tilted1), tuple(tilted2)))
    stored = links[1].segment.normals
    for a, b in ((stored[0], axis), (stored[1], axis), (stored[0], stored[1])):
        assert abs(float(np.dot(a, b))) < 1e-15
    assert max(abs(float(np.linalg.norm(n)) - 1.0) for n in stored) < 1e-15
    np.testing.assert_allclose(stored, [n1, n2], atol=1e-15)
    exact_joints, exact_links = chain((tuple(n1), tuple(n2)))
    q, qd, qdd = random_states(rng, 500, 2)
    expected = ref.hydro(exact_joints, exact_links, q, qd, qdd)
    natural = natural_scales(exact_joints, exact_links, qd, qdd, cd=2.2, cm=0.5)
    for out, path in ((uwml.Leg(joints, links).hydro(q, qd, qdd), "chain"), (uwml.Robot(joints, links).hydro(q, qd, qdd), "robot")):
        for key in ("drag", "added_mass", "buoyancy"):
            assert_batch_close(getattr(out, key), expected[key], 1e-12, f"{path} {key}", natural[key])


@pytest.mark.filterwarnings("ignore::uwml.PlausibilityWarning")  # values beyond plausible on purpose
@pytest.mark.parametrize("size", [1e5, 1e8, 1e10, 1e15, 1e300])
def test_huge_joint_angles_keep_their_accuracy(size: float) -> None:
    """The batch path's SIMD sine and cosine reduce their argument in double precision only
    (exact to about 1e8 rad, 4e-7 relative off at 1e10 and 0.02 at 1e15); angles beyond 1e6 rad
    are reduced exactly first. So at any finite angle the batch, the one-state path, the scalar
    jacobians and the reference agree to rounding (the jacobians' docstring: 1e-13)."""
    leg = uwml.Leg.paper()
    q = np.array([[size, -0.3 * size + 0.1, size / 7.0], [0.2, size, -size]])
    qd, qdd = np.full_like(q, 0.5), np.full_like(q, -0.8)
    out = leg.hydro(q, qd, qdd)
    expected = ref.hydro(leg.joints, leg.links, q, qd, qdd)
    for key in ("drag", "added_mass", "buoyancy", "gravity"):
        scale = float(np.max(np.abs(expected[key])))
        np.testing.assert_allclose(getattr(out, key), expected[key], rtol=0, atol=1e-13 * scale, err_msg=key)
    one = leg.hydro(q[0], qd[0], qdd[0])
    np.testing.assert_array_equal(one.total, out.total[0])
    environment = leg.environment(q, qd, qdd).total
    value = leg.jacobians(q, qd, qdd).value
    np.testing.assert_allclose(value, environment, rtol=0, atol=1e-13 * float(np.max(np.abs(environment))))


def test_per_leg_regressors_take_what_hydro_takes() -> None:
    """``per="leg"`` regressors sum over links, so they take per-link coefficients that are one
    value over the links carrying a segment, as :meth:`Leg.hydro` does (the paper's first link
    has none: ``cd=[0, 2.2, 2.2]`` is ``cd=2.2``); coefficients that differ between segment links
    still need ``per="direction"``."""
    leg = uwml.Leg.paper()
    rng = np.random.default_rng(2)
    q, qd, qdd = (rng.uniform(-1, 1, (20, 3)) for _ in range(3))
    assert leg.links[0].segment is None and all(link.segment is not None for link in leg.links[1:])
    regressors = leg.hydro_regressors(q, qd, qdd)
    for cd, cm in (([0.0, 2.2, 2.2], [7.0, 0.5, 0.5]), ([[9.0, 1.0], [2.2, 2.2], [2.2, 2.2]], 0.5)):
        expected = leg.hydro(q, qd, qdd, cd=cd, cm=cm)
        got = regressors.torques(cd=cd, cm=cm)
        np.testing.assert_allclose(got.total, expected.total, rtol=1e-12, atol=1e-12)
    with pytest.raises(ValueError, match="differs between links that carry a segment"):
        regressors.torques(cd=[2.2, 2.0, 2.2])
    with pytest.raises(ValueError, match="differs between links that carry a segment"):
        regressors.torques(cm=[[0.5, 0.5], [0.5, 0.6], [0.5, 0.5]])
