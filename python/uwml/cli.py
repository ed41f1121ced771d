"""The ``uwml`` command line."""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence

import numpy as np

from .leg import Leg
from .model import Water

__all__ = ["gait_like_motion", "main"]


def gait_like_motion(n_samples: int = 9, period: float = 2.0) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """A smooth, gait-like periodic motion of the paper's leg over one cycle (illustrative).

    Each joint follows ``q = mean + amplitude * sin(2π t / period + phase)``: the hip yaw swings
    the leg forward and back, the hip roll lifts it during the swing half, the knee folds and
    unfolds. Returns ``(t, q, qd, qdd)`` with exact derivatives.
    """
    mean = np.array([0.0, -0.25, 0.45])
    amplitude = np.array([0.35, 0.15, 0.25])
    phase = np.array([0.0, np.pi / 2, np.pi])
    omega = 2.0 * np.pi / period
    t = np.linspace(0.0, period, n_samples)
    angle = omega * t[:, None] + phase
    q = mean + amplitude * np.sin(angle)
    qd = amplitude * omega * np.cos(angle)
    qdd = -amplitude * omega**2 * np.sin(angle)
    return t, q, qd, qdd


def _demo(args: argparse.Namespace) -> int:
    leg = Leg.paper()
    water = Water(density=args.density, gravity=9.81)
    t, q, qd, qdd = gait_like_motion(args.samples, args.period)
    tau = leg.hydro(q, qd, qdd, cd=args.cd, cm=args.cm, water=water)
    print(f"uwml demo: the paper's leg (Table II) in water of {water.density:g} kg/m³, Cd = {args.cd:g}, Cm = {args.cm:g},")
    print(f"along a gait-like motion of period {args.period:g} s. Torques on each joint [N·m], environment on joint.")
    header = f"{'t [s]':>6} {'joint':>5} {'q [rad]':>8} {'qd [rad/s]':>10} {'drag':>9} {'added mass':>10} {'buoyancy':>9} {'total':>9}"
    print(header)
    print("-" * len(header))
    for i in range(len(t)):
        for j in range(leg.n_joints):
            print(
                f"{t[i]:6.2f} {j + 1:5d} {q[i, j]:8.3f} {qd[i, j]:10.3f} "
                f"{tau.drag[i, j]:9.3f} {tau.added_mass[i, j]:10.3f} {tau.buoyancy[i, j]:9.3f} {tau.total[i, j]:9.3f}"
            )
    rms = lambda x: np.sqrt(np.mean(x**2, axis=0))
    print()
    print("RMS over the cycle     " + "   ".join(f"joint {j + 1}" for j in range(leg.n_joints)))
    for name in ("drag", "added_mass", "buoyancy"):
        print(f"  {name:<20} " + "   ".join(f"{v:7.3f}" for v in rms(getattr(tau, name))))
    return 0


def _positive(text: str) -> float:
    value = float(text)
    if not np.isfinite(value) or value <= 0:
        raise argparse.ArgumentTypeError(f"must be a positive number, got {text}")
    return value


def _non_negative(text: str) -> float:
    value = float(text)
    if not np.isfinite(value) or value < 0:
        raise argparse.ArgumentTypeError(f"must be a non-negative number, got {text}")
    return value


def _count(text: str) -> int:
    value = int(text)
    if value < 2:
        raise argparse.ArgumentTypeError(f"must be an integer >= 2, got {text}")
    return value


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="uwml", description="Hydrodynamic joint torques of underwater legs and arms.")
    commands = parser.add_subparsers(dest="command", required=True)
    demo = commands.add_parser("demo", help="print the paper leg's torque components along a gait-like motion")
    demo.add_argument("--samples", type=_count, default=9, help="samples over one cycle (default 9)")
    demo.add_argument("--period", type=_positive, default=2.0, help="cycle period [s] (default 2)")
    demo.add_argument("--cd", type=_non_negative, default=2.2, help="drag coefficient (default 2.2, the paper's fit)")
    demo.add_argument("--cm", type=_non_negative, default=0.5, help="added-mass coefficient (default 0.5, the paper's fit)")
    demo.add_argument("--density", type=_positive, default=1000.0, help="water density [kg/m³] (default 1000)")
    demo.set_defaults(run=_demo)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    args = build_parser().parse_args(argv)
    return int(args.run(args))


if __name__ == "__main__":
    sys.exit(main())
