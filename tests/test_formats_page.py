"""The site's file formats page (docs/formats.md) against the readers of the files
(``uwml.io.hydrofile``, ``uwml.io.modelfile``): every key a table of either file takes is on the
page, in that table's section, and no key on the page is one the table refuses.

What each table takes is asked of the readers themselves: a file with an unknown key in that
table is refused with the list of the keys it allows (``(allowed: a, b, ...)``), so the test
holds the page to what the readers do, not to a copy of their tuples. The page's examples load,
its bounds are the code's constants, and the joint losses' defaults are their classes'.
"""

from __future__ import annotations

import dataclasses
import re
import tomllib
from pathlib import Path

import pytest
import uwml
from uwml.domains import MAX_AREA, MAX_COEFFICIENT, MAX_LENGTH, MAX_MASS, MAX_VOLUME
from uwml.io import hydrofile, modelfile
from uwml.io._hydro_masses import MAX_INERTIA
from uwml.io._model_tables import MAX_THRUSTERS, WATER_DENSITY_RANGE, WATER_GRAVITY_RANGE
from uwml.model.lumped import MAX_LUMPED
from uwml.model.thrusters import MAX_CURVE_POINTS, MAX_POLYNOMIAL_DEGREE

ROOT = Path(__file__).resolve().parents[1]
PAGE = (ROOT / "docs/formats.md").read_text(encoding="utf-8")
MODEL_HEAD = 'format = "uwml-robot"\nversion = 1\n'
BODY = "mass = 1.0\ncom = [0.0, 0.0, 0.0]\nvolume = 0.001\ncob = [0.0, 0.0, 0.0]\n"
THRUSTER = "position = [0.0, 0.0, 0.0]\ndirection = [1.0, 0.0, 0.0]\n"

#: Per table of the hydro file, as the page heads its section: a file whose table holds an
#: unknown key ``zz_unknown`` (the readers list the keys they allow in the error).
HYDRO = {
    "Top level": "",
    "[water]": "[water]\n",
    "[base]": "[base]\n",
    "[links.NAME]": "[links.a]\n",
    "[links.NAME.lumped]": "[links.a.lumped]\n",
    "[[links.NAME.segments]]": "[[links.a.segments]]\n",
    "[[links.NAME.items]]": "[[links.a.items]]\n",
    "[[links.NAME.thrusters]]": "[[links.a.thrusters]]\n",
    "[links.NAME.thrusters.curve]": f"[[links.a.thrusters]]\n{THRUSTER}[links.a.thrusters.curve]\n",
    "[joints.NAME]": "[joints.j]\n",
    "[joints.NAME.drive]": "[joints.j]\n[joints.j.drive]\n",
    "[joints.NAME.oil]": "[joints.j]\n[joints.j.oil]\n",
    "[joints.NAME.seal]": "[joints.j]\n[joints.j.seal]\n",
}
#: The same for the model file's own sections.
MODEL = {
    "Top level": MODEL_HEAD,
    "[[joints]]": f"{MODEL_HEAD}links = []\n[[joints]]\n",
    "[base] and [[links]]": f"{MODEL_HEAD}joints = []\n[[links]]\n",
}
#: The model file's tables that the page gives as "the keys of" a hydro file's section, each
#: with a file that puts an unknown key there.
MODEL_AS_HYDRO = {
    "[base]": (f"{MODEL_HEAD}joints = []\nlinks = []\n[base]\n", "[base] and [[links]]", MODEL),
    "[water]": (f"{MODEL_HEAD}joints = []\nlinks = []\n[water]\n", "[water]", HYDRO),
    "[[links.segments]]": (f"{MODEL_HEAD}joints = []\n[[links]]\n[[links.segments]]\n", "[[links.NAME.segments]]", HYDRO),
    "[[base.segments]]": (f"{MODEL_HEAD}joints = []\nlinks = []\n[base]\n{BODY}[[base.segments]]\n", "[[links.NAME.segments]]", HYDRO),
    "[links.lumped]": (f"{MODEL_HEAD}joints = []\n[[links]]\n{BODY}[links.lumped]\n", "[links.NAME.lumped]", HYDRO),
    "[base.lumped]": (f"{MODEL_HEAD}joints = []\nlinks = []\n[base]\n{BODY}[base.lumped]\n", "[links.NAME.lumped]", HYDRO),
    "[[links.thrusters]]": (f"{MODEL_HEAD}joints = []\n[[links]]\n{BODY}[[links.thrusters]]\n", "[[links.NAME.thrusters]]", HYDRO),
    "[links.thrusters.curve]": (
        f"{MODEL_HEAD}joints = []\n[[links]]\n{BODY}[[links.thrusters]]\n{THRUSTER}[links.thrusters.curve]\n",
        "[links.NAME.thrusters.curve]",
        HYDRO,
    ),
    "[joints.losses]": (f"{MODEL_HEAD}links = []\n[[joints]]\n[joints.losses]\n", "[joints.NAME]", HYDRO),
    "[joints.losses.drive]": (
        f"{MODEL_HEAD}links = []\n[[joints]]\n[joints.losses]\n[joints.losses.drive]\n",
        "[joints.NAME.drive]",
        HYDRO,
    ),
    "[joints.losses.oil]": (f"{MODEL_HEAD}links = []\n[[joints]]\n[joints.losses]\n[joints.losses.oil]\n", "[joints.NAME.oil]", HYDRO),
    "[joints.losses.seal]": (f"{MODEL_HEAD}links = []\n[[joints]]\n[joints.losses]\n[joints.losses.seal]\n", "[joints.NAME.seal]", HYDRO),
}


