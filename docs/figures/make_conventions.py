"""The diagrams of docs/conventions.md: frames, the vehicle's pose and twist, and the signs of
uwml's forces, drawn as side views (x to the right, z up: y points into the page).

Run: ``python docs/figures/make_conventions.py [FOLDER]`` (writes ``conventions_frames.svg`` and
``conventions_signs.svg`` into FOLDER, by default this script's folder). Only matplotlib is
needed; the output is the same on every run (no date, fixed ids).
"""

from __future__ import annotations

import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
from matplotlib.patches import Arc, Circle, FancyArrowPatch, Polygon

#: The files this script writes, by name.
FIGURES = ("conventions_frames.svg", "conventions_signs.svg")

WORLD, BASE, LINK, SEGMENT, FORCE, MOTION = "#222222", "#1f4e9c", "#2e8b57", "#b8860b", "#c0392b", "#7b3fa0"


def _rotation(angle: float) -> np.ndarray:
    """The side view's image of a rotation by ``angle`` about +y (into the page): positive turns
    z towards x, clockwise as seen."""
    c, s = np.cos(angle), np.sin(angle)
    return np.array([[c, s], [-s, c]])


def _arrow(ax: plt.Axes, start: np.ndarray, vector: np.ndarray, color: str, label: str = "", where: float = 1.12, **text: object) -> None:
    start = np.asarray(start, dtype=float)
    end = start + np.asarray(vector, dtype=float)
    ax.add_patch(FancyArrowPatch(start, end, arrowstyle="-|>", mutation_scale=12, lw=1.6, color=color, shrinkA=0, shrinkB=0))
    if label:
        spot = start + where * np.asarray(vector, dtype=float)
        ax.text(*spot, label, **{"color": color, "ha": "center", "va": "center", **text})


def _into_page(ax: plt.Axes, at: np.ndarray, color: str, label: str = "", offset: tuple[float, float] = (0.09, -0.09)) -> None:
    """An axis pointing into the page (a circle with a cross), like y in every view here."""
    x, y = at
    r = 0.045
    ax.add_patch(Circle((x, y), r, fill=False, color=color, lw=1.3))
    d = r * 0.7
    ax.plot([x - d, x + d], [y - d, y + d], color=color, lw=1.1)
    ax.plot([x - d, x + d], [y + d, y - d], color=color, lw=1.1)
    if label:
        ax.text(x + offset[0], y + offset[1], label, color=color, ha="center", va="center")


def _frame(ax: plt.Axes, origin: np.ndarray, rotation: np.ndarray, name: str, color: str, size: float = 0.45) -> None:
    """A frame's x and z axes in the page, and its y into it."""
    origin = np.asarray(origin, dtype=float)
    _arrow(ax, origin, size * rotation[:, 0], color, f"$x_{{{name}}}$")
    _arrow(ax, origin, size * rotation[:, 1], color, f"$z_{{{name}}}$")
    _into_page(ax, origin, color, f"$y_{{{name}}}$")


def _turn(ax: plt.Axes, center: np.ndarray, radius: float, start: float, end: float, color: str, label: str = "", **text: object) -> None:
    """An arc from angle ``start`` to ``end`` [degrees, counter-clockwise from the page's right]
    with an arrowhead at ``end``."""
    ax.add_patch(Arc(center, 2 * radius, 2 * radius, theta1=min(start, end), theta2=max(start, end), color=color, lw=1.6))
    tip = np.radians(end)
    step = np.radians(8.0) * (1 if end > start else -1)
    a = np.asarray(center) + radius * np.array([np.cos(tip - step), np.sin(tip - step)])
    b = np.asarray(center) + radius * np.array([np.cos(tip), np.sin(tip)])
    ax.add_patch(FancyArrowPatch(a, b, arrowstyle="-|>", mutation_scale=12, color=color, lw=1.6, shrinkA=0, shrinkB=0))
    if label:
        middle = np.radians(0.5 * (start + end))
        spot = np.asarray(center) + 1.35 * radius * np.array([np.cos(middle), np.sin(middle)])
        ax.text(*spot, label, **{"color": color, "ha": "center", "va": "center", **text})


def _hull(ax: plt.Axes, center: np.ndarray, rotation: np.ndarray, size: tuple[float, float], color: str) -> None:
    w, h = size
    corners = np.array([[-w, -h], [w, -h], [w, h], [-w, h]]) / 2.0
    ax.add_patch(Polygon(np.asarray(center) + corners @ rotation.T, closed=True, facecolor=color, alpha=0.12, edgecolor=color, lw=1.2))


def _axes(fig: plt.Figure, where: list[float], title: str, limits: tuple[float, float, float, float]) -> plt.Axes:
    ax = fig.add_axes(where)
    ax.set_xlim(limits[0], limits[1])
    ax.set_ylim(limits[2], limits[3])
    ax.set_aspect("equal")
    ax.axis("off")
    ax.set_title(title, fontsize=11, loc="left")
    return ax


