"""docs/performance.md's figures come from one script (benches/performance_report.py, issue 35
point 1): its generated tables exist, the page includes each of them and no other figure file,
each table names the machine it ran on, and the benchmarks' measuring functions the script calls
are there. The report itself is not run here (minutes): `python benches/performance_report.py`."""

from __future__ import annotations

import importlib
import re
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
BENCHES = ROOT / "benches"
TABLES = BENCHES / "performance_tables.md"
PAGE = ROOT / "docs" / "performance.md"


@pytest.fixture(scope="module")
def report():  # type: ignore[no-untyped-def]
    sys.path.insert(0, str(BENCHES))
    try:
        yield importlib.import_module("performance_report")
    finally:
        sys.path.remove(str(BENCHES))


def _sections(text: str) -> dict[str, str]:
    return dict(re.findall(r"<!-- --8<-- \[start:(\w+)\] -->\n(.*?)\n<!-- --8<-- \[end:\1\] -->", text, re.DOTALL))


def test_the_page_includes_every_generated_table(report) -> None:  # type: ignore[no-untyped-def]
    sections = _sections(TABLES.read_text(encoding="utf-8"))
    assert set(sections) == set(report.SECTIONS)
    included = re.findall(r'^--8<-- "([^":]+):(\w+)"$', PAGE.read_text(encoding="utf-8"), re.MULTILINE)
    assert {file for file, _ in included} == {str(TABLES.relative_to(ROOT))}
    assert sorted(name for _, name in included) == sorted(report.SECTIONS)
    assert "python benches/performance_report.py" in PAGE.read_text(encoding="utf-8")


def test_each_table_names_the_machine(report) -> None:  # type: ignore[no-untyped-def]
    sections = _sections(TABLES.read_text(encoding="utf-8"))
    machine = dict(re.findall(r"^\| (\w[\w ]*) \| (.+) \|$", sections["machine"], re.MULTILINE))
    for key in ("CPU", "cores", "clock", "Python", "numpy", "MuJoCo", "JAX", "date", "commit"):
        assert machine.get(key), f"the machine table has no {key}"
    for name, body in sections.items():
        if name != "machine":
            assert f"*Measured on {machine['CPU']}, {machine['cores']} cores" in body, f"table {name} does not name the machine"
            assert machine["date"] in body


def test_the_page_states_no_figure_of_its_own() -> None:
    """Figures are the generated tables': the page's own text has no timings or counts."""
    text = re.sub(r"```.*?```", "", PAGE.read_text(encoding="utf-8"), flags=re.DOTALL)
    timings = re.findall(r"\d[\d.,–-]*\s*(?:ns|µs|ms|million states|M states|instructions)\b", text)
    assert not timings, timings


def test_the_measuring_functions_are_there(report) -> None:  # type: ignore[no-untyped-def]
    assert callable(report.main) and callable(report.machine) and callable(report.targets)
    info = report.machine()
    assert info["CPU"] and info["cores"] and info["Python"]
    for module, names in {
        "batch": ("measure", "reference_per_state", "limits_times"),
        "single_state": ("measure",),
        "cli_startup": ("best",),
        "large_log": ("measure_row",),
        "study": ("measure",),
        "accelerated": ("evaluations",),
    }.items():
        loaded = importlib.import_module(module)
        for name in names:
            assert callable(getattr(loaded, name)), f"{module}.{name}"
    pytest.importorskip("mujoco")
    simulation = importlib.import_module("simulation")
    assert callable(simulation.robot_steps) and callable(simulation.vehicle_rows)


def test_the_targets_table_says_what_was_not_measured(report) -> None:  # type: ignore[no-untyped-def]
    text = report.targets({"batch": {"paper leg, hydro, 1 thread": 1e-7, "paper leg, hydro, 2 threads": 5e-8}})
    assert "| 10.0 million/s | **met** |" in text
    assert "not measured in this run" in text
