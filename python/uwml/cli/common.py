"""What the ``uwml`` commands share: the usage error, the check of an output path, the robot of
``--robot`` and ``--hydro``, a fit's output, and the help texts on logs and exit codes."""

from __future__ import annotations

import json
import os
from pathlib import Path
from typing import Any

from ..errors import UwmlError
from ..io.descriptions import DescriptionParts, mjcf_parts, urdf_parts
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


def print_fit(result: Any, as_json: bool, heading: str) -> int:
    """A fit's output on standard output: its summary as JSON (``--json``), or ``heading`` and its
    report; the exit status, 0."""
    if as_json:
        print(json.dumps(result.summary()))
    else:
        print(heading)
        print(result.fit_report())
    return 0


def load_robot(path: str, hydro: str | None = None) -> Any:
    """The robot of a description file given with ``--robot``: a uwml model file (``.toml``), a
    URDF (``.urdf``) or an MJCF (``.xml``, ``.mjcf``), with ``--hydro`` for the last two."""
    return load_described(path, hydro)[0]


def load_described(path: str, hydro: str | None = None) -> tuple[Robot, DescriptionParts | None]:
    """:func:`load_robot`'s robot, and for a URDF or MJCF its parts (the hydro file's point items
    and mass overrides with them; None for a uwml model file)."""
    suffix = Path(path).suffix.lower()
    if suffix == ".toml":
        if hydro is not None:
            raise _UsageError("--hydro goes with a URDF or MJCF --robot; a uwml model file holds its hydrodynamic parameters")
        return Robot.load(path), None
    if suffix in (".urdf", ".xml", ".mjcf"):
        parts = (urdf_parts if suffix == ".urdf" else mjcf_parts)(path, hydro)
        return parts.build(Robot), parts
    raise ValueError(
        f"{path}: --robot takes a uwml model file (.toml), a URDF (.urdf) or an MJCF (.xml, .mjcf); got a {suffix or 'suffix-less'} file"
    )


def load_robot_floating(path: str, hydro: str | None = None) -> tuple[Any, bool]:
    """The robot of ``--robot`` (:func:`load_robot`) and whether its base floats: a URDF or MJCF
    whose root is on a free joint (an MJCF ``<freejoint/>``, or the hydro file's ``[base]
    floating = true``); a uwml model file with a base body (it holds no such flag: its base body
    is taken for the vehicle)."""
    suffix = Path(path).suffix.lower()
    if suffix not in (".urdf", ".xml", ".mjcf"):
        robot = load_robot(path, hydro)
        return robot, robot.base is not None
    import mujoco

    from ..robot.files import model_and_robot

    model, robot = model_and_robot(path, hydro)
    return robot, any(int(kind) == int(mujoco.mjtJoint.mjJNT_FREE) for kind in model.jnt_type)


_LOG_FORMAT = """Log format (uwml.io.logs, docs/logs.md): CSV with a header row; columns
time [s] (strictly increasing), q1..qN [rad], optionally qd1..qdN [rad/s] and qdd1..qddN
[rad/s²] (else estimated by a Savitzky-Golay filter, which needs uniform sampling), and the
vehicle's x, y, z [m], qw, qx, qy, qz (or roll, pitch, yaw [rad]), twist u, v, w [m/s], p, q, r
[rad/s] (body frame) and its rate u_dot..r_dot; extra columns are ignored. Parquet (.parquet)
holds the same columns. A file recorded with other names, signs, offsets, units or streams:
--columns MAP.toml (docs/logs.md)."""
_EXIT = "Exit status: 0 on success, 2 for usage errors and bad input files (the message names file, row and column), 1 otherwise."
