"""Large logs: write, read, ``uwml fit hydro`` and ``uwml torques`` on files of 1e6 and 1e7 rows.

Run: ``python benches/large_log.py [--rows 1e6 1e7] [--formats csv parquet] [--torques] [--dir DIR]``.

The log is synthetic (:func:`uwml.paper.synthetic.land_water_experiment` with the default gait at
1 kHz, true Cd = 2.2 and Cm = 0.5; columns time, q, qd, qdd, tau_land, tau_water: 16 columns
for the paper's 3-joint leg). Every measurement runs in a subprocess of its own, so that the
peak resident memory (``ru_maxrss`` of that child, from ``os.wait4``) is its alone:

* write: ``uwml.write_log`` of the log; the time is the call's, the peak includes building the
  log in memory first (about 16 × 8 bytes a row);
* read: ``uwml.read_log``; the time is the call's;
* fit: the command ``uwml fit hydro FILE`` (joint 1, one Cd and Cm; the report on standard
  output), wall time of the whole process (Python start-up and imports included);
* torques (with ``--torques``): ``uwml torques FILE --out OUT.parquet`` (derivatives given),
  wall time of the process; its peak shows the streaming's bounded memory.

The files are written in a temporary directory (or ``--dir``) and deleted afterwards; 1e7 rows
take about 3 GB of CSV and 1.3 GB of Parquet.

``python benches/large_log.py --fit-settings 1e7``: instead, the fit alone on a log built in
memory, each setting of :func:`uwml.fit.hydro_coefficients` timed once with the growth of the
process's peak resident memory it causes, and compared with a dense solve of the same problem by
``numpy.linalg.lstsq`` on the materialized design (run only where that design fits in 2 GB).
"""

from __future__ import annotations

import argparse
import json
import os
import re
import resource
import shutil
import subprocess
import sys
import tempfile
import time
from typing import Any


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


def fit_settings(n: int) -> None:
    """The fit settings on a log in memory (no file): time and growth of peak memory each."""
    import numpy as np
    import uwml
    from uwml import fit
    from uwml.paper import synthetic

    leg = uwml.paper_leg()
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


def _child(kind: str, n: int, path: str) -> None:
    """One measurement in this (child) process; prints its time [s] as JSON."""
    import uwml

    if kind == "write":
        from uwml.paper import synthetic

        leg = uwml.paper_leg()
        rate = 1000.0
        log = synthetic.land_water_experiment(leg, cycles=n / rate / uwml.WalkingGait().period + 1.0, rate_hz=rate, seed=1)
        log = uwml.Log(
            time=log.time[:n], q=log.q[:n], qd=log.qd[:n], qdd=log.qdd[:n], tau_land=log.tau_land[:n], tau_water=log.tau_water[:n]
        )
        start = time.perf_counter()
        uwml.write_log(log, path)
    else:
        start = time.perf_counter()
        log = uwml.read_log(path)
        assert log.n_samples == n
    print(json.dumps({"seconds": time.perf_counter() - start}))


def _run(command: list[str], quiet: bool = False) -> tuple[float, float, str]:
    """(wall time [s], peak resident memory of the child [MB], its standard output)."""
    start = time.perf_counter()
    with subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL if quiet else None, text=True) as process:
        out = process.stdout.read() if process.stdout else ""
        _, status, usage = os.wait4(process.pid, 0)
        process.returncode = os.waitstatus_to_exitcode(status)
    wall = time.perf_counter() - start
    if process.returncode != 0:
        raise SystemExit(f"failed ({process.returncode}): {' '.join(command)}")
    return wall, usage.ru_maxrss / 1024.0, out


def measure_row(n: int, fmt: str, directory: str, torques: bool = False) -> dict[str, Any]:
    """One log of ``n`` rows in ``fmt`` (csv or parquet) in ``directory``, each step in a process
    of its own: ``file MB``, ``write s``/``write MB`` (time, peak), ``read s``/``read MB``,
    ``fit s``/``fit MB`` (the whole ``uwml fit hydro`` process), with ``torques`` also
    ``torques s``/``torques MB`` (``uwml torques --out FILE.parquet``); and the fitted ``cd``,
    ``cm`` (text). The file is deleted afterwards."""
    path = os.path.join(directory, f"log-{n}.{fmt}")
    me = [sys.executable, os.path.abspath(__file__), "--child"]
    row: dict[str, Any] = {}
    try:
        _, row["write MB"], out = _run([*me, "write", str(n), path])
        row["write s"] = json.loads(out)["seconds"]
        row["file MB"] = os.path.getsize(path) / 1e6
        _, row["read MB"], out = _run([*me, "read", str(n), path])
        row["read s"] = json.loads(out)["seconds"]
        row["fit s"], row["fit MB"], out = _run([sys.executable, "-m", "uwml", "fit", "hydro", path])
        row |= dict(re.findall(r"^\s+(cd|cm):\s+(\S+) \+/-", out, re.MULTILINE))
        if torques:
            out_path = os.path.join(directory, "torques.parquet")
            row["torques s"], row["torques MB"], _ = _run([sys.executable, "-m", "uwml", "torques", path, "--out", out_path], quiet=True)
            os.remove(out_path)
    finally:
        if os.path.exists(path):
            os.remove(path)
    return row


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--rows", type=float, nargs="+", default=[1e6, 1e7], help="log lengths (default 1e6 1e7)")
    parser.add_argument("--formats", nargs="+", choices=("csv", "parquet"), default=["csv", "parquet"])
    parser.add_argument("--torques", action="store_true", help="also time uwml torques (to Parquet)")
    parser.add_argument("--dir", help="directory for the files (default: a temporary one)")
    parser.add_argument("--fit-settings", type=float, metavar="N", help="instead: the fit settings on an in-memory log of N rows")
    parser.add_argument("--child", nargs=3, metavar=("KIND", "N", "PATH"), help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.fit_settings:
        fit_settings(int(args.fit_settings))
        return
    if args.child:
        _child(args.child[0], int(args.child[1]), args.child[2])
        return
    directory = tempfile.mkdtemp(prefix="uwml-large-log-", dir=args.dir)
    header = f"{'rows':>12} {'format':>8} {'file MB':>8} | {'write s':>8} {'peak MB':>8} | {'read s':>7} {'peak MB':>8} | "
    header += f"{'fit s':>6} {'peak MB':>8}" + (f" | {'torques s':>9} {'peak MB':>8}" if args.torques else "")
    print(header)
    print("-" * len(header))
    try:
        for rows in args.rows:
            n = int(rows)
            for fmt in args.formats:
                row = measure_row(n, fmt, directory, args.torques)
                line = f"{n:>12,} {fmt:>8} {row['file MB']:>8,.0f} | {row['write s']:>8.1f} {row['write MB']:>8,.0f} | "
                line += f"{row['read s']:>7.1f} {row['read MB']:>8,.0f} | {row['fit s']:>6.1f} {row['fit MB']:>8,.0f}"
                if args.torques:
                    line += f" | {row['torques s']:>9.1f} {row['torques MB']:>8,.0f}"
                print(line + f"   (cd = {row['cd']}, cm = {row['cm']})", flush=True)
    finally:
        shutil.rmtree(directory, ignore_errors=True)


if __name__ == "__main__":
    main()
