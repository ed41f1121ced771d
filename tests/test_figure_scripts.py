"""The site's figure scripts (``docs/figures/make_walkthrough.py``, ``docs/figures/make_gallery.py``):
every figure they make is committed under ``docs/figures/`` and shown by its page, and every
figure a page shows from their folders is one they make; the walkthrough's figures are written
by the page's own Python blocks (``tests/test_site_snippets.py`` runs those), the gallery's by
the command lines the page lists, which the command line's parser takes. The pages are in the
site's navigation, the walkthrough first after Getting started."""

import importlib.util
import re
import shlex
from pathlib import Path
from types import ModuleType

import pytest
from test_site_snippets import blocks as fenced_blocks
from uwml.cli import build_parser

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"
#: Each script and the page that shows its figures.
SCRIPTS = {"make_walkthrough.py": "walkthrough.md", "make_gallery.py": "gallery.md"}


def script(name: str) -> ModuleType:
    spec = importlib.util.spec_from_file_location(name.removesuffix(".py"), DOCS / "figures" / name)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def blocks(page: str, language: str) -> list[str]:
    """The page's blocks of ``language``, as tests/test_site_snippets.py reads fenced blocks."""
    return [code for kind, _, code in fenced_blocks(DOCS / page) if kind == language]


@pytest.mark.parametrize(("name", "page"), SCRIPTS.items())
def test_every_figure_a_script_makes_is_committed_and_shown_and_every_figure_shown_is_made(name: str, page: str) -> None:
    module = script(name)
    folder = DOCS / module.FOLDER
    text = (DOCS / page).read_text(encoding="utf-8")
    made = set(module.FIGURES.values())
    assert len(made) == len(module.FIGURES), f"{name}: two figures under one name"
    for figure in sorted(made):
        path = folder / figure
        assert path.is_file(), f"{path.relative_to(ROOT)} is not committed: run python docs/figures/{name}"
        head = path.read_bytes()[:8]
        assert head == b"\x89PNG\r\n\x1a\n" and path.stat().st_size > 10_000, f"{path.relative_to(ROOT)} is not a figure"
        assert f"]({module.FOLDER}/{figure})" in text, f"docs/{page} does not show {module.FOLDER}/{figure}"
    shown = set(re.findall(rf"\]\({re.escape(module.FOLDER)}/([^)]+)\)", text))
    assert shown == made, f"docs/{page} shows figures {name} does not make: {sorted(shown - made)}"
    kept = {path.name for path in folder.iterdir()}
    assert kept == made, f"docs/{module.FOLDER} holds figures {name} does not make: {sorted(kept - made)}"


def test_the_walkthroughs_figures_are_written_by_its_own_blocks() -> None:
    module = script("make_walkthrough.py")
    code = module.python_blocks()
    assert code == blocks("walkthrough.md", "python") and len(code) == 8
    for made in module.FIGURES:
        # A figure of the block's own (savefig, draw, plot_replay), or one of a study's figures.
        first = made.split("/")[0]
        assert any(f'"{first}"' in block for block in code), f"no Python block of docs/walkthrough.md writes {made}"
    assert any('study.figures("vehicle-results")' in block for block in code)


def test_the_gallerys_commands_are_the_pages_and_the_command_line_takes_them() -> None:
    module = script("make_gallery.py")
    (listed,) = blocks("gallery.md", "sh")
    lines = [shlex.split(line) for line in listed.strip().splitlines()]
    assert [words[1:] for words in lines] == module.COMMANDS and all(words[0] == "uwml" for words in lines)
    parser = build_parser()
    for command in module.COMMANDS:
        parser.parse_args(command)
    outputs = {word for command in module.COMMANDS for word in command}
    for made in module.FIGURES:
        assert made.split("/")[0] in outputs, f"no command of docs/gallery.md writes {made}"
    # The inputs the commands read are made by the script.
    for command in module.COMMANDS:
        for word in command:
            if word.endswith((".csv", ".toml")) and not word.startswith("examples/"):
                assert word in module.INPUTS, f"{word} is read by `uwml {' '.join(command)}` but not made"


def test_the_walkthrough_and_the_gallery_are_in_the_navigation() -> None:
    nav = (ROOT / "mkdocs.yml").read_text(encoding="utf-8").split("\nnav:\n", 1)[1].split("\n\n", 1)[0]
    pages = re.findall(r":\s*(\S+\.md)\s*$", nav.split("markdown_extensions:")[0], re.MULTILINE)
    assert pages[:4] == ["index.md", "getting-started.md", "walkthrough.md", "gallery.md"], pages
