"""The command line starts fast (issue: ``uwml --help`` in well under a second): a bare ``uwml
--help`` or ``--version`` imports none of the heavy libraries a command may need (scipy,
matplotlib, MuJoCo, pyarrow, Ray, JAX); each command imports them when it runs. The time itself
is a benchmark's (``benches/cli_startup.py``), not a test's."""

import subprocess
import sys

import pytest

HEAVY = ("scipy", "matplotlib", "mujoco", "pyarrow", "ray", "jax", "pandas")


@pytest.mark.parametrize("flag", ["--help", "--version"])
def test_a_bare_uwml_imports_no_heavy_library(flag: str) -> None:
    probe = (
        "import sys\n"
        "from uwml.cli import main\n"
        "try:\n"
        f"    main([{flag!r}])\n"
        "except SystemExit:\n"
        "    pass\n"
        f"print(sorted({{m.split('.')[0] for m in sys.modules}} & set({HEAVY!r})))\n"
    )
    result = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, check=True)
    assert result.stdout.strip().splitlines()[-1] == "[]", result.stdout


def test_the_fits_names_come_without_their_modules() -> None:
    """``uwml.fit``'s names are imported on first use (the package imports scipy lazily)."""
    probe = (
        "import sys, uwml.fit\nassert 'scipy.stats' not in sys.modules\nuwml.fit.hydro_coefficients\nprint('scipy.stats' in sys.modules)"
    )
    result = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, check=True)
    assert result.stdout.strip() == "True"
    import uwml.fit

    assert "hydro_coefficients" in dir(uwml.fit)
    with pytest.raises(AttributeError, match="no attribute 'nothing'"):
        uwml.fit.nothing  # noqa: B018
