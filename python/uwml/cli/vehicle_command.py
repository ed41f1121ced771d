"""``uwml fit vehicle``: a free-floating vehicle's hull and trim from pool trials with the arm moving
and the thrusters off, by output error with the replay in the loop
(:func:`uwml.sim.free_floating.vehicle_from_trials`)."""

from __future__ import annotations

import argparse
import math
from typing import Any

from ..fit.vehicle_parameters import COB_OFFSET_BOUND, VEHICLE_PARAMETERS
from ..sim.mujoco import INTEGRATORS
from ..sim.replay_inputs import MAX_GAP_S, SMOOTHING_S, START_WINDOW_S
from .argument_types import _positive, _quoted, _workers
from .common import _EXIT, print_fit


def _parameter_list(text: str) -> list[str]:
    """``--params``: a comma-separated list of :data:`VEHICLE_PARAMETERS`."""
    names = [name.strip() for name in text.split(",") if name.strip()]
    wrong = [name for name in names if name not in VEHICLE_PARAMETERS]
    if not names or wrong:
        raise argparse.ArgumentTypeError(f"must be a comma-separated list of {', '.join(VEHICLE_PARAMETERS)}, got {_quoted(text)}")
    return names


def _bound(text: str) -> tuple[str, tuple[float, float]]:
    """``--bounds NAME=LOW:HIGH`` (``inf`` and ``-inf`` allowed)."""
    name, _, pair = text.partition("=")
    low, _, high = pair.partition(":")
    try:
        values = (float(low), float(high))
    except ValueError:
        values = (math.nan, math.nan)
    if name.strip() not in VEHICLE_PARAMETERS or any(math.isnan(v) for v in values):
        raise argparse.ArgumentTypeError(f"must be NAME=LOW:HIGH with NAME one of the parameters (--params), got {_quoted(text)}")
    return name.strip(), values


def _start(text: str) -> tuple[str, float]:
    """``--start NAME=VALUE``."""
    name, _, value = text.partition("=")
    try:
        number = float(value)
    except ValueError:
        number = math.nan
    if name.strip() not in VEHICLE_PARAMETERS or not math.isfinite(number):
        raise argparse.ArgumentTypeError(f"must be NAME=VALUE with NAME one of the parameters (--params), got {_quoted(text)}")
    return name.strip(), number


def _fit_vehicle(args: argparse.Namespace) -> int:
    """``uwml fit vehicle``: :func:`uwml.sim.free_floating.vehicle_from_trials`."""
    from ..sim.free_floating import vehicle_from_trials

    settings: dict[str, Any] = {
        "smoothing": args.smoothing, "max_gap": args.max_gap, "start_window": args.start_window, "timestep": args.timestep,
        "integrator": args.integrator, "columns": args.columns, "sigma": args.sigma, "fit_start": not args.no_fit_start,
    }  # fmt: skip
    result = vehicle_from_trials(
        args.trials, args.robot, args.hydro, parameters=args.params, bounds=dict(args.bounds), start=dict(args.start),
        test=args.test, on_ray=args.ray, address=args.address, workers=args.workers, **settings,
    )  # fmt: skip
    return print_fit(result, args.json, f"uwml fit vehicle: {result.source}, --robot {args.robot}, parameters {', '.join(args.params)}")


