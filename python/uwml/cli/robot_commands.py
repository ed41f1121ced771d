"""The commands on one robot: ``uwml torques`` (every torque component along a log),
``uwml describe`` (what the robot is made of, drawn), ``uwml export`` (its model for firmware)
and ``uwml replay`` (its vehicle floating while the arm follows a log)."""

from __future__ import annotations

import argparse
import os
import sys
from typing import IO, Any

import numpy as np

from ..domains import MAX_ROBOT_JOINTS
from ..model.parts import SEA_WATER, Water
from ..robot.presets import paper_leg
from ..sim.mujoco import INTEGRATORS
from ..sim.replay_inputs import MAX_GAP_S, SMOOTHING_S, START_WINDOW_S
from .argument_types import _depth, _finite, _n_joints, _non_negative, _positive
from .common import _EXIT, _LOG_FORMAT, _check_output, _UsageError, load_described, load_robot

#: Rows per chunk of ``uwml torques``, which reads, evaluates and writes one chunk at a time;
#: longer inputs report progress on stderr.
CHUNK_ROWS = 100_000


def _vehicle_motion(present: dict[str, tuple[str, ...]], floating: bool, what: str) -> bool:
    """Whether ``uwml torques`` moves the base as the log's vehicle columns say (``present``:
    the vehicle's fields the log has, with their columns; a twist without its rate has it
    estimated), saying so on standard error in one line: the columns used, or, on a fixed
    base, the columns ignored (a warning)."""
    motion = {field: columns for field, columns in present.items() if field in ("base_position", *_MOTION)}
    if not motion:
        return False
    named = "; ".join(", ".join(columns) for columns in motion.values())
    if not floating:
        print(f"uwml torques: warning: {what} has a fixed base (its description does not float it): the log's vehicle columns "
              f"{named} are ignored", file=sys.stderr)  # fmt: skip
        return False
    used = [f"{', '.join(present[field])} ({label})" for field, label in _MOTION.items() if field in present]
    if not used:
        print(f"uwml torques: the log's vehicle position {named} is not used (no orientation or twist columns)", file=sys.stderr)
        return False
    if "base_twist" in present and "base_twist_dot" not in present:
        used.append("its rate estimated (Savitzky-Golay)")
    left = [note for field, note in (("base_orientation", "upright"), ("base_twist", "at rest")) if field not in present]
    unused = ["x, y, z not used"] if "base_position" in present else []
    extra = f" [{'; '.join(left + unused)}]" if left or unused else ""
    print(f"uwml torques: the vehicle's motion from the log's columns {'; '.join(used)}{extra}", file=sys.stderr)
    return True


#: The vehicle's fields that move the base in ``uwml torques``, and what they are.
_MOTION = {"base_orientation": "orientation", "base_twist": "twist", "base_twist_dot": "its rate"}


