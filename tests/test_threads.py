"""The batch call into Rust releases the GIL: another Python thread runs while it computes.

While a thread holds the GIL, no other thread executes Python code, except for at most one
switch interval (``sys.getswitchinterval()``, 5 ms) before the holder enters native code. So
a spinning thread's progress during a long batch call tells whether the GIL was released: about
its full rate times the call's duration if it was, at most a switch interval's worth if not.
"""

import subprocess
import sys
import threading
import time
from pathlib import Path

import numpy as np
import pytest
import uwml


def test_batch_call_releases_the_gil():
    leg = uwml.paper_leg()
    rng = np.random.default_rng(0)
    n = 1_000_000
    q, qd, qdd = (rng.uniform(-1, 1, (n, 3)) for _ in range(3))
    # The native call itself, its conditions read before, so that no Python runs in this thread
    # during it.
    conditions = leg._native(uwml.Conditions())
    native = leg._core

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
        native.hydro(q, qd, qdd, conditions, checked=True)
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


def _states(n: int, seed: int = 1) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    rng = np.random.default_rng(seed)
    return rng.uniform(-3, 3, (n, 3)), rng.uniform(-2, 2, (n, 3)), rng.uniform(-9, 9, (n, 3))


def test_threads_give_the_same_results_bit_for_bit():
    """Splitting a batch over threads changes nothing: each sample is the same evaluation."""
    leg, losses = uwml.paper_leg(), [None, uwml.JointLosses(), uwml.JointLosses()]
    q, qd, qdd = _states(10_007)  # not a multiple of any thread count below
    depth = np.linspace(0.0, 3000.0, len(q))
    one = leg.hydro(q, qd, qdd)
    env_one = leg.environment(q, qd, qdd, depth=depth, losses=losses)
    for threads in (2, 3, 16, 20_000):
        many = leg.hydro(q, qd, qdd, threads=threads)
        for name in ("drag", "added_mass", "buoyancy", "gravity"):
            np.testing.assert_array_equal(getattr(many, name), getattr(one, name))
        env_many = leg.environment(q, qd, qdd, depth=depth, losses=losses, threads=threads)
        for name in ("drag", "added_mass", "buoyancy", "gravity", "visc", "seal", "current"):
            np.testing.assert_array_equal(getattr(env_many, name), getattr(env_one, name))
    # One sample, and none, on several threads.
    np.testing.assert_array_equal(leg.hydro(q[0], qd[0], qdd[0], threads=4).total, one.total[0])
    assert leg.hydro(q[:0], qd[:0], qdd[:0], threads=4).total.shape == (0, 3)


@pytest.mark.parametrize("n", [1, 2, 3, 4, 5, 6, 7, 9, 13])
def test_each_row_is_its_states_own_evaluation(n: int):
    """The batch evaluates four states at once, one per SIMD lane, and pads a last group of fewer
    than four: a state's row does not depend on its neighbours, its place, or the padding."""
    leg, losses = uwml.paper_leg(), [None, uwml.JointLosses(), uwml.JointLosses()]
    q, qd, qdd = _states(n, seed=n)
    depth = np.linspace(0.0, 3000.0, n)
    batch = leg.hydro(q, qd, qdd)
    env = leg.environment(q, qd, qdd, depth=depth, losses=losses)
    regressors = leg.hydro_regressors(q, qd, qdd)
    order = np.random.default_rng(n).permutation(n)
    shuffled = leg.hydro(q[order], qd[order], qdd[order])
    for s in range(n):
        single = leg.hydro(q[s], qd[s], qdd[s])
        for name in ("drag", "added_mass", "buoyancy", "gravity"):
            np.testing.assert_array_equal(getattr(batch, name)[s], getattr(single, name))
            np.testing.assert_array_equal(getattr(shuffled, name)[np.argsort(order)][s], getattr(single, name))
        single_env = leg.environment(q[s], qd[s], qdd[s], depth=depth[s], losses=losses)
        for name in ("drag", "buoyancy", "visc", "seal", "current"):
            np.testing.assert_array_equal(getattr(env, name)[s], getattr(single_env, name))
        single_regressors = leg.hydro_regressors(q[s], qd[s], qdd[s])
        for name in ("drag", "added_mass", "buoyancy"):
            np.testing.assert_array_equal(getattr(regressors, name)[s], getattr(single_regressors, name))


def test_threads_report_the_first_bad_sample_of_the_whole_batch():
    leg = uwml.paper_leg()
    q, qd, qdd = _states(1000)
    qd[700, 2] = np.nan  # in the last of 4 parts
    qdd[900, 0] = np.inf
    with pytest.raises(ValueError, match=r"qd\[700, 2\] is NaN"):
        leg.hydro(q, qd, qdd, threads=4)
    depth = np.zeros(len(q))
    depth[600] = np.nan
    with pytest.raises(ValueError, match=r"depth\[600\] is nan m: depth must be finite"):
        leg.environment(q, np.zeros_like(qd), np.zeros_like(qdd), depth=depth, threads=4)


@pytest.mark.parametrize("threads", [0, -1, 1.5, True, "2", None])
def test_bad_thread_counts(threads):
    leg = uwml.paper_leg()
    with pytest.raises(ValueError, match="threads must be an integer >= 1"):
        leg.hydro([0.1, 0.2, 0.3], [0.0] * 3, [0.0] * 3, threads=threads)
    with pytest.raises(ValueError, match="threads must be an integer >= 1"):
        leg.environment([0.1, 0.2, 0.3], [0.0] * 3, [0.0] * 3, threads=threads)


def test_every_evaluation_from_eight_threads_is_the_sequential_one():
    """Every public evaluation, called on one object from 8 threads at once, gives the bits of a
    sequential run, and never hangs: the check runs in its own process under a watchdog (a
    deadlock holding the GIL would stop this process's threads too)."""
    script = Path(__file__).with_name("_thread_check.py")
    try:
        done = subprocess.run([sys.executable, str(script)], capture_output=True, text=True, timeout=300, check=False)
    except subprocess.TimeoutExpired as error:
        pytest.fail(f"deadlock: the threads did not finish in 300 s; last output:\n{error.stdout}")
    assert done.returncode == 0, done.stdout + done.stderr
    assert done.stdout.strip().endswith("ok")
