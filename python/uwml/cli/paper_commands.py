"""The paper's commands: ``uwml demo`` (the paper leg's torque components along a gait-like
motion), ``uwml paper`` (the paper's analysis end to end) and ``uwml simulate`` (the paper's
control question, simulated)."""

from __future__ import annotations

import argparse
import json
from pathlib import Path
from typing import Any

import numpy as np

from ..model.parts import Water
from ..paper.analysis import _component_table, _rms, gait_like_motion
from ..paper.control_study import CONTROLLERS, MAX_CYCLES, fluid_models, preset, run, write_report
from ..robot.presets import paper_leg
from ..sim.control import ROV_CURRENT, TEMPERATURE_C, rov_drift
from .argument_types import (
    MAX_DEMO_SAMPLES,
    MAX_DEPTHS,
    _count,
    _cycles,
    _depth_list,
    _non_negative,
    _positive,
    _seed,
    _workers,
)
from .common import _EXIT


def _demo(args: argparse.Namespace) -> int:
    leg = paper_leg()
    water = Water(density=args.density, gravity=9.81)
    t, q, qd, qdd = gait_like_motion(args.samples, args.period)
    tau = leg.hydro(q, qd, qdd, cd=args.cd, cm=args.cm, water=water)
    print(f"uwml demo: the paper's leg (Table II) in water of {water.density:g} kg/m³, Cd = {args.cd:g}, Cm = {args.cm:g},")
    print(f"along a gait-like motion of period {args.period:g} s. Torques on each joint [N·m], environment on joint.")
    print("\n".join(_component_table(t, q, qd, tau)))
    print()
    print("RMS over the cycle     " + "   ".join(f"joint {j + 1}" for j in range(leg.n_joints)))
    for name in ("drag", "added_mass", "buoyancy"):
        print(f"  {name:<20} " + "   ".join(f"{v:7.3f}" for v in _rms(getattr(tau, name))))
    return 0


def _paper(args: argparse.Namespace) -> int:
    from ..paper.analysis import run

    return run(args.out, args.seed)


def _simulate(args: argparse.Namespace) -> int:
    """``uwml simulate``: the study of :func:`uwml.paper.control_study.preset`, its report in
    ``--out``, a summary (or JSON) on standard output."""
    try:
        import mujoco  # noqa: F401
    except ImportError:
        raise ImportError('uwml simulate needs MuJoCo: pip install "uwml[mujoco]"') from None
    from ..study import loads, read_results, run_study
    from ..study.runner import progress_bar

    out, depths, cycles, as_json = args.out, args.depths, args.cycles, args.json
    config = loads(preset(depths, cycles), "uwml simulate")
    root = Path(out)
    results = root / f"study-{config.fingerprint()}"
    resume = (results / "study.json").exists()
    serial = not (args.ray or args.address)
    run_study(config, results, serial=serial, address=args.address, workers=args.workers, resume=resume, progress=progress_bar)
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


