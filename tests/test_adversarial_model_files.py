"""Hostile model files and export inputs (hypothesis where it helps): control characters and
injection in names, arrays nested deeper than Python recurses, bytes that are not UTF-8, huge
arrays, strings and keys, water outside its range, a directory, an empty file, and a value of
the wrong type at every key of every table.

What must hold (docs/domains.md): loading gives a robot, or a ``uwml.ModelFileError`` whose
message names the file and is shorter than 500 characters; never another exception. Exporting
gives source in which names are only comment text (the code lines are those of the same robot
with plain names), or a ``ValueError`` naming the argument. ``tests/test_export.py`` compiles
such exports; ``tests/test_modelfile.py`` holds the single cases these generalize.
"""

from __future__ import annotations

import datetime
import math
import re
import tomllib
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
import uwml
from hypothesis import given, settings
from hypothesis import strategies as st
from uwml.examples import arm_on_rov
from uwml.io.export import to_c, to_rust
from uwml.io.modelfile import dumps
from uwml.robot.files import loads

SOURCE = "hostile.toml"
MAX_MESSAGE = 500


def small_robot() -> uwml.Robot:
    """Two named joints (one with every loss), two links with two segments each, a base with a
    circular segment, sea water: every table and key a model file can hold."""
    arm = arm_on_rov()
    joints = [uwml.Joint(j.origin, j.axis, parent=j.parent, kind=j.kind, name=f"joint {i}") for i, j in enumerate(arm.joints[:2])]
    links = [
        uwml.Link(link.mass, link.com, link.volume, cob=link.cob, segments=link.segments, name=f"link {i}")
        for i, link in enumerate(arm.links[:2])
    ]
    losses = [uwml.JointLosses(oil=uwml.OilDrag()), None]
    return uwml.Robot(joints, links, base=arm.base, losses=losses, water=uwml.Water(1025.0, 9.81))


TEXT = dumps(small_robot())
DOCUMENT = tomllib.loads(TEXT)


def refused_or_loaded(load: Any, source: str) -> uwml.Robot | None:
    """``load()``'s robot, or None after checking that it raised a short ModelFileError that
    names ``source``; any other exception propagates and fails the test."""
    try:
        return load()
    except uwml.ModelFileError as exc:
        message = str(exc)
        assert message.startswith(f"{source}: "), message[:MAX_MESSAGE]
        assert len(message) < MAX_MESSAGE, message[:MAX_MESSAGE]
        return None


def from_text(text: str) -> uwml.Robot | None:
    return refused_or_loaded(lambda: loads(text, SOURCE), SOURCE)


def from_file(path: Path) -> uwml.Robot | None:
    return refused_or_loaded(lambda: uwml.Robot.load(path), str(path))


# A small TOML writer (every table inline), so that a document can be changed anywhere.
def toml_string(text: str) -> str:
    escaped = "".join({'"': '\\"', "\\": "\\\\"}.get(c, f"\\u{ord(c):04X}" if ord(c) < 0x20 or ord(c) == 0x7F else c) for c in text)
    return f'"{escaped}"'


