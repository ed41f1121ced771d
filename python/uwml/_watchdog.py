"""Ends a local Ray's processes when the process that started it ends, however it ends
(:func:`uwml._ray.ray_session` starts this; standard library only, run as a script).

``python -I _watchdog.py TOKEN``, its standard input a pipe from that process (the driver), in a
session of its own (a terminal's Ctrl-C reaches the driver, not this). The driver sets
``UWML_RAY_WATCH=TOKEN`` in its environment while ``ray.init`` starts the Ray, so that the
processes it starts inherit it (the GCS, the raylet, the monitors, and from the raylet its
agents and workers), then writes a line to the pipe. An environment can be unreadable (a
process that renames itself, as Ray's agents do, may write over it), so the watchdog also notes,
every 0.5 s while Ray starts and every 2 s after, the marked processes and their descendants,
and takes a process whose ``RAY_RAYLET_PID`` is one of them as theirs. When the pipe closes (the
driver ended: returned, raised, or was killed with SIGKILL), it kills all of them, those it
noted and those it finds then; then exits.

Why: Ray starts the GCS and the raylet with the kernel's parent-death signal (they end with the
driver), but not the raylet's agents: with Ray 2.60 the dashboard agent and the runtime-env
agent of a driver killed with SIGKILL were still running a minute after.
"""

from __future__ import annotations

import os
import select
import signal
import sys
import time

#: The environment variable that marks a watched Ray's processes.
VARIABLE = "UWML_RAY_WATCH"
#: How long it keeps killing what it finds once the driver ended (a process then starting).
GRACE_S = 20.0


def _processes() -> dict[int, tuple[int, str, frozenset[bytes]]]:
    """Every process but this one: pid -> (parent, start time, environment entries), from
    Linux's /proc, elsewhere from psutil if it can be imported (else none)."""
    found: dict[int, tuple[int, str, frozenset[bytes]]] = {}
    if os.path.exists("/proc/self/environ"):
        for name in os.listdir("/proc"):
            if not name.isdigit() or int(name) == os.getpid():
                continue
            try:
                with open(f"/proc/{name}/stat", "rb") as handle:
                    stat = handle.read()
                fields = stat[stat.rindex(b")") + 2 :].split()
                with open(f"/proc/{name}/environ", "rb") as handle:
                    environ = frozenset(handle.read().split(b"\0"))
                found[int(name)] = (int(fields[1]), fields[19].decode(), environ)
            except (OSError, ValueError, IndexError):  # gone, a zombie, or not ours
                continue
        return found
    try:
        import psutil  # type: ignore[import-untyped,unused-ignore]
    except ImportError:
        return found
    for process in psutil.process_iter():
        try:
            if process.pid != os.getpid():
                environ = frozenset(f"{k}={v}".encode() for k, v in process.environ().items())
                found[process.pid] = (process.ppid(), str(process.create_time()), environ)
        except (psutil.Error, OSError):
            continue
    return found


def _ours(token: str, known: dict[int, str]) -> dict[int, str]:
    """The watched Ray's live processes (module docstring), pid -> start time: those marked,
    those of a raylet marked now or noted before (``known``), those noted before, and their
    descendants."""
    table = _processes()
    mark = f"{VARIABLE}={token}".encode()
    ours = {pid: start for pid, (_, start, environ) in table.items() if mark in environ}
    ours |= {pid: start for pid, start in known.items() if pid in table and table[pid][1] == start}
    raylets = {f"RAY_RAYLET_PID={pid}".encode() for pid in ours.keys() | known.keys()}
    ours |= {pid: start for pid, (_, start, environ) in table.items() if environ & raylets}
    for pid in table:
        chain, seen = pid, []
        while chain in table and chain not in ours and chain not in seen:
            seen.append(chain)
            chain = table[chain][0]
        if chain in ours:
            ours |= {p: table[p][1] for p in seen}
    return ours


def main(argv: list[str]) -> int:
    token = argv[1]
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    known: dict[int, str] = {}
    ready = False
    while True:  # until the driver's end of the pipe closes; a look every 0.5 s, 2 s once up
        if select.select([0], [], [], 2.0 if ready else 0.5)[0]:
            data = os.read(0, 4096)
            if not data:
                break
            ready = ready or b"\n" in data
        known |= _ours(token, known)
    deadline = time.monotonic() + GRACE_S
    while time.monotonic() < deadline:
        found = _ours(token, known)
        if not found:
            return 0
        for pid in found:
            try:
                os.kill(pid, signal.SIGKILL)
            except OSError:  # gone already
                pass
        time.sleep(0.2)
    return 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
