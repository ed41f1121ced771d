"""The batch call into Rust releases the GIL: another Python thread runs while it computes.

While a thread holds the GIL, no other thread executes Python code, except for at most one
switch interval (``sys.getswitchinterval()``, 5 ms) before the holder enters native code. So
a spinning thread's progress during a long batch call tells whether the GIL was released: about
its full rate times the call's duration if it was, at most a switch interval's worth if not.
"""

import sys
import threading
import time

import numpy as np
import uwml


def test_batch_call_releases_the_gil():
    leg = uwml.Leg.paper()
    rng = np.random.default_rng(0)
    n = 1_000_000
    q, qd, qdd = (rng.uniform(-1, 1, (n, 3)) for _ in range(3))
    cd, cm = np.full((3, 2), 2.2), np.full((3, 2), 0.5)
    chain = leg._chain  # the native call itself, so that no Python runs in this thread during it

    count = 0
    stop = threading.Event()

    def spin():
        nonlocal count
        while not stop.is_set():
            count += 1

    spinner = threading.Thread(target=spin)
    spinner.start()
    try:
        # The spinner's rate while this thread sleeps (sleeping releases the GIL).
        start_count, start = count, time.perf_counter()
        time.sleep(0.1)
        rate = (count - start_count) / (time.perf_counter() - start)
        # Its progress during the batch call.
        start_count, start = count, time.perf_counter()
        chain.hydro(q, qd, qdd, cd, cm, 1000.0, 9.81)
        duration = time.perf_counter() - start
        progress = count - start_count
    finally:
        stop.set()
        spinner.join()

    switch = sys.getswitchinterval()
    assert duration > 8 * switch, f"the call took {duration:.3f} s: too short to tell"
    # Held GIL: progress <= rate * switch, i.e. at most 1/8 of rate * duration. Released: about
    # rate * duration (the spinner runs on the other core); a quarter leaves room for scheduling.
    assert progress > 0.25 * rate * duration, (progress, rate, duration)
