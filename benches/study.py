"""A study on Ray against the same runs serially (``uwml.study``; docs/scale.md, "What it costs").

Run: ``python benches/study.py [--runs 1000] [--cycles 0.2] [--workers 2]``.

Prints, in one run on this machine:

* the serial loop over the runs (``run_study(serial=True)``, in this process);
* the same study on a local Ray of ``--workers`` CPUs, its start-up and shut-down included, and
  without them (Ray started before, as on a cluster);
* the overhead per task: a study of tasks that do nothing (``cycles`` so short that a run is
  ~0.1 ms), batch by batch, against the same runs serially, per batch.
"""

from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path

from uwml import study
from uwml.study import runner


def config(runs: int, cycles: float) -> study.StudyConfig:
    return study.loads(
        f"""
[scenario]
kind = "paper_leg"
cycles = {cycles!r}
[parameters]
depth = [0.0, 3000.0, 6000.0, 9000.0]
controller = ["land", "hydro", "hydro_losses", "hydro_wrong", "hydro_losses_wrong"]
payload = {{ distribution = "uniform", low = 0.0, high = 2.0 }}
[sampling]
samples = {max(1, runs // 20)}
seed = 0
""",
        "bench",
    )


def timed(function) -> float:  # type: ignore[no-untyped-def]
    start = time.perf_counter()
    function()
    return time.perf_counter() - start


TINY_RUNS = 200


def measure(runs: int, cycles: float, workers: int) -> dict[str, float]:
    """Seconds of the study of ``runs`` runs of ``cycles`` gait cycles: ``serial`` (in this
    process), ``Ray, started`` (a local Ray of ``workers`` CPUs started and stopped for it),
    ``Ray, running`` (Ray started before); and ``per task``, Ray's overhead per task (runs of
    almost nothing, one a task, against the same runs serially)."""
    import ray

    work = config(runs, cycles)
    with tempfile.TemporaryDirectory() as folder:
        root = Path(folder)
        serial = timed(lambda: study.run_study(work, root / "serial", serial=True))
        cold = timed(lambda: study.run_study(work, root / "cold", workers=workers))
        ray.init(num_cpus=workers, include_dashboard=False, logging_level="ERROR", log_to_driver=False)
        try:
            warm = timed(lambda: study.run_study(work, root / "warm"))
            # The overhead per task: runs of almost nothing, one per task, on Ray and serially.
            tiny = config(TINY_RUNS, 1e-3)
            saved = runner.MAX_BATCH
            runner.MAX_BATCH = 1
            try:
                tasks = timed(lambda: study.run_study(tiny, root / "tiny-ray"))
            finally:
                runner.MAX_BATCH = saved
        finally:
            ray.shutdown()
        alone = timed(lambda: study.run_study(tiny, root / "tiny-serial", serial=True))
    per_task = (tasks - alone / workers) / tiny.n_runs * workers
    return {"serial": serial, "Ray, started": cold, "Ray, running": warm, "per task": per_task, "runs": work.n_runs}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--runs", type=int, default=1000)
    parser.add_argument("--cycles", type=float, default=0.2)
    parser.add_argument("--workers", type=int, default=2)
    args = parser.parse_args()
    times = measure(args.runs, args.cycles, args.workers)
    serial, cold, warm, per_task = (times[k] for k in ("serial", "Ray, started", "Ray, running", "per task"))
    n = int(times["runs"])
    print(f"{n} runs of {args.cycles:g} gait cycles (paper_leg), {args.workers} workers:")
    print(f"  serial, in this process:          {serial:7.2f} s  ({1e3 * serial / n:.1f} ms a run)")
    print(f"  Ray, started for the study:       {cold:7.2f} s  ({serial / cold:.2f}x the serial loop)")
    print(f"  Ray, already running:             {warm:7.2f} s  ({serial / warm:.2f}x)")
    print(f"  overhead per task (one run each): {1e3 * per_task:7.2f} ms  ({TINY_RUNS} tasks of ~0.1 ms runs)")


if __name__ == "__main__":
    main()