def add_vehicle_fit(fits: Any, formatter: type[argparse.HelpFormatter]) -> None:
    """``uwml fit vehicle`` on ``uwml fit``'s commands."""
    vehicle = fits.add_parser(
        "vehicle",
        help="a free-floating vehicle's hull damping, added mass and trim from trials with the arm moving, thrusters off",
        formatter_class=formatter,
        description=f"""The hull's chosen parameters from pool trials of the vehicle floating free, its thrusters
off, while the arm moves (uwml.sim.free_floating.vehicle_from_trials; docs/identification.md):
each trial is replayed as uwml replay replays it (the joints follow the log, the vehicle starts
from a state fitted over --start-window) with the parameters in the hull, and the simulated roll
and pitch are fitted to the measured ones by bounded nonlinear least squares; standard errors
from the Jacobian (forward differences, each column a replay) at the optimum. Each training
trial's start roll, pitch and twist are fitted too unless --no-fit-start. Trials given to
--test are held out: replayed with the described and the fitted parameters.

Parameters (--params): added_mass[i], linear_damping[i] and quadratic_damping[i], the
diagonal entries of the base's lumped model (i = 0 .. 5: x, y, z, roll, pitch, yaw; bounds
[0, inf) by default); cob_x, cob_y, cob_z, the offset of the hull's centre of buoyancy from the
description's [m] (default bounds +/-{COB_OFFSET_BOUND:g}); volume, its displaced volume [m³] (at least 0).

Input: trials (CSV or Parquet) with time, q1..qN and the vehicle's pose x, y, z and qw, qx,
qy, qz (or roll, pitch, yaw); or read through a column map (--columns, docs/logs.md).

Output: the fit report (value +/- standard error, statistics, correlations, bounds, each trial's
RMS of roll and pitch with the described and the fitted parameters); with --json only the
result's summary as JSON.""",
        epilog=_EXIT,
    )
    vehicle.add_argument("trials", metavar="TRIAL", nargs="+", help="the trials fitted (files or glob patterns)")
    vehicle.add_argument("--robot", required=True, metavar="FILE", help="the vehicle: a URDF (.urdf) or MJCF (.xml), floated")
    vehicle.add_argument("--hydro", metavar="FILE", help="its hydro file (the hull's lumped model)")
    vehicle.add_argument(
        "--params",
        required=True,
        type=_parameter_list,
        metavar="NAME,...",
        help="the parameters fitted (quoted: 'linear_damping[3],cob_z')",
    )
    vehicle.add_argument("--test", nargs="+", action="extend", default=[], metavar="TRIAL", help="trials held out (files or glob patterns)")
    vehicle.add_argument(
        "--bounds", type=_bound, action="append", default=[], metavar="NAME=LOW:HIGH", help="a parameter's bounds (repeat for several)"
    )
    vehicle.add_argument(
        "--start", type=_start, action="append", default=[], metavar="NAME=VALUE", help="a parameter's start (default the description's)"
    )
    vehicle.add_argument("--sigma", type=_positive, metavar="RAD", help="standard error of a measured angle [rad] (default: estimated)")
    vehicle.add_argument("--no-fit-start", action="store_true", help="replay from the window's start state, without fitting it")
    vehicle.add_argument(
        "--start-window", type=_positive, default=START_WINDOW_S, metavar="S",
        help=f"the first poses the start state is fitted over [s] (default {START_WINDOW_S:g})",
    )  # fmt: skip
    vehicle.add_argument(
        "--smoothing", type=_positive, default=SMOOTHING_S, metavar="S", help=f"the joints' smoothing window [s] (default {SMOOTHING_S:g})"
    )
    vehicle.add_argument(
        "--max-gap", type=_positive, default=MAX_GAP_S, metavar="S", help=f"longest step between joint samples [s] (default {MAX_GAP_S:g})"
    )
    vehicle.add_argument("--timestep", type=_positive, metavar="S", help="the replays' time step [s] (default the description's)")
    vehicle.add_argument("--integrator", choices=INTEGRATORS, default="euler", type=str.lower, help="semi-implicit euler (default) or rk4")
    vehicle.add_argument("--columns", metavar="MAP", help="a column map (TOML) each TRIAL is read through (docs/logs.md)")
    vehicle.add_argument("--ray", action="store_true", help="replay on the workers of a local Ray (docs/scale.md)")
    vehicle.add_argument("--address", metavar="ADDR", help="a Ray cluster's address: the replays' workers there")
    vehicle.add_argument("--workers", type=_workers, metavar="N", help="CPUs of the local Ray (default all)")
    vehicle.add_argument("--json", action="store_true", help="print the result's summary as JSON only")
    vehicle.set_defaults(run=_fit_vehicle)