def _torques(args: argparse.Namespace) -> int:
    from ..io._log_stream import check_log
    from ..io.column_map import load_column_map
    from ..io.logs import log_rows, read_log
    from ..io.vehicle_columns import vehicle_layout
    from ..model.joint_losses import JointLosses
    from ..robot.base_motion import BaseMotion
    from .common import load_robot_floating

    out = args.out
    _check_output(out, "--out")
    parquet = out is not None and out.lower().endswith(".parquet")
    if parquet:
        try:
            import pyarrow
        except ImportError:
            raise _UsageError(f"{out}: Parquet output needs pyarrow (pip install pyarrow); write CSV instead") from None
    leg: Any
    leg, floating = (paper_leg(), False) if args.robot is None else load_robot_floating(args.robot, args.hydro)
    what = "the leg (the paper's)" if args.robot is None else f"the robot ({args.robot})"
    # Coefficients: the paper's fit for its leg; a robot's segments carry their own.
    cd = args.cd if args.cd is not None else (2.2 if args.robot is None else None)
    cm = args.cm if args.cm is not None else (0.5 if args.robot is None else None)
    # The water: the paper's leg at depth moves in sea water; a robot in its own.
    water = SEA_WATER if args.robot is None else None
    expected = leg.n_joints if args.joints is None else args.joints
    chunks: Any
    if args.columns is not None:
        # Through a column map: the log is read whole, its streams joined.
        column_map = load_column_map(args.columns)
        whole = read_log(args.log, expected, columns=column_map).with_derivatives()
        n, n_joints = whole.n_samples, whole.n_joints
        chunks = (log_rows(whole, slice(start, start + CHUNK_ROWS)) for start in range(0, n, CHUNK_ROWS))
        present = vehicle_layout(column_map.targets, column_map.source)
    else:
        # The log is checked (header, time column) here, and read chunk by chunk below.
        checked = check_log(args.log, expected)
        n, n_joints, chunks = checked.count, checked.n_joints, checked.chunks(CHUNK_ROWS)
        present = {field: columns for field, columns in checked.families.items() if field.startswith("base_")}
    moving = _vehicle_motion(present, floating, what)
    if n_joints != leg.n_joints:
        raise ValueError(
            f"{args.log}: row 1 (header), column 'q{min(n_joints, leg.n_joints) + 1}': the log has {n_joints} joints, {what} {leg.n_joints}"
        )
    families = ["drag", "added_mass", "buoyancy"] + (["visc", "seal", "current"] if args.losses else []) + ["total"]
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
            from ..io._arrow_csv import CsvColumnsWriter

            sys.stdout.flush()
            handle = sys.stdout.buffer if partial is None else open(partial, "wb")  # noqa: SIM115
            writer = CsvColumnsWriter(handle, names)
        for log in chunks:
            assert log.qd is not None and log.qdd is not None
            motion = BaseMotion(**log.base_motion()) if moving else None
            tau = leg.environment(
                log.q, log.qd, log.qdd, base=bool(base_names), base_motion=motion,
                depth=args.depth, temperature_c=args.temperature, losses=losses, cd=cd, cm=cm, water=water,
            )  # fmt: skip
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
        if base_names:
            print(
                "uwml torques: base_fx..base_mz: the water's wrench on the robot (drag, added mass and the gross buoyancy; "
                "not the weight), about the base origin in base axes",
                file=sys.stderr,
            )
    return 0


def _export(args: argparse.Namespace) -> int:
    from ..io.export import to_c, to_rust

    robot = load_robot(args.robot, args.hydro) if args.robot else paper_leg()
    source = args.robot or "the paper's leg"
    precision = "f32" if args.f32 else "f64"
    text = to_rust(robot, precision, source=source) if args.rust else to_c(robot, precision, prefix=args.name, source=source)
    sys.stdout.write(text)
    return 0


def _describe(args: argparse.Namespace) -> int:
    from ..viz.describe import describe, draw

    _check_output(args.plot, "--plot")
    robot, parts = load_described(args.robot, args.hydro) if args.robot else (paper_leg(), None)
    water = robot.water if args.density is None else Water(density=args.density, gravity=robot.water.gravity)
    print(describe(robot, water, items=parts.items if parts else (), overrides=parts.overrides if parts else ()))
    if args.plot:
        draw(robot, args.plot, title=f"{args.robot or 'the paper leg'} at q = 0", outlines=parts.outlines if parts else ())
        print(f"\nwrote {args.plot}")
    return 0


def _replay(args: argparse.Namespace) -> int:
    from ..sim.replay import command

    settings = {"smoothing": args.smoothing, "max_gap": args.max_gap, "start_window": args.start_window}
    settings |= {"start_at_rest": args.start_at_rest, "timestep": args.timestep, "integrator": args.integrator, "columns": args.columns}
    return command(args.log, args.robot, args.hydro, args.out, parquet=args.parquet, as_json=args.json, **settings)


