"""How long the ``uwml`` command takes to answer ``--version`` and ``--help`` (issue 35: under
0.5 s), best of ``N`` runs each, each in a fresh interpreter: ``python benches/cli_startup.py [N]``
(default 10). Also ``python -c "import uwml"`` alone, the floor under both."""

from __future__ import annotations

import subprocess
import sys
import time

#: The commands timed, by label.
COMMANDS = {
    "python -c 'import uwml'": [sys.executable, "-c", "import uwml"],
    "uwml --version": [sys.executable, "-m", "uwml", "--version"],
    "uwml --help": [sys.executable, "-m", "uwml", "--help"],
}


def best(command: list[str], runs: int) -> float:
    times = []
    for _ in range(runs):
        start = time.perf_counter()
        subprocess.run(command, capture_output=True, check=True)
        times.append(time.perf_counter() - start)
    return min(times)


def main() -> None:
    runs = int(sys.argv[1]) if len(sys.argv) > 1 else 10
    print(f"seconds, best of {runs} runs in fresh interpreters")
    for label, command in COMMANDS.items():
        print(f"  {label:26s} {best(command, runs):6.3f}")


if __name__ == "__main__":
    main()
