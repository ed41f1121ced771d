"""Tests of the numpy reference ``python/uwml/reference/`` (serial chains, the paper, losses).

The package is loaded standalone from its directory, so these tests run without the compiled
extension. The brute-force checks below share no code with it: forward kinematics by
quaternions, joint Jacobians by complex-step differentiation (the principle of virtual work:
the moment arm of joint j is ``∂p/∂q_j``), slice accelerations by finite differences of those
exact velocities along a trajectory, and high-order Gauss-Legendre quadrature.
"""

import itertools
import math
from types import SimpleNamespace
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from pure import load_reference

ref = load_reference()
JOINTS, LINKS = ref.paper_leg()

RHO = 1000.0
G = 9.81
L2, L3, L2C, L3C = 0.660, 0.714, 0.506, 0.560
M2, M3 = 19.261, 10.375
RHO_M = 2700.0

angles = st.floats(-math.pi, math.pi, allow_nan=False)
rates = st.floats(-3.0, 3.0, allow_nan=False)
seeds = st.integers(0, 2**32 - 1)
FAST = settings(max_examples=40, deadline=None)


# --------------------------------------------------------------------------------------------
# Brute force, independent of the reference
# --------------------------------------------------------------------------------------------


def _quaternion_rotation(axis: np.ndarray, angle: Any) -> np.ndarray:
    """Rotation matrix from the unit quaternion (cos θ/2, sin θ/2 axis); complex angles allowed."""
    w = np.cos(angle / 2)
    x, y, z = np.sin(angle / 2) * axis
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
        ]
    )


def _frames(joints: Any, q: np.ndarray) -> list[tuple[np.ndarray, np.ndarray]]:
    """World (rotation, origin) of every link frame; q may be complex."""
    rotation, origin = np.eye(3, dtype=q.dtype), np.zeros(3, dtype=q.dtype)
    frames = []
    for joint, angle in zip(joints, q, strict=True):
        origin = origin + rotation @ np.asarray(joint.origin)
        rotation = rotation @ _quaternion_rotation(np.asarray(joint.axis), angle)
        frames.append((rotation, origin))
    return frames


def _slice_points(joints: Any, link: int, segment: Any, q: np.ndarray, s: np.ndarray) -> np.ndarray:
    """World positions (len(s), 3) of the slices at arc lengths s of ``segment`` on ``link``."""
    rotation, origin = _frames(joints, q)[link]
    local = np.asarray(segment.start) + s[:, None] * np.asarray(segment.axis)
    return origin + local @ rotation.T


def _jacobian(fun: Any, q: np.ndarray) -> np.ndarray:
    """∂fun/∂q by complex step, exact to rounding: shape fun(q).shape + (n,)."""
    h = 1e-30
    return np.stack([np.imag(fun(q + 1j * h * e)) / h for e in np.eye(len(q))], axis=-1)


def _directional(fun: Any, q: np.ndarray, direction: np.ndarray) -> np.ndarray:
    return np.imag(fun(q + 1e-30j * direction)) / 1e-30


def _gauss_legendre(cuts: list[float], nodes: int) -> tuple[np.ndarray, np.ndarray]:
    """Nodes and weights of ``nodes``-point Gauss-Legendre on each interval between cuts."""
    t, w = np.polynomial.legendre.leggauss(nodes)
    pieces = list(itertools.pairwise(cuts))
    return np.concatenate([a + (b - a) * (t + 1) / 2 for a, b in pieces]), np.concatenate([(b - a) / 2 * w for a, b in pieces])


