"""``uwml fit``: ``fit hydro`` (Cd and Cm, axial drag, lumped models, from a land/water
experiment or a captive test, or with ``--water-only`` from logs of the water run alone),
``fit hull`` (a vehicle's lumped model from free-running logs), ``fit vehicle`` (its hull and trim
from free-floating trials, :mod:`uwml.cli.vehicle_command`) and ``fit losses`` (the joints'
oil-drag and seal models)."""

from __future__ import annotations

import argparse
import json
import os
from pathlib import Path
from typing import Any

from ..fit.loss_regressors import LOSS_TERMS
from ..fit.robot_design import BASE_ROWS, HULL_TERMS
from ..io.sampling import WINDOW_S
from ..robot.presets import paper_leg
from .argument_types import _base_rows, _depth, _finite, _joint_list_or_none, _positive, _workers
from .common import _EXIT, _LOG_FORMAT, _check_output, _UsageError, load_robot, print_fit
from .vehicle_command import add_vehicle_fit


def _fit_hydro(args: argparse.Namespace) -> int:
    from .. import fit

    _check_output(args.plot, "--plot")
    if args.water_only:
        return _fit_water_only(args)
    if args.losses is not None or args.depth != 0.0 or args.temperature != 20.0:
        raise _UsageError("--losses, --depth and --temperature go with --water-only (a land/water experiment's losses cancel)")
    _refuse_water_log(args.logs, args.columns)
    leg: Any = paper_leg() if args.robot is None else load_robot(args.robot, args.hydro)
    what = "the leg (the paper's)" if args.robot is None else f"the robot ({args.robot})"
    joints = ([] if args.base else [1]) if args.joints is None else args.joints
    if any(j > leg.n_joints for j in joints):
        raise _UsageError(f"--joints: {what} has joints 1 to {leg.n_joints}, got {','.join(map(str, joints))}")
    if args.base and args.robot is None:
        raise _UsageError("--base: the paper's leg stands on a fixed base; give the --robot whose base (hull) is fitted")
    if args.no_points and (args.robust or args.plot is not None):
        raise _UsageError("--no-points: a robust fit and the figure need the points (leave out --robust and --plot)")
    if not joints and not args.base:
        raise _UsageError("--joints none: give --base, or at least one joint")
    source: Any = _pair(args.logs, args.columns) or (args.logs[0] if len(args.logs) == 1 else list(args.logs))
    result = fit.hydro_coefficients(
        source,
        leg,
        joints=[j - 1 for j in joints],
        per=args.per,
        robust=args.robust,
        base=args.base,
        lumped=args.lumped,
        on_ray=args.ray or args.address is not None,
        address=args.address,
        workers=args.workers,
        points=not args.no_points,
        columns=args.columns,
    )
    rows = f"joints {','.join(map(str, joints)) or 'none'} (1-based)" + (
        f", base {','.join(BASE_ROWS[c] for c in args.base)}" if args.base else ""
    )
    return _print_hydro(args, result, rows)


def _print_hydro(args: argparse.Namespace, result: Any, rows: str) -> int:
    """``uwml fit hydro``'s output of ``result`` (the figure, the JSON or the report)."""
    if args.plot is not None:
        from ..viz import plot

        plot.hydro_fit_plot(result, args.plot)
    model = "" if args.robot is None else f", --robot {args.robot}"
    print_fit(result, args.json, f"uwml fit hydro: {result.source}{model}, {rows}, per {args.per}")
    if args.plot is not None and not args.json:
        print(f"figure: {args.plot}")
    return 0


def _fit_water_only(args: argparse.Namespace) -> int:
    """``uwml fit hydro --water-only``: :func:`uwml.fit.hydro_from_water_logs`."""
    from .. import fit

    if args.robot is None:
        raise _UsageError(
            "--water-only: give the robot's description, --robot URDF or MJCF (with --hydro): its rigid-body inverse dynamics "
            "stands in for the land run"
        )
    if args.base:
        raise _UsageError("--water-only fits the joints' torques, not --base (a vehicle's hull from free-running logs: uwml fit hull)")
    if args.no_points or args.ray or args.address is not None:
        raise _UsageError("--water-only reads its logs whole in this process: leave out --no-points, --ray and --address")
    joints = None if args.joints is None else [j - 1 for j in args.joints]
    if joints == []:
        raise _UsageError("--joints none: a water-only fit needs at least one joint")
    losses: Any = False if args.losses is None else (args.losses or True)
    source: Any = args.logs[0] if len(args.logs) == 1 else list(args.logs)
    result = fit.hydro_from_water_logs(
        source, args.robot, args.hydro, joints=joints, per=args.per, losses=losses, depth=args.depth,
        temperature_c=args.temperature, lumped=args.lumped, robust=args.robust, columns=args.columns,
    )  # fmt: skip
    numbered = ",".join(str(j + 1) for j in result.joints)
    return _print_hydro(args, result, f"joints {numbered} (1-based), water only, losses {', '.join(result.losses) or 'held'}")


