"""Tests of the whole-robot numpy reference's lumped model, Fossen's added mass and damping of a
body about a point ``P`` (docs/model.md section 12.1), on the reference alone.

Robots are built from :mod:`uwml.model`'s ``Joint``, ``Link`` and ``LumpedModel``, loaded from the
source tree without the compiled extension (:mod:`pure`). A brute force written here (poses by
quaternions along a trajectory in time, twists by complex-step derivatives, their rates by
finite differences, Jacobians by complex steps) checks the reference's virtual work; the other
tests check invariants: power, Galilean riding, terminal velocity, frame invariance, strip theory
and Fossen's Coriolis term.
"""

import math
from types import SimpleNamespace
from typing import Any

import numpy as np
import pytest
from pure import load
from reference_trees import (
    KEYS,
    RHO,
    assert_close,
    hydro,
    quat_matrix,
    quat_mul,
    random_quaternion,
    random_unit,
    ref,
)
from test_reference_robot_invariants import _poses

parts = load("model.parts")
LumpedModel = load("model.lumped").LumpedModel

SEEDS = range(6)


# --------------------------------------------------------------------------------------------
# Random robots with lumped bodies
# --------------------------------------------------------------------------------------------


def random_lumped(rng: np.random.Generator, *, added: bool = True, damping: bool = True, point: Any = "random") -> Any:
    """A random ``LumpedModel``: ``M_A = A Aᵀ``, ``D_L = B Bᵀ + K − Kᵀ``, ``d_i ≥ 0``."""
    a = rng.normal(size=(6, 6)) * rng.uniform(0.3, 2.0)
    b = rng.normal(size=(6, 6)) * rng.uniform(0.3, 2.0)
    k = rng.normal(size=(6, 6))
    return LumpedModel(
        point=tuple(rng.uniform(-0.4, 0.4, 3)) if point == "random" else point,
        added_mass=a @ a.T if added else np.zeros((6, 6)),
        linear_damping=b @ b.T + k - k.T if damping else np.zeros((6, 6)),
        quadratic_damping=rng.uniform(0.0, 5.0, 6) if damping else np.zeros(6),
    )


def random_segment(rng: np.random.Generator) -> Any:
    axis = random_unit(rng)
    start = tuple(rng.uniform(-0.3, 0.3, 3))
    length = float(rng.uniform(0.1, 0.8))
    if rng.random() < 0.5:
        return parts.Segment(start=start, axis=tuple(axis), length=length, section="circular", diameter=float(rng.uniform(0.02, 0.2)))
    n1 = np.cross(axis, random_unit(rng))
    n1 /= np.linalg.norm(n1)
    widths = rng.uniform(0.03, 0.3, 2)
    return parts.Segment(
        start=start,
        axis=tuple(axis),
        length=length,
        normals=(tuple(n1), tuple(np.cross(axis, n1))),
        widths=tuple(widths),
        area=float(widths.prod()),
    )


def random_link(rng: np.random.Generator, *, lumped: Any = None, segments: bool = False, massive: bool = False) -> Any:
    com = tuple(rng.uniform(-0.3, 0.3, 3))
    mass = float(rng.uniform(0.5, 10.0)) if massive else 0.0
    volume = mass / 2000.0
    cob = tuple(rng.uniform(-0.3, 0.3, 3))
    segs = tuple(random_segment(rng) for _ in range(int(rng.integers(0, 3)))) if segments else ()
    return parts.Link(mass=mass, com=com, volume=volume, cob=cob, segments=segs, lumped=lumped)


