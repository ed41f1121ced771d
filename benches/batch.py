"""Throughput of the batch call ``Leg.hydro`` against the numpy reference, on one thread.

Run: ``python benches/batch.py [n_states]`` (default 1e6). Prints states per second for both and
their ratio, measured in this one run (best of 3 for the Rust path, 1 run of the reference).
"""

import sys
import time

import numpy as np
import uwml
from uwml import reference


def main() -> None:
    n = int(float(sys.argv[1])) if len(sys.argv) > 1 else 1_000_000
    rng = np.random.default_rng(0)
    q = rng.uniform(-np.pi, np.pi, (n, 3))
    qd = rng.uniform(-3, 3, (n, 3))
    qdd = rng.uniform(-10, 10, (n, 3))
    leg = uwml.Leg.paper()
    leg.hydro(q[:10], qd[:10], qdd[:10])

    best = np.inf
    for _ in range(3):
        start = time.perf_counter()
        leg.hydro(q, qd, qdd)
        best = min(best, time.perf_counter() - start)
    start = time.perf_counter()
    leg.hydro_regressors(q, qd, qdd)
    regressors = time.perf_counter() - start

    m = min(n, 200_000)
    start = time.perf_counter()
    reference.hydro(leg.joints, leg.links, q[:m], qd[:m], qdd[:m])
    numpy_time = (time.perf_counter() - start) * n / m

    print(f"states: {n:,}")
    print(f"uwml Leg.hydro (Rust, GIL released): {best:8.3f} s  {n / best / 1e6:7.2f} M states/s  {best / n * 1e9:7.1f} ns/state")
    print(f"uwml Leg.hydro_regressors:           {regressors:8.3f} s  {n / regressors / 1e6:7.2f} M states/s")
    print(f"uwml.reference.hydro (numpy):        {numpy_time:8.3f} s  {n / numpy_time / 1e6:7.2f} M states/s  (timed on {m:,} states)")
    print(f"speed-up of the Rust path over the numpy reference: {numpy_time / best:.1f}x")


if __name__ == "__main__":
    main()
