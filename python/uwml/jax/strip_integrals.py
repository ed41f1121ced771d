"""The exact strip integrals over one straight segment (docs/model.md sections 3 and 10), written
for JAX without branches on the data: every piece is computed for every input and the right one
selected with ``jnp.where``, the core's ``select`` (``crates/uwml-core/src/strip.rs``, the same
schemes, so the two agree to rounding).

A division or square root in a piece that is not selected is given a safe input (the "double
where"), so that it is finite and its derivative too: a NaN in a discarded branch would still
reach the gradient through ``where``'s derivative. ``|x|`` is taken as ``x · sign(x)``, whose
derivative at 0 is ``sign(0) = 0`` (the convention of the core's dual numbers).
"""

from __future__ import annotations

import jax
import jax.numpy as jnp
import numpy as np

__all__ = ["added_mass_moments", "circular_speed_moments", "drag_moments", "magnitude", "safe_sqrt"]

Array = jax.Array

#: The 2-point Gauss-Legendre nodes on [0, 1], ``(1 ∓ 1/√3)/2``.
_GAUSS_2 = (0.2113248654051871177454256097490212721762, 0.7886751345948128822545743902509787278238)
#: The 8-point Gauss-Legendre rule on [−1, 1] (nodes ±x, weights), the core's ``GAUSS_LEGENDRE_8``.
_X8, _W8 = np.polynomial.legendre.leggauss(8)
#: The Bernstein ellipse's semi-axes (ρ = 8) in half-lengths, the core's ``ELLIPSE_SEMI_AXES``.
_ELLIPSE = (4.0625, 3.9375)


def magnitude(x: Array) -> Array:
    """``|x|`` with derivative ``sign(x)``, 0 at 0."""
    return x * jnp.sign(x)


def safe_sqrt(x: Array) -> Array:
    """``sqrt(x)`` for ``x ≥ 0``, with derivative 0 (not infinity) at 0."""
    positive = x > 0
    return jnp.where(positive, jnp.sqrt(jnp.where(positive, x, 1)), 0)


def _dot(a: Array, b: Array) -> Array:
    return jnp.sum(a * b, axis=-1)


def _gauss_legendre_2(v0: Array, v1: Array, start: Array, width: Array) -> tuple[Array, Array]:
    """``(∫ h|h|, ∫ s h|h|)`` over ``[start, start + width]``, ``h = v0 + v1 s``: exact where h
    keeps its sign."""
    s1, s2 = start + width * _GAUSS_2[0], start + width * _GAUSS_2[1]
    h1, h2 = v0 + v1 * s1, v0 + v1 * s2
    f1, f2 = h1 * magnitude(h1), h2 * magnitude(h2)
    half = width * 0.5
    return half * (f1 + f2), half * (s1 * f1 + s2 * f2)


def drag_moments(v0: Array, v1: Array, length: Array) -> tuple[Array, Array]:
    """``(∫₀ᴸ h|h| ds, ∫₀ᴸ s h|h| ds)`` for ``h(s) = v0 + v1 s``, exactly: 2-point Gauss-Legendre
    on both sides of the sign change ``s* = L h(0)/(h(0) − h(L))`` (the second side empty where
    there is none). The root's denominator is the larger of the two magnitudes where the sign
    changes, and 1 elsewhere (double where)."""
    end = v0 + v1 * length
    changes = v0 * end < 0
    root = jnp.where(changes, length * (v0 / jnp.where(changes, v0 - end, 1)), length)
    a0, a1 = _gauss_legendre_2(v0, v1, jnp.zeros_like(root), root)
    b0, b1 = _gauss_legendre_2(v0, v1, root, length - root)
    return a0 + b0, a1 + b1


def added_mass_moments(a0: Array, a1: Array, length: Array) -> tuple[Array, Array]:
    """``(∫₀ᴸ (a0 + a1 s) ds, ∫₀ᴸ s (a0 + a1 s) ds)`` in closed form."""
    l2 = length * length * 0.5
    l3 = length * length * length / 3.0
    return a0 * length + a1 * l2, a0 * l2 + a1 * l3


