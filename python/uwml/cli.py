"""The ``uwml`` command line.

Subcommands (``uwml <command> --help`` for each):

* ``uwml demo``: the paper leg's torque components along a gait-like motion, as a table.
* ``uwml paper``: the paper's analysis end to end on built-in defaults (figures, report, summary).
* ``uwml torques LOG``: every torque component along a logged trajectory, as CSV (or Parquet).
* ``uwml fit hydro LOG...``: Cd and Cm (and a robot's hull) from land/water experiments.
* ``uwml fit losses CSV``: the oil-drag and seal models from a three-configuration experiment.
* ``uwml simulate``: the paper's leg walking in sea water under five controllers (MuJoCo).
* ``uwml study CONFIG``: a scenario over grids and random draws of its parameters, on Ray.

Exit codes: 0 on success, 2 for usage errors and bad input files (the message names the file,
row and column), 1 for other failures (out of memory included). Errors are printed as one line,
``uwml: error: <message>``. Size-like arguments are bounded (``--samples``, ``--cycles``,
``--joints``, the number of ``--depths``), so that no argument asks for an absurd allocation.
"""

from __future__ import annotations

import argparse
import os
import sys
from collections.abc import Sequence
from typing import IO, Any

import numpy as np

from ._cli_arguments import (
    MAX_DEMO_SAMPLES,
    MAX_DEPTHS,
    _count,
    _cycles,
    _depth,
    _depth_list,
    _finite,
    _n_joints,
    _non_negative,
    _positive,
    _seed,
    _workers,
)
from ._cli_common import _EXIT, _LOG_FORMAT, _check_output, _UsageError, load_robot
from ._cli_fit import add_fit_commands
from ._cli_study import add_study_command
from .domains import MAX_ROBOT_JOINTS
from .model.parts import SEA_WATER, Water
from .robot.leg import Leg
from .robot.tree import Robot
from .sim.paper_analysis import _component_table, _rms, gait_like_motion
from .sim.studies import MAX_CYCLES

__all__ = ["build_parser", "gait_like_motion", "main"]

#: Rows per chunk of ``uwml torques``, which reads, evaluates and writes one chunk at a time;
#: longer inputs report progress on stderr.
CHUNK_ROWS = 100_000


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
    from .sim.paper_analysis import run

    return run(args.out, args.seed)


# --------------------------------------------------------------------------------------------
# uwml torques
# --------------------------------------------------------------------------------------------