def random_robot(
    rng: np.random.Generator,
    *,
    added: bool = True,
    damping: bool = True,
    segments: bool = False,
    massive: bool = False,
    n: int | None = None,
) -> tuple[list, list, Any]:
    """A random tree (revolute and prismatic joints), every body but some links lumped."""
    n = int(rng.integers(1, 5)) if n is None else n
    joints, links = [], []
    for i in range(n):
        r = rng.random()
        parent = None if r < 0.5 else int(rng.integers(-1, i))
        kind = "prismatic" if rng.random() < 0.3 else "revolute"
        joints.append(parts.Joint(origin=tuple(rng.uniform(-0.5, 0.5, 3)), axis=tuple(random_unit(rng)), parent=parent, kind=kind))
        lumped = random_lumped(rng, added=added, damping=damping) if (i == 0 or rng.random() < 0.7) else None
        links.append(random_link(rng, lumped=lumped, segments=segments, massive=massive))
    base = random_link(rng, lumped=random_lumped(rng, added=added, damping=damping), segments=segments, massive=massive)
    return joints, links, base


def random_state(rng: np.random.Generator, m: int, n: int, *, still: bool = False) -> dict[str, np.ndarray]:
    return {
        "q": rng.uniform(-math.pi, math.pi, (m, n)),
        "qd": rng.uniform(-2.0, 2.0, (m, n)),
        "qdd": rng.uniform(-3.0, 3.0, (m, n)),
        "orientation": random_quaternion(rng, m),
        "velocity": rng.uniform(-1.0, 1.0, (m, 3)),
        "angular_velocity": rng.uniform(-1.0, 1.0, (m, 3)),
        "acceleration": rng.uniform(-2.0, 2.0, (m, 3)),
        "angular_acceleration": rng.uniform(-2.0, 2.0, (m, 3)),
        "current": np.zeros((m, 3)) if still else rng.uniform(-0.8, 0.8, (m, 3)),
        "current_acceleration": np.zeros((m, 3)) if still else rng.uniform(-1.0, 1.0, (m, 3)),
    }


def lumped_bodies(links: list, base: Any) -> list[tuple[int, Any]]:
    """(body index, lumped model) of every lumped body: 0 the base, i + 1 link i."""
    return [(b, body.lumped) for b, body in enumerate([base, *links]) if body is not None and body.lumped is not None]