def _link_brute_force(
    joints: Any, link: int, seg: Any, q: np.ndarray, qd: np.ndarray, qdd: np.ndarray, nodes: int
) -> tuple[np.ndarray, np.ndarray]:
    """Drag and added-mass regressors (n, 2) of one link's segment; see :func:`_brute_force`."""
    normals = np.asarray(seg.normals) @ _frames(joints, q)[link][0].T  # (2, 3) world

    def points(s: np.ndarray) -> Any:
        return lambda qq: _slice_points(joints, link, seg, qq, s)

    def velocity(s: np.ndarray, t: float = 0.0) -> np.ndarray:
        """World velocities (len(s), 3) at time t along q(t) = q + q̇ t + q̈ t²/2."""
        return _directional(points(s), q + qd * t + qdd * t * t / 2, qd + qdd * t)

    drag = np.zeros((len(joints), 2))
    ends = velocity(np.array([0.0, seg.length])) @ normals.T  # (2 ends, 2 directions)
    for k in range(2):
        (ha, hb), cuts = ends[:, k], [0.0, seg.length]
        if ha * hb < 0:
            cuts.insert(1, seg.length * ha / (ha - hb))
        s, w = _gauss_legendre(cuts, nodes)
        g = _jacobian(points(s), q).transpose(0, 2, 1) @ normals[k]  # (nodes, n)
        h = velocity(s) @ normals[k]
        drag[:, k] = -0.5 * RHO * seg.widths[k] * (g * (h * np.abs(h) * w)[:, None]).sum(axis=0)

    s, w = _gauss_legendre([0.0, seg.length], nodes)
    dt = 1e-3
    acc = (8 * (velocity(s, dt) - velocity(s, -dt)) - (velocity(s, 2 * dt) - velocity(s, -2 * dt))) / (12 * dt)
    g = _jacobian(points(s), q).transpose(0, 2, 1) @ normals.T  # (nodes, n, 2)
    added_mass = -RHO * seg.area * np.einsum("pjk,pk,p->jk", g, acc @ normals.T, w)
    return drag, added_mass


def _brute_force(joints: Any, links: Any, q: np.ndarray, qd: np.ndarray, qdd: np.ndarray, nodes: int = 40) -> tuple[np.ndarray, np.ndarray]:
    """Drag and added-mass regressors (n, n_links, 2) by virtual work and dense quadrature.

    The moment arm of joint j is ``∂p/∂q_j`` (complex step). Drag: Gauss-Legendre with ``nodes``
    nodes on each interval where the normal velocity keeps its sign. Added mass: the slice
    acceleration ``d²p/dt²`` along ``q(t) = q + q̇ t + q̈ t²/2`` by a 4th-order central difference
    of the complex-step velocity.
    """
    drag = np.zeros((len(joints), len(links), 2))
    added_mass = np.zeros((len(joints), len(links), 2))
    for i, link in enumerate(links):
        for segment in link.segments:
            drag[:, i], added_mass[:, i] = _link_brute_force(joints, i, segment, q, qd, qdd, nodes)
    return drag, added_mass


def _random_unit(rng: np.random.Generator) -> np.ndarray:
    v = rng.normal(size=3)
    return v / np.linalg.norm(v)


def _random_chain(rng: np.random.Generator) -> tuple[list[Any], list[Any]]:
    """A random chain of 1-4 joints; duck-typed SimpleNamespace objects, some links dry."""
    n = int(rng.integers(1, 5))
    joints, links = [], []
    for i in range(n):
        joints.append(SimpleNamespace(origin=tuple(rng.uniform(-0.5, 0.5, 3)), axis=tuple(_random_unit(rng))))
        mass = float(rng.uniform(0.5, 5.0))
        com = tuple(rng.uniform(-0.4, 0.4, 3))
        segment = None
        if i == n - 1 or rng.random() < 0.7:
            axis = _random_unit(rng)
            n1 = np.cross(axis, _random_unit(rng))
            n1 /= np.linalg.norm(n1)
            n2 = np.cross(axis, n1)
            widths = tuple(rng.uniform(0.05, 0.3, 2))
            segment = SimpleNamespace(
                start=tuple(rng.uniform(-0.2, 0.2, 3)),
                axis=tuple(axis),
                length=float(rng.uniform(0.1, 1.0)),
                normals=(tuple(n1), tuple(n2)),
                widths=widths,
                area=widths[0] * widths[1],
            )
        links.append(
            SimpleNamespace(
                mass=mass,
                com=com,
                volume=mass / 2700.0,
                cob=tuple(rng.uniform(-0.4, 0.4, 3)),
                segments=() if segment is None else (segment,),
            )
        )
    return joints, links


def _random_state(rng: np.random.Generator, n: int, size: tuple[int, ...] = ()) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    return rng.uniform(-math.pi, math.pi, (*size, n)), rng.normal(size=(*size, n)), rng.normal(size=(*size, n))


def _assert_close(actual: np.ndarray, expected: np.ndarray, rtol: float) -> None:
    """Agreement relative to the largest entry (components may cancel to near zero)."""
    scale = max(float(np.max(np.abs(expected))), 1e-300)
    np.testing.assert_allclose(actual, expected, rtol=0, atol=rtol * scale)


# --------------------------------------------------------------------------------------------
# Reference values and the paper's leg
# --------------------------------------------------------------------------------------------


