"""The paper's printed equations (Liao et al., eqs. 8-22) for its 3-DOF leg, in uwml's sign.

For side-by-side comparison with :func:`uwml.reference.hydro` on :func:`uwml.reference.paper_leg`
(docs/model.md section 6, which lists where uwml departs from the printed equations and why).
"""

import numpy as np
from numpy.typing import ArrayLike

from ._inputs import Array, _number, _states
from .chain import PAPER_D21, PAPER_D22, PAPER_D31, PAPER_D32, PAPER_L2, PAPER_L2C, PAPER_L3, PAPER_L3C, PAPER_LINK_DENSITY, PAPER_MASSES

__all__ = ["paper_equations"]

#: Gauss-Legendre nodes per sub-interval in :func:`paper_equations`.
_PAPER_NODES = 24
#: Extra calf breakpoints at ``near ± width · grading`` around the calf's closest approach to the
#: hip (see :func:`paper_equations`), for the near-pole of ``1/r32²`` when ``cos q3 ≈ 0``.
_PAPER_GRADING = 8.0 ** np.arange(11)


# --------------------------------------------------------------------------------------------
# Public API: the paper's printed equations
# --------------------------------------------------------------------------------------------


def _quadrature(length: float, breaks: Array) -> tuple[Array, Array]:
    """Gauss-Legendre nodes and weights (m, P) on [0, length] split at ``breaks`` (m, b).

    Breaks outside [0, length] (or non-finite) are clipped to the ends, giving empty pieces,
    whose nodes are put mid-interval (with zero weights) so that no integrand sees x = 0.
    """
    t, w = np.polynomial.legendre.leggauss(_PAPER_NODES)
    clipped = np.clip(np.nan_to_num(breaks, nan=length, posinf=length, neginf=0.0), 0.0, length)
    edges = np.sort(np.concatenate([np.zeros((breaks.shape[0], 1)), clipped, np.full((breaks.shape[0], 1), length)], axis=1), axis=1)
    half = 0.5 * np.diff(edges, axis=1)[:, :, None]  # (m, pieces, 1)
    nodes = np.where(half > 0.0, edges[:, :-1, None] + half * (t + 1.0), 0.5 * length)
    weights = half * w
    return nodes.reshape(len(breaks), -1), weights.reshape(len(breaks), -1)


