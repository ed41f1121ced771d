"""Every cross-reference in the code and the docs names a file users have, and a part of it that
exists.

A citation has one form everywhere (code comments, docstrings, docs, test data):

* ``docs/model.md section 10``: a numbered section, a ``## 10. ...`` heading of that file; several
  as ``sections 3 and 10``, ``sections 2-9`` or ``sections 2, 3 and 4``;
* ``docs/model.md section 10, "From URDF and MJCF"``: a heading inside that section;
* ``docs/simulation.md, "Added mass in the mass matrix"``: a heading of a file without numbers.

A heading is cited by its title, or by the part of it before a colon or a parenthesis
(``"Invariants"`` for "Invariants (tested, Rust and Python)"). The file may also be a Markdown link
(``[docs/model.md](model.md) section 10``). Anything else that looks like a section after a file
name (``docs/model.md, section 4``, ``docs/model.md (section 4)``, ``docs/model.md §4``) is refused,
so that every citation is one this test can check. No file cites the internal ``MODEL.md``; every
relative Markdown link in ``docs/`` and ``README.md`` points to an existing file.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from functools import cache
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
#: What is scanned: the code, the docs, the examples, the benchmarks and the tests.
SCANNED = ("python", "crates", "docs", "examples", "benches", "tests", "README.md")
#: The text files among them (compiled modules, figures and data logs are not read).
SUFFIXES = {".py", ".pyi", ".rs", ".md", ".toml", ".urdf", ".xml", ".c", ".h", ".txt"}
SKIPPED_DIRS = {"target", "__pycache__", ".hypothesis", ".pytest_cache", ".mypy_cache", ".ruff_cache"}
#: The internal contract's name, which no file may cite (spelled in two parts so that this file does not either).
INTERNAL = "MODEL" + ".md"

#: A cited Markdown file: a link ``[text](path.md)`` (relative to the citing file) or a path
#: ``docs/name.md`` (relative to the repository).
FILE = re.compile(r"\[[^\]\n]*\]\((?P<link>[^)\s]*?\.md)(?:#[^)\s]*)?\)|(?<![\w/.-])(?P<path>docs/[\w-]+\.md)\b")
#: What follows a cited file, in the one accepted form.
CITATION = re.compile(
    r' (?:section (?P<one>\d+)\b|sections (?P<many>\d+(?:(?:, | and |-)\d+)*)\b)(?:, "(?P<sub>[^"]+)")?'
    r'|, "(?P<heading>[^"]+)"'
)
#: What would be a citation in another form: a section or heading right after the file name.
LOOSE = re.compile(r"""[ ,;:(]{0,3}(?:[Ss]ections?\s*\d|§|"[A-Z]|Section\b)""")
#: Comment markers stripped before lines are joined, so that a citation may wrap.
COMMENT = re.compile(r"^\s*(?://[/!]?|#+:?|/\*+|\*+/?|<!--|--)?\s*")


@dataclass
class Headings:
    """The headings of one Markdown file: numbered sections and the headings inside each."""

    titles: set[str] = field(default_factory=set)
    sections: dict[int, set[str]] = field(default_factory=dict)


def _names(title: str) -> set[str]:
    """The ways a heading may be cited: its title, or the part before a colon or a parenthesis."""
    title = title.replace("`", "").replace("*", "").strip()
    names = {title}
    for stop in (": ", " ("):
        if stop in title:
            names.add(title.split(stop, 1)[0].strip())
    return names


def _without_code_blocks(text: str) -> list[tuple[int, str]]:
    """The lines of a Markdown file outside fenced code blocks, numbered from 1."""
    lines, fenced = [], False
    for number, line in enumerate(text.splitlines(), 1):
        if line.lstrip().startswith("```"):
            fenced = not fenced
        elif not fenced:
            lines.append((number, line))
    return lines


def parse_headings(text: str) -> Headings:
    headings = Headings()
    current: int | None = None
    for _, line in _without_code_blocks(text):
        match = re.match(r"^(#{1,6})\s+(.*?)\s*#*\s*$", line)
        if not match:
            continue
        level, title = len(match.group(1)), match.group(2)
        numbered = re.match(r"^(\d+)\.\s+(.*)$", title)
        if level == 2:
            current = int(numbered.group(1)) if numbered else None
            if current is not None:
                headings.sections[current] = set()
        if numbered:
            title = numbered.group(2)
        headings.titles |= _names(title)
        if level > 2 and current is not None:
            headings.sections[current] |= _names(title)
    return headings


@cache
def headings_of(path: Path) -> Headings:
    return parse_headings(path.read_text(encoding="utf-8"))


def _section_numbers(many: str) -> list[int]:
    numbers: list[int] = []
    for part in re.split(r", | and ", many):
        if "-" in part:
            first, last = (int(x) for x in part.split("-"))
            numbers += list(range(first, last + 1)) if first <= last else [first, last]
        else:
            numbers.append(int(part))
    return numbers


def _joined(text: str) -> tuple[str, list[int]]:
    """The text with comment markers stripped and lines joined by spaces, and where each line starts."""
    parts, starts, offset = [], [], 0
    for line in text.splitlines():
        stripped = COMMENT.sub("", line, count=1).rstrip()
        starts.append(offset)
        parts.append(stripped)
        offset += len(stripped) + 1
    return " ".join(parts), starts


def _shown(path: Path) -> str:
    return path.relative_to(ROOT).as_posix() if path.is_relative_to(ROOT) else str(path)


def citation_problems(text: str, citing: Path) -> list[str]:
    """What is wrong with the citations in ``text`` (the content of the file ``citing``)."""
    problems = []
    joined, starts = _joined(text)

    def where(position: int) -> str:
        return f"{_shown(citing)}:{sum(1 for start in starts if start <= position)}"

    if INTERNAL in text:
        line = text[: text.index(INTERNAL)].count("\n") + 1
        problems.append(f"{_shown(citing)}:{line}: cites {INTERNAL}, which users do not have")
    for found in FILE.finditer(joined):
        name = found.group("link") or found.group("path")
        if "://" in name:
            continue
        target = citing.parent / name if found.group("link") else ROOT / name
        if not target.is_file():
            problems.append(f"{where(found.start())}: cites {name}, which does not exist")
            continue
        cited = CITATION.match(joined, found.end())
        if cited is None:
            if LOOSE.match(joined, found.end()):
                shown = joined[found.start() : found.end() + 24]
                problems.append(f'{where(found.start())}: "{shown}..." is not in the citation form (docs/model.md section N[, "Heading"])')
            continue
        headings = headings_of(target.resolve())
        heading, sub = cited.group("heading"), cited.group("sub")
        if heading is not None:
            if heading not in headings.titles:
                problems.append(f'{where(found.start())}: {name} has no heading "{heading}"')
            continue
        numbers = [int(cited.group("one"))] if cited.group("one") else _section_numbers(cited.group("many"))
        missing = [n for n in numbers if n not in headings.sections]
        if missing:
            problems.append(f"{where(found.start())}: {name} has no section {', '.join(map(str, missing))}")
        elif sub is not None and (len(numbers) != 1 or sub not in headings.sections[numbers[0]]):
            problems.append(f'{where(found.start())}: {name} section {numbers[0]} has no heading "{sub}"')
    return problems


def scanned_files() -> list[Path]:
    this = Path(__file__).resolve()
    files = []
    for name in SCANNED:
        top = ROOT / name
        candidates = [top] if top.is_file() else sorted(top.rglob("*"))
        for path in candidates:
            if path.resolve() == this or not path.is_file() or path.suffix not in SUFFIXES:
                continue
            if SKIPPED_DIRS.intersection(path.relative_to(ROOT).parts):
                continue
            files.append(path)
    return files


def link_problems(text: str, linking: Path) -> list[str]:
    """Relative Markdown links (and images) of ``text`` that point to no file."""
    problems = []
    for number, line in _without_code_blocks(text):
        line = re.sub(r"`[^`]*`", "", line)  # a link in inline code is not a link
        for target in re.findall(r"\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)", line):
            if re.match(r"^[a-z][a-z0-9+.-]*:", target) or target.startswith("#"):
                continue
            path = target.split("#", 1)[0]
            if not (linking.parent / path).exists():
                problems.append(
                    f"{linking.relative_to(ROOT) if linking.is_relative_to(ROOT) else linking}:{number}: link to {target}, which does not exist"
                )
    return problems


def markdown_files() -> list[Path]:
    return [ROOT / "README.md", *sorted((ROOT / "docs").rglob("*.md"))]


# --------------------------------------------------------------------------------------------
# The repository
# --------------------------------------------------------------------------------------------


def test_the_scan_covers_code_docs_and_tests() -> None:
    names = {path.relative_to(ROOT).as_posix() for path in scanned_files()}
    for expected in (
        "README.md",
        "docs/model.md",
        "python/uwml/robot/tree.py",
        "crates/uwml-core/src/hydro.rs",
        "tests/test_chain_reference.py",
    ):
        assert expected in names
    assert "tests/test_doc_references.py" not in names


def test_the_model_doc_has_numbered_sections() -> None:
    # The citations below rely on them: a renumbering must show here first.
    headings = headings_of(ROOT / "docs" / "model.md")
    assert sorted(headings.sections) == list(range(1, len(headings.sections) + 1))
    assert len(headings.sections) >= 10
    assert "From URDF and MJCF" in headings.sections[10]


def test_the_model_doc_refers_to_its_own_sections_that_exist() -> None:
    # Inside docs/model.md a section is named without the file: "section 7", "sections 2-9".
    text = _joined((ROOT / "docs" / "model.md").read_text(encoding="utf-8"))[0]
    numbers = headings_of(ROOT / "docs" / "model.md").sections
    found = re.findall(r"(?<!DNV-RP-C205 )\b[Ss]ections? (\d+(?:(?:, | and |-)\d+)*)\b(?!\.\d)", text)
    assert len(found) >= 5
    missing = [group for group in found if any(n not in numbers for n in _section_numbers(group))]
    assert not missing, missing


def test_every_citation_names_an_existing_section() -> None:
    problems, citations = [], 0
    for path in scanned_files():
        text = path.read_text(encoding="utf-8", errors="replace")
        citations += len(FILE.findall(_joined(text)[0]))
        problems += citation_problems(text, path)
    assert not problems, "\n".join(problems)
    assert citations > 100  # the scan does find the citations


def test_every_relative_markdown_link_points_to_a_file() -> None:
    problems = []
    for path in markdown_files():
        problems += link_problems(path.read_text(encoding="utf-8"), path)
    assert not problems, "\n".join(problems)


# --------------------------------------------------------------------------------------------
# The checks themselves, on made-up text
# --------------------------------------------------------------------------------------------

HERE = ROOT / "python" / "uwml" / "example.py"


@pytest.mark.parametrize(
    "text",
    [
        "# docs/model.md section 10",
        '"""Regressors (docs/model.md sections 3 and 4; docs/model.md sections 2-9)."""',
        '/// docs/model.md section 10, "Base motion and\n/// current"',
        '// docs/model.md section 10, "Invariants": the frame',
        '(docs/simulation.md, "Energy-consistent added mass")',
        "see docs/model.md for the model",
        '# docs/losses.md, "The models"',
    ],
)
def test_a_good_citation_passes(text: str) -> None:
    assert citation_problems(text, HERE) == []


@pytest.mark.parametrize(
    ("text", "problem"),
    [
        ("# docs/model.md section 42", "has no section 42"),
        ("# docs/model.md sections 40-41", "has no section 40, 41"),
        ('# docs/model.md section 2, "From URDF and MJCF"', 'section 2 has no heading "From URDF and MJCF"'),
        ('# docs/simulation.md, "Added mass in the matrix"', 'has no heading "Added mass in the matrix"'),
        ("# docs/model.md, section 4", "is not in the citation form"),
        ("# docs/model.md (section 4)", "is not in the citation form"),
        ("# docs/model.md §4", "is not in the citation form"),
        ('# docs/model.md ("Precision")', "is not in the citation form"),
        ("# docs/absent.md section 1", "docs/absent.md, which does not exist"),
        ("see docs/absent.md", "docs/absent.md, which does not exist"),
        ("# see " + INTERNAL + " section 9", "cites MODEL.md"),
    ],
)
def test_a_bad_citation_is_reported(text: str, problem: str) -> None:
    problems = citation_problems(text, HERE)
    assert any(problem in p for p in problems), problems


def test_a_broken_link_is_reported() -> None:
    doc = ROOT / "docs" / "example.md"
    text = "See [the model](model.md), [a figure](figures/absent.png) and [the web](https://example.org).\n```\n[code](nowhere.md)\n```\n"
    assert link_problems(text, doc) == ["docs/example.md:1: link to figures/absent.png, which does not exist"]
