"""The documentation site (mkdocs.yml, built strictly by .ci/run): every page of the docs folder is
in its navigation; every name its Python reference renders has a docstring, as have their
public methods and properties, and those docstrings render cleanly (no reStructuredText literal
``::``, no paragraph taken for a section's item); the C API's page renders every constant, type,
field and function of the header from its doc comments; the conventions' figures come from
their script and are shown. The file formats page has its own test (test_formats_page.py)."""

import importlib
import inspect
import re
import subprocess
import sys
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


def _documented(thing: object, where: str) -> list[tuple[str, str]]:
    """``(name, docstring)`` of a rendered object and of its public methods and properties, as the
    Python reference renders them (mkdocs.yml: members not starting with ``_``)."""
    found = [(where, inspect.getdoc(thing) or "")]
    if inspect.isclass(thing):
        for name, member in vars(thing).items():
            function = member.fget if isinstance(member, property) else getattr(member, "__func__", member)
            if not name.startswith("_") and inspect.isfunction(function):
                found.append((f"{where}.{name}", inspect.getdoc(function) or ""))
    return found


@pytest.mark.parametrize("dotted", NAMES)
def test_every_name_of_the_reference_has_docstrings(dotted: str) -> None:
    for where, doc in _documented(_object(dotted), dotted):
        assert doc, f"{where} has no docstring"


#: reStructuredText that Markdown shows as written: a literal block's ``::`` and directives.
RST_MARKUP = re.compile(r"::[ \t]*$|^\s*\.\. [\w-]+::", re.MULTILINE)
#: A numpy section's item: ``name``, ``a, b`` or ``name : type``.
SECTION_ITEM = re.compile(r"^\*{0,2}\w+(?:\s*,\s*\*{0,2}\w+)*(?:\s+:\s.*|\s*:)?$")
ITEM_SECTIONS = {"Parameters", "Returns", "Yields", "Receives", "Raises", "Warns", "Attributes", "Other Parameters"}


@pytest.mark.parametrize("dotted", NAMES)
def test_the_references_docstrings_render_cleanly(dotted: str) -> None:
    """No literal ``::`` on the API pages (an example is a numpy ``Examples`` section), and no
    paragraph after a numpy section that the section would take for one of its items."""
    for where, doc in _documented(_object(dotted), dotted):
        assert not RST_MARKUP.search(doc), f"{where}: reStructuredText literal block or directive: {RST_MARKUP.search(doc)}"
        lines = doc.splitlines()
        section = None
        for index, line in enumerate(lines):
            if index + 1 < len(lines) and re.fullmatch(r"-{3,}", lines[index + 1].strip()) and line.strip():
                section = line.strip()
            elif section in ITEM_SECTIONS and line and not line.startswith(" ") and not re.fullmatch(r"-{3,}", line):
                assert SECTION_ITEM.match(line), f"{where}, {section}: {line!r} is read as an item of the section (a paragraph after it?)"


def _hook(name: str) -> object:
    sys.path.insert(0, str(ROOT))
    try:
        return importlib.import_module(name)
    finally:
        sys.path.remove(str(ROOT))


def test_the_c_api_page_renders_every_declaration_of_the_header() -> None:
    c_api = _hook("mkdocs_c_api")
    config = (ROOT / "mkdocs.yml").read_text(encoding="utf-8")
    assert "mkdocs_c_api.py" in config.split("hooks:", 1)[1].split("plugins:", 1)[0], "the hook is not in mkdocs.yml"
    page = (ROOT / "docs/reference/c.md").read_text(encoding="utf-8")
    assert c_api.MARKER in page and "--8<--" not in page, "docs/reference/c.md must be rendered from the header, not include it"
    header = (ROOT / c_api.HEADER).read_text(encoding="utf-8")
    rendered = c_api.on_page_markdown(page)
    # The header's names, read here independently of the hook's parser.
    functions = set(re.findall(r"^[\w ]*?\**(uwml_\w+)\(", header, re.MULTILINE))
    types = set(re.findall(r"^typedef struct (\w+) \{", header, re.MULTILINE))
    constants = set(re.findall(r"^#define (UWML_\w+) ", header, re.MULTILINE))
    assert len(functions) >= 29 and len(types) >= 20 and len(constants) >= 30
    for name in sorted(functions | types):
        assert f"### `{name}`" in rendered, f"docs/reference/c.md has no section for {name}"
    for name in sorted(constants):
        assert f"| `{name}` |" in rendered, f"docs/reference/c.md does not list {name}"
    for struct in re.finditer(r"^typedef struct (\w+) \{\n(.*?)^\} \1;", header, re.MULTILINE | re.DOTALL):
        section = rendered.split(f"### `{struct.group(1)}`", 1)[1].split("\n### ", 1)[0]
        for field in re.findall(r"^    [\w ]+?\**(\w+)(?:\[[^\]]*\])*;", struct.group(2), re.MULTILINE):
            assert f"- `{field}` (" in section, f"{struct.group(1)}.{field} is not on the page"
    # Every doc comment's words are on the page, none of its comment markers.
    for comment in re.findall(r"/\*\*(.*?)\*/", header, re.DOTALL):
        first = re.sub(r"^\s*\* ?", "", comment.strip().split("\n")[0]).split("`")[0].split("(")[0].strip()
        assert first.split(" ")[0] in rendered, f"a doc comment starting {first!r} is not on the page"
    assert "/**" not in rendered and "*/" not in rendered
    # Names link to their sections.
    assert "[`uwml_robot_new_f64`](#uwml_robot_new_f64)" in rendered and "[`UwmlError`](#uwmlerror)" in rendered


def test_the_conventions_figures_are_made_by_their_script_and_shown(tmp_path: Path) -> None:
    script = ROOT / "docs/figures/make_conventions.py"
    done = subprocess.run([sys.executable, str(script), str(tmp_path)], capture_output=True, text=True, timeout=120, check=False)
    assert done.returncode == 0, done.stderr[-3000:]
    made = sorted(path.name for path in tmp_path.iterdir())
    page = (ROOT / "docs/conventions.md").read_text(encoding="utf-8")
    for name in made:
        assert (tmp_path / name).read_text(encoding="utf-8").lstrip().startswith("<?xml")
        assert (ROOT / "docs/figures" / name).is_file(), f"docs/figures/{name} is not committed: run {script.relative_to(ROOT)}"
        assert f"](figures/{name})" in page, f"docs/conventions.md does not show figures/{name}"
    assert len(made) == 2