def add_robot_commands(commands: Any, formatter: type[argparse.HelpFormatter]) -> None:
    """``uwml torques``, ``uwml describe``, ``uwml export`` and ``uwml replay`` on the ``uwml``
    parser's commands."""
    torques = commands.add_parser(
        "torques",
        help="every torque component along a logged trajectory, as CSV (or Parquet)",
        formatter_class=formatter,
        description=f"""Every torque component of the paper's leg (or of --robot) along the trajectory of LOG.

{_LOG_FORMAT}
Torque columns are not needed.

Output (CSV, to FILE or standard output; Parquet if FILE ends in .parquet): columns time,
drag1..N, added_mass1..N, buoyancy1..N [N·m], with --losses visc1..N, seal1..N [N·m] and
current1..N [A], and total1..N [N·m] (= drag + added mass + buoyancy, + visc + seal with
--losses; the weight, gravity, is not in it). With --robot (a uwml model file, a URDF or an MJCF),
six more columns base_fx..base_mz: the water's force [N] and moment [N·m] on the whole robot, about
the base origin in base axes: drag + added mass + the gross buoyancy ρ V g (with Froude-Krylov),
not net of the weight (base_fz of a vehicle at rest is its buoyancy, upwards). The base moves as the log's vehicle
columns say (orientation, twist u..r and its rate; docs/logs.md) where the robot's base floats (a
free root, or [base] floating = true in its hydro file; a model file with a base body), and
standard error names the columns used; on a fixed base (the paper's leg too) they are named as
ignored. Without them the base is fixed and upright.
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
    torques.add_argument(
        "--columns", metavar="MAP", help="a column map (TOML) to read LOG as recorded: names, signs, offsets, units, streams (docs/logs.md)"
    )
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

    replay = commands.add_parser(
        "replay",
        help="simulate the vehicle floating freely while its arm follows a log's joint angles (needs uwml[mujoco])",
        formatter_class=formatter,
        description="""The vehicle's response to a recorded arm motion (uwml.sim.replay; docs/model.md section 12.4):
the description's root floats freely while the joints follow the log's angles exactly, its thrusters
driven by the log's commands u1..un (one per thruster of the robot, each held until the next sample,
as an ESC holds it) or idle without them; the vehicle's pose and twist over time go to replay.csv (or
replay.parquet with --parquet) and a figure, replay.png, in --out. When the log also holds the measured
pose (x, y, z and qw, qx, qy, qz or roll, pitch, yaw), the RMS error of roll, pitch, yaw rate and heave,
simulated against measured, is printed (--json: as JSON, with the start twist, the thrusters and how the
log was read). A file recorded with other names, signs, offsets, units or in streams is read through a
column map (--columns, docs/logs.md). The log's format and how to join streams recorded apart:
uwml.sim.replay; how it is cleaned (repeated samples collapsed, the joints'
rates from a smoothing fit, gaps, the start twist fitted to the first poses): uwml.sim.replay_inputs
and docs/simulation.md.""",
        epilog=_EXIT,
    )
    replay.add_argument(
        "log",
        nargs="+",
        help="the joint log (CSV or Parquet): time, q1..qN, optionally the vehicle's pose and thruster commands u1..un; or one file "
        "per stream (with --columns: one log, the map's stream without a file)",
    )
    replay.add_argument(
        "--columns", metavar="MAP", help="a column map (TOML) to read LOG as recorded: names, signs, offsets, units, streams (docs/logs.md)"
    )
    replay.add_argument("--robot", required=True, metavar="DESCRIPTION", help="the robot's URDF or MJCF file")
    replay.add_argument("--hydro", default=None, metavar="FILE", help="its hydro file")
    replay.add_argument("--out", default="uwml-replay", metavar="DIR", help="directory for the outputs (default uwml-replay)")
    replay.add_argument("--parquet", action="store_true", help="write replay.parquet instead of replay.csv")
    replay.add_argument(
        "--json", action="store_true", help="print as JSON only: the errors (or null), the start twist, how the log was read"
    )
    replay.add_argument(
        "--smoothing", type=_positive, default=SMOOTHING_S, metavar="S",
        help=f"window of the joints' smoothing fit [s], for their rates and accelerations (default {SMOOTHING_S:g})",
    )  # fmt: skip
    replay.add_argument(
        "--max-gap", type=_positive, default=MAX_GAP_S, metavar="S",
        help=f"longest step between joint samples [s]; gaps in a pose stream are bridged (default {MAX_GAP_S:g})",
    )  # fmt: skip
    replay.add_argument(
        "--start-window", type=_positive, default=START_WINDOW_S, metavar="S",
        help=f"the first poses the start twist is fitted over [s] (default {START_WINDOW_S:g})",
    )  # fmt: skip
    replay.add_argument("--start-at-rest", action="store_true", help="start the vehicle at rest instead of fitting its start twist")
    replay.add_argument(
        "--timestep", type=_positive, default=None, metavar="S", help="the simulation's time step [s] (default the description's)"
    )
    replay.add_argument("--integrator", choices=INTEGRATORS, default="euler", type=str.lower, help="semi-implicit euler (default) or rk4")
    replay.set_defaults(run=_replay)