def frames(path: Path) -> None:
    """Left: the world, the vehicle's pose and its body twist. Right: an arm at q = 0, its link
    frames parallel to the base frame, its joint axes and a segment's geometry."""
    fig = plt.figure(figsize=(11.0, 5.2))
    ax = _axes(fig, [0.01, 0.02, 0.47, 0.9], "(a) World, base pose and body twist", (-0.3, 3.6, -0.35, 3.1))
    _frame(ax, (0.0, 0.0), np.eye(2), "w", WORLD)
    ax.text(0.0, -0.27, "world: z up, against gravity", color=WORLD, ha="left", va="center", fontsize=9)
    _arrow(ax, (0.25, 1.7), (0.0, -0.5), WORLD, "$g$", where=1.2)
    pitch = 0.25
    turned = _rotation(pitch)
    origin = np.array([2.0, 1.35])
    _hull(ax, origin, turned, (1.6, 0.55), BASE)
    _arrow(ax, (0.0, 0.0), origin, WORLD, "", where=0.5)
    ax.text(0.72, 0.92, "position $(x, y, z)$\nof the base origin,\nworld axes", color=WORLD, ha="center", va="center", fontsize=9)
    _frame(ax, origin, turned, "b", BASE, size=0.55)
    _arrow(ax, origin + 0.62 * turned[:, 0], 0.45 * turned[:, 0], MOTION, "$u$", where=1.25)
    _arrow(ax, origin + 0.62 * turned[:, 1], 0.35 * turned[:, 1], MOTION, "$w$", where=1.3)
    _turn(ax, origin, 0.33, 200, 120, MOTION, "$q$")  # about +y: clockwise as seen
    ax.text(
        1.75,
        2.85,
        "orientation: world from base, quaternion $(w, x, y, z)$, scalar first\n"
        r"twist $\nu = (u, v, w, p, q, r)$ in base axes (Fossen's $\nu$)"
        "\npitch here is positive: about $+y$, nose down",
        color=BASE,
        ha="center",
        va="center",
        fontsize=9,
    )
    _arrow(ax, (2.55, 0.2), (0.7, 0.0), FORCE)
    ax.text(2.9, 0.32, "current $c$ (world axes)", color=FORCE, ha="center", va="bottom", fontsize=9)

    ax = _axes(fig, [0.5, 0.02, 0.49, 0.9], "(b) An arm at q = 0: link frames parallel to the base frame", (-0.75, 3.4, -1.85, 1.3))
    _hull(ax, (0.1, 0.55), np.eye(2), (1.5, 0.55), BASE)
    _frame(ax, (0.1, 0.55), np.eye(2), "b", BASE, size=0.4)
    joint0 = np.array([0.7, 0.275])
    joint1 = joint0 + np.array([1.2, 0.0])
    ax.plot(*np.stack([joint0, joint1]).T, color=LINK, lw=6, alpha=0.35, solid_capstyle="round")
    ax.plot(*np.stack([joint1, joint1 + np.array([0.0, -1.2])]).T, color=LINK, lw=6, alpha=0.35, solid_capstyle="round")
    _frame(ax, joint0, np.eye(2), "0", LINK, size=0.36)
    _turn(ax, joint0, 0.22, 250, 160, LINK, "$+q_0$", fontsize=9)
    ax.text(
        joint0[0] - 0.2,
        joint0[1] - 0.62,
        "joint 0: axis $+y$ (into the page);\nlink $i$'s frame: origin at joint $i$",
        color=LINK,
        ha="center",
        va="center",
        fontsize=8,
    )
    _frame(ax, joint1, np.eye(2), "1", LINK, size=0.36)
    _arrow(ax, joint1, (0.42, 0.42), MOTION, "joint 1 axis", where=1.45, fontsize=8)
    ax.text(joint1[0] + 0.75, joint1[1] - 0.12, "a unit vector in\nits parent's frame", color=MOTION, ha="left", va="center", fontsize=8)
    start = joint1 + np.array([0.0, -0.25])
    _arrow(ax, start, (0.0, -0.95), SEGMENT, "segment axis $u$", where=1.12, fontsize=9)
    ax.plot(*start, "o", color=SEGMENT)
    ax.text(start[0] - 0.12, start[1], "start", color=SEGMENT, ha="right", va="center", fontsize=9)
    slice_at = start + np.array([0.0, -0.55])
    _arrow(ax, slice_at, (0.4, 0.0), SEGMENT, "$n_0$", where=1.2)
    _into_page(ax, slice_at, SEGMENT, "$n_1$", offset=(-0.13, -0.02))
    ax.text(
        0.55,
        -1.25,
        "slice at $s$: start $+ s\\,u$, $0 \\leq s \\leq$ length\n"
        "$n_0, n_1$: unit, $\\perp u$ and each other;\n"
        "widths[k] faces flow along $n_k$;\ncd[k], cm[k] act along $n_k$",
        color=SEGMENT,
        ha="center",
        va="center",
        fontsize=9,
    )
    _write(fig, path)