def fossen(model: Any, nu: np.ndarray, nu_dot: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(damping, added-mass) wrenches at P in body components, from the formula of docs/model.md
    section 12.1 as written there."""
    m_a, d_l, d_q = np.array(model.added_mass), np.array(model.linear_damping), np.array(model.quadratic_damping)
    momentum = m_a @ nu
    v, w, p, h = nu[:3], nu[3:], momentum[:3], momentum[3:]
    coriolis = np.concatenate([np.cross(w, p), np.cross(v, p) + np.cross(w, h)])
    return -d_l @ nu - d_q * np.abs(nu) * nu, -m_a @ nu_dot - coriolis


# --------------------------------------------------------------------------------------------
# Brute force: a trajectory in time, quaternion poses, complex-step twists
# --------------------------------------------------------------------------------------------

EPS = 1e-30  # complex step
H = 1e-3  # finite-difference step in time (fourth order)


def _vee(m: np.ndarray) -> np.ndarray:
    return np.array([m[2, 1], m[0, 2], m[1, 0]])


def _trajectory(rng: np.random.Generator, n: int) -> SimpleNamespace:
    """``q(t) = q0 + q1 t + q2 t²``, base ``R(t) = R0 Q(φ1 t + φ2 t²)`` (``Q(φ)`` the rotation of
    the quaternion ``(1, φ/2)`` normalized), base origin ``x1 t + x2 t²``, current ``c0 + c1 t``."""
    return SimpleNamespace(
        q=rng.uniform(-math.pi, math.pi, (3, n)) * np.array([[1.0], [0.7], [0.8]]),
        quaternion=random_quaternion(rng),
        phi=rng.uniform(-1.0, 1.0, (2, 3)),
        x=rng.uniform(-1.0, 1.0, (2, 3)),
        c=rng.uniform(-0.8, 0.8, (2, 3)),
    )


def _pose_at(joints: list, traj: SimpleNamespace, t: complex) -> list[tuple[np.ndarray, np.ndarray]]:
    q = traj.q[0] + traj.q[1] * t + traj.q[2] * t * t
    phi = traj.phi[0] * t + traj.phi[1] * t * t
    quaternion = np.concatenate([[1.0 + 0j], phi / 2])
    quaternion = quaternion / np.sqrt(np.sum(quaternion * quaternion))  # analytic (no conjugate)
    rot = quat_matrix(traj.quaternion) @ quat_matrix(quaternion)
    return _poses(joints, q, rot, traj.x[0] * t + traj.x[1] * t * t)


def _twists(joints: list, traj: SimpleNamespace, t: float, local: list[tuple[int, np.ndarray]], *, current: bool = True) -> np.ndarray:
    """``ν_r = (Rᵀ(v_P − c), Rᵀω)`` (K, 6) of the points ``local`` = [(body, P in its frame)] at
    time ``t``, by complex-step derivatives in time."""
    poses = _pose_at(joints, traj, t + 1j * EPS)
    c = traj.c[0] + traj.c[1] * t if current else np.zeros(3)
    out = []
    for b, p in local:
        rot, pos = poses[b]
        r = rot.real
        velocity = (pos + rot @ p).imag / EPS
        out.append(np.concatenate([r.T @ (velocity - c), _vee(r.T @ (rot.imag / EPS))]))
    return np.array(out)


def _rates(joints: list, traj: SimpleNamespace, local: list, *, current: bool = True) -> tuple[np.ndarray, np.ndarray]:
    """The twists at ``t = 0`` and their component derivatives (fourth-order central differences)."""

    def at(t: float) -> np.ndarray:
        return _twists(joints, traj, t, local, current=current)

    rate = (-at(2 * H) + 8 * at(H) - 8 * at(-H) + at(-2 * H)) / (12 * H)
    return at(0.0), rate


def _reference_inputs(joints: list, traj: SimpleNamespace) -> dict[str, np.ndarray]:
    """The trajectory's state at ``t = 0`` as the reference takes it."""
    base, base_rate = _rates(joints, traj, [(0, np.zeros(3))], current=False)
    return {
        "q": traj.q[0],
        "qd": traj.q[1],
        "qdd": 2 * traj.q[2],
        "orientation": traj.quaternion,
        "velocity": base[0, :3],
        "angular_velocity": base[0, 3:],
        "acceleration": base_rate[0, :3],
        "angular_acceleration": base_rate[0, 3:],
        "current": traj.c[0],
        "current_acceleration": traj.c[1],
    }


def _jacobian(joints: list, traj: SimpleNamespace, local: list) -> np.ndarray:
    """``J`` (K, 6, 6 + N): twists at the points ``local`` per unit base twist (base components)
    and joint rate, at the trajectory's pose at ``t = 0``, by complex steps."""
    n = len(joints)
    columns = []
    for k in range(6 + n):
        e = np.eye(6 + n)[k]
        rot0 = quat_matrix(traj.quaternion)
        line = SimpleNamespace(
            q=np.stack([traj.q[0], e[6:], np.zeros(n)]),
            quaternion=traj.quaternion,
            phi=np.stack([e[3:6], np.zeros(3)]),
            x=np.stack([rot0 @ e[0:3], np.zeros(3)]),
            c=np.zeros((2, 3)),
        )
        columns.append(_twists(joints, line, 0.0, local))
    return np.stack(columns, axis=-1)


def _generalized(out: dict[str, np.ndarray], part: str) -> np.ndarray:
    return np.concatenate([out[f"base_{part}"], out[part]], axis=-1)


# --------------------------------------------------------------------------------------------
# Tests
# --------------------------------------------------------------------------------------------


@pytest.mark.parametrize("seed", SEEDS)
def test_generalized_forces_are_the_virtual_work_of_the_lumped_wrenches(seed):
    """Every part of the joint forces and base wrench is ``Σ_b J_bᵀ W_b``, the twists, their
    rates and ``J`` by the brute force; the added-mass matrix is ``Σ_b J_bᵀ M_A J_b``."""
    rng = np.random.default_rng(100 + seed)
    joints, links, base = random_robot(rng)
    lumped = lumped_bodies(links, base)
    local = [(b, np.array(model.point)) for b, model in lumped]
    traj = _trajectory(rng, len(joints))
    state = _reference_inputs(joints, traj)
    nu, nu_dot = _rates(joints, traj, local)
    jac = _jacobian(joints, traj, local)
    expected = {"drag": 0.0, "added_mass": 0.0}
    matrix = np.zeros((6 + len(joints),) * 2)
    for (_, model), j_b, v, a in zip(lumped, jac, nu, nu_dot, strict=True):
        drag, added = fossen(model, v, a)
        expected["drag"] = expected["drag"] + j_b.T @ drag
        expected["added_mass"] = expected["added_mass"] + j_b.T @ added
        matrix += j_b.T @ np.array(model.added_mass) @ j_b
    for form in ("morison", "kirchhoff"):
        out = hydro(joints, links, base, state, added_mass=form)
        for part in ("drag", "added_mass"):
            assert_close(_generalized(out, part), expected[part], 1e-8, f"{form} {part}")
    got = ref.robot_added_mass_matrix(joints, links, base, state["q"], orientation=state["orientation"])
    assert_close(got, matrix, 1e-12, "added-mass matrix")


@pytest.mark.parametrize("seed", SEEDS)
def test_added_mass_power_in_still_water(seed):
    """``W_am·ν + τ_am·q̇ = −Σ_b ν_rᵀ M_A ν̇_r``: Fossen's ``C_A`` does no work."""
    rng = np.random.default_rng(200 + seed)
    joints, links, base = random_robot(rng, damping=False)
    lumped = lumped_bodies(links, base)
    local = [(b, np.array(model.point)) for b, model in lumped]
    traj = _trajectory(rng, len(joints))
    traj.c[:] = 0.0
    state = _reference_inputs(joints, traj)
    nu, nu_dot = _rates(joints, traj, local)
    terms = [-(v @ np.array(model.added_mass) @ a) for (_, model), v, a in zip(lumped, nu, nu_dot, strict=True)]
    out = hydro(joints, links, base, state)
    velocity = np.concatenate([state["velocity"], state["angular_velocity"], state["qd"]])
    power = _generalized(out, "added_mass") @ velocity
    scale = sum(abs(t) for t in terms)
    assert abs(power - sum(terms)) <= 1e-8 * scale, (power, sum(terms))
    # Damping is off: no drag at all.
    assert np.all(out["drag"] == 0.0) and np.all(out["base_drag"] == 0.0)


@pytest.mark.parametrize("seed", SEEDS)
def test_riding_with_the_current_feels_no_damping_and_no_added_mass(seed):
    rng = np.random.default_rng(300 + seed)
    joints, links, base = random_robot(rng, segments=True)
    m, n = 6, len(joints)
    state = random_state(rng, m, n)
    rot = np.array([quat_matrix(qq) for qq in state["orientation"]])
    riding = state | {
        "qd": np.zeros((m, n)),
        "qdd": np.zeros((m, n)),
        "velocity": np.einsum("nba,nb->na", rot, state["current"]),
        "angular_velocity": np.zeros((m, 3)),
        "acceleration": np.zeros((m, 3)),
        "angular_acceleration": np.zeros((m, 3)),
        "current_acceleration": np.zeros((m, 3)),
    }
    for form in ("morison", "kirchhoff"):
        out = hydro(joints, links, base, riding, added_mass=form)
        for key in ("drag", "base_drag", "added_mass", "base_added_mass"):
            assert np.all(np.abs(out[key]) <= 1e-13), (form, key, out[key])
    # In still water the same motion is felt.
    out = hydro(joints, links, base, riding | {"current": np.zeros((m, 3))})
    assert np.all(np.linalg.norm(out["base_drag"][:, :3], axis=1) > 1e-3)


@pytest.mark.parametrize("seed", SEEDS)
def test_terminal_velocity_on_each_axis(seed):
    """A base-only robot with ``D_L = diag(d)`` and quadratic ``q`` moving at constant speed ``u``
    along one axis (``P`` at rest for the angular ones) feels ``−(d u + q |u| u)`` there: at
    ``u = (−d + √(d² + 4 q F)) / (2 q)`` it balances ``F``."""
    rng = np.random.default_rng(400 + seed)
    d, qd = rng.uniform(0.5, 20.0, 6), rng.uniform(0.5, 50.0, 6)
    point = rng.uniform(-0.5, 0.5, 3)
    base = parts.Link(
        mass=0.0, com=(0, 0, 0), volume=0.0, lumped=LumpedModel(point=tuple(point), linear_damping=np.diag(d), quadratic_damping=qd)
    )
    for axis in range(6):
        thrust = float(rng.uniform(1.0, 100.0))
        sign = rng.choice([-1.0, 1.0])
        u = (-d[axis] + math.sqrt(d[axis] ** 2 + 4 * qd[axis] * thrust)) / (2 * qd[axis])
        direction = np.eye(3)[axis % 3]
        omega = sign * u * direction if axis >= 3 else np.zeros(3)
        velocity = sign * u * direction if axis < 3 else -np.cross(omega, point)  # P at rest when turning
        out = ref.robot_hydro(
            [], [], base, [], [], [], orientation=random_quaternion(rng), velocity=velocity, angular_velocity=omega, gravity=0.0
        )
        wrench = out["base_drag"]
        if axis < 3:
            force = -sign * thrust * direction
            expected = np.concatenate([force, np.cross(point, force)])
        else:
            expected = np.concatenate([np.zeros(3), -sign * thrust * direction])
        assert_close(wrench, expected, 1e-12, f"axis {axis}", atol=1e-12)
        np.testing.assert_array_equal(out["base_added_mass"], np.zeros(6))


@pytest.mark.parametrize("seed", SEEDS)
def test_rotation_of_the_world_changes_nothing(seed):
    rng = np.random.default_rng(500 + seed)
    joints, links, base = random_robot(rng, segments=True, massive=True)
    m = 5
    state = random_state(rng, m, len(joints))
    turn = random_quaternion(rng)
    rot = quat_matrix(turn)
    turned = state | {
        "orientation": np.array([quat_mul(turn, qq) for qq in state["orientation"]]),
        "current": state["current"] @ rot.T,
        "current_acceleration": state["current_acceleration"] @ rot.T,
    }
    for form in ("morison", "kirchhoff"):
        before = hydro(joints, links, base, state, gravity=0.0, added_mass=form)
        after = hydro(joints, links, base, turned, gravity=0.0, added_mass=form)
        for key in KEYS:
            assert_close(after[key], before[key], 1e-12, f"{form} {key}", atol=1e-12)
    # The lumped models are felt: without them the forces differ.
    bare = [parts.Link(mass=k.mass, com=k.com, volume=k.volume, cob=k.cob, segments=k.segments) for k in [base, *links]]
    without = hydro(joints, bare[1:], bare[0], state, gravity=0.0)
    assert not np.allclose(without["base_drag"], before["base_drag"])
    assert not np.allclose(without["base_added_mass"], before["base_added_mass"])


def _strip_equivalent(rng: np.random.Generator, *, along_x: bool) -> tuple[Any, Any]:
    """A slender rectangular segment (``cd = 0``) and the lumped model strip theory gives it,
    about its midpoint: ``M_A = diag(0, m_y L, m_z L, 0, m_z L³/12, m_y L³/12)`` for a segment
    along x with normals y and z (in general the same in the frame ``(u, n_1, n_2)``)."""
    length, area = float(rng.uniform(0.2, 1.2)), float(rng.uniform(0.002, 0.05))
    cm = rng.uniform(0.3, 1.5, 2)
    start = rng.uniform(-0.4, 0.4, 3)
    if along_x:
        axis, n1, n2 = np.eye(3)
    else:
        axis = random_unit(rng)
        n1 = np.cross(axis, random_unit(rng))
        n1 /= np.linalg.norm(n1)
        n2 = np.cross(axis, n1)
    segment = parts.Segment(
        start=tuple(start),
        axis=tuple(axis),
        length=length,
        normals=(tuple(n1), tuple(n2)),
        widths=(0.1, 0.2),
        area=area,
        cd=(0.0, 0.0),
        cm=tuple(cm),
    )
    # The normals as the segment keeps them (made exactly orthonormal).
    axis, (n1, n2) = np.array(segment.axis), np.array(segment.normals)
    m_y, m_z = RHO * area * cm
    frame = np.stack([axis, n1, n2], axis=1)  # body from (u, n1, n2)
    block = np.zeros((6, 6))
    block[:3, :3], block[3:, 3:] = frame, frame
    local = np.diag([0.0, m_y * length, m_z * length, 0.0, m_z * length**3 / 12, m_y * length**3 / 12])
    lumped = LumpedModel(point=tuple(start + 0.5 * length * axis), added_mass=block @ local @ block.T)
    return segment, lumped


@pytest.mark.parametrize("seed", SEEDS)
@pytest.mark.parametrize("along_x", [True, False])
def test_strip_theory_equivalent_gives_the_same_added_mass(seed, along_x):
    """A link (or the base) with the lumped model strip theory gives a slender segment has the
    segment's added-mass matrix; and, since Kirchhoff's strips are Fossen's equations slice by
    slice, the same added-mass forces as Kirchhoff's form of the segment at any motion."""
    rng = np.random.default_rng(600 + seed + (0 if along_x else 50))
    joints, links, base = random_robot(rng, added=False, damping=False, segments=True)
    segment, lumped = _strip_equivalent(rng, along_x=along_x)
    bodies = [base, *links]
    carrier = int(rng.integers(0, len(bodies)))
    owner = bodies[carrier]

    def with_(**kwargs: Any) -> list:
        body = parts.Link(mass=owner.mass, com=owner.com, volume=owner.volume, cob=owner.cob, **kwargs)
        return [body if b == carrier else bd for b, bd in enumerate(bodies)]

    strips = with_(segments=(*owner.segments, segment), lumped=None)
    lump = with_(segments=owner.segments, lumped=lumped)
    m = 4
    state = random_state(rng, m, len(joints))
    by_strips = ref.robot_added_mass_matrix(joints, strips[1:], strips[0], state["q"], orientation=state["orientation"])
    by_lump = ref.robot_added_mass_matrix(joints, lump[1:], lump[0], state["q"], orientation=state["orientation"])
    assert_close(by_lump, by_strips, 1e-10, "added-mass matrix")
    # The other bodies' segments in Kirchhoff's form too (the lumped model is the same in both).
    kirchhoff = hydro(joints, strips[1:], strips[0], state, added_mass="kirchhoff")
    fossen_ = hydro(joints, lump[1:], lump[0], state, added_mass="kirchhoff")
    for key in ("added_mass", "base_added_mass"):
        assert_close(fossen_[key], kirchhoff[key], 1e-10, key)
    # Morison's strips lack the Coriolis terms: they differ while anything turns.
    morison, fossen_ = hydro(joints, strips[1:], strips[0], state), hydro(joints, lump[1:], lump[0], state)
    assert not np.allclose(morison["base_added_mass"], fossen_["base_added_mass"])


@pytest.mark.parametrize("seed", SEEDS)
def test_coriolis_term_of_a_turning_base(seed):
    """A base at identity orientation with ``M_A`` only, at ``(v, ω)`` with no acceleration:
    ``ν̇_r = 0`` and the base feels at ``P`` ``(−ω × p, −(v_P × p + ω × h))``, ``(p, h) = M_A ν``."""
    rng = np.random.default_rng(700 + seed)
    lumped = random_lumped(rng, damping=False)
    point = np.array(lumped.point)
    com = rng.uniform(-0.3, 0.3, 3)
    base = parts.Link(mass=0.0, com=tuple(com), volume=0.0, lumped=lumped)
    v, w = rng.uniform(-1.0, 1.0, 3), rng.uniform(-1.0, 1.0, 3)
    nu = np.concatenate([v + np.cross(w, point), w])
    momentum = np.array(lumped.added_mass) @ nu
    p, h = momentum[:3], momentum[3:]
    force = -np.cross(w, p)
    moment = -(np.cross(nu[:3], p) + np.cross(w, h))
    for form in ("morison", "kirchhoff"):
        out = ref.robot_hydro([], [], base, [], [], [], velocity=v, angular_velocity=w, added_mass=form)
        assert_close(out["base_added_mass"], np.concatenate([force, moment + np.cross(point, force)]), 1e-13, form, atol=1e-15)
        np.testing.assert_array_equal(out["base_drag"], np.zeros(6))
    # Each body's total wrench, about its centre of mass (world = base here).
    wrenches = ref.robot_link_wrenches([], [], base, [], [], [], velocity=v, angular_velocity=w)
    assert_close(wrenches[0], np.concatenate([force, moment + np.cross(point - com, force)]), 1e-13, "link wrench", atol=1e-15)


def test_descriptions_and_defaults():
    rng = np.random.default_rng(800)
    joints, links, base = random_robot(rng, n=2)
    state = random_state(rng, 3, 2)
    out = hydro(joints, links, base, state)
    # A uwml.Link puts the lumped model's missing point at the centre of buoyancy; the reference
    # does the same for a duck-typed model without one.
    cob = (0.1, -0.2, 0.05)
    model = random_lumped(rng, point=None)
    link = parts.Link(mass=1.0, com=(0, 0, 0), volume=0.0, cob=cob, lumped=model)
    assert link.lumped.point == cob
    duck = SimpleNamespace(mass=1.0, com=(0, 0, 0), volume=0.0, cob=cob, segments=(), lumped=model)
    a, b = hydro(joints, [links[0], link], base, state), hydro(joints, [links[0], duck], base, state)
    for key in KEYS:
        np.testing.assert_array_equal(a[key], b[key])
    # A body without the attribute is a body without a lumped model.
    plain = SimpleNamespace(mass=1.0, com=(0, 0, 0), volume=0.0, cob=cob, segments=())
    c = hydro(joints, [links[0], plain], base, state)
    d = hydro(joints, [links[0], parts.Link(mass=1.0, com=(0, 0, 0), volume=0.0, cob=cob)], base, state)
    for key in KEYS:
        np.testing.assert_array_equal(c[key], d[key])
    assert not np.allclose(a["base_added_mass"], c["base_added_mass"])
    assert out["drag"].shape == (3, 2)
    # Malformed duck-typed models are refused.
    for bad in (
        SimpleNamespace(point=None, added_mass=np.eye(5), linear_damping=np.zeros((6, 6)), quadratic_damping=np.zeros(6)),
        SimpleNamespace(point=(0, 0), added_mass=np.eye(6), linear_damping=np.zeros((6, 6)), quadratic_damping=np.zeros(6)),
        SimpleNamespace(point=None, added_mass=np.triu(np.ones((6, 6))), linear_damping=np.zeros((6, 6)), quadratic_damping=np.zeros(6)),
        SimpleNamespace(point=None, added_mass=np.eye(6), linear_damping=np.full((6, 6), np.nan), quadratic_damping=np.zeros(6)),
        SimpleNamespace(point=None, added_mass=np.eye(6), linear_damping=np.zeros((6, 6)), quadratic_damping=-np.ones(6)),
    ):
        body = SimpleNamespace(mass=1.0, com=(0, 0, 0), volume=0.0, cob=None, segments=(), lumped=bad)
        with pytest.raises(ValueError, match="lumped"):
            hydro(joints, [links[0], body], base, state)
