"""``uwml simulate``: the paper's control question (:mod:`uwml.sim.studies`) as a study preset:
the ``paper_leg`` scenario over the grid depth × controller, run by :func:`run_study` (here in
this process, or on Ray), its results in ``OUT/study-<fingerprint>/`` (the same depths and
cycles again reuse them), then the report: the table and the depth sweep from the study's rows,
the tracking figure from the deepest depth's runs simulated again for their time series, MuJoCo's
fluid models beside uwml's, and an arm on a drifting ROV."""

from __future__ import annotations

import json
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from ..sim.studies import CONTROLLERS, ROV_CURRENT, TEMPERATURE_C, fluid_models, rov_drift, run, write_report
from .config import StudyConfig, loads
from .results import read_results
from .runner import progress_bar, run_study

__all__ = ["command", "paper_study"]


def paper_study(depths: Sequence[float], cycles: float) -> StudyConfig:
    """The study of ``uwml simulate``: every controller at every depth, ``cycles`` gait cycles."""
    grid = ", ".join(repr(float(d)) for d in depths)
    controllers = ", ".join(f'"{c}"' for c in CONTROLLERS)
    text = f'[scenario]\nkind = "paper_leg"\ncycles = {float(cycles)!r}\n[parameters]\ndepth = [{grid}]\ncontroller = [{controllers}]\n'
    return loads(text, "uwml simulate")


def command(
    out: str,
    depths: Sequence[float],
    cycles: float,
    as_json: bool,
    *,
    ray: bool = False,
    address: str | None = None,
    workers: int | None = None,
) -> int:
    """``uwml simulate``: the study, its report in ``out``, a summary (or JSON) on standard output."""
    try:
        import mujoco  # noqa: F401
    except ImportError:
        raise ImportError('uwml simulate needs MuJoCo: pip install "uwml[mujoco]"') from None
    config = paper_study(depths, cycles)
    root = Path(out)
    results = root / f"study-{config.fingerprint()}"
    resume = (results / "study.json").exists()
    run_study(config, results, serial=not (ray or address), address=address, workers=workers, resume=resume, progress=progress_bar)
    table = read_results(results)
    rows: list[dict[str, Any]] = table.to_pylist()
    failed = [row for row in rows if row["error"] is not None]
    if failed:
        raise RuntimeError(f"run {failed[0]['run']} ({failed[0]['controller']} at {failed[0]['depth']:g} m) failed: {failed[0]['error']}")
    deepest = max(float(d) for d in depths)
    series = [run(controller, deepest, cycles) for controller in CONTROLLERS]
    shallowest = min(float(d) for d in depths)
    lossless = [run(controller, shallowest, cycles, plant_losses=False) for controller in ("hydro", "hydro_wrong")]
    fluid = fluid_models()
    drifts = [rov_drift(False), rov_drift(True)]
    report = write_report(rows, series, root, fluid, drifts, lossless)
    summaries = [
        {
            "controller": row["controller"],
            "depth_m": row["depth"],
            "rms_error_rad": [row[f"rms_error_{j}"] for j in (1, 2, 3)],
            "peak_error_rad": [row[f"peak_error_{j}"] for j in (1, 2, 3)],
            "positive_work_per_cycle_j": row["positive_work"],
        }
        for row in rows
    ]
    if as_json:
        comparison = {name: fluid.relative_difference(name).tolist() for name in ("box", "ellipsoid")}
        vehicle = [drift.summary() for drift in drifts]
        print(json.dumps({"runs": summaries, "fluid_models_relative_rms_difference": comparison, "rov": vehicle}))
        return 0
    print(f"uwml simulate: the paper's leg on our gait, sea water at {TEMPERATURE_C:g} °C; last of {cycles:g} cycles")
    columns = [f"RMS j{j} [°]" for j in (1, 2, 3)] + [f"peak j{j} [°]" for j in (1, 2, 3)]
    print(f"{'depth [m]':>9} {'controller':>18} " + " ".join(f"{c:>12}" for c in columns) + f" {'work/cycle [J]':>15}")
    for row in summaries:
        errors = np.degrees([*row["rms_error_rad"], *row["peak_error_rad"]])
        cells = " ".join(f"{x:12.3f}" for x in errors)
        print(f"{row['depth_m']:9g} {row['controller']:>18} {cells} {row['positive_work_per_cycle_j']:15.1f}")
    for name in ("box", "ellipsoid"):
        difference = ", ".join(f"{100 * x:.0f} %" for x in fluid.relative_difference(name))
        print(f"MuJoCo's {name} fluid model against uwml on one gait cycle, RMS difference per joint: {difference}")
    for drift in drifts:
        summary = drift.summary()
        print(
            f"ROV in a {ROV_CURRENT:g} m/s current, station keeping {summary['station_keeping']}: drift {summary['rms_drift_m']:.3f} m RMS, "
            f"{summary['max_drift_m']:.3f} m max; attitude {summary['rms_attitude_deg']:.1f}° RMS"
        )
    print(f"report: {report}; the study's runs: {results}")
    return 0
