"""The paper's commands: ``uwml demo`` (the paper leg's torque components along a gait-like
motion), ``uwml paper`` (the paper's analysis end to end) and ``uwml simulate`` (the paper's
control question, simulated)."""

from __future__ import annotations

import argparse
from typing import Any

from ..model.parts import Water
from ..robot.leg import Leg
from ..sim.paper_analysis import _component_table, _rms, gait_like_motion
from ..sim.studies import MAX_CYCLES
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
    leg = Leg.paper()
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
    from ..sim.paper_analysis import run

    return run(args.out, args.seed)


def _simulate(args: argparse.Namespace) -> int:
    from ..study.paper import command

    return command(args.out, args.depths, args.cycles, args.json, ray=args.ray, address=args.address, workers=args.workers)


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
        description="""The paper's control question, simulated (uwml.sim.studies; MuJoCo with uwml's forces and the
added mass in the mass matrix): the paper's leg on a fixed stand follows our walking gait in sea
water at 4 °C at each depth, under PD + the land model's feedforward (land), + uwml's hydrodynamic
feedforward (hydro), + the joint losses' feedforward (hydro_losses), and the last two with Cd and
Cm 30 % too high (hydro_wrong, hydro_losses_wrong). The plant's inertias are assumed (uniform boxes; see uwml.sim.studies).

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
