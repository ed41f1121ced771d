"""Code that may hang (a read of a named pipe), run in a fresh interpreter under a watchdog: a
hang fails the test instead of stopping the suite."""

from __future__ import annotations

import subprocess
import sys
import textwrap
from pathlib import Path

import pytest


def run_with_watchdog(code: str, cwd: Path, timeout: float = 30.0) -> subprocess.CompletedProcess[str]:
    """``code`` in a fresh interpreter, killed (and the test failed) if it has not ended in
    ``timeout`` seconds: a load that blocks on a named pipe blocks in MuJoCo or in ``open``."""
    try:
        return subprocess.run(
            [sys.executable, "-c", textwrap.dedent(code)], cwd=cwd, capture_output=True, text=True, timeout=timeout, check=False
        )
    except subprocess.TimeoutExpired:
        pytest.fail(f"the load hung (still running after {timeout} s): {code.strip()}")
