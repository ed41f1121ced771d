"""The one evaluation of the Rust core (``uwml.Robot.hydro``, ``uwml.Robot.hydro_regressors``)
on serial chains, the paper's leg (``uwml.paper_leg``) and random ones, held against the numpy
reference (``uwml.reference``: the paper's leg to 1e-12 of each sample's torques, also against
the reference's own Table II leg; random chains to 1e-10), docs/model.md section 5's reference values and the
paper's printed equations (eqs. 8, 9, 17, 21).

Nothing expected here is produced by the code under test; ``chains.py`` says how a relative
error is measured. Whole robots (trees, a moving base, a current) are ``test_robot.py``'s.
"""

import math

import numpy as np
import pytest
import uwml
from chains import (
    D21,
    D22,
    D31,
    D32,
    L2,
    L2C,
    L3,
    L3C,
    LAYOUTS,
    M2,
    M3,
    PAPER,
    PROPERTY_EXAMPLES,
    REFERENCE_EXAMPLES,
    RHO,
    RHO_M,
    RTOL_PAPER,
    RTOL_REFERENCE,
    RTOL_ROUNDING,
    TINY,
    assert_batch_close,
    drawn,
    natural_scales,
    per_segment,
    random_coefficients,
    random_states,
    random_water,
    seeds,
    segment_coefficients,
)
from hypothesis import given
from hypothesis import strategies as st
from uwml import reference as ref

layouts = st.sampled_from(LAYOUTS)


# --------------------------------------------------------------------------------------------
# 1. The Rust core against the numpy reference
# --------------------------------------------------------------------------------------------


@pytest.mark.parametrize("kind", ["paper", "chain"])
@REFERENCE_EXAMPLES
@given(seed=seeds, layout=layouts)
def test_hydro_matches_reference(kind: str, seed: int, layout: str) -> None:
    rng, leg, joints, links, (q, qd, qdd) = drawn(kind, seed)
    cd, cm = random_coefficients(rng, leg.n_joints, layout)
    density, gravity = random_water(rng)
    out = leg.hydro(q, qd, qdd, cd=per_segment(links, cd), cm=per_segment(links, cm), water=uwml.Water(density=density, gravity=gravity))
    expected = ref.hydro(joints, links, q, qd, qdd, cd=cd, cm=cm, density=density, gravity=gravity)
    natural = natural_scales(joints, links, qd, qdd, density, gravity, cd, cm)
    references = {kind: expected}
    if kind == "paper":
        # The preset against the reference's own Table II leg too (catches preset mistakes that
        # leg.joints/leg.links would carry over to the reference).
        references["paper preset"] = ref.hydro(*ref.paper_leg(), q, qd, qdd, cd=cd, cm=cm, density=density, gravity=gravity)
    rtol = RTOL_PAPER if kind == "paper" else RTOL_REFERENCE
    for what, values in references.items():
        for key in ("drag", "added_mass", "buoyancy", "gravity", "total"):
            assert_batch_close(getattr(out, key), values[key], rtol, f"{what} {key}", natural[key])


@pytest.mark.parametrize("kind", ["paper", "chain"])
@REFERENCE_EXAMPLES
@given(seed=seeds, layout=layouts)
def test_regressors_match_reference(kind: str, seed: int, layout: str) -> None:
    rng, leg, joints, links, (q, qd, qdd) = drawn(kind, seed)
    n, m = leg.n_joints, len(q)
    rtol = RTOL_PAPER if kind == "paper" else RTOL_REFERENCE
    density, gravity = random_water(rng)
    water = uwml.Water(density=density, gravity=gravity)
    expected = ref.regressors(joints, links, q, qd, qdd, density=density, gravity=gravity)
    unit = natural_scales(joints, links, qd, qdd, density, gravity)  # at Cd = Cm = 1

    regressors = leg.hydro_regressors(q, qd, qdd, water=water)
    owners = [i for i, link in enumerate(links) if link.segments]
    s = len(owners)
    assert regressors.drag.shape == regressors.added_mass.shape == (m, n, s, 2)
    assert regressors.buoyancy.shape == regressors.gravity.shape == (m, n)
    # The reference's columns per link; a link without a segment has none in the robot's.
    for key in ("drag", "added_mass"):
        per_link = np.zeros((m, n, n, 2))
        per_link[:, :, owners, :] = getattr(regressors, key)
        assert_batch_close(per_link, expected[key], rtol, f"{kind} {key} regressor per link and direction", unit[key])
        whole = getattr(regressors, key).sum(axis=(-2, -1))
        assert_batch_close(whole, expected[key].sum(axis=(-2, -1)), rtol, f"{kind} {key} regressor of the leg", unit[key])
    assert_batch_close(regressors.buoyancy, expected["buoyancy"], rtol, f"{kind} buoyancy", unit["buoyancy"])

    # Regressors.torques(cd, cm) equals the evaluation, in every coefficient layout.
    cd, cm = segment_coefficients(rng, links, layout)
    direct = leg.hydro(q, qd, qdd, cd=cd, cm=cm, water=water)
    natural = natural_scales(joints, links, qd, qdd, density, gravity, np.max(cd, initial=0.0), np.max(cm, initial=0.0))
    torques = regressors.torques(cd, cm)
    for key in ("drag", "added_mass", "buoyancy", "gravity", "total"):
        assert_batch_close(getattr(torques, key), getattr(direct, key), RTOL_ROUNDING, f"{kind} torques().{key}", natural[key])


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
    np.testing.assert_allclose(2.2 * reg.drag.sum(axis=(-2, -1)), SECTION5["drag"], rtol=1e-6)
    np.testing.assert_allclose(0.5 * reg.added_mass.sum(axis=(-2, -1)), SECTION5["added_mass"], rtol=1e-6)
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