def _torques(args: argparse.Namespace) -> int:
    from .io._log_stream import log_chunks
    from .model.joint_losses import JointLosses

    out = args.out
    _check_output(out, "--out")
    parquet = out is not None and out.lower().endswith(".parquet")
    if parquet:
        try:
            import pyarrow
        except ImportError:
            raise _UsageError(f"{out}: Parquet output needs pyarrow (pip install pyarrow); write CSV instead") from None
    leg: Any = Leg.paper() if args.robot is None else load_robot(args.robot, args.hydro)
    what = "the leg (the paper's)" if args.robot is None else f"the robot ({args.robot})"
    # Coefficients: the paper's fit for its leg; a robot's segments carry their own.
    cd = args.cd if args.cd is not None else (2.2 if args.robot is None else None)
    cm = args.cm if args.cm is not None else (0.5 if args.robot is None else None)
    # The water: the paper's leg at depth moves in sea water; a robot in its own.
    water = SEA_WATER if args.robot is None else None
    # The log is checked (header, time column) here, and read chunk by chunk below.
    n, n_joints, chunks = log_chunks(args.log, leg.n_joints if args.joints is None else args.joints, rows=CHUNK_ROWS)
    if n_joints != leg.n_joints:
        raise ValueError(
            f"{args.log}: row 1 (header), column 'q{min(n_joints, leg.n_joints) + 1}': the log has {n_joints} joints, {what} {leg.n_joints}"
        )
    families = ["drag", "added_mass", "buoyancy"] + (["visc", "seal", "current", "total"] if args.losses else [])
    names = ["time"] + [f"{family}{k}" for family in families for k in range(1, n_joints + 1)]
    base_names = ["base_fx", "base_fy", "base_fz", "base_mx", "base_my", "base_mz"] if args.robot is not None else []
    names += base_names
    losses = JointLosses() if args.losses else None
    progress = n > CHUNK_ROWS
    # A file is written under a temporary name and renamed when complete: a bad cell found
    # half-way leaves no partial output behind (standard output gets the rows before it).
    partial = None if out is None else f"{out}.partial-{os.getpid()}"
    handle: IO[bytes] | None = None
    writer: Any = None
    done = 0
    try:
        if parquet:
            import pyarrow
            import pyarrow.parquet

            schema = pyarrow.schema([(name, pyarrow.float64()) for name in names])
            writer = pyarrow.parquet.ParquetWriter(partial, schema)
        else:
            from .io._arrow_csv import CsvColumnsWriter

            sys.stdout.flush()
            handle = sys.stdout.buffer if partial is None else open(partial, "wb")  # noqa: SIM115
            writer = CsvColumnsWriter(handle, names)
        for log in chunks:
            assert log.qd is not None and log.qdd is not None
            tau = leg.environment(
                log.q, log.qd, log.qdd, depth=args.depth, temperature_c=args.temperature, losses=losses, cd=cd, cm=cm, water=water
            )
            blocks = [getattr(tau, family) for family in families] + ([tau.base.total] if base_names else [])
            columns = [log.time] + [block[:, k] for block in blocks for k in range(block.shape[1])]
            if parquet:
                writer.write_table(pyarrow.table({name: np.ascontiguousarray(c) for name, c in zip(names, columns, strict=True)}))
            else:
                writer.write(columns)
            done += log.n_samples
            if progress:
                print(f"uwml torques: {done}/{n} rows ({100.0 * done / n:.0f} %)", file=sys.stderr, flush=True)
        writer.close()
        writer = None
        if handle is not None:
            if handle is sys.stdout.buffer:
                handle.flush()
            else:
                handle.close()
            handle = None
        if partial is not None:
            os.replace(partial, out)
            partial = None
    finally:
        if writer is not None:
            writer.close()
        if handle is not None and handle is not sys.stdout.buffer:
            handle.close()
        if partial is not None and os.path.exists(partial):
            os.remove(partial)
    if out is not None:
        print(f"uwml torques: {n} rows, {len(names)} columns written to {out}", file=sys.stderr)
    return 0


def _export(args: argparse.Namespace) -> int:
    from .io.export import to_c, to_rust

    robot = load_robot(args.robot, args.hydro) if args.robot else Robot.from_leg(Leg.paper())
    source = args.robot or "the paper's leg"
    precision = "f32" if args.f32 else "f64"
    text = to_rust(robot, precision, source=source) if args.rust else to_c(robot, precision, prefix=args.name, source=source)
    sys.stdout.write(text)
    return 0


def _describe(args: argparse.Namespace) -> int:
    from .viz.describe import describe, draw

    _check_output(args.plot, "--plot")
    robot = load_robot(args.robot, args.hydro) if args.robot else Robot.from_leg(Leg.paper())
    water = robot.water if args.density is None else Water(density=args.density, gravity=robot.water.gravity)
    print(describe(robot, water))
    if args.plot:
        draw(robot, args.plot, title=f"{args.robot or 'the paper leg'} at q = 0")
        print(f"\nwrote {args.plot}")
    return 0


# --------------------------------------------------------------------------------------------
# Parser
# --------------------------------------------------------------------------------------------


def _installed_version() -> str:
    """The installed package's version (its metadata; the source's own when not installed)."""
    from importlib import metadata

    try:
        return metadata.version("uwml")
    except metadata.PackageNotFoundError:
        return "(not installed)"


