"""Hostile robot descriptions: what ``test_adversarial_descriptions*.py`` share (the URDF and
MJCF pieces they build files of, and the check of a refusal: a short DescriptionError naming the
file)."""

from __future__ import annotations

import re
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest
import uwml

DATA = Path(__file__).parent / "data"
MAX_MESSAGE = 500

INERTIAL = '<inertial><mass value="{mass}"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>'


def link(name: str, mass: float | str | None = 1.0, collision: str = '<box size="0.1 0.2 0.3"/>') -> str:
    inertial = "" if mass is None else INERTIAL.format(mass=mass)
    geometry = f"<collision><geometry>{collision}</geometry></collision>" if collision else ""
    return f'<link name="{name}">{inertial}{geometry}</link>'


def joint(name: str, parent: str, child: str, kind: str = "continuous", extra: str = "") -> str:
    return (
        f'<joint name="{name}" type="{kind}"><parent link="{parent}"/><child link="{child}"/>'
        f'<origin xyz="0.2 0 0"/><axis xyz="0 0 1"/>{extra}</joint>'
    )


def urdf(*parts: str) -> str:
    return '<robot name="r">' + "".join(parts) + "</robot>"


ARM = urdf(link("base", 2.0), link("upper"), link("fore"), joint("shoulder", "base", "upper"), joint("elbow", "upper", "fore"))

MJCF = """<mujoco><worldbody><body name="base"><inertial pos="0 0 0" mass="{mass}" diaginertia="1 1 1"/><geom size="0.1"/>
<body name="arm"><joint name="shoulder"/><geom type="box" size="0.1 0.2 0.3"/></body></body></worldbody></mujoco>"""


def write(tmp_path: Path, name: str, text: str | bytes) -> Path:
    path = tmp_path / name
    if isinstance(text, bytes):
        path.write_bytes(text)
    else:
        path.write_text(text)
    return path


def refused(load: Callable[[], Any], *names: str, match: str = "") -> str:
    """The message of the DescriptionError ``load()`` raises: short, naming one of the files."""
    with pytest.raises(uwml.DescriptionError) as info:
        load()
    message = str(info.value)
    assert len(message) < MAX_MESSAGE, (len(message), message[:300])
    assert any(name in message for name in names), (names, message)
    assert re.search(match, message), (match, message)
    return message