def paper_equations(
    q: ArrayLike,
    qd: ArrayLike,
    qdd: ArrayLike,
    cd: float = 2.2,
    cm: float = 0.5,
    density: float = 1000.0,
    gravity: float = 9.81,
) -> dict[str, Array]:
    """The paper's printed eqs. (8)-(22) for its 3-DOF leg with Table II, in uwml's sign.

    For side-by-side comparison with :func:`hydro` (docs/model.md section 6). Returned: ``drag = −τ_d``,
    ``added_mass = −τ_m``, ``buoyancy = τ_f``, ``total = τ_w = τ_f − τ_d − τ_m``. The integrals
    are evaluated by Gauss-Legendre quadrature (24 nodes per piece). The calf is split at the
    root of ``v31``, at the calf's closest approach to the hip ``x0 = −L2 s3`` (where ``r32`` is
    least and may vanish) and, geometrically graded, at ``x0 ± L2 |c3| 8^k`` (k = 0..10) to
    resolve the near-pole of ``1/r32²`` in ``x cos α v̇32`` when ``cos q3 ≈ 0``; the result is
    converged to 1e-12 of the largest torque or better (1e-14 unless ``|cos q3| < 1e-9``; checked
    against 200 nodes and k = 0..14).
    Every joint-1 integrand is a polynomial of degree ≤ 3 on each piece, integrated exactly.
    Cost: about 0.1 s per 1000 samples.

    How the printed terms are read (x: distance of the slice from its link's joint; s_i, c_i are
    sin and cos of q_i, s23 = sin(q2 + q3), c23 = cos(q2 + q3)):

    * Eq. (8): the first term (link 1, ``D_11 = 0``, ``L_1 = 0``) is zero. The calf's moment arm
      is read ``L2 c2 + x s23`` (the printed ``x cos(q2+q3)`` is a typo: eqs. 7, 9, 17 use sin);
      this is the only change to the printed equations.
    * Eq. (9): ``A_1 = 0``, ``A_2 = D21 D22``, ``A_3 = D31 D32``. Its integrands are printed with
      ``v21``, ``v31``, without the dot; they are read as ``v̇21``, ``v̇31`` (eq. 4, docs/model.md
      section 6 item 2).
    * ``v̇`` is the time derivative of the printed scalar speed:
      ``v̇21 = q̈1 x c2 − q̇1 q̇2 x s2``,
      ``v̇31 = q̈1 (L2 c2 + x s23) + q̇1 (−q̇2 L2 s2 + (q̇2 + q̇3) x c23)``, ``v̇22 = q̈2 x``,
      ``v̇32 = q̈2 r32 + q̇2 q̇3 L2 x c3 / r32``, ``v̇33 = q̈3 x``.
    * ``r32 = sqrt(L2² + x² + 2 L2 x s3)`` (eq. 13; computed as ``hypot(x + L2 s3, L2 c3)``, the
      same number without cancellation), ``x`` from the knee; ``v32 = q̇2 r32``;
      ``cos α = (x² + r32² − L2²) / (2 x r32)`` evaluated as printed (so ``r32 cos α = x + L2 s3``).
    * Eq. (15): ``½ρCd [D22 ∫₀^L2 x v22|v22| + D32 ∫₀^L3 r32 v32|v32| + D32 ∫₀^L3 r32 cos α v33|v33|]``,
      one ``v|v|`` per joint as printed (superposed, not the total velocity).
    * Eq. (16): ``ρCm [A2 ∫ x v̇22 + A3 ∫ r32 v̇32 + A3 ∫ r32 cos α v̇33]``, the third term read with
      ``v̇33`` (printed ``v̇32``), as docs/model.md section 6 says.
    * Eqs. (19), (20): ``½ρCd D32 [∫ x v33|v33| + ∫ x cos α v32|v32|]`` and
      ``ρCm A3 [∫ x v̇33 + ∫ x cos α v̇32]``.
    * Eqs. (10), (17), (21): ``τ_f1 = 0``,
      ``τ_f2 = (m2 g L2c c2 + m3 g (L2 c2 + L3c s23)) ρ/ρm``, ``τ_f3 = m3 g L3c s23 ρ/ρm``, with
      ``ρm = 2700`` and ρ = ``density``.

    For pure yaw (``q̇2 = q̇3 = q̈2 = q̈3 = 0``) joint 1's drag and added mass equal :func:`hydro`'s
    for :func:`paper_leg`; the buoyancy equals it for every state.

    Parameters
    ----------
    q, qd, qdd : array_like
        Joint states, each of shape ``(3,)`` or ``(m, 3)``.
    cd, cm : float
        Drag and added-mass coefficients (one of each, as in the paper), ≥ 0.
    density : float
        Water density [kg/m³], > 0.
    gravity : float
        Gravitational acceleration [m/s²], ≥ 0.

    Returns
    -------
    dict
        ``drag``, ``added_mass``, ``buoyancy``, ``total``, each shaped like ``q`` [N·m].

    Raises
    ------
    ValueError
        On states of the wrong shape or non-finite values, negative coefficients,
        ``density <= 0`` or ``gravity < 0``.
    """
    shape, qs, qds, qdds = _states(q, qd, qdd, 3)
    cd = _number(cd, "cd", positive=False)
    cm = _number(cm, "cm", positive=False)
    rho = _number(density, "density", positive=True)
    g = _number(gravity, "gravity", positive=False)
    q2, q3 = qs[:, 1, None], qs[:, 2, None]  # the yaw angle q1 does not enter
    w1, w2, w3 = (qds[:, i, None] for i in range(3))
    a1, a2, a3 = (qdds[:, i, None] for i in range(3))
    s2, c2, s3, c3 = np.sin(q2), np.cos(q2), np.sin(q3), np.cos(q3)
    s23, c23 = np.sin(q2 + q3), np.cos(q2 + q3)
    L2, L3 = PAPER_L2, PAPER_L3
    A2, A3 = PAPER_D21 * PAPER_D22, PAPER_D31 * PAPER_D32
    m2, m3 = PAPER_MASSES[1], PAPER_MASSES[2]

    def vv(v: Array) -> Array:
        return v * np.abs(v)

    # Thigh (link 2), x in [0, L2]: no kinks.
    x, wx = _quadrature(L2, np.empty((len(qs), 0)))
    v21, dv21 = w1 * x * c2, a1 * x * c2 - w1 * w2 * x * s2
    v22, dv22 = w2 * x, a2 * x
    thigh_d1 = np.sum(x * c2 * vv(v21) * wx, axis=1)
    thigh_m1 = np.sum(x * c2 * dv21 * wx, axis=1)
    thigh_d2 = np.sum(x * vv(v22) * wx, axis=1)
    thigh_m2 = np.sum(x * dv22 * wx, axis=1)

    # Calf (link 3), x in [0, L3] from the knee: split where v31 = 0 and where r32 is least.
    with np.errstate(divide="ignore", over="ignore", invalid="ignore"):
        root = np.where(s23 != 0.0, -L2 * c2 / s23, np.inf)
    near, width = -L2 * s3, L2 * np.abs(c3)  # r32² = (x − near)² + width²
    grading = width * _PAPER_GRADING
    x, wx = _quadrature(L3, np.concatenate([root, near, near - grading, near + grading], axis=1))
    arm1 = L2 * c2 + x * s23
    v31, dv31 = w1 * arm1, a1 * arm1 + w1 * (-w2 * L2 * s2 + (w2 + w3) * x * c23)
    r32 = np.hypot(x + L2 * s3, L2 * c3)  # eq. 13's sqrt(L2² + x² + 2 L2 x s3), without cancellation
    v32, dv32 = w2 * r32, a2 * r32 + w2 * w3 * L2 * x * c3 / r32
    v33, dv33 = w3 * x, a3 * x
    cos_alpha = (x**2 + r32**2 - L2**2) / (2.0 * x * r32)
    calf_d1 = np.sum(arm1 * vv(v31) * wx, axis=1)
    calf_m1 = np.sum(arm1 * dv31 * wx, axis=1)
    calf_d2 = np.sum((r32 * vv(v32) + r32 * cos_alpha * vv(v33)) * wx, axis=1)
    calf_m2 = np.sum((r32 * dv32 + r32 * cos_alpha * dv33) * wx, axis=1)
    calf_d3 = np.sum((x * vv(v33) + x * cos_alpha * vv(v32)) * wx, axis=1)
    calf_m3 = np.sum((x * dv33 + x * cos_alpha * dv32) * wx, axis=1)

    half = 0.5 * rho * cd
    tau_d = np.stack(
        [
            half * (PAPER_D21 * thigh_d1 + PAPER_D31 * calf_d1),
            half * (PAPER_D22 * thigh_d2 + PAPER_D32 * calf_d2),
            half * PAPER_D32 * calf_d3,
        ],
        axis=1,
    )
    tau_m = np.stack(
        [
            rho * cm * (A2 * thigh_m1 + A3 * calf_m1),
            rho * cm * (A2 * thigh_m2 + A3 * calf_m2),
            rho * cm * A3 * calf_m3,
        ],
        axis=1,
    )
    ratio = rho / PAPER_LINK_DENSITY
    tau_f = np.concatenate(
        [
            np.zeros_like(c2),
            (m2 * g * PAPER_L2C * c2 + m3 * g * (L2 * c2 + PAPER_L3C * s23)) * ratio,
            m3 * g * PAPER_L3C * s23 * ratio,
        ],
        axis=1,
    )
    return {
        "drag": (-tau_d).reshape(shape),
        "added_mass": (-tau_m).reshape(shape),
        "buoyancy": tau_f.reshape(shape),
        "total": (tau_f - tau_d - tau_m).reshape(shape),
    }