def _part(title: str) -> str:
    """The page's ``## title`` part, up to the next ``## `` heading."""
    match = re.search(rf"^## {re.escape(title)}\n(.*?)(?=^## |\Z)", PAGE, re.MULTILINE | re.DOTALL)
    assert match is not None, f"docs/formats.md has no part '## {title}'"
    return match.group(1)


def _sections(part: str) -> dict[str, str]:
    """A part's ``### `` sections by their heading, backticks removed."""
    pieces = re.split(r"^### (.+)\n", part, flags=re.MULTILINE)
    return {heading.replace("`", "").strip(): body for heading, body in zip(pieces[1::2], pieces[2::2], strict=True)}


HYDRO_PAGE = _sections(_part("The hydro file"))
MODEL_PAGE = _sections(_part("The model file"))


def _cells(line: str) -> list[str]:
    return [cell.strip() for cell in line.strip().strip("|").split("|")]


def _rows(section: str) -> list[list[str]]:
    """The cells of a section's table rows (its header and rule left out)."""
    rows = [line for line in section.splitlines() if line.startswith("| ")]
    return [_cells(row) for row in rows[1:]]


def _keys(section: str) -> set[str]:
    """The keys a section's table lists: its rows' first cells."""
    return {row[0].strip("`") for row in _rows(section)}


def _allowed(read: object, text: str, tmp_path: Path) -> set[str]:
    """The keys the reader allows in the table that ``text`` ends in: ``text`` with an unknown key
    there is refused with that list."""
    path = tmp_path / "probe.toml"
    path.write_text(text + "zz_unknown = 1\n", encoding="utf-8")
    with pytest.raises(ValueError, match="zz_unknown") as caught:
        read(path)  # type: ignore[operator]
    listed = re.search(r"\(allowed: ([^)]*)\)", str(caught.value))
    assert listed is not None, str(caught.value)
    return set(listed.group(1).split(", "))


def test_the_page_has_a_section_for_every_table() -> None:
    assert set(HYDRO) <= set(HYDRO_PAGE), set(HYDRO) - set(HYDRO_PAGE)
    assert set(MODEL) <= set(MODEL_PAGE), set(MODEL) - set(MODEL_PAGE)


#: Each file: its reader, its probes by table and the page's sections of it.
FILES = {"hydro": (hydrofile.read_hydro, HYDRO, HYDRO_PAGE), "model": (modelfile.read, MODEL, MODEL_PAGE)}


@pytest.mark.parametrize(("file", "table"), [(file, table) for file, (_, probes, _) in FILES.items() for table in probes])
def test_each_table_lists_exactly_the_keys_the_reader_takes(file: str, table: str, tmp_path: Path) -> None:
    read, probes, sections = FILES[file]
    allowed = _allowed(read, probes[table], tmp_path)
    on_page = _keys(sections[table])
    assert on_page == allowed, (
        f"docs/formats.md, {table}: missing {sorted(allowed - on_page)}, unknown to the reader {sorted(on_page - allowed)}"
    )


@pytest.mark.parametrize("table", MODEL_AS_HYDRO)
def test_the_model_files_shared_tables_take_the_keys_of_the_section_the_page_names(table: str, tmp_path: Path) -> None:
    text, section, sections = MODEL_AS_HYDRO[table]
    page = MODEL_PAGE if sections is MODEL else HYDRO_PAGE
    assert _allowed(modelfile.read, text, tmp_path) == _keys(page[section])
    assert f"`{table}`" in _part("The model file"), f"the model file's part does not name {table}"


