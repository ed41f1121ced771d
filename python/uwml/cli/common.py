"""What the ``uwml`` commands share: the usage error, the check of an output path, the robot of
``--robot`` and ``--hydro``, and the help texts on logs and exit codes."""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

from ..errors import UwmlError
from ..robot.tree import Robot


class _UsageError(UwmlError):
    """A bad combination of options (exit code 2)."""


def _check_output(path: str | None, option: str) -> None:
    """An output file can be written where ``option`` says, before any work (else a usage error)."""
    if path is None:
        return
    if os.path.isdir(path):
        raise _UsageError(f"{path}: is a directory; {option} takes a file")
    folder = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(folder):
        raise _UsageError(f"{path}: no such directory: {folder}")


def load_robot(path: str, hydro: str | None = None) -> Any:
    """The robot of a description file given with ``--robot``: a uwml model file (``.toml``), a
    URDF (``.urdf``) or an MJCF (``.xml``, ``.mjcf``), with ``--hydro`` for the last two."""
    suffix = Path(path).suffix.lower()
    if suffix == ".toml":
        if hydro is not None:
            raise _UsageError("--hydro goes with a URDF or MJCF --robot; a uwml model file holds its hydrodynamic parameters")
        return Robot.load(path)
    if suffix == ".urdf":
        return Robot.from_urdf(path, hydro=hydro)
    if suffix in (".xml", ".mjcf"):
        return Robot.from_mjcf(path, hydro=hydro)
    raise ValueError(
        f"{path}: --robot takes a uwml model file (.toml), a URDF (.urdf) or an MJCF (.xml, .mjcf); got a {suffix or 'suffix-less'} file"
    )


_LOG_FORMAT = """Log format (uwml.io.logs, docs/identification.md): CSV with a header row; columns
time [s] (strictly increasing), q1..qN [rad], optionally qd1..qdN [rad/s] and qdd1..qddN
[rad/s²] (else estimated by a Savitzky-Golay filter, which needs uniform sampling); extra
columns are ignored. Parquet (.parquet) holds the same columns."""
_EXIT = "Exit status: 0 on success, 2 for usage errors and bad input files (the message names file, row and column), 1 otherwise."
