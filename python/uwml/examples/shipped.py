"""The files that ship with the package (the :mod:`uwml.examples` table) and the robots made from
them."""

from __future__ import annotations

from importlib import resources
from pathlib import Path

from ..robot.tree import Robot

__all__ = ["bluerov2", "my_arm", "names", "path"]

#: Where the files are: the package's data folder (the repository's examples/ links to it).
_PACKAGE, _FOLDER = "uwml.examples", "data"


def names() -> tuple[str, ...]:
    """The examples :func:`path` finds: the folders and files of the package's data folder."""
    here = resources.files(_PACKAGE).joinpath(_FOLDER)
    return tuple(sorted(entry.name for entry in here.iterdir() if not entry.name.startswith(("_", "."))))


def path(name: str, *parts: str) -> Path:
    """The installed example ``name`` (a folder or file, :func:`names`), or a file in it
    (``path("bluerov2", "bluerov2_arm.urdf")``): a real path, readable by any tool."""
    if not isinstance(name, str) or name not in names():
        raise ValueError(f"no example {name!r}; the examples are {', '.join(names())}")
    found = Path(str(resources.files(_PACKAGE).joinpath(_FOLDER).joinpath(name, *parts)))
    if not found.exists():
        raise ValueError(f"example {name!r} has no {'/'.join(parts)!r}")
    return found


def bluerov2() -> Robot:
    """The BlueROV2 Heavy with its 2-joint arm, from its URDF and hydro file (``path("bluerov2")``)."""
    from ..robot.files import from_urdf

    return from_urdf(path("bluerov2", "bluerov2_arm.urdf"), path("bluerov2", "bluerov2_arm.hydro.toml"))


def my_arm() -> Robot:
    """The 4-joint arm of ``path("my_arm")``, from its URDF and hydro file."""
    from ..robot.files import from_urdf

    return from_urdf(path("my_arm", "my_arm.urdf"), path("my_arm", "my_arm.hydro.toml"))
