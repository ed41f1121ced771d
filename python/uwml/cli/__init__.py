"""The ``uwml`` command line: :func:`main` (the ``uwml`` program, ``python -m uwml``) and its
commands, one module per group (``uwml <command> --help`` for each):

* :mod:`~uwml.cli.paper_commands`: ``uwml demo`` (the paper leg's torque components along a
  gait-like motion, as a table), ``uwml paper`` (the paper's analysis end to end on built-in
  defaults: figures, report, summary) and ``uwml simulate`` (the paper's leg walking in sea water
  under five controllers, MuJoCo);
* :mod:`~uwml.cli.robot_commands`: ``uwml torques LOG`` (every torque component along a logged
  trajectory, as CSV or Parquet), ``uwml describe`` (a robot in words and drawn), ``uwml export``
  (its model for firmware, C or Rust) and ``uwml replay LOG`` (a vehicle floating while its arm
  follows a log);
* :mod:`~uwml.cli.fit_commands`: ``uwml fit hydro LOG...`` (Cd and Cm, and a robot's hull, from
  land/water experiments) and ``uwml fit losses CSV`` (the oil-drag and seal models from a
  three-configuration experiment);
* :mod:`~uwml.cli.study_commands`: ``uwml study CONFIG`` (a scenario over grids and random
  draws of its parameters, on Ray);
* :mod:`~uwml.cli.example_commands`: ``uwml examples [DIR]`` (the examples that ship with the
  package, copied into ``DIR/examples``).

The arguments' types are :mod:`~uwml.cli.argument_types`'s; what the commands share (the usage
error, the robot of ``--robot``, the help on logs and exit codes) is :mod:`~uwml.cli.common`'s.

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

from .common import _EXIT
from .example_commands import add_example_command
from .fit_commands import add_fit_commands
from .paper_commands import add_paper_commands
from .robot_commands import add_robot_commands
from .study_commands import add_study_command

__all__ = ["build_parser", "main"]


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
    add_paper_commands(commands, formatter)
    add_robot_commands(commands, formatter)
    add_fit_commands(commands, formatter)
    add_study_command(commands, formatter)
    add_example_command(commands, formatter)
    return parser


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
