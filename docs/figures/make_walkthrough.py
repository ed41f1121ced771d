"""The figures of docs/walkthrough.md, made by the page's own code: each Python block of the page
runs as written, on its own, in a fresh interpreter (warnings as errors), all in one empty
folder; the figures they write are copied to ``docs/figures/walkthrough/`` under the names
:data:`FIGURES` gives.

Run: ``python docs/figures/make_walkthrough.py [OUT]`` (OUT: where to put the figures instead of
``docs/figures/walkthrough/``). About 25 s.
"""

from __future__ import annotations

import re
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
PAGE = ROOT / "docs" / "walkthrough.md"
#: Where the figures are kept, relative to docs/ (the page shows ``figures/walkthrough/NAME``).
FOLDER = "figures/walkthrough"
#: Each figure the page's blocks write (in the folder they run in) and its name in FOLDER.
FIGURES = {
    "hydro_file.png": "hydro_file.png",
    "describe.png": "describe.png",
    "torques.png": "torques.png",
    "simulation.png": "simulation.png",
    "replay.png": "replay.png",
    "hull_fit.png": "hull_fit.png",
    "vehicle-results/figures/rms_drift.png": "study_rms_drift.png",
    "vehicle-results/figures/rms_pitch.png": "study_rms_pitch.png",
    "firmware.png": "firmware.png",
}


def python_blocks(page: Path = PAGE) -> list[str]:
    """The page's Python blocks, in order."""
    return re.findall(r"^```python\n(.*?)^```$", page.read_text(encoding="utf-8"), re.MULTILINE | re.DOTALL)


def main(out: Path) -> None:
    with tempfile.TemporaryDirectory() as folder:
        for number, code in enumerate(python_blocks(), 1):
            start = time.perf_counter()
            done = subprocess.run([sys.executable, "-W", "error", "-c", code], cwd=folder, capture_output=True, text=True, check=False)
            if done.returncode:
                raise SystemExit(f"block {number} of {PAGE.name} failed:\n{code}\n{done.stderr}")
            print(f"block {number}: {time.perf_counter() - start:.1f} s")
        out.mkdir(parents=True, exist_ok=True)
        for made, name in FIGURES.items():
            source = Path(folder) / made
            if not source.is_file():
                raise SystemExit(f"no block of {PAGE.name} wrote {made}")
            shutil.copyfile(source, out / name)
            print(f"wrote {out / name}")


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else ROOT / "docs" / FOLDER)
