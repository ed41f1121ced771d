"""Identification of Cd and Cm on a large log: time and peak memory of ``uwml.fit.hydro_coefficients``.

Run: ``python benches/large_log.py [n_rows]`` (default 1e7). The log is synthetic
(:func:`uwml.synthetic.land_water_experiment` with the default gait at 1 kHz, true Cd = 2.2 and
Cm = 0.5, 0.5 N·m torque noise) and built in memory first; then each fit setting is timed once,
with the growth of the process's peak resident memory it causes (``ru_maxrss``), and compared
with a dense solve of the same problem by ``numpy.linalg.lstsq`` on the materialized design
(what the fit did before it streamed; run only where that design fits in 2 GB).
"""

import resource
import sys
import time

import numpy as np
import uwml
from uwml import fit, synthetic


def peak_mb() -> float:
    """Peak resident memory of this process since the last :func:`reset_peak` [MB] (Linux)."""
    with open("/proc/self/status") as status:
        for line in status:
            if line.startswith("VmHWM:"):
                return int(line.split()[1]) / 1024.0
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def current_mb() -> float:
    with open("/proc/self/status") as status:
        for line in status:
            if line.startswith("VmRSS:"):
                return int(line.split()[1]) / 1024.0
    return float("nan")


def reset_peak() -> None:
    """Reset the peak to the current resident memory (Linux ≥ 4.0: ``echo 5 > clear_refs``)."""
    with open("/proc/self/clear_refs", "w") as clear:
        clear.write("5")


def main() -> None:
    n = int(float(sys.argv[1])) if len(sys.argv) > 1 else 10_000_000
    leg = uwml.Leg.paper()
    start = time.perf_counter()
    rate = 1000.0
    period = uwml.WalkingGait().period
    log = synthetic.land_water_experiment(leg, cycles=n / rate / period, rate_hz=rate, seed=1)
    log = uwml.Log(time=log.time[:n], q=log.q[:n], qd=log.qd[:n], qdd=log.qdd[:n], tau_land=log.tau_land[:n], tau_water=log.tau_water[:n])
    print(
        f"log: {log.n_samples:,} rows x {log.n_joints} joints, built in {time.perf_counter() - start:.1f} s; peak RSS {peak_mb():,.0f} MB"
    )
    settings = [
        ("joint 1, one Cd and Cm (the paper)", {"joints": (0,)}),
        ("all joints, per link and direction", {"joints": (0, 1, 2), "per": "direction"}),
        ("joint 1, robust (Huber)", {"joints": (0,), "robust": True}),
    ]
    for label, kwargs in settings:
        reset_peak()
        before = current_mb()
        start = time.perf_counter()
        result = fit.hydro_coefficients(log, leg, **kwargs)
        elapsed = time.perf_counter() - start
        values = ", ".join(f"{k} = {v:.5f} ± {result.stderr[k] or float('nan'):.5f}" for k, v in list(result.params.items())[:2])
        print(f"{label:38s} {elapsed:6.2f} s  peak memory +{peak_mb() - before:,.0f} MB over the log's  ({values}, ...)")

    # The dense alternative: the design materialized, then one least-squares solve.
    # The joint-1 regressors (drag, added mass, buoyancy, gravity: 4 × 3 floats a row) under 2 GB.
    if n * 12 * 8 < 2e9:
        regressors = leg.hydro_regressors(log.q, log.qd, log.qdd)
        x = np.stack([regressors.drag[:, 0], regressors.added_mass[:, 0]], axis=1)
        y = -(log.tau_water[:, 0] - log.tau_land[:, 0]) - regressors.buoyancy[:, 0]
        start = time.perf_counter()
        np.linalg.lstsq(x, y, rcond=None)
        print(f"{'numpy lstsq on the dense design (joint 1)':38s} {time.perf_counter() - start:6.2f} s  (solve only, design in memory)")
        start = time.perf_counter()
        gram, rhs = x.T @ x, x.T @ y
        np.linalg.solve(gram, rhs)
        print(f"{'normal equations on the same design':38s} {time.perf_counter() - start:6.2f} s")


if __name__ == "__main__":
    main()