def _refuse_water_log(logs: list[str], columns: str | None) -> None:
    """A single log of the water run alone (``tau*`` without ``tau_land*``) given without
    ``--water-only``: a ValueError saying what to give."""
    from ..io._log_stream import _header
    from ..io.column_map import load_column_map
    from ..io.logs import _layout

    if len(logs) != 1 or not os.path.isfile(logs[0]):
        return
    path = logs[0]
    header = _header(path, path) if columns is None else load_column_map(columns).targets
    try:
        _, families, _ = _layout(header, None, path)
    except ValueError:
        return  # the fit names what is wrong with the header
    if "tau" in families and "tau_land" not in families and "tau_water" not in families:
        raise ValueError(
            f"{path}: row 1 (header), column 'tau_land1': a log of the water run alone (tau1 …): give --water-only with the "
            "robot's description (--robot URDF or MJCF, --hydro), whose rigid-body inverse dynamics stands in for the land run; "
            "or a land log beside it (uwml fit hydro LAND WATER)"
        )


def _fit_hull(args: argparse.Namespace) -> int:
    """``uwml fit hull``: :func:`uwml.fit.hull_from_free_running`."""
    from .. import fit

    source: Any = args.logs[0] if len(args.logs) == 1 else list(args.logs)
    result = fit.hull_from_free_running(
        source, args.robot, args.hydro, terms=args.terms, hydrostatics=args.hydrostatics, hold=args.hold,
        robust=args.robust, columns=args.columns, window_s=args.window,
    )  # fmt: skip
    return print_fit(result, args.json, f"uwml fit hull: {result.source}, --robot {args.robot}, terms {', '.join(args.terms)}")


def _names(allowed: tuple[str, ...] | None) -> Any:
    """An argument type: a comma-separated list of names (of ``allowed``, where given)."""

    def parse(text: str) -> list[str]:
        names = [name.strip() for name in text.split(",") if name.strip()]
        wrong = [name for name in names if allowed is not None and name not in allowed]
        if not names or wrong:
            raise argparse.ArgumentTypeError(f"must be a comma-separated list of {', '.join(allowed or ('names',))}, got {text[:60]!r}")
        return names

    return parse


def _read_losses(path: str, pairs: bool) -> Any:
    """One loss-experiment CSV, its errors naming it."""
    import csv

    from .. import fit
    from ..io._arrow_csv import not_utf8_error
    from ..io.logs import _check_file

    _check_file(path, path)  # no such file, a directory
    try:
        # utf-8-sig: a byte-order mark (Excel's "CSV UTF-8") is skipped.
        with open(path, newline="", encoding="utf-8-sig") as handle:
            return fit.read_loss_csv(handle, pairs)
    except UnicodeDecodeError:
        raise not_utf8_error(lambda: open(path, "rb"), f"{path}: ") from None  # noqa: SIM115 (opened and closed by the callee)
    except csv.Error as exc:
        raise ValueError(f"{path}: not CSV ({exc}; is a quote not closed?)") from None
    except ValueError as exc:
        raise ValueError(f"{path}: {exc}") from None