def test_model_section5_reference_values() -> None:
    out = ref.hydro(JOINTS, LINKS, [0.3, -0.4, 0.6], [0.8, 0.5, -0.7], [1.0, -2.0, 0.5])
    np.testing.assert_allclose(out["drag"], [-24.24084, -5.060505, -0.7383118], rtol=1e-6)
    np.testing.assert_allclose(out["added_mass"], [-8.525438, 21.77596, 9.484545], rtol=1e-6)
    np.testing.assert_allclose(out["buoyancy"], [0.0, 59.72457, 4.193843], rtol=1e-6, atol=1e-12)
    np.testing.assert_allclose(out["total"], out["drag"] + out["added_mass"] + out["buoyancy"], rtol=1e-15)


@FAST
@given(q1=angles, q2=angles, q3=angles)
def test_paper_leg_matches_model_section2(q1: float, q2: float, q3: float) -> None:
    frames = _frames(JOINTS, np.array([q1, q2, q3]))
    e_r, e_t, z = np.array([math.cos(q1), math.sin(q1), 0.0]), np.array([-math.sin(q1), math.cos(q1), 0.0]), np.array([0.0, 0.0, 1.0])
    u2 = math.cos(q2) * e_r + math.sin(q2) * z
    u3 = math.sin(q2 + q3) * e_r - math.cos(q2 + q3) * z
    n2 = -math.sin(q2) * e_r + math.cos(q2) * z
    n3 = math.cos(q2 + q3) * e_r + math.sin(q2 + q3) * z
    (r2, o2), (r3, o3) = frames[1], frames[2]
    (thigh,), (calf,) = LINKS[1].segments, LINKS[2].segments
    np.testing.assert_allclose(r2 @ thigh.axis, u2, atol=1e-15)
    np.testing.assert_allclose(r3 @ calf.axis, u3, atol=1e-15)
    np.testing.assert_allclose(r2 @ np.array(thigh.normals).T, np.stack([e_t, n2], axis=1), atol=1e-15)
    np.testing.assert_allclose(r3 @ np.array(calf.normals).T, np.stack([e_t, n3], axis=1), atol=1e-15)
    np.testing.assert_allclose(o2, 0.0, atol=1e-15)
    np.testing.assert_allclose(o3, L2 * u2, atol=1e-15)
    np.testing.assert_allclose(o2 + r2 @ LINKS[1].com, L2C * u2, atol=1e-15)
    np.testing.assert_allclose(o3 + r3 @ LINKS[2].com, L2 * u2 + L3C * u3, atol=1e-15)
    assert thigh.widths == (0.131, 0.238) and calf.widths == (0.131, 0.279)
    assert (thigh.length, calf.length) == (L2, L3)
    assert [link.volume * RHO_M for link in LINKS] == pytest.approx([10.758, M2, M3], rel=1e-15)


@FAST
@given(q1=angles, q2=angles, q3=angles, w1=rates, a1=rates)
def test_pure_yaw_joint1_equals_paper_equations(q1: float, q2: float, q3: float, w1: float, a1: float) -> None:
    state = ([q1, q2, q3], [w1, 0.0, 0.0], [a1, 0.0, 0.0])
    ours, paper = ref.hydro(JOINTS, LINKS, *state), ref.paper_equations(*state)
    scale = RHO * (w1 * w1 + abs(a1)) + 1e-300
    for key in ("drag", "added_mass"):
        np.testing.assert_allclose(ours[key][0], paper[key][0], rtol=1e-10, atol=1e-13 * scale)


@FAST
@given(q2=angles, q3=angles, w3=rates, a3=rates)
def test_pure_knee_motion_equals_paper_equations(q2: float, q3: float, w3: float, a3: float) -> None:
    """With only the knee moving, eqs. (15), (16) (read with v̇33), (19) and (20) agree with uwml."""
    state = ([0.4, q2, q3], [0.0, 0.0, w3], [0.0, 0.0, a3])
    ours, paper = ref.hydro(JOINTS, LINKS, *state), ref.paper_equations(*state)
    scale = RHO * (w3 * w3 + abs(a3)) + 1e-300
    for key in ("drag", "added_mass"):
        np.testing.assert_allclose(ours[key], paper[key], rtol=1e-10, atol=1e-13 * scale)