def signs(path: Path) -> None:
    """Left: a joint's torque and what makes it, with buoyancy and weight apart. Right: the
    wrench on the base and a thruster's."""
    fig = plt.figure(figsize=(11.0, 4.8))
    ax = _axes(fig, [0.01, 0.02, 0.48, 0.88], "(a) A joint: the environment's torque, positive along $+q$", (-0.6, 3.2, -2.0, 1.2))
    joint = np.array([0.0, 0.0])
    tip = np.array([2.4, -0.8])
    ax.plot(*np.stack([joint, tip]).T, color=LINK, lw=8, alpha=0.35, solid_capstyle="round")
    _into_page(ax, joint, LINK, "axis $+y$", offset=(0.0, 0.14))
    _turn(ax, joint, 0.45, 150, 70, MOTION, r"$\dot q > 0$")
    _turn(ax, joint, 0.7, 30, 105, FORCE, r"$\tau_{drag} < 0$")
    middle = joint + 0.35 * (tip - joint)
    direction = (tip - joint) / np.linalg.norm(tip - joint)
    normal = np.array([direction[1], -direction[0]])  # the way the link moves for q̇ > 0
    _arrow(ax, middle + 0.08 * normal, 0.45 * normal, MOTION, "velocity", where=1.3, fontsize=9)
    _arrow(ax, middle - 0.08 * normal, -0.45 * normal, FORCE, "drag", where=1.35, fontsize=9)
    cob = joint + 0.9 * (tip - joint) + np.array([0.0, 0.06])
    com = joint + 0.62 * (tip - joint) - np.array([0.0, 0.06])
    _arrow(ax, cob, (0.0, 0.55), BASE, r"buoyancy $\rho V g$, at the COB", where=1.2, fontsize=9)
    _arrow(ax, com, (0.0, -0.5), WORLD, "gravity $m g$, at the COM\n(apart: not in total)", where=1.55, fontsize=9)
    ax.text(
        1.3,
        -1.75,
        r"total $= $ drag $+$ added mass $+$ buoyancy: the water's on the joint;"
        "\n"
        r"the motor supplies $-$total on top of its torque on land",
        color=FORCE,
        ha="center",
        va="center",
        fontsize=9,
    )

    ax = _axes(fig, [0.52, 0.02, 0.47, 0.88], "(b) The base wrench: about the base origin, in base axes", (-1.6, 2.1, -1.4, 1.4))
    turned = _rotation(0.18)
    _hull(ax, (0.0, 0.0), turned, (2.2, 0.75), BASE)
    _frame(ax, (0.0, 0.0), turned, "b", BASE, size=0.5)
    _arrow(ax, (0.0, 0.0), 0.9 * turned @ np.array([-0.8, 0.6]), FORCE, "$F$", where=1.12)
    _turn(ax, (0.0, 0.0), 0.32, 300, 210, FORCE, "$M_y > 0$", fontsize=9)  # about +y: clockwise as seen
    thruster = turned @ np.array([-0.95, -0.2])
    _arrow(ax, thruster, 0.55 * turned @ np.array([1.0, 0.0]), MOTION, "", where=1.2)
    ax.plot(*thruster, "s", color=MOTION)
    ax.text(
        thruster[0] - 0.05,
        thruster[1] - 0.3,
        "thruster at $r$, thrust $T d$\n($T > 0$ along $d$)",
        color=MOTION,
        ha="center",
        va="center",
        fontsize=8,
    )
    ax.text(
        0.25,
        -1.15,
        r"$W = (F_x, F_y, F_z, M_x, M_y, M_z)$ of all the water does to the robot;"
        "\n"
        r"a thruster's: $(T d,\ T\, r \times d)$, in $W = B\,T$",
        color=FORCE,
        ha="center",
        va="center",
        fontsize=9,
    )
    _write(fig, path)


def _write(fig: plt.Figure, path: Path) -> None:
    fig.savefig(path, metadata={"Date": None, "Creator": None})
    plt.close(fig)


def main(folder: Path) -> list[Path]:
    """Writes the figures into ``folder``; returns their paths."""
    plt.rcParams.update({"svg.hashsalt": "uwml-conventions", "svg.fonttype": "none", "font.size": 10, "font.family": "DejaVu Sans"})
    folder.mkdir(parents=True, exist_ok=True)
    paths = [folder / name for name in FIGURES]
    frames(paths[0])
    signs(paths[1])
    return paths


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent)