def build_parser() -> argparse.ArgumentParser:
    """The ``uwml`` argument parser."""
    formatter = argparse.RawDescriptionHelpFormatter
    parser = argparse.ArgumentParser(
        prog="uwml",
        description="Hydrodynamic joint torques and joint losses of underwater legs and arms (the paper's 3-DOF leg built in).",
        epilog=_EXIT,
    )
    parser.add_argument("--version", action="version", version=f"uwml {_installed_version()}")
    commands = parser.add_subparsers(dest="command", required=True)

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

    torques = commands.add_parser(
        "torques",
        help="every torque component along a logged trajectory, as CSV (or Parquet)",
        formatter_class=formatter,
        description=f"""Every torque component of the paper's leg (or of --robot) along the trajectory of LOG.

{_LOG_FORMAT}
Torque columns are not needed.

Output (CSV, to FILE or standard output; Parquet if FILE ends in .parquet): columns time,
drag1..N, added_mass1..N, buoyancy1..N [N·m], and with --losses visc1..N, seal1..N [N·m],
current1..N [A] and total1..N [N·m] (= drag + added mass + buoyancy + visc + seal). With
--robot (a uwml model file, a URDF or an MJCF), the robot on a fixed, upright base, and six more columns
base_fx..base_mz: the hydrodynamic force [N] and moment [N·m] on the base (about its origin).
Sign: the environment's torque on each joint, in the joint's positive direction. Losses use
the illustrative defaults of uwml.model.losses on every joint (uwml.JointLosses()). The paper's leg
moves in sea water (1025 kg/m³), a --robot in its own water (its description's); that water's
column gives the hydrostatic pressure at --depth.

The log is read, evaluated and written {CHUNK_ROWS} rows at a time, in bounded memory
whatever its length (estimated derivatives add 8 bytes a row); longer inputs report progress
on standard error. A bad cell met half-way stops the command with exit status 2: FILE is then
not written (standard output has the rows before it).""",
        epilog=_EXIT,
    )
    torques.add_argument("log", metavar="LOG", help="trajectory log (CSV, or .parquet)")
    torques.add_argument("--out", metavar="FILE", help="output file (.csv, or .parquet); default: standard output")
    torques.add_argument(
        "--depth", type=_depth, default=0.0, metavar="M", help="depth [m] for the pressure of the losses, 0 to 11000 (default 0)"
    )
    torques.add_argument("--temperature", type=_finite, default=20.0, metavar="C", help="oil temperature [°C] (default 20)")
    torques.add_argument(
        "--robot", metavar="FILE", help="the robot: a uwml model file (.toml), a URDF (.urdf) or an MJCF (.xml); default the paper's leg"
    )
    torques.add_argument("--hydro", metavar="FILE", help="the hydro file of a URDF or MJCF robot")
    torques.add_argument(
        "--cd",
        type=_non_negative,
        default=None,
        metavar="X",
        help="drag coefficient for every segment (default: 2.2, the paper's fit; a robot's own)",
    )
    torques.add_argument("--cm", type=_non_negative, default=None, metavar="X", help="added-mass coefficient (default: 0.5; a robot's own)")
    torques.add_argument("--losses", action="store_true", help="add the oil-viscous and seal losses, loss current and total")
    torques.add_argument(
        "--joints",
        type=_n_joints,
        default=None,
        metavar="N",
        help=f"number of joints the log must have, 1 to {MAX_ROBOT_JOINTS} (default: the robot's; 3, the paper leg's)",
    )
    torques.set_defaults(run=_torques)

    describe = commands.add_parser(
        "describe",
        help="a robot's joints, links, segments, volumes, masses and net buoyancy, and a picture at q = 0",
        description="Print what a robot is made of (joints, bodies with mass, volume and net buoyancy, segments with their "
        "coefficients) and, with --plot, draw it at q = 0 with its segments. Without --robot: the paper's leg.",
    )
    describe.add_argument("--robot", metavar="FILE", help="the robot: a uwml model file (.toml), a URDF (.urdf) or an MJCF (.xml)")
    describe.add_argument("--hydro", metavar="FILE", help="the hydro file of a URDF or MJCF robot (TOML; see examples/hydro.toml)")
    describe.add_argument(
        "--density", type=_positive, default=None, help="water density for the net buoyancy [kg/m³] (default: the robot's water, else 1000)"
    )
    describe.add_argument("--plot", metavar="FILE", help="save a 3-D picture of the robot at q = 0 (format from the extension)")
    describe.set_defaults(run=_describe)

    export = commands.add_parser(
        "export",
        help="a robot's model as Rust constants or C initializers, for firmware",
        description="Print the robot's validated model as Rust constants of uwml-core's types (--rust) or as C initializers "
        "of the C ABI's structs (--c), every number written so that it reads back to the same float. Without --robot: the "
        "paper's leg.",
    )
    export.add_argument("--robot", metavar="FILE", help="the robot: a uwml model file (.toml), a URDF (.urdf) or an MJCF (.xml)")
    export.add_argument("--hydro", metavar="FILE", help="the hydro file of a URDF or MJCF robot")
    language = export.add_mutually_exclusive_group(required=True)
    language.add_argument("--rust", action="store_true", help="Rust: N_JOINTS, N_SEGMENTS, JOINTS, LINKS, BASE, SEGMENTS")
    language.add_argument("--c", action="store_true", help="C: NAME_JOINTS, NAME_LINKS, NAME_BASE, NAME_SEGMENTS and their counts")
    export.add_argument("--f32", action="store_true", help="single precision (default double)")
    export.add_argument("--name", default="ROBOT", metavar="NAME", help="prefix of the C names (default ROBOT)")
    export.set_defaults(run=_export)

    add_fit_commands(commands, formatter)
    add_study_command(commands, formatter)
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

    replay = commands.add_parser(
        "replay",
        help="simulate the vehicle floating freely while its arm follows a log's joint angles (needs uwml[mujoco])",
        formatter_class=formatter,
        description="""The vehicle's response to a recorded arm motion (uwml.sim.replay; docs/model.md section 12.4):
the description's root floats freely, thrusters off, while the joints follow the log's angles exactly;
the vehicle's pose and twist over time go to replay.csv (or replay.parquet with --parquet) and a figure,
replay.png, in --out. When the log also holds the measured pose (x, y, z and qw, qx, qy, qz or roll,
pitch, yaw), the RMS error of roll, pitch, yaw rate and heave, simulated against measured, is printed
(--json: as JSON). The log's format and how to join streams recorded apart: uwml.sim.replay.""",
        epilog=_EXIT,
    )
    replay.add_argument(
        "log", nargs="+", help="the joint log (CSV or Parquet): time, q1..qN, optionally the vehicle's pose; or one file per stream"
    )
    replay.add_argument("--robot", required=True, metavar="DESCRIPTION", help="the robot's URDF or MJCF file")
    replay.add_argument("--hydro", default=None, metavar="FILE", help="its hydro file")
    replay.add_argument("--out", default="uwml-replay", metavar="DIR", help="directory for the outputs (default uwml-replay)")
    replay.add_argument("--parquet", action="store_true", help="write replay.parquet instead of replay.csv")
    replay.add_argument("--json", action="store_true", help="print the errors (or null) as JSON only")
    replay.set_defaults(run=_replay)
    return parser


def _replay(args: argparse.Namespace) -> int:
    from .sim.replay import command

    return command(args.log, args.robot, args.hydro, args.out, parquet=args.parquet, as_json=args.json)


def _simulate(args: argparse.Namespace) -> int:
    from .study.paper import command

    return command(args.out, args.depths, args.cycles, args.json, ray=args.ray, address=args.address, workers=args.workers)


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; returns the exit status (0 success, 2 bad input, 1 other failures).

    ``--help`` and usage errors raise ``SystemExit`` (status 0 and 2) from argparse; an
    unexpected exception (a bug) propagates with its traceback, which exits with status 1.
    """
    args = build_parser().parse_args(argv)  # --help and usage errors exit here (status 0 and 2)
    try:
        return int(args.run(args))
    except BrokenPipeError:  # the reader of standard output went away (``uwml torques LOG | head``)
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        return 1
    except (ValueError, OSError) as exc:
        print(f"uwml: error: {exc}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("uwml: interrupted", file=sys.stderr)
        return 130
    except ImportError as exc:  # an optional dependency is missing
        print(f"uwml: error: {exc}", file=sys.stderr)
        return 1
    except MemoryError:
        print("uwml: error: out of memory (a log too large for this machine's memory?)", file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main())
