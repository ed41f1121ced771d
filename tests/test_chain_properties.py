"""Properties of docs/model.md section 5 that the Rust core's evaluation of serial chains (the
paper's leg and random ones) must have: drag dissipative and homogeneous in the speeds, added
mass linear in the accelerations with a symmetric positive semi-definite matrix, buoyancy and
gravity the gradients of potentials (the heights from forward kinematics written here), every
term linear in its coefficient, the water's density and gravity as factors. Each relation
compares two evaluations; ``chains.py`` says how a relative error is measured.
"""

import math

import numpy as np
import pytest
import uwml
from chains import (
    L2,
    L2C,
    L3,
    L3C,
    M2,
    M3,
    PAPER,
    PROPERTY_EXAMPLES,
    RHO_M,
    RTOL_ROUNDING,
    TINY,
    assert_batch_close,
    chain_or_paper,
    drawn,
    gradient,
    natural_scales,
    per_segment,
    potential_heights,
    random_coefficients,
    random_states,
    seeds,
    segment_coefficients,
)
from hypothesis import given
from hypothesis import strategies as st
from uwml import reference as ref

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
    cd, cm = per_segment(links, cd), per_segment(links, cm)
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
    m = 100
    rng, leg, joints, links, (q, qd, qdd) = drawn(kind, seed, m)
    cd, cm = segment_coefficients(rng, links)
    n = leg.n_joints
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
    s = len(leg.segments)
    cd1, cm1 = rng.uniform(0.0, 3.0, (s, 2)), rng.uniform(0.0, 1.5, (s, 2))
    cd2, cm2 = rng.uniform(0.0, 3.0, (s, 2)), rng.uniform(0.0, 1.5, (s, 2))
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
