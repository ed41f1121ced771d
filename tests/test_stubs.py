"""The type stubs of the native module match it (``mypy.stubtest``)."""

import subprocess
import sys


def test_native_module_stubs_match_the_runtime():
    result = subprocess.run([sys.executable, "-m", "mypy.stubtest", "uwml._core"], check=False, capture_output=True, text=True, timeout=300)
    assert result.returncode == 0, result.stdout + result.stderr