def add_paper_commands(commands: Any, formatter: type[argparse.HelpFormatter]) -> None:
    """``uwml demo``, ``uwml paper`` and ``uwml simulate`` on the ``uwml`` parser's commands."""
    demo = commands.add_parser("demo", help="print the paper leg's torque components along a gait-like motion")
    demo.add_argument("--samples", type=_count, default=9, help=f"samples over one cycle, 2 to {MAX_DEMO_SAMPLES} (default 9)")
    demo.add_argument("--period", type=_positive, default=2.0, help="cycle period [s] (default 2)")
    demo.add_argument("--cd", type=_non_negative, default=2.2, help="drag coefficient (default 2.2, the paper's fit)")
    demo.add_argument("--cm", type=_non_negative, default=0.5, help="added-mass coefficient (default 0.5, the paper's fit)")
    demo.add_argument("--density", type=_positive, default=1000.0, help="water density [kg/m³] (default 1000)")
    demo.set_defaults(run=_demo)

    paper = commands.add_parser(
        "paper",
        help="reproduce the paper's analysis on built-in defaults: figures, report.md, summary",
        formatter_class=formatter,
        description="""The paper's analysis end to end, on built-in defaults (runs in a few seconds):

  * the component torques (total, drag, added mass, buoyancy) of the paper's leg over one cycle
    of our walking gait, which swings the hip yaw (cf. Fig. 8)            -> fig8_torques.png
  * a SYNTHETIC land/water experiment (true Cd = 2.2, Cm = 0.5) sized and spoiled like the
    paper's (noise and a documented model error), its fit on joint 1 (cf. Fig. 7), and what
    each part of the model error does to Cd and Cm      -> land_water.csv, fig7_fit.png
  * the joint-loss maps of the ILLUSTRATIVE loss defaults (Figs. 13-14)  -> fig13_14_loss_maps.png
  * the rated current left after the losses over speed and depth        -> efficiency_map.png
  * the loss current at 10 r/min, 10 MPa, 20 °C (the paper's 27.4 %)
  * report.md with the numbers and figure links.

A summary table (RMS torques per joint, fitted Cd and Cm with standard errors, reduced chi-square
and COD weighted and unweighted beside the paper's, loss current and share) is printed to the
terminal.""",
        epilog=_EXIT,
    )
    paper.add_argument("--out", default="uwml-paper", metavar="DIR", help="output directory, created if needed (default uwml-paper)")
    paper.add_argument("--seed", type=_seed, default=0, metavar="N", help="seed of the synthetic experiment's noise (default 0)")
    paper.set_defaults(run=_paper)

    simulate = commands.add_parser(
        "simulate",
        help="the paper's leg walking in sea water under five controllers, simulated (needs uwml[mujoco])",
        formatter_class=formatter,
        description="""The paper's control question, simulated (uwml.paper.control_study; MuJoCo with uwml's forces and the
added mass in the mass matrix): the paper's leg on a fixed stand follows our walking gait in sea
water at 4 °C at each depth, under PD + the land model's feedforward (land), + uwml's hydrodynamic
feedforward (hydro), + the joint losses' feedforward (hydro_losses), and the last two with Cd and
Cm 30 % too high (hydro_wrong, hydro_losses_wrong). The plant's inertias are assumed (uniform boxes; see uwml.paper.control_study).

A study preset (uwml.study, docs/scale.md): the grid depth x controller of the paper_leg
scenario, its runs written to --out/study-<fingerprint>/runs/*.parquet (the same depths and
cycles again reuse them); in this process by default, on Ray with --ray or --address.

Output: a table of RMS and peak tracking error per joint and the motor's positive work per cycle
(last cycle), or with --json the runs' summaries as JSON; report.md, tracking.png and
depth_sweep.png in --out. A progress bar on standard error.""",
        epilog=_EXIT,
    )
    simulate.add_argument("--out", default="uwml-simulate", metavar="DIR", help="directory for the report (default uwml-simulate)")
    simulate.add_argument(
        "--depths",
        type=_depth_list,
        default=[0.0, 1000.0, 3000.0, 6000.0],
        metavar="0,1000,...",
        help=f"depths [m], 0 to 11000, at most {MAX_DEPTHS} of them",
    )
    simulate.add_argument(
        "--cycles",
        type=_cycles,
        default=2.0,
        metavar="N",
        help=f"gait cycles per run, up to {MAX_CYCLES} (default 2; metrics over the last)",
    )
    simulate.add_argument("--json", action="store_true", help="print the runs' summaries as JSON only")
    simulate.add_argument("--ray", action="store_true", help="run the study on a local Ray (default: here, one run after the other)")
    simulate.add_argument("--address", metavar="ADDR", help="run the study on the Ray cluster at this address")
    simulate.add_argument("--workers", type=_workers, metavar="N", help="CPUs of the local Ray (default all)")
    simulate.set_defaults(run=_simulate)
