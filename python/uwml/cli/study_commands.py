"""``uwml study CONFIG.toml``: a study's runs on Ray (or serially), its results, figures and
summary (:mod:`uwml.study`)."""

from __future__ import annotations

import argparse
import json
from typing import Any

from .argument_types import _workers
from .common import _EXIT


def _study(args: argparse.Namespace) -> int:
    from .. import study
    from ..study.runner import progress_bar
    from ..study.study_results import axis_label

    config = study.load(args.config)  # every key checked before anything runs
    outcome = study.run_study(
        config, args.out, address=args.address, serial=args.serial, workers=args.workers, resume=args.resume,
        progress=None if args.json else progress_bar,
    )  # fmt: skip
    written = [] if args.no_figures else study.figures(args.out)
    result = study.summary(args.out) | {"ran": outcome.ran, "skipped": outcome.skipped}
    if args.json:
        print(json.dumps(result))
        return 0
    lost = f" ({result['lost']} lost by Ray, not by the run: --resume runs them again)" if result["lost"] else ""
    print(
        f"uwml study: {config.source}, {result['runs']} runs: {outcome.ran} run now, {outcome.skipped} done before, {result['failed']} failed{lost}"
    )
    # Per group of runs (the categorical parameters' values: a controller), not averaged across them.
    grouped = [group for group in result["groups"] if group["parameters"]]
    for group in grouped or [{"parameters": {}, "runs": result["done"], "metrics": result["metrics"]}]:
        if grouped:
            said = ", ".join(f"{name} = {value}" for name, value in group["parameters"].items())
            print(f"\n{said} ({group['runs']} runs{', ' + str(group['failed']) + ' failed' if group['failed'] else ''})")
        print(f"{'metric':>30} {'mean':>12} {'min':>12} {'max':>12}")
        for name, values in group["metrics"].items():
            cells = " ".join(f"{'—' if values[k] is None else format(values[k], '.5g'):>12}" for k in ("mean", "min", "max"))
            print(f"{axis_label(name, result['units'][name]):>30} {cells}")
    print(f"results: {args.out}/runs/*.parquet (uwml.study.read_results){'; figures: ' + str(args.out) + '/figures/' if written else ''}")
    return 0


def add_study_command(commands: Any, formatter: type[argparse.HelpFormatter]) -> None:
    """``uwml study`` on the ``uwml`` parser's commands."""
    parser = commands.add_parser(
        "study",
        help="simulate a scenario over grids and random draws of its parameters, on Ray",
        formatter_class=formatter,
        description="""A study (uwml.study, docs/scale.md): the runs a TOML file names (a scenario, grids and
distributions of its parameters, a seed), each a Ray task: on a local Ray started for the
study (--workers CPUs, default all), on a cluster (--address), or serially (--serial).

Output in --out: runs/part-*.parquet (one row per run: its parameters, its metrics, its error
if it failed), written as batches finish, so that a study that stops keeps what it finished
and --resume runs only the rest, and the runs Ray lost (not those that failed by themselves);
study.json (the study's fingerprint, its robot files' digests: --resume refuses another study,
or a robot file that changed); study.lock (one process at a time); figures/<metric>.png (each
metric, in its unit, against each parameter, the runs coloured by the values of the categorical
parameters, a controller). A summary on standard output, per group of runs sharing those values
(--json: as JSON, "groups" and the mean over all runs, "metrics").""",
        epilog=_EXIT,
    )
    parser.add_argument("config", metavar="CONFIG", help="the study's TOML file")
    parser.add_argument("--out", default="uwml-study", metavar="DIR", help="output directory (default uwml-study)")
    parser.add_argument("--address", metavar="ADDR", help="a Ray cluster's address (auto, or ray://host:10001); default a local Ray")
    parser.add_argument("--workers", type=_workers, metavar="N", help="CPUs of the local Ray (default all)")
    parser.add_argument("--serial", action="store_true", help="run here, one run after the other, without Ray")
    parser.add_argument("--resume", action="store_true", help="run only the runs --out lacks, and those Ray lost")
    parser.add_argument("--no-figures", action="store_true", help="skip the figures")
    parser.add_argument("--json", action="store_true", help="print the summary as JSON only")
    parser.set_defaults(run=_study)