def _fit_losses(args: argparse.Namespace) -> int:
    import numpy as np

    from .. import fit
    from ..fit.log_set import expand_patterns

    paths = [str(p) for p in expand_patterns(list(args.csv))]
    if args.ray or args.address is not None:
        # Each file read and checked by a Ray worker; the rows fitted here.
        from .._ray import ray_session

        with ray_session(args.address, args.workers) as ray:
            read = ray.remote(_read_losses)
            tables = ray.get([read.remote(path, len(paths) == 1) for path in paths])
    else:
        tables = [_read_losses(path, pairs=len(paths) == 1) for path in paths]
    for path, table in zip(paths, tables, strict=True):
        if ("temperature_c" in table) != ("temperature_c" in tables[0]):
            raise ValueError(f"{path}: row 1 (header), column 'temperature_c': in some files and not in others ({paths[0]})")
    # Several files: their rows, one after the other.
    data = {key: np.concatenate([table[key] for table in tables]) for key in tables[0]}
    source = paths[0] if len(paths) == 1 else f"{paths[0]} and {len(paths) - 1} more files"
    if len(paths) > 1:
        try:
            fit.validate_loss_data(data)  # the pairs of configurations, across the files
        except ValueError as exc:
            raise ValueError(f"{source}, their rows one after the other: {exc}") from None
    args.csv = source
    results: dict[str, Any] = {}
    for name, function in (("oil_drag", fit.oil_drag), ("seal", fit.seal)):
        try:
            results[name] = function(data)
        except ValueError as exc:
            raise ValueError(f"{args.csv}: {name} fit: {exc}") from None
    figures = []
    if args.plot is not None:
        from ..viz import plot

        directory = Path(args.plot)
        directory.mkdir(parents=True, exist_ok=True)
        for name, result in results.items():
            figures.append(directory / f"{name}_fit.png")
            plot.fit_plot(result, figures[-1])
    if args.json:
        print(json.dumps({name: result.summary() for name, result in results.items()}))
    else:
        for name, result in results.items():
            print(f"uwml fit losses: {args.csv}, {name.replace('_', ' ')} model")
            print(result.fit_report())
            print()
        for figure in figures:
            print(f"figure: {figure}")
    return 0


def _pair(logs: list[str], columns: str | None = None) -> tuple[str, str] | None:
    """Two logs of one environment each (``tau*`` columns, not ``tau_land*``; or a column map
    ``columns`` giving those): a (land, water) pair; anything else: None."""
    from ..io._log_stream import _header
    from ..io.column_map import load_column_map
    from ..io.logs import _check_file, _layout

    if len(logs) != 2 or not all(os.path.isfile(path) for path in logs):
        return None
    mapped = None if columns is None else load_column_map(columns)
    for path in logs:
        _check_file(path, path)
        header = _header(path, path) if mapped is None else mapped.targets
        _, families, _ = _layout(header, None, path if mapped is None else mapped.source)
        if "tau" not in families and "wrench" not in families:
            return None
    return logs[0], logs[1]