def _quadrature(middle: Array, r: Array, half: Array) -> Array:
    """The three moments by 8-point Gauss-Legendre in ``t = s − L/2``: ``(..., 3)``."""
    t = half[..., None] * jnp.asarray(_X8, dtype=half.dtype)  # (..., 8)
    weight = half[..., None] * jnp.asarray(_W8, dtype=half.dtype)
    velocity = middle[..., None, :] + t[..., None] * r[..., None, :]
    f = weight * safe_sqrt(_dot(velocity, velocity))
    s = half[..., None] + t
    return jnp.stack([jnp.sum(f, axis=-1), jnp.sum(s * f, axis=-1), jnp.sum(s * s * f, axis=-1)], axis=-1)


def _closed_form(middle: Array, r: Array, length: Array, half: Array) -> Array:
    """The three moments by the closed forms about the speed's minimum (``r ≠ 0``): ``(..., 3)``."""
    a = _dot(r, r)
    b = _dot(middle, r)
    cross = jnp.cross(middle, r)
    c2 = _dot(cross, cross) / (a * a)  # the squared distance of the minimum from zero, in s
    sigma = half - b / a
    tiny = half * float(np.finfo(half.dtype).eps) ** 2
    kept = c2 > tiny * tiny  # below, c² asinh(τ/c) is under rounding: dropped
    c2_kept = jnp.where(kept, c2, 0)

    def end(tau: Array) -> tuple[Array, Array, Array, Array]:
        r2 = tau * tau + c2
        root = safe_sqrt(r2)
        cube = r2 * root
        ahead = tau >= 0
        # τ + R, written c²/(R − τ) for τ < 0 where the sum would cancel.
        p = jnp.where(ahead, tau + root, c2 / jnp.where(ahead, 1, root - tau))
        return 0.5 * tau * root, cube / 3.0, tau * cube, p

    lo0, lo1, lo_cube, lo_p = end(-sigma)
    hi0, hi1, hi_cube, hi_p = end(length - sigma)
    log_ratio = jnp.log(jnp.where(kept, hi_p / jnp.where(kept, lo_p, 1), 1))
    j0 = hi0 - lo0 + 0.5 * c2_kept * log_ratio
    j1 = hi1 - lo1
    j2 = 0.25 * (hi_cube - lo_cube - c2 * j0)
    sqrt_a = jnp.sqrt(a)
    return jnp.stack([sqrt_a * j0, sqrt_a * (j1 + sigma * j0), sqrt_a * (j2 + sigma * (j1 + j1) + sigma * sigma * j0)], axis=-1)


def circular_speed_moments(p: Array, r: Array, length: Array) -> Array:
    """``(∫₀ᴸ |p + s r| ds, ∫₀ᴸ s |p + s r| ds, ∫₀ᴸ s² |p + s r| ds)`` for vectors ``p``, ``r``
    ``(..., 3)`` and lengths ``(...)``: ``(..., 3)``, the moments of a circular segment's normal
    speed (docs/model.md section 10, "The circular strip integral").

    Both of the core's methods, the one chosen as it chooses: 8-point Gauss-Legendre where the
    integrand's branch points lie outside the Bernstein ellipse ``E_8`` of the segment (``r = 0``
    included), the closed forms about the speed's minimum elsewhere. Each is evaluated on inputs
    safe for it where it is not chosen (a constant unit speed; a unit speed turning by a right
    angle), so that neither gives a NaN to the gradient.
    """
    half = length * 0.5
    middle = p + r * half[..., None]
    a = _dot(r, r)
    b = _dot(middle, r)
    cross = jnp.cross(middle, r)
    outside = b * b / (_ELLIPSE[0] * _ELLIPSE[0]) + _dot(cross, cross) / (_ELLIPSE[1] * _ELLIPSE[1])
    gauss = (outside >= a * a * half * half)[..., None]
    unit_x = jnp.zeros_like(middle).at[..., 0].set(1)
    unit_y = jnp.zeros_like(middle).at[..., 1].set(1)
    quadrature = _quadrature(jnp.where(gauss, middle, unit_x), jnp.where(gauss, r, 0), half)
    closed = _closed_form(jnp.where(gauss, unit_x, middle), jnp.where(gauss, unit_y, r), length, half)
    return jnp.where(gauss, quadrature, closed)
