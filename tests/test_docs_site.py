"""The documentation site (mkdocs.yml, built strictly by .ci/run): every page of the docs folder is
in its navigation, and every name its Python reference renders has a docstring, as have their
public methods and properties."""

import importlib
import inspect
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
REFERENCE = (ROOT / "docs/reference/python.md").read_text(encoding="utf-8")
NAMES = re.findall(r"^::: ([\w.]+)$", REFERENCE, re.MULTILINE)


def _object(dotted: str) -> object:
    module, _, name = dotted.rpartition(".")
    return getattr(importlib.import_module(module), name)


def test_every_page_is_in_the_navigation() -> None:
    config = (ROOT / "mkdocs.yml").read_text(encoding="utf-8")
    pages = {str(path.relative_to(ROOT / "docs")) for path in (ROOT / "docs").rglob("*.md")}
    listed = set(re.findall(r":\s+([\w/.-]+\.md)\s*$", config, re.MULTILINE))
    assert pages == listed, (pages - listed, listed - pages)


@pytest.mark.parametrize("dotted", NAMES)
def test_every_name_of_the_reference_has_docstrings(dotted: str) -> None:
    thing = _object(dotted)
    assert inspect.getdoc(thing), f"{dotted} has no docstring"
    if inspect.isclass(thing):
        for name, member in vars(thing).items():
            if name.startswith("_"):
                continue
            function = member.fget if isinstance(member, property) else getattr(member, "__func__", member)
            if inspect.isfunction(function):
                assert inspect.getdoc(function), f"{dotted}.{name} has no docstring"