def add_fit_commands(commands: Any, formatter: type[argparse.HelpFormatter]) -> None:
    """``uwml fit hydro``, ``uwml fit hull``, ``uwml fit vehicle`` and ``uwml fit losses`` on the
    ``uwml`` parser's commands."""
    fit_parser = commands.add_parser(
        "fit",
        help="identify Cd, Cm (fit hydro), a hull from free running (fit hull) or free floating (fit vehicle), or the joint-loss "
        "models (fit losses) from files",
    )
    fits = fit_parser.add_subparsers(dest="fit_command", required=True)
    hydro = fits.add_parser(
        "hydro",
        help="Cd and Cm from a land/water experiment",
        formatter_class=formatter,
        description=f"""Cd and Cm of the paper's leg (or of --robot, on a fixed base) from a land/water
experiment (uwml.fit.hydro_coefficients): weighted linear least squares of
-(tau_water - tau_land) - buoyancy against the drag and added-mass regressors (the paper's
eqs. 23-24). With --robot, --per link gives one Cd and Cm per link named after it (cd_<link>),
and the robot's axial drag and lumped models are fitted too (uwml.fit.robot_design).

Input: logs of both runs (columns tau_land1..N and tau_water1..N): one, several, or glob
patterns (quoted: 'dives/*.parquet'), fitted together with each log's diagnostics (rows,
residual RMS, the logs whose own fit disagrees with the pooled one by more than 3 sigma); files
over 64 MiB are read chunk by chunk on every pass, in bounded memory. Or two logs (land, then
water) of one run each (columns tau1..N), paired by time. With --base, a
captive test of the robot's base (its hull) on a rig: the rig's wrench on the base
(fx_land..mz_land and fx_water..mz_water, or fx..mz: force [N], moment [N·m] about the body
origin, body components), the vehicle's twist u, v, w [m/s], p, q, r [rad/s] (body frame; its
rate u_dot..r_dot estimated where absent) and orientation qw, qx, qy, qz or roll, pitch, yaw
(upright where absent); docs/logs.md. With --water-only, logs of the water run alone (tau1..N,
no land run): the --robot description's rigid-body inverse dynamics (MuJoCo's mj_inverse,
gravity on) stands in for the land run, and --losses fits the joints' loss levels (oil k_oil,
seal c0, s0, d0) at --depth and --temperature too (uwml.fit.hydro_from_water_logs).

{_LOG_FORMAT}

Output: the fit report (value +/- standard error, reduced chi-square, COD, AIC/BIC,
correlations) on standard output; with --json only the result's summary as JSON (keys params,
stderr, covar, redchi, rsquared, ..., points); with --plot the measured and fitted torque
(cf. Fig. 7) as an image.""",
        epilog=_EXIT,
    )
    hydro.add_argument(
        "logs",
        metavar="LOG",
        nargs="+",
        help="logs of both runs (files or glob patterns, fitted together), or a land log and a water log of one run each",
    )
    hydro.add_argument(
        "--joints",
        type=_joint_list_or_none,
        default=None,
        metavar="1,2,3",
        help="joints to fit, numbered from 1, or none (default 1, the paper's hip yaw; none with --base)",
    )
    hydro.add_argument(
        "--base",
        type=_base_rows,
        default=[],
        metavar="fx,fy,...",
        help="the base wrench's components to fit too (fx, fy, fz, mx, my, mz, or all): a captive test of a --robot's hull",
    )
    hydro.add_argument(
        "--lumped",
        choices=("diagonal", "full", "given"),
        default="diagonal",
        help="which entries of the lumped models to fit: their diagonals (default), all 63, or those not zero in the model",
    )
    hydro.add_argument(
        "--per",
        choices=("leg", "link", "direction"),
        default="leg",
        help="one Cd and Cm (for the whole leg or robot); one per link; one per link and direction",
    )
    hydro.add_argument(
        "--robot", metavar="FILE", help="the robot: a uwml model file (.toml), a URDF (.urdf) or an MJCF (.xml); default the paper's leg"
    )
    hydro.add_argument("--hydro", metavar="FILE", help="the hydro file of a URDF or MJCF robot")
    hydro.add_argument("--robust", action="store_true", help="Huber loss instead of squares (resists outliers)")
    hydro.add_argument(
        "--columns", metavar="MAP", help="a column map (TOML) each LOG is read through, whole: names, signs, offsets, units (docs/logs.md)"
    )
    hydro.add_argument(
        "--no-points",
        action="store_true",
        help="keep no per-point arrays (the statistics from sums over the logs): bounded memory for many or long logs; "
        "not with --robust or --plot",
    )
    hydro.add_argument("--ray", action="store_true", help="share the logs out among the workers of a local Ray (docs/scale.md)")
    hydro.add_argument("--address", metavar="ADDR", help="a Ray cluster's address (auto, or ray://host:10001): the logs' workers there")
    hydro.add_argument("--workers", type=_workers, metavar="N", help="CPUs of the local Ray (default all)")
    hydro.add_argument("--json", action="store_true", help="print the result's summary as JSON only")
    hydro.add_argument("--plot", metavar="FILE", help="save the measured-vs-fitted figure (format from the extension, e.g. .png)")
    hydro.add_argument(
        "--water-only",
        action="store_true",
        help="logs of the water run alone (tau1..N): the --robot description's rigid-body inverse dynamics (MuJoCo) stands in "
        "for the land run (uwml.fit.hydro_from_water_logs; default joints: all)",
    )
    hydro.add_argument(
        "--losses",
        nargs="?",
        const=[],
        type=_names(LOSS_TERMS),
        metavar="k_oil,c0,s0,d0",
        help="with --water-only: fit these loss levels on each joint too (alone: k_oil,c0,s0); the others held at the "
        "description's losses (docs/losses.md)",
    )
    hydro.add_argument(
        "--depth", type=_depth, default=0.0, metavar="M", help="with --water-only: depth of the losses' pressure [m] (default 0)"
    )
    hydro.add_argument(
        "--temperature", type=_finite, default=20.0, metavar="C", help="with --water-only: oil temperature [°C] (default 20)"
    )
    hydro.set_defaults(run=_fit_hydro)

    hull = fits.add_parser(
        "hull",
        help="a vehicle's hull (lumped model) from free-running logs and its thruster commands",
        formatter_class=formatter,
        description=f"""The diagonals of the base's lumped model (added mass, linear and quadratic damping) and
optionally its buoyancy (rho V, rho V r_B) from logs of the vehicle running free
(uwml.fit.hull_from_free_running): the thruster commands u1..un through each thruster's curve and
the allocation give the thrust; MuJoCo's inverse dynamics of the --robot description gives the
rigid-body part; equation-error weighted least squares of the base's six equations. Terms the
data do not determine are refused by name; a negative damping, added mass or volume is warned
of by name.

Input: logs with time, q1..qN (the arm, still or moving), the orientation qw, qx, qy, qz (or
roll, pitch, yaw), the twist u, v, w, p, q, r (its rate u_dot..r_dot estimated where absent) and
one command u1..un per thruster of the description (docs/logs.md).

{_LOG_FORMAT}

Output: the fit report on standard output; with --json only the result's summary as JSON.""",
        epilog=_EXIT,
    )
    hull.add_argument("logs", metavar="LOG", nargs="+", help="free-running logs (files or glob patterns, fitted together)")
    hull.add_argument("--robot", required=True, metavar="FILE", help="the vehicle: a URDF (.urdf) or MJCF (.xml), floated")
    hull.add_argument("--hydro", metavar="FILE", help="its hydro file (the lumped model and the thrusters)")
    hull.add_argument(
        "--terms",
        type=_names(HULL_TERMS),
        default=list(HULL_TERMS),
        metavar="added_mass,...",
        help="the lumped model's families whose diagonals are fitted (default all three)",
    )
    hull.add_argument("--hydrostatics", action="store_true", help="fit the base's rho V and rho V r_B too")
    hull.add_argument(
        "--hold",
        type=_names(None),
        default=[],
        metavar="NAME,...",
        help="terms held at the description's values, as the report names them (quoted: 'base.linear_damping[1][1]')",
    )
    hull.add_argument("--robust", action="store_true", help="Huber loss instead of squares (resists outliers)")
    hull.add_argument(
        "--window",
        type=_positive,
        default=WINDOW_S,
        metavar="S",
        help=f"the smoothing fit's window for absent rates [s] (default {WINDOW_S:g})",
    )
    hull.add_argument("--columns", metavar="MAP", help="a column map (TOML) each LOG is read through (docs/logs.md)")
    hull.add_argument("--json", action="store_true", help="print the result's summary as JSON only")
    hull.set_defaults(run=_fit_hull)

    add_vehicle_fit(fits, formatter)

    losses = fits.add_parser(
        "losses",
        help="the oil-drag and seal loss models from a three-configuration experiment",
        formatter_class=formatter,
        description="""The oil-drag and dynamic-seal models (uwml.fit.oil_drag and uwml.fit.seal) from the paper's
three-configuration experiment (docs/losses.md).

Input: CSV with columns configuration (dry, oil or oil_seal), speed_rpm, pressure_mpa,
current_a, optionally startup (0/1) and temperature_c; the default drive (uwml.Drive()).

Output: both fit reports on standard output; with --json only {"oil_drag": summary,
"seal": summary} as JSON; with --plot DIR the figures oil_drag_fit.png and seal_fit.png.""",
        epilog=_EXIT,
    )
    losses.add_argument("csv", metavar="CSV", nargs="+", help="loss-experiment CSV files or glob patterns (their rows fitted together)")
    losses.add_argument("--json", action="store_true", help="print both results' summaries as JSON only")
    losses.add_argument("--ray", action="store_true", help="read the files on the workers of a local Ray (docs/scale.md)")
    losses.add_argument("--address", metavar="ADDR", help="read the files on the Ray cluster at this address")
    losses.add_argument("--workers", type=_workers, metavar="N", help="CPUs of the local Ray (default all)")
    losses.add_argument("--plot", metavar="DIR", help="directory for the fit figures (created if needed)")
    losses.set_defaults(run=_fit_losses)