def test_every_row_gives_a_value_a_default_and_what_is_allowed() -> None:
    for part in (HYDRO_PAGE, MODEL_PAGE):
        for heading, section in part.items():
            header = _cells(next((line for line in section.splitlines() if line.startswith("| ")), "|"))
            for row in _rows(section):
                assert len(row) == len(header), f"{heading}: row {row} has {len(row)} cells, the table {len(header)}"
                named = dict(zip(header, row, strict=True))
                assert named["key"] and named["value"] and named["default"], f"{heading}: {row[0]} lacks its value or default"
                assert heading == "Top level" or "allowed" in named, f"{heading}: the table has no column of allowed values"


def _e(x: float) -> str:
    """A bound as the page writes it: ``1e3``, ``1e17``."""
    mantissa, exponent = f"{x:e}".split("e")
    return f"{float(mantissa):g}e{int(exponent)}"


def test_the_bounds_on_the_page_are_the_codes() -> None:
    links = HYDRO_PAGE["[links.NAME]"]
    for bound in (MAX_COEFFICIENT, MAX_VOLUME, MAX_LENGTH, MAX_MASS, MAX_INERTIA):
        assert _e(bound) in links, f"[links.NAME] does not state {_e(bound)}"
    assert f"at most {uwml.MAX_SEGMENTS}" in links and f"at most {hydrofile.MAX_ITEMS}" in links
    assert f"at most {MAX_THRUSTERS}" in links
    segments = HYDRO_PAGE["[[links.NAME.segments]]"]
    assert _e(MAX_AREA) in segments and f"at most {uwml.MAX_SEGMENTS} segments" in segments
    assert _e(MAX_LUMPED) in HYDRO_PAGE["[links.NAME.lumped]"]
    curve = HYDRO_PAGE["[links.NAME.thrusters.curve]"]
    assert f"2 to {MAX_CURVE_POINTS}" in curve and f"degree at most {MAX_POLYNOMIAL_DEGREE}" in curve
    water = HYDRO_PAGE["[water]"]
    for low, high in (WATER_DENSITY_RANGE, WATER_GRAVITY_RANGE):
        assert f"{low:g} to {high:g}" in water
    defaults = {row[0].strip("`"): row[3] for row in _rows(water)}
    assert defaults["density"].startswith(f"{uwml.Water().density:g}") and defaults["gravity"] == f"{uwml.Water().gravity:g}"
    assert f"at most {uwml.MAX_LUMPED_BODIES}" in MODEL_PAGE["[base] and [[links]]"]
    assert f"1 to {uwml.MAX_ROBOT_JOINTS}" in MODEL_PAGE["Top level"]


@pytest.mark.parametrize(
    ("table", "kind"), [("[joints.NAME.drive]", uwml.Drive), ("[joints.NAME.oil]", uwml.OilDrag), ("[joints.NAME.seal]", uwml.Seal)]
)
def test_the_joint_losses_defaults_are_their_classes(table: str, kind: type) -> None:
    defaults = {row[0].strip("`"): float(row[3]) for row in _rows(HYDRO_PAGE[table])}
    assert defaults == {f.name: f.default for f in dataclasses.fields(kind)}


def test_the_smooth_signs_default_is_the_classs() -> None:
    defaults = {row[0].strip("`"): row[3] for row in _rows(HYDRO_PAGE["[joints.NAME]"])}
    assert float(defaults["epsilon"]) == uwml.JointLosses.epsilon


def _toml_blocks(part: str) -> list[str]:
    return re.findall(r"^```toml\n(.*?)^```$", part, re.MULTILINE | re.DOTALL)


def test_the_examples_are_files_the_readers_take(tmp_path: Path) -> None:
    (hydro,) = _toml_blocks(_part("The hydro file"))
    path = tmp_path / "example.hydro.toml"
    path.write_text(hydro, encoding="utf-8")
    read = hydrofile.read_hydro(path)
    assert set(read.links) == set(tomllib.loads(hydro)["links"]) and read.water is not None
    assert read.joints["elbow"].seal is not None and read.joints["elbow"].oil is None
    (model,) = _toml_blocks(_part("The model file"))
    path = tmp_path / "example.uwml.toml"
    path.write_text(model, encoding="utf-8")
    robot = uwml.Robot.load(path)
    assert robot.n_joints == 1 and robot.water.density == 1025.0