@FAST
@given(q1=angles, q2=angles, q3=angles, w=st.lists(rates, min_size=3, max_size=3), a=st.lists(rates, min_size=3, max_size=3))
def test_buoyancy_equals_eqs_17_and_21(q1: float, q2: float, q3: float, w: list[float], a: list[float]) -> None:
    ours, paper = ref.hydro(JOINTS, LINKS, [q1, q2, q3], w, a), ref.paper_equations([q1, q2, q3], w, a)
    eq17 = (M2 * G * L2C * math.cos(q2) + M3 * G * (L2 * math.cos(q2) + L3C * math.sin(q2 + q3))) * RHO / RHO_M
    eq21 = M3 * G * L3C * math.sin(q2 + q3) * RHO / RHO_M
    assert ours["buoyancy"][0] == 0.0
    assert ours["gravity"][0] == 0.0
    np.testing.assert_allclose(ours["buoyancy"][1:], [eq17, eq21], rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(paper["buoyancy"], [0.0, eq17, eq21], rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(ours["gravity"], -RHO_M / RHO * ours["buoyancy"], rtol=1e-12, atol=1e-12)


@FAST
@given(q=st.lists(angles, min_size=3, max_size=3), w=st.lists(rates, min_size=3, max_size=3), a=st.lists(rates, min_size=3, max_size=3))
def test_joint1_drag_equals_eq8_for_every_state(q: list[float], w: list[float], a: list[float]) -> None:
    """Roll motion is in the leg plane, so joint 1's drag is eq. (8)'s (sin fix) for any motion."""
    ours, paper = ref.hydro(JOINTS, LINKS, q, w, a), ref.paper_equations(q, w, a)
    scale = RHO * float(np.dot(w, w)) + 1e-300
    np.testing.assert_allclose(ours["drag"][0], paper["drag"][0], rtol=1e-10, atol=1e-13 * scale)


def test_paper_equations_section5_state() -> None:
    """At the section-5 state the printed equations differ from uwml as docs/model.md section 6 says."""
    state = ([0.3, -0.4, 0.6], [0.8, 0.5, -0.7], [1.0, -2.0, 0.5])
    paper, ours = ref.paper_equations(*state), ref.hydro(JOINTS, LINKS, *state)
    np.testing.assert_allclose(paper["drag"][0], ours["drag"][0], rtol=1e-12)
    np.testing.assert_allclose(paper["buoyancy"], ours["buoyancy"], rtol=1e-14)
    np.testing.assert_allclose(paper["total"], paper["buoyancy"] + paper["drag"] + paper["added_mass"], rtol=1e-14)
    assert abs(paper["added_mass"][0] - ours["added_mass"][0]) > 0.1  # item 2: Coriolis term
    assert abs(paper["drag"][1] - ours["drag"][1]) > 1.0  # items 3-4


# --------------------------------------------------------------------------------------------
# Exactness against brute force, on the paper leg and random chains
# --------------------------------------------------------------------------------------------


@settings(max_examples=25, deadline=None)
@given(seed=seeds)
def test_drag_and_added_mass_match_brute_force(seed: int) -> None:
    rng = np.random.default_rng(seed)
    joints, links = (JOINTS, LINKS) if seed % 4 == 0 else _random_chain(rng)
    q, qd, qdd = _random_state(rng, len(joints))
    drag, added_mass = _brute_force(joints, links, q, qd, qdd)
    out = ref.regressors(joints, links, q, qd, qdd)
    _assert_close(out["drag"], drag, 1e-10)
    _assert_close(out["added_mass"], added_mass, 1e-8)


def test_drag_sign_change_brute_force_paper_leg() -> None:
    """The section-5 state and one where the calf's yaw velocity changes sign along the calf."""
    q2, q3 = 0.2, -1.8
    assert 0.0 < -L2 * math.cos(q2) / math.sin(q2 + q3) < L3  # the root of v31 lies on the calf
    for state in (([0.3, -0.4, 0.6], [0.8, 0.5, -0.7], [1.0, -2.0, 0.5]), ([0.0, q2, q3], [1.0, 0.3, 0.4], [0.0, 0.0, 0.0])):
        q, qd, qdd = (np.array(x) for x in state)
        drag, _ = _brute_force(JOINTS, LINKS, q, qd, qdd, nodes=60)
        _assert_close(ref.regressors(JOINTS, LINKS, q, qd, qdd)["drag"], drag, 1e-10)


def test_drag_integral_against_midpoint_rule() -> None:
    """The closed-form ``∫₀¹ g h|h|`` against a 20000-point midpoint rule, with and without a root."""
    rng = np.random.default_rng(7)
    ga, gb, ha, hb = rng.normal(size=(4, 200))
    ha[:5], hb[5:10], ha[10:15], hb[10:15] = 0.0, 0.0, 1e-3, -1e-3
    t = (np.arange(20000) + 0.5) / 20000
    g, h = ga[:, None] + (gb - ga)[:, None] * t, ha[:, None] + (hb - ha)[:, None] * t
    expected = (g * h * np.abs(h)).mean(axis=1)
    scale = (np.abs(ga) + np.abs(gb)) * (ha * ha + hb * hb)
    assert np.all(np.abs(ref._drag_integral(ga, gb, ha, hb) - expected) <= 1e-8 * scale)


@settings(max_examples=30, deadline=None)
@given(seed=seeds)
def test_buoyancy_is_conservative(seed: int) -> None:
    """τ_buoy = ∂/∂q (ρ g Σ V_i c_i,z) and τ_grav = −∂/∂q (g Σ m_i com_i,z)."""
    rng = np.random.default_rng(seed)
    joints, links = _random_chain(rng)
    q, qd, qdd = _random_state(rng, len(joints))

    def height(qq: np.ndarray, point: str, weight: str) -> Any:
        return sum(
            getattr(link, weight) * (o + r @ np.asarray(getattr(link, point)))[2]
            for link, (r, o) in zip(links, _frames(joints, qq), strict=True)
        )

    out = ref.hydro(joints, links, q, qd, qdd)
    np.testing.assert_allclose(out["buoyancy"], RHO * G * _jacobian(lambda qq: height(qq, "cob", "volume"), q), rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(out["gravity"], -G * _jacobian(lambda qq: height(qq, "com", "mass"), q), rtol=1e-12, atol=1e-12)


# --------------------------------------------------------------------------------------------
# Properties of docs/model.md section 5
# --------------------------------------------------------------------------------------------


@settings(max_examples=30, deadline=None)
@given(seed=seeds, scale=st.floats(-4.0, 4.0, allow_nan=False))
def test_drag_dissipative_and_homogeneous(seed: int, scale: float) -> None:
    rng = np.random.default_rng(seed)
    joints, links = _random_chain(rng)
    q, qd, qdd = _random_state(rng, len(joints), (8,))
    drag = ref.hydro(joints, links, q, qd, qdd)["drag"]
    power = np.einsum("mj,mj->m", qd, drag)
    assert np.all(power <= 1e-12 * np.abs(qd).sum(axis=1) * np.abs(drag).sum(axis=1))
    scaled = ref.hydro(joints, links, q, scale * qd, qdd)["drag"]
    np.testing.assert_allclose(scaled, scale * abs(scale) * drag, rtol=1e-12, atol=1e-12 * np.abs(drag).max())


@settings(max_examples=30, deadline=None)
@given(seed=seeds)
def test_added_mass_matrix_symmetric_psd(seed: int) -> None:
    rng = np.random.default_rng(seed)
    joints, links = _random_chain(rng)
    n = len(joints)
    q = rng.uniform(-math.pi, math.pi, n)
    columns = ref.hydro(joints, links, np.tile(q, (n, 1)), np.zeros((n, n)), np.eye(n))["added_mass"]
    matrix = -columns.T  # M_A[:, l] = −τ_am(q̈ = e_l)
    np.testing.assert_allclose(matrix, matrix.T, rtol=0, atol=1e-12 * np.abs(matrix).max())
    assert np.linalg.eigvalsh(matrix).min() >= -1e-12 * np.abs(matrix).max()
    qdd = rng.normal(size=n)
    np.testing.assert_allclose(ref.hydro(joints, links, q, np.zeros(n), qdd)["added_mass"], -matrix @ qdd, rtol=1e-12, atol=1e-12)


def test_regressors_consistency_and_coefficient_broadcasting() -> None:
    rng = np.random.default_rng(3)
    joints, links = _random_chain(rng)
    while len(joints) < 3:
        joints, links = _random_chain(rng)
    n = len(joints)
    q, qd, qdd = _random_state(rng, n, (5,))
    reg = ref.regressors(joints, links, q, qd, qdd)
    assert reg["buoyancy"].shape == (5, n) and reg["drag"].shape == reg["added_mass"].shape == (5, n, n, 2)
    cd, cm = rng.uniform(0.5, 3.0, (n, 2)), rng.uniform(0.1, 1.0, (n, 2))
    out = ref.hydro(joints, links, q, qd, qdd, cd=cd, cm=cm)
    expected = reg["buoyancy"] + np.einsum("...jlk,lk->...j", reg["drag"], cd) + np.einsum("...jlk,lk->...j", reg["added_mass"], cm)
    np.testing.assert_allclose(out["total"], expected, rtol=1e-13, atol=1e-13)
    per_link = ref.hydro(joints, links, q, qd, qdd, cd=cd[:, 0], cm=cm[:, 1])
    repeated = ref.hydro(joints, links, q, qd, qdd, cd=np.repeat(cd[:, :1], 2, 1), cm=np.repeat(cm[:, 1:], 2, 1))
    for key in ("drag", "added_mass", "total"):
        np.testing.assert_array_equal(per_link[key], repeated[key])
    scalar = ref.hydro(joints, links, q, qd, qdd, cd=1.7, cm=0.3)
    full = ref.hydro(joints, links, q, qd, qdd, cd=np.full((n, 2), 1.7), cm=np.full((n, 2), 0.3))
    for key in scalar:
        np.testing.assert_array_equal(scalar[key], full[key])
    # Upper-triangular structure: a link loads only the joints that move it.
    for link in range(n):
        assert np.all(reg["drag"][:, link + 1 :, link] == 0.0)
        assert np.all(reg["added_mass"][:, link + 1 :, link] == 0.0)
    for link, item in enumerate(links):
        if not item.segments:
            assert np.all(reg["drag"][..., link, :] == 0.0)


def test_batches_and_single_samples_agree() -> None:
    rng = np.random.default_rng(11)
    q, qd, qdd = _random_state(rng, 3, (6,))
    batch = ref.hydro(JOINTS, LINKS, q, qd, qdd)
    paper = ref.paper_equations(q, qd, qdd)
    for m in range(6):
        one = ref.hydro(JOINTS, LINKS, q[m], qd[m], qdd[m])
        for key in batch:
            assert one[key].shape == (3,)
            np.testing.assert_allclose(one[key], batch[key][m], rtol=1e-14, atol=1e-14)
        np.testing.assert_allclose(ref.paper_equations(q[m], qd[m], qdd[m])["total"], paper["total"][m], rtol=1e-13)


# --------------------------------------------------------------------------------------------
# Input validation
# --------------------------------------------------------------------------------------------

GOOD = ([0.1, 0.2, 0.3], [0.1, 0.2, 0.3], [0.1, 0.2, 0.3])


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"q": [0.1, 0.2]}, "q must have shape"),
        ({"q": 0.1}, "q must have shape"),
        ({"qd": [[0.1, 0.2, 0.3]]}, "same shape"),
        ({"qdd": [0.1, math.nan, 0.3]}, "qdd must be finite"),
        ({"qd": [0.1, math.inf, 0.3]}, "qd must be finite"),
        ({"qd": ["a", 1, 2]}, "qd must be an array"),
        ({"cd": -1.0}, "cd must be finite and non-negative"),
        ({"cm": [0.5, 0.5, -0.1]}, "cm must be finite and non-negative"),
        ({"cd": np.ones(4)}, r"cd must be a scalar, shape \(3,\)"),
        ({"cm": np.ones((3, 3))}, r"cm must be a scalar, shape \(3,\)"),
        ({"cd": "big"}, "cd must be a number"),
        ({"density": 0.0}, "density must be finite and > 0"),
        ({"density": math.nan}, "density"),
        ({"gravity": -9.81}, "gravity must be finite and >= 0"),
    ],
)
def test_hydro_rejects_bad_input(kwargs: dict[str, Any], match: str) -> None:
    args = dict(zip(("q", "qd", "qdd"), GOOD, strict=True)) | kwargs
    with pytest.raises(ValueError, match=match):
        ref.hydro(JOINTS, LINKS, **args)


def test_other_functions_reject_bad_input() -> None:
    with pytest.raises(ValueError, match="equal length"):
        ref.hydro(JOINTS, LINKS[:2], *GOOD)
    with pytest.raises(ValueError, match=r"joints\[1\]\.axis must be a unit vector"):
        ref.regressors([JOINTS[0], SimpleNamespace(origin=(0, 0, 0), axis=(0, 2, 0)), JOINTS[2]], LINKS, *GOOD)
    with pytest.raises(ValueError, match="density"):
        ref.regressors(JOINTS, LINKS, *GOOD, density=-1.0)
    with pytest.raises(ValueError, match="q must have shape"):
        ref.paper_equations([0.1, 0.2], [0.1, 0.2], [0.1, 0.2])
    with pytest.raises(ValueError, match="cm must be finite"):
        ref.paper_equations(*GOOD, cm=-0.5)
    with pytest.raises(ValueError, match="gravity"):
        ref.paper_equations(*GOOD, gravity=math.inf)
