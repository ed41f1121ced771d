"""The README's example runs as written, in a fresh interpreter, in an empty folder (as after
``pip install uwml``: the examples are the package's); so does the tour's own-robot section
(``docs/tour.md``, moved there from the README): its command-line block line by line after its
Python (it copies the examples with ``uwml examples .``, then uses the files they and
``examples/my_arm/make_logs.py`` make), and the URDF and hydro file it shows are the example's
files. (The site's other checks are ``tests/test_site_snippets.py``'s.)"""

import re
import shlex
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
README = (ROOT / "README.md").read_text(encoding="utf-8")
PYTHON = re.findall(r"```python\n(.*?)```", README, re.DOTALL)
#: The tour's page, which holds the own-robot walk-through that the README held.
TOUR = (ROOT / "docs" / "tour.md").read_text(encoding="utf-8")
#: The command-line block of "Your own robot, from its URDF".
COMMANDS = next(block for block in re.findall(r"```bash\n(.*?)```", TOUR, re.DOTALL) if "make_logs.py" in block)


@pytest.fixture(scope="module")
def folder(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """An empty folder for the snippets and what they write."""
    return tmp_path_factory.mktemp("readme")


def run(arguments: list[str], folder: Path) -> subprocess.CompletedProcess[str]:
    return subprocess.run(arguments, cwd=folder, capture_output=True, text=True, timeout=600, check=False)


@pytest.mark.parametrize("index", range(len(PYTHON)))
def test_each_python_snippet_runs_on_its_own(index: int, folder: Path) -> None:
    pytest.importorskip("mujoco")
    done = run([sys.executable, "-W", "error", "-c", PYTHON[index]], folder)
    assert done.returncode == 0, f"snippet {index}:\n{PYTHON[index]}\n{done.stderr[-3000:]}"


def test_the_command_line_block_runs_line_by_line(folder: Path) -> None:
    pytest.importorskip("mujoco")
    # my_arm.toml: written by the tour's snippet of "Your own robot".
    if not (folder / "my_arm.toml").exists():
        snippet = next(block for block in re.findall(r"```python\n(.*?)```", TOUR, re.DOTALL) if 'arm.save("my_arm.toml")' in block)
        assert run([sys.executable, "-c", snippet], folder).returncode == 0
    for line in COMMANDS.strip().splitlines():
        command = line.split("  #")[0].strip()
        command, _, into = command.partition(">")
        words = shlex.split(command)
        program = [sys.executable] if words[0] == "python" else [sys.executable, "-m", "uwml"]
        done = run([*program, *words[1:]], folder)
        assert done.returncode == 0, f"{command}\n{done.stderr[-3000:]}"
        if into.strip():
            (folder / into.strip()).write_text(done.stdout)
    assert (folder / "my_arm.png").stat().st_size > 10_000
    assert (folder / "torques.csv").read_text().startswith("time,drag1,drag2,")
    assert "#define MY_ARM_WATER_DENSITY 1025.0" in (folder / "my_arm.h").read_text()


def test_the_files_shown_are_the_examples_files() -> None:
    urdf = re.search(r"```xml\n(<robot name=\"my_arm\">.*?)```", TOUR, re.DOTALL)
    hydro = re.search(r"```toml\n(# examples/my_arm/my_arm.hydro.toml.*?)```", TOUR, re.DOTALL)
    assert urdf is not None and hydro is not None
    assert urdf.group(1) == (ROOT / "examples/my_arm/my_arm.urdf").read_text(encoding="utf-8")
    assert hydro.group(1) == (ROOT / "examples/my_arm/my_arm.hydro.toml").read_text(encoding="utf-8")


def test_the_examples_study_is_a_valid_study() -> None:
    from uwml import study

    assert study.load(ROOT / "examples/study.toml").n_runs == 36


def test_the_examples_small_log_gives_back_its_coefficients() -> None:
    """examples/my_arm/land_water.csv: made with Cd 1.1 and Cm 0.9 (examples/my_arm/make_logs.py)."""
    import uwml
    from uwml import fit

    pytest.importorskip("mujoco")
    arm = uwml.Robot.from_urdf(ROOT / "examples/my_arm/my_arm.urdf", hydro=ROOT / "examples/my_arm/my_arm.hydro.toml")
    result = fit.hydro_coefficients(str(ROOT / "examples/my_arm/land_water.csv"), arm, joints=(0, 1))
    for name, truth in (("cd", 1.1), ("cm", 0.9)):  # within 4 standard errors (the log's torques have noise)
        stderr = result.stderr[name]
        assert stderr is not None and abs(result.params[name] - truth) <= 4.0 * stderr, (name, result.params[name], stderr)