def toml_value(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        return "nan" if math.isnan(value) else ("inf" if value > 0 else "-inf") if math.isinf(value) else repr(value)
    if isinstance(value, str):
        return toml_string(value)
    if isinstance(value, datetime.date | datetime.time):
        return value.isoformat()
    if isinstance(value, list):
        return "[" + ", ".join(toml_value(item) for item in value) + "]"
    assert isinstance(value, dict)
    return "{" + ", ".join(f"{toml_string(key)} = {toml_value(item)}" for key, item in value.items()) + "}"


def toml_document(document: dict[str, Any]) -> str:
    return "".join(f"{toml_string(key)} = {toml_value(value)}\n" for key, value in document.items())


def test_the_writer_writes_the_model_file() -> None:
    assert loads(toml_document(DOCUMENT)) == small_robot()


def paths(value: Any, prefix: tuple[Any, ...] = ()) -> Iterator[tuple[Any, ...]]:
    """Every place in a document: each key of each table, each item of each array."""
    items = value.items() if isinstance(value, dict) else enumerate(value) if isinstance(value, list) else ()
    for key, item in items:
        yield (*prefix, key)
        yield from paths(item, (*prefix, key))


PATHS = list(paths(DOCUMENT))


def replaced(path: tuple[Any, ...], new: Any) -> dict[str, Any]:
    """DOCUMENT with the value at ``path`` replaced by ``new`` (a deep copy)."""
    document = tomllib.loads(TEXT)
    place = document
    for key in path[:-1]:
        place = place[key]
    place[path[-1]] = new
    return document


def kind(value: Any) -> str:
    if isinstance(value, bool):
        return "boolean"
    if isinstance(value, int | float):
        return "number"
    if isinstance(value, str):
        return "string"
    if isinstance(value, list):
        return "array"
    if isinstance(value, dict):
        return "table"
    return "date"


WRONG = ["wrong", True, 1.5, ["a", "b"], {"x": 1}, datetime.datetime(1979, 5, 27, 7, 32, tzinfo=datetime.UTC)]


def test_a_wrong_type_at_any_key_is_refused_naming_it() -> None:
    checked = 0
    # Every key of every table; of the items of an array, the first (the others take the same path).
    for path in (path for path in PATHS if all(not isinstance(part, int) or part == 0 for part in path)):
        original = DOCUMENT
        for key in path:
            original = original[key]
        for new in WRONG:
            if kind(new) == kind(original):
                continue
            with pytest.raises(uwml.ModelFileError) as info:
                loads(toml_document(replaced(path, new)), SOURCE)
            message = str(info.value)
            assert message.startswith(f"{SOURCE}: ") and len(message) < MAX_MESSAGE, message[:MAX_MESSAGE]
            # The message names the key (for an item of an array, the array's key).
            key = next(part for part in reversed(path) if isinstance(part, str))
            assert key in message, (path, new, message)
            checked += 1
    assert checked > 200


# Any TOML value: numbers of every size, strings, dates, arrays and tables of them.
TOML_VALUES = st.recursive(
    st.one_of(
        st.booleans(),
        st.integers(),
        st.floats(),
        st.text(max_size=8),
        st.datetimes(timezones=st.one_of(st.none(), st.just(datetime.UTC))),
        st.dates(),
        st.times(),
    ),
    lambda inner: st.one_of(st.lists(inner, max_size=4), st.dictionaries(st.text(max_size=6), inner, max_size=4)),
    max_leaves=12,
)


@given(path=st.sampled_from(PATHS), new=TOML_VALUES)
def test_any_value_anywhere_is_loaded_or_refused(path: tuple[Any, ...], new: Any) -> None:
    from_text(toml_document(replaced(path, new)))


@given(key=st.text(min_size=1, max_size=30), table=st.sampled_from([(), ("water",), ("base",), ("joints", 0), ("joints", 0, "losses")]))
def test_any_unknown_key_is_refused(key: str, table: tuple[Any, ...]) -> None:
    place: Any = DOCUMENT
    for part in table:
        place = place[part]
    if key in place:
        return
    document = tomllib.loads(TEXT)
    target = document
    for part in table:
        target = target[part]
    target[key] = 1.0
    assert from_text(toml_document(document)) is None


# Names: raw text in a TOML string, escapes, injection.
HOSTILE = st.one_of(
    st.text(min_size=1, max_size=20),
    st.sampled_from(
        [
            "x */ int pwned(void) { return 42; } /* y",
            "a\npub fn pwned() -> i32 { 42 }\n//",
            '" \nmass = 1e9\n# ',
            "\\u0000",
            "\\",
            "\x00",
            "\r\n[[joints]]\n",
            "\ud800",
            "\u202e",
        ]
    ),
)


@given(name=HOSTILE, raw=st.booleans())
def test_names_in_a_file_are_loaded_or_refused(name: str, raw: bool) -> None:
    # raw: the name's characters as they are between the quotes (control characters, a quote,
    # a backslash, a line break: not valid TOML, or other TOML); else a correctly escaped string.
    literal = f'"{name}"' if raw else toml_string(name)
    robot = from_text(TEXT.replace('name = "joint 0"', f"name = {literal}", 1))
    if robot is not None and not raw:
        assert robot.joint_names[0] == name


@settings(max_examples=max(10, int(settings.default.max_examples / 4)))
@given(names=st.lists(HOSTILE, min_size=4, max_size=4, unique=True))
def test_any_names_are_saved_exactly_or_refused(tmp_path_factory: pytest.TempPathFactory, names: list[str]) -> None:
    robot = small_robot()
    joints = [uwml.Joint(j.origin, j.axis, parent=j.parent, kind=j.kind, name=n) for j, n in zip(robot.joints, names)]
    links = [
        uwml.Link(link.mass, link.com, link.volume, cob=link.cob, segments=link.segments, name=n) for link, n in zip(robot.links, names[2:])
    ]
    named = uwml.Robot(joints, links, base=robot.base, losses=robot.losses, water=robot.water)
    path = tmp_path_factory.mktemp("names") / "named.toml"
    path.write_text("the old file\n")
    try:
        named.save(path)
    except ValueError as exc:
        assert any("\ud800" <= c <= "\udfff" for c in "".join(names)), exc  # only a lone surrogate is refused
        assert "cannot be written" in str(exc) and len(str(exc)) < MAX_MESSAGE
        assert path.read_text() == "the old file\n"
        return
    assert uwml.Robot.load(path) == named


CODE_LINE = re.compile(r"^\s*(/\*|\*|//)")


def code_lines(source: str) -> list[str]:
    """The lines of generated source that are not comments (C block comments here start a line
    and end it; Rust comments are whole lines)."""
    return [line for line in source.splitlines() if not CODE_LINE.match(line)]


@given(names=st.lists(HOSTILE, min_size=4, max_size=4, unique=True), source=st.one_of(st.none(), HOSTILE))
def test_exported_names_are_only_comments(names: list[str], source: str | None) -> None:
    robot = small_robot()

    def named(names: list[str]) -> uwml.Robot:
        joints = [uwml.Joint(j.origin, j.axis, parent=j.parent, kind=j.kind, name=n) for j, n in zip(robot.joints, names)]
        links = [
            uwml.Link(link.mass, link.com, link.volume, cob=link.cob, segments=link.segments, name=n)
            for link, n in zip(robot.links, names[2:])
        ]
        return uwml.Robot(joints, links, base=robot.base, losses=robot.losses, water=robot.water)

    hostile, plain = named(names), named(["a", "b", "c", "d"])
    for export in (to_c, to_rust):
        text, reference = export(hostile, source=source), export(plain, source="plain")
        assert len(text.splitlines()) == len(reference.splitlines())
        assert code_lines(text) == code_lines(reference)
        assert {ch for ch in text if not ch.isascii()} <= {"³", "²"}  # the units in the Rust water's doc comment
        if export is to_c:  # a C comment opens only where its line starts and closes only where it ends
            for line in text.splitlines():
                if CODE_LINE.match(line):
                    assert "/*" not in line[2:] and "*/" not in line[:-2] and line.rstrip().endswith(("*/", line.rstrip())), line


@given(prefix=st.text(max_size=12))
def test_the_c_prefix_is_an_identifier_or_refused(prefix: str) -> None:
    try:
        text = to_c(small_robot(), prefix=prefix)
    except ValueError as exc:
        assert "prefix must be an upper-case C identifier" in str(exc) and len(str(exc)) < MAX_MESSAGE
        assert not (re.fullmatch(r"[A-Z_][A-Z0-9_]*", prefix) and re.search("[A-Z]", prefix))
        return
    assert re.fullmatch(r"[A-Z_][A-Z0-9_]*", prefix) and re.search("[A-Z]", prefix) and f"#define {prefix}_N_JOINTS 2u" in text


# Structure: nesting, size, bytes.
@settings(max_examples=max(10, int(settings.default.max_examples / 10)))
@given(path=st.sampled_from(PATHS), depth=st.one_of(st.integers(1, 50), st.integers(50, 200_000)))
def test_nested_arrays_are_loaded_or_refused(path: tuple[Any, ...], depth: int) -> None:
    text = toml_document(replaced(path, "NESTED")).replace('"NESTED"', "[" * depth + "1.0" + "]" * depth)
    assert from_text(text) is None


@settings(max_examples=max(5, int(settings.default.max_examples / 20)))
@given(
    path=st.sampled_from(PATHS),
    n=st.integers(4, 200_000),
    item=st.sampled_from(["0.5", '"x"', "[1.0, 2.0, 3.0]", "{a = 1}"]),
)
def test_huge_arrays_are_refused_briefly(path: tuple[Any, ...], n: int, item: str) -> None:
    text = toml_document(replaced(path, "HUGE")).replace('"HUGE"', "[" + ", ".join([item] * n) + "]")
    assert from_text(text) is None


@settings(max_examples=max(5, int(settings.default.max_examples / 20)))
@given(path=st.sampled_from(PATHS), n=st.integers(100, 1_000_000), key=st.booleans())
def test_huge_strings_and_keys_are_refused_briefly(path: tuple[Any, ...], n: int, key: bool) -> None:
    if key:  # an unknown key of that length in the table at path (or its parent)
        table = path[:-1]
        document = tomllib.loads(TEXT)
        place: Any = document
        for part in table:
            place = place[part]
        if not isinstance(place, dict):
            return
        place["k" * n] = 1.0
    else:
        document = replaced(path, "s" * n)
        if path[-1] == "name":  # any string is a name
            return
    assert from_text(toml_document(document)) is None


@given(offset=st.integers(0, len(TEXT.encode())), junk=st.binary(min_size=1, max_size=4))
def test_bytes_that_are_not_utf8_name_the_file_and_the_offset(tmp_path_factory: pytest.TempPathFactory, offset: int, junk: bytes) -> None:
    data = TEXT.encode()
    data = data[:offset] + junk + data[offset:]
    path = tmp_path_factory.mktemp("bytes") / "bytes.toml"
    path.write_bytes(data)
    try:
        data.decode("utf-8")
    except UnicodeDecodeError as exc:
        with pytest.raises(uwml.ModelFileError, match=rf"not UTF-8 text: byte 0x{data[exc.start]:02x} at offset {exc.start} \(line"):
            uwml.Robot.load(path)
    from_file(path)


# Water.
@given(
    density=st.one_of(st.floats(), st.floats(800.0, 1400.0), st.sampled_from([1.025, 1025.0, 1e300, 0.0, -1025.0])),
    gravity=st.one_of(st.floats(), st.floats(9.5, 10.1), st.sampled_from([0.0, 1.0, 9.81, 32.2, -9.81])),
)
def test_water_is_loaded_only_within_its_range(density: float, gravity: float) -> None:
    text = TEXT.replace("density = 1025.0", f"density = {toml_value(density)}").replace(
        "gravity = 9.81", f"gravity = {toml_value(gravity)}"
    )
    within = 900.0 <= density <= 1300.0 and 9.7 <= gravity <= 9.9  # docs/domains.md
    if within and density > 1100.0:  # a brine: loaded, with a warning (uwml.plausibility)
        with pytest.warns(uwml.PlausibilityWarning, match="outside 500 to 1100 kg/m³"):
            robot = from_text(text)
    else:
        robot = from_text(text)
    assert (robot is not None) == within
    if robot is not None:
        assert robot.water.density == density and robot.water.gravity == gravity


# Files that are not files of text.
def test_a_directory_an_empty_file_and_a_missing_one(tmp_path: Path) -> None:
    folder = tmp_path / "folder.toml"
    folder.mkdir()
    with pytest.raises(uwml.ModelFileError, match=r"folder.toml: the model file cannot be read: it is a directory"):
        uwml.Robot.load(folder)
    empty = tmp_path / "empty.toml"
    empty.write_bytes(b"")
    with pytest.raises(uwml.ModelFileError, match=r"empty.toml: top level, key 'format': is missing"):
        uwml.Robot.load(empty)
    with pytest.raises(uwml.ModelFileError, match=r"missing.toml: the model file cannot be read: no such file"):
        uwml.Robot.load(tmp_path / "missing.toml")
    for path in (folder, empty, tmp_path / "missing.toml"):
        assert from_file(path) is None
    # Saving over a directory fails and leaves it, and no temporary file.
    with pytest.raises(OSError):
        small_robot().save(folder)
    assert folder.is_dir() and sorted(p.name for p in tmp_path.iterdir()) == ["empty.toml", "folder.toml"]


@pytest.mark.skipif(not hasattr(__import__("os"), "mkfifo"), reason="named pipes need os.mkfifo")
def test_a_named_pipe_is_refused_not_waited_on(tmp_path: Path) -> None:
    """A model file that is a named pipe with no writer: ``Robot.load`` waited forever."""
    import os

    from watchdog import run_with_watchdog

    os.mkfifo(tmp_path / "arm.toml")
    run = run_with_watchdog(
        """
        import uwml
        try:
            uwml.Robot.load("arm.toml")
        except uwml.ModelFileError as exc:
            print(exc)
        """,
        tmp_path,
    )
    assert run.returncode == 0, run.stderr[-2000:]
    assert (
        run.stdout.strip()
        == "arm.toml: the model file cannot be read: it is not a regular file (a named pipe); uwml reads regular files only"
    )
