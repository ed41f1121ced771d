"""``uwml examples [DIR]``: copies the examples that ship with the package (:mod:`uwml.examples`)
into ``DIR/examples``, so that the site's command lines run as written from any folder."""

from __future__ import annotations

import argparse
import shutil
from pathlib import Path
from typing import Any

from .common import _EXIT


def _examples(args: argparse.Namespace) -> int:
    from ..examples import names, path

    target = Path(args.dir) / "examples"
    clashes = [name for name in names() if (target / name).exists()]
    if clashes and not args.force:
        raise ValueError(f"{target} already holds {', '.join(clashes)}: give another DIR, or --force to replace them")
    target.mkdir(parents=True, exist_ok=True)
    for name in names():
        source, destination = path(name), target / name
        if source.is_dir():
            shutil.copytree(source, destination, dirs_exist_ok=True, ignore=shutil.ignore_patterns("__pycache__"))
        else:
            shutil.copy2(source, destination)
    print(f"uwml examples: {', '.join(names())} copied into {target}")
    return 0


def add_example_command(commands: Any, formatter: type[argparse.HelpFormatter]) -> None:
    """``uwml examples`` on the ``uwml`` parser's commands."""
    parser = commands.add_parser(
        "examples",
        help="copy the examples that ship with uwml (robots, logs, study files) into DIR/examples",
        formatter_class=formatter,
        description="""The examples that ship with the package (uwml.examples: the BlueROV2 with its arm and
thrusters, a 2-joint arm with a land/water log, a hydro file with every key, study files),
copied into DIR/examples (default: the current folder), where the documentation's command
lines find them (uwml describe --robot examples/my_arm/my_arm.urdf ...). In Python,
uwml.examples.path("my_arm") finds them where they are installed. Files already there are
refused unless --force.""",
        epilog=_EXIT,
    )
    parser.add_argument("dir", nargs="?", default=".", metavar="DIR", help="where to put the examples/ folder (default .)")
    parser.add_argument("--force", action="store_true", help="replace examples already in DIR/examples")
    parser.set_defaults(run=_examples)
