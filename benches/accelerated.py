"""Throughput of uwml on JAX, one run per device (issue 34, point 5): states/s of the paper's leg
and of the 7-joint arm on a moving ROV in a current (``uwml.examples.arm_on_rov``), in
float32 and float64, under ``jit`` and ``vmap``; the compile time of each; and, where
``uwml.sim.mjx`` is there, steps/s of the BlueROV2 example with its arm at several batch sizes,
bare MJX against the full uwml step.

    python benches/accelerated.py [--sizes 1024,8192,65536] [--states 1e6] [--repeats 5] [--mjx]

Prints one table per device JAX sees first (``jax.devices()[0]``). On a CPU the figures only say
that it runs: the CPU path (``uwml.Robot.hydro``) is the faster one there (docs/batched.md).
The accelerator check (``benches/accelerated_check.sh``) runs this on a GPU within 8 minutes.
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from collections.abc import Callable
from typing import Any

import numpy as np


def timed(call: Callable[[], Any], repeats: int) -> tuple[float, float]:
    """(first call's seconds: compile and run; best of ``repeats`` later calls), each call
    waited on (``block_until_ready``)."""
    import jax

    start = time.perf_counter()
    jax.block_until_ready(call())
    first = time.perf_counter() - start
    best = np.inf
    for _ in range(repeats):
        start = time.perf_counter()
        jax.block_until_ready(call())
        best = min(best, time.perf_counter() - start)
    return first, best


def evaluations(states: int, repeats: int) -> list[tuple[str, str, float, float]]:
    """(robot, dtype, compile seconds, states per second) of ``uwml.jax.hydro`` under jit
    and vmap, for the paper's leg and the arm on a moving ROV in a current."""
    import jax
    import uwml
    import uwml.jax
    from uwml.examples import arm_on_rov

    rng = np.random.default_rng(0)
    arm_conditions = uwml.Conditions(
        base_motion=uwml.BaseMotion(velocity=(0.5, 0.0, 0.1), angular_velocity=(0.0, 0.05, 0.02)), current=(0.2, 0.0, 0.0)
    )
    robots = {"paper leg": (uwml.paper_leg(), uwml.Conditions()), "7-joint arm on a moving ROV": (arm_on_rov(), arm_conditions)}
    rows = []
    for name, (robot, conditions) in robots.items():
        model, motion = uwml.jax.compile_robot(robot, conditions), uwml.jax.motion(conditions)
        n = robot.n_joints
        for dtype in (np.float32, np.float64):
            if dtype == np.float64 and not jax.config.jax_enable_x64:
                continue
            q, qd, qdd = (rng.uniform(-1.0, 1.0, (states, n)).astype(dtype) for _ in range(3))
            q, qd, qdd = (jax.device_put(x) for x in (q, qd, qdd))
            batched = jax.jit(jax.vmap(uwml.jax.hydro, in_axes=(None, 0, 0, 0, None)))
            inputs = (model, q, qd, qdd, motion)
            first, best = timed(lambda b=batched, a=inputs: b(*a).total, repeats)  # type: ignore[misc]
            rows.append((name, np.dtype(dtype).name, first - best, states / best))
    return rows


def mjx_steps(sizes: list[int], repeats: int) -> list[tuple[str, int, float, float]] | None:
    """(what, environments, compile seconds, steps per second) of the BlueROV2 example with its
    arm: bare MJX and the full uwml step (``uwml.sim.mjx``), if it is there."""
    try:
        from uwml.sim import mjx as uwml_mjx
    except ImportError:
        return None
    runner = getattr(uwml_mjx, "benchmark_steps", None)
    if runner is None:
        return None
    return list(runner(sizes, repeats))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--states", type=float, default=1e6, help="states per evaluation batch (default 1e6)")
    parser.add_argument("--sizes", default="1024,8192,65536", help="environments of the MJX batches")
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--mjx", action="store_true", help="also the MJX steps (uwml.sim.mjx)")
    parser.add_argument("--x64", action="store_true", help="float64 too (jax_enable_x64)")
    args = parser.parse_args()
    if args.x64:
        os.environ["JAX_ENABLE_X64"] = "1"
    try:
        import jax
    except ImportError:
        sys.exit('benches/accelerated.py needs JAX: pip install "uwml[jax]"')
    device = jax.devices()[0]
    print(f"device: {device.platform} ({device.device_kind}); jax {jax.__version__}")
    print(f"\nuwml.jax.hydro under jit and vmap, {int(args.states):,} states a batch (best of {args.repeats})")
    print(f"  {'robot':30s} {'dtype':8s} {'compile [s]':>12s} {'states/s':>12s}")
    for name, dtype, compile_s, rate in evaluations(int(args.states), args.repeats):
        print(f"  {name:30s} {dtype:8s} {compile_s:12.2f} {rate:12.3g}")
    if args.mjx:
        sizes = [int(s) for s in args.sizes.split(",")]
        rows = mjx_steps(sizes, args.repeats)
        if rows is None:
            print("\nuwml.sim.mjx is not there (or has no benchmark_steps): MJX steps left out")
            return
        print("\nBlueROV2 with its arm, one step of every environment (best of repeats)")
        print(f"  {'what':30s} {'environments':>12s} {'compile [s]':>12s} {'steps/s':>12s}")
        for what, size, compile_s, rate in rows:
            print(f"  {what:30s} {size:12d} {compile_s:12.2f} {rate:12.3g}")


if __name__ == "__main__":
    main()
