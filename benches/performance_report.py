"""Every measured table of docs/performance.md, in one run on this machine:

    python benches/performance_report.py [--out benches/performance_tables.md] [--timing PATH]

It runs the benchmarks of this folder at small sizes (a few minutes on 2 cores), through their
own measuring functions (``batch.measure``, ``single_state.measure``, ``simulation.robot_steps``,
``cli_startup.best``, ``large_log.measure_row``, ``study.measure``, ``accelerated.evaluations``,
``accelerated.mjx_steps``),
and, where valgrind is there, counts the instructions of the Rust core's ``timing`` example
(``valgrind --tool=callgrind`` of ``timing 20000 MODE T`` minus ``timing 10000 MODE T``, per
call). Build that example first:

    cargo build --release --example timing -p uwml-core --features wide

(``--timing PATH`` if it is not ``target/release/examples/timing``). The peers are measured in
the same run and given as ratios: the numpy reference (``uwml.reference``) and ``uwml.jax`` on
the CPU against the Rust batch, MuJoCo's own fluid models against uwml's step. Each table is
followed by the machine it ran on. The output is Markdown with one named section per table
(``<!-- --8<-- [start:NAME] -->``), which docs/performance.md includes with ``pymdownx.snippets``.
A benchmark whose requirements are missing (MuJoCo, Ray, JAX, valgrind, the example) leaves its
table saying so.
"""

from __future__ import annotations

import os

# numpy's BLAS threads, left spinning after a call, would take the second core from threads=2.
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
# JAX on the CPU, in float64 too (to compare with the Rust batch's float64).
os.environ.setdefault("JAX_PLATFORMS", "cpu")
os.environ.setdefault("JAX_ENABLE_X64", "1")

import argparse
import datetime
import importlib
import json
import platform
import re
import shutil
import subprocess
import sys
import tempfile
import time
import traceback
from collections.abc import Callable
from pathlib import Path

BENCHES = Path(__file__).resolve().parent
ROOT = BENCHES.parent
sys.path.insert(0, str(BENCHES))

#: The tables, in the order they are measured and written (each a named snippet section).
SECTIONS = (
    "machine",
    "batch",
    "reference",
    "jax",
    "single_state",
    "instructions",
    "simulation",
    "vehicle",
    "mjx",
    "cli",
    "large_logs",
    "study",
    "limits",
    "targets",
)

#: The ``timing`` example's configurations counted with callgrind: (MODE, T, what).
TIMING_MODES = (
    ("robot-leg", "f64", "paper leg, fixed base, still water"),
    ("robot-leg", "f32", "paper leg, fixed base, still water"),
    ("robot-leg", "f64x4", "paper leg, fixed base, still water"),
    ("robot-leg-moving", "f64", "paper leg, moving base in a current"),
    ("environment", "f64", "paper leg with the default losses on its three joints"),
    ("regressors", "f64", "paper leg, every drag and added-mass column"),
    ("kinematics", "f64", "paper leg, foot position and Jacobian"),
    ("robot-arm", "f64", "7-joint arm on a moving ROV in a current"),
    ("robot-arm", "f64x4", "7-joint arm on a moving ROV in a current"),
    ("robot-arm-hull", "f64", "the same with a lumped hull"),
)


def _version(module: str) -> str:
    try:
        return str(importlib.import_module(module).__version__)
    except Exception:  # noqa: BLE001 - absent or broken: say so
        return "absent"


def machine() -> dict[str, str]:
    """The machine and software the run is on: CPU model, cores, clock, versions, date, commit."""
    model, mhz = platform.processor() or platform.machine(), ""
    try:
        cpuinfo = Path("/proc/cpuinfo").read_text()
        found = re.search(r"^model name\s*:\s*(.+)$", cpuinfo, re.MULTILINE)
        model = found.group(1).strip() if found else model
        clock = re.search(r"^cpu MHz\s*:\s*([\d.]+)", cpuinfo, re.MULTILINE)
        mhz = f"{float(clock.group(1)):.0f} MHz (as /proc/cpuinfo reports it)" if clock else ""
    except OSError:
        pass
    try:
        top = int(Path("/sys/devices/system/cpu/cpu0/cpufreq/cpuinfo_max_freq").read_text()) / 1000
        mhz += f", up to {top:.0f} MHz"
    except (OSError, ValueError):
        pass
    cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count()
    commit = subprocess.run(
        ["git", "rev-parse", "--short=12", "HEAD"], cwd=ROOT, capture_output=True, text=True, check=False
    ).stdout.strip()
    return {
        "CPU": model,
        "cores": str(cores),
        "clock": mhz or "unknown",
        "system": f"{platform.system()} {platform.release()}",
        "Python": platform.python_version(),
        "numpy": _version("numpy"),
        "MuJoCo": _version("mujoco"),
        "JAX": _version("jax"),
        "Ray": _version("ray"),
        "pyarrow": _version("pyarrow"),
        "valgrind": _valgrind_version(),
        "date": datetime.datetime.now(datetime.UTC).strftime("%Y-%m-%d %H:%M UTC"),
        "commit": commit or "unknown",
    }


def _valgrind_version() -> str:
    if shutil.which("valgrind") is None:
        return "absent"
    return subprocess.run(["valgrind", "--version"], capture_output=True, text=True, check=False).stdout.strip()


def machine_line(info: dict[str, str]) -> str:
    """The line under each table: where and when it was measured."""
    return (
        f"*Measured on {info['CPU']}, {info['cores']} cores, {info['clock']}; Python {info['Python']}, "
        f"numpy {info['numpy']}, MuJoCo {info['MuJoCo']}, JAX {info['JAX']}; {info['date']}, commit {info['commit']}.*"
    )


def table(header: list[str], rows: list[list[str]]) -> str:
    lines = ["| " + " | ".join(header) + " |", "|" + "|".join("---" for _ in header) + "|"]
    lines += ["| " + " | ".join(row) + " |" for row in rows]
    return "\n".join(lines)


def _n(x: float, digits: int = 1) -> str:
    return f"{x:,.{digits}f}"


# Each measurement returns its table's Markdown (without the machine line).


def measure_batch(n: int, results: dict[str, object]) -> str:
    import batch

    timings = batch.measure(n)
    results["batch"] = timings
    rows = [[label, _n(t * 1e9), _n(1e-6 / t, 2)] for label, t in timings.items()]
    return f"`benches/batch.py`'s evaluations, {n:,} states each, best of 3 calls.\n\n" + table(
        ["evaluation (Python batch)", "ns per state", "million states/s"], rows
    )


def measure_reference(n: int, results: dict[str, object]) -> str:
    import batch

    timings = results.get("batch") or batch.measure(n)
    rust = timings["paper leg, hydro, 1 thread"]  # type: ignore[index]
    numpy_reference = batch.reference_per_state(n, runs=2)
    rows = [
        ["uwml batch (`Robot.hydro`, Rust core, 1 thread)", _n(rust * 1e9), "1"],
        ["numpy reference (`uwml.reference.hydro`)", _n(numpy_reference * 1e9), f"**{numpy_reference / rust:.1f}×** slower"],
    ]
    return f"The paper leg's forces, {n:,} states, best of 2 calls (the reference) and 3 (the batch).\n\n" + table(
        ["implementation", "ns per state", "against the Rust batch"], rows
    )


def measure_jax(states: int, results: dict[str, object]) -> str:
    import accelerated
    import jax

    timings = results.get("batch") or {}
    rust = {
        "paper leg": timings.get("paper leg, hydro, 1 thread"),
        "7-joint arm on a moving ROV": timings.get("7-joint arm on a moving ROV, current, 1 thread"),
    }  # type: ignore[union-attr]
    rows = []
    for name, dtype, compile_s, rate in accelerated.evaluations(states, 3):
        ours = rust.get(name)
        ratio = f"{(1.0 / ours) / rate:.1f}× slower" if ours else "—"
        if ours and rate > 1.0 / ours:
            ratio = f"{rate * ours:.1f}× faster"
        rows.append([name, dtype, _n(compile_s, 2), _n(rate / 1e6, 2), _n(1e-6 / ours, 2) if ours else "—", ratio])
    device = jax.devices()[0]
    return (
        f"`uwml.jax.hydro` under `jit` and `vmap` on `{device.platform}` (`benches/accelerated.py`'s evaluations), "
        f"{states:,} states a batch, best of 3 calls after the compiling one; against the Rust batch of the same robot "
        "on one thread (the table above; float64, its own states and conditions).\n\n"
        + table(["robot", "JAX dtype", "compile s", "JAX million states/s", "Rust batch million states/s", "JAX against Rust"], rows)
    )


def measure_single_state(repeats: int, results: dict[str, object]) -> str:
    import single_state

    timings = single_state.measure(repeats)
    results["single_state"] = timings
    rows = [[label, _n(t * 1e6, 2)] for label, t in timings.items()]
    return f"`benches/single_state.py`'s calls, best of {repeats} `timeit` runs of {single_state.CALLS:,} calls.\n\n" + table(
        ["one state per call, from Python", "µs per call"], rows
    )


def _instructions(binary: Path, n: int, mode: str, precision: str) -> int:
    with tempfile.TemporaryDirectory() as folder:
        out = Path(folder) / "callgrind.out"
        subprocess.run(
            ["valgrind", "--tool=callgrind", f"--callgrind-out-file={out}", str(binary), str(n), mode, precision],
            capture_output=True,
            check=True,
        )
        found = re.search(r"^(?:summary|totals):\s*(\d+)", out.read_text(), re.MULTILINE)
        if found is None:
            raise RuntimeError(f"no instruction count in callgrind's output for {mode} {precision}")
        return int(found.group(1))


def measure_instructions(binary: Path | None, results: dict[str, object]) -> str:
    if binary is None or not binary.exists():
        return "Not measured in this run: the `timing` example was not built (see above)."
    if shutil.which("valgrind") is None:
        return "Not measured in this run: valgrind is not installed."
    rows = []
    for mode, precision, what in TIMING_MODES:
        per_call = (_instructions(binary, 20_000, mode, precision) - _instructions(binary, 10_000, mode, precision)) / 10_000
        lanes = 4 if precision == "f64x4" else 1
        wall = subprocess.run([str(binary), "200000", mode, precision], capture_output=True, text=True, check=True).stdout
        ns = float(re.search(r"([\d.]+) ns per call", wall).group(1))  # type: ignore[union-attr]
        rows.append([what, f"`{mode}`", f"`{precision}`", _n(per_call, 0), _n(per_call / lanes, 0), _n(ns / lanes, 0)])
        results[f"instructions {mode} {precision}"] = (per_call / lanes, ns / lanes)
    return (
        "The Rust core alone (`crates/uwml-core/examples/timing.rs`, release build with the `wide` feature, the x86-64 "
        "baseline): instructions per call from `valgrind --tool=callgrind` (`timing 20000 MODE T` minus `timing 10000 MODE T`, "
        "divided by 10,000; they do not vary between runs), and the wall time of `timing 200000 MODE T` (noisy). `f64x4` "
        "evaluates four states per call, one per SIMD lane.\n\n"
        + table(["evaluation", "MODE", "T", "instructions per call", "per state", "ns per state (wall)"], rows)
    )


def measure_simulation(steps: int, results: dict[str, object]) -> str:
    import simulation

    parts = []
    for name, (file, hydro) in simulation.ROBOTS.items():
        rows = simulation.robot_steps(file, hydro, steps)
        bare, euler = rows["bare mj_step"], rows["uwml.sim.mujoco, euler"]
        results[f"simulation {name}"] = rows
        lines = [[label, _n(micro, 1), f"{micro / bare:.2f}×", f"{micro / euler:.2f}×"] for label, micro in rows.items()]
        parts.append(f"**{name}**\n\n" + table(["step", "µs per step", "against a bare `mj_step`", "against uwml's Euler step"], lines))
    return (
        f"`benches/simulation.py`'s robots (tests/data), median of 5 runs of {steps:,} steps ({steps // 4:,} for the RK4 rows), "
        "each run from the same state. MuJoCo's fluid models (inertia box; ellipsoid) are MuJoCo's own, in water; "
        "uwml's forward pass alone is `Simulation.forward`, four of which an RK4 step makes.\n\n" + "\n\n".join(parts)
    )


def measure_vehicle(steps: int, results: dict[str, object]) -> str:
    import simulation

    rows = simulation.vehicle_rows(steps)
    plain = rows["uwml step"]
    results["vehicle"] = rows
    lines = [[label, _n(micro, 1), f"{micro / plain:.2f}×"] for label, micro in rows.items()]
    return f"The BlueROV2 example with its arm, floating, median of 5 runs of {steps:,} steps.\n\n" + table(
        ["step", "µs per step", "against the plain uwml step"], lines
    )


def measure_mjx(sizes: list[int], results: dict[str, object]) -> str:
    import accelerated
    import jax
    import numpy as np

    found = accelerated.mjx_steps(sizes, 3)
    if found is None:
        raise RuntimeError("uwml.sim.mjx (MuJoCo MJX) is not installed")
    cpu = (results.get("vehicle") or {}).get("with thrust (8 thrusters)")  # type: ignore[attr-defined]
    rows = []
    for what, size, compile_s, rate in found:
        against = f"{rate * cpu * 1e-6:.2f}×" if cpu else "—"
        rows.append([what, f"{size:,}", _n(compile_s, 1), _n(rate / 1e3, 1), against])
    device = jax.devices()[0]
    dtype = np.dtype(jax.dtypes.canonicalize_dtype(np.float64)).name
    return (
        f"The same vehicle in MJX on `{device.platform}` in {dtype} (`benches/accelerated.py --mjx`, "
        "`uwml.sim.mjx.benchmark_steps`): one step of every environment of a batch under `jit` and `vmap`, 20 steps a call, "
        "best of 3 calls after the compiling one; bare MJX (`mujoco.mjx.step` on the same model) against uwml's full step "
        "(the hull's lumped model, the arm's strips, the added mass in the mass matrix, a current, the thrusters), and "
        "against the CPU simulation's step with thrust on one thread (the table above).\n\n"
        + table(["step", "environments", "compile s", "thousand steps/s", "steps/s against the CPU step's"], rows)
    )


def measure_cli(runs: int, results: dict[str, object]) -> str:
    import cli_startup

    rows = []
    for label, command in cli_startup.COMMANDS.items():
        results[f"cli `{label}`"] = seconds = cli_startup.best(command, runs)
        rows.append([f"`{label}`", _n(seconds, 2)])
    return f"Best of {runs} runs, each in a fresh interpreter (`benches/cli_startup.py`).\n\n" + table(["command", "seconds"], rows)


def measure_large_logs(rows_: int, results: dict[str, object]) -> str:
    rows = []
    with tempfile.TemporaryDirectory(prefix="uwml-report-") as directory:
        for fmt in ("csv", "parquet"):
            # In a small process of its own: a child's peak memory starts from its parent's (fork).
            script = f"import json, large_log; print(json.dumps(large_log.measure_row({rows_}, {fmt!r}, {directory!r}, True)))"
            done = subprocess.run([sys.executable, "-c", script], cwd=BENCHES, capture_output=True, text=True, check=True)
            row = json.loads(done.stdout.strip().splitlines()[-1])
            rows.append(
                [
                    f"{rows_:,}",
                    fmt,
                    _n(row["file MB"], 1),
                    f"{row['write s']:.2f} s",
                    f"{row['read s']:.2f} s, {row['read MB']:,.0f} MB",
                    f"{row['fit s']:.2f} s, {row['fit MB']:,.0f} MB",
                    f"{row['torques s']:.2f} s, {row['torques MB']:,.0f} MB",
                ]
            )
    return (
        f"`benches/large_log.py`'s steps on a synthetic log of the paper's leg at 1 kHz (16 columns), {rows_:,} rows; "
        "each in a process of its own, its peak resident memory that process's. Write and read are the library calls' "
        "times; `uwml fit hydro` and `uwml torques --out FILE.parquet` are whole processes, start-up included.\n\n"
        + table(["rows", "format", "file MB", "write", "read, peak", "`uwml fit hydro`, peak", "`uwml torques`, peak"], rows)
    )


def measure_study(runs: int, results: dict[str, object]) -> str:
    import study

    times = study.measure(runs, 0.2, 2)
    serial = times["serial"]
    rows = [
        ["serial, in this process", f"{serial:.2f} s", "1"],
        ["Ray on 2 CPUs, started for the study", f"{times['Ray, started']:.2f} s", f"{serial / times['Ray, started']:.2f}×"],
        ["Ray on 2 CPUs, already running", f"{times['Ray, running']:.2f} s", f"{serial / times['Ray, running']:.2f}×"],
    ]
    return (
        f"`benches/study.py`: {int(times['runs']):,} runs of the `paper_leg` scenario, 0.2 gait cycles each. "
        f"Ray's overhead per task (tasks of one run of almost nothing): {times['per task'] * 1e3:.1f} ms.\n\n"
        + table(["", "time", "speed against the serial loop"], rows)
    )


def measure_limits(n: int, results: dict[str, object]) -> str:
    import batch
    import numpy as np

    times = batch.limits_times(n, np.random.default_rng(1))
    if times is None:
        return "Not measured in this run: MuJoCo (which reads the arm's URDF) is not installed."
    rows = [
        [f"`Robot.{label}`", _n(without * 1e9), _n(with_ * 1e9), f"{with_ / without:.2f}×"] for label, (without, with_) in times.items()
    ]
    return (
        f"The arm of `examples/my_arm` from its URDF, {n:,} states, without and with its joint limits alternately, best of 3 "
        "calls each (`benches/batch.py`'s `limits_times`; no state here warns).\n\n"
        + table(["evaluation", "without the limits, ns per state", "with them", "with / without"], rows)
    )


def _verdict(value: float | None, bound: float, text: str) -> list[str]:
    if value is None:
        return [text, "not measured in this run"]
    return [text, "**met**" if value <= bound else "not met"]


def targets(results: dict[str, object]) -> str:
    """The targets, each against this run's figure (from the tables above)."""
    batch = results.get("batch") or {}
    single = results.get("single_state") or {}
    arm = results.get("simulation arm on a floating hull") or {}
    vehicle = results.get("vehicle") or {}

    def get(mapping: object, key: str) -> float | None:
        return mapping.get(key) if isinstance(mapping, dict) else None

    def worst(mapping: object, start: str, end: str) -> float | None:
        """The slowest of the one-state calls labelled ``start…, end`` (every coefficient form), µs."""
        if not isinstance(mapping, dict):
            return None
        found = [v for k, v in mapping.items() if k.startswith(start) and k.endswith(", " + end)]
        return max(found) * 1e6 if found else None

    def instructions(mode: str, precision: str, index: int) -> float | None:
        pair = results.get(f"instructions {mode} {precision}")
        return pair[index] if isinstance(pair, tuple) else None

    leg1, leg2 = get(batch, "paper leg, hydro, 1 thread"), get(batch, "paper leg, hydro, 2 threads")
    rate = 1.0 / leg1 if leg1 else None
    bare, euler = (get(arm, k) for k in ("bare mj_step", "uwml.sim.mujoco, euler"))
    plain = get(vehicle, "uwml step")
    worst_vehicle = max(get(vehicle, k) or 0.0 for k in ("with thrust (8 thrusters)", "with a prescribed motion")) if plain else None
    rows = []
    # Each target an upper bound on its figure; one of at least x is given as at most -x (the
    # figure negated too, and shown by its size).
    for text, value, bound, shown in (
        ("≤ 100 ns per paper-leg evaluation (f64, Rust, one per call)", instructions("robot-leg", "f64", 1), 100.0, "{:.0f} ns"),
        ("the same, four states per call, per state", instructions("robot-leg", "f64x4", 1), 100.0, "{:.0f} ns"),
        (
            "≤ 50 ns per full environment evaluation (forces and losses, f64, Rust)",
            instructions("environment", "f64", 1),
            50.0,
            "{:.0f} ns",
        ),
        ("Python batch ≥ 10 million states/s on one thread (paper leg, `hydro`)", rate and -rate / 1e6, -10.0, "{:.1f} million/s"),
        ("Python batch ≥ 20 million states/s on one thread", rate and -rate / 1e6, -20.0, "{:.1f} million/s"),
        (
            "paper leg, Python batch, one thread, as fast as the old chain path (79–132 ns per state in its tables)",
            leg1 and leg1 * 1e9,
            79.0,
            "{:.0f} ns",
        ),
        ("`threads=2` scales on both cores (≥ 1.8×)", leg1 and leg2 and -leg1 / leg2, -1.8, "{:.2f}×"),
        (
            "7-joint arm on a moving ROV, Python batch, one thread, ≤ 1 µs per state",
            get(batch, "7-joint arm on a moving ROV, current, 1 thread")
            and get(batch, "7-joint arm on a moving ROV, current, 1 thread") * 1e6,
            1.0,
            "{:.2f} µs",
        ),  # type: ignore[operator]
        (
            "one state from Python ≤ 2 µs: the paper leg at depth with its losses, `Conditions` once",
            (get(single, "paper leg, environment, one JointLosses, Conditions once") or 0) * 1e6 or None,
            2.0,
            "{:.2f} µs",
        ),
        (
            "one state from Python ≤ 2 µs: the 7-joint arm on a moving ROV, `Conditions` once, a fresh result, any coefficient form",
            worst(single, "arm on a moving ROV, current", "Conditions once"),
            2.0,
            "{:.2f} µs",
        ),
        (
            "the same into a `Workspace`",
            worst(single, "arm on a moving ROV, current", "Conditions once, workspace"),
            2.0,
            "{:.2f} µs",
        ),
        ("MuJoCo step with uwml, Euler, the floating arm, ≤ 1.5× a bare `mj_step`", euler and bare and euler / bare, 1.5, "{:.2f}×"),
        (
            "BlueROV2 with thrust or a prescribed motion ≤ 2× the plain uwml step",
            worst_vehicle and plain and worst_vehicle / plain,
            2.0,
            "{:.2f}×",
        ),
        ("`uwml --version` under 0.5 s", results.get("cli `uwml --version`"), 0.5, "{:.2f} s"),  # type: ignore[arg-type]
    ):
        verdict = _verdict(value, bound, text)  # type: ignore[arg-type]
        figure = shown.format(abs(value)) if value is not None else "—"  # type: ignore[arg-type]
        rows.append([verdict[0], figure, verdict[1]])
    return "Each target against this run's figure, from the tables on this page.\n\n" + table(["target", "this run", ""], rows)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--out", type=Path, default=BENCHES / "performance_tables.md", help="the generated Markdown")
    parser.add_argument("--timing", type=Path, default=None, help="the built timing example (default: target/release/examples/timing)")
    parser.add_argument("--states", type=int, default=200_000, help="states of each batch (default 2e5)")
    args = parser.parse_args()
    timing = args.timing
    if timing is None:
        target = Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target"))
        timing = target / "release" / "examples" / "timing"
    info = machine()
    line = machine_line(info)
    results: dict[str, object] = {}
    steps: list[tuple[str, Callable[[], str]]] = [
        ("batch", lambda: measure_batch(args.states, results)),
        ("reference", lambda: measure_reference(args.states, results)),
        ("jax", lambda: measure_jax(args.states // 2, results)),
        ("single_state", lambda: measure_single_state(3, results)),
        ("instructions", lambda: measure_instructions(timing, results)),
        ("simulation", lambda: measure_simulation(1000, results)),
        ("vehicle", lambda: measure_vehicle(1000, results)),
        ("mjx", lambda: measure_mjx([16, 64], results)),
        ("cli", lambda: measure_cli(3, results)),
        ("large_logs", lambda: measure_large_logs(100_000, results)),
        ("study", lambda: measure_study(100, results)),
        ("limits", lambda: measure_limits(args.states, results)),
        ("targets", lambda: targets(results)),
    ]
    machine_table = table(["", ""], [[k, v] for k, v in info.items()])
    sections = {"machine": machine_table}
    started = time.perf_counter()
    for name, step in steps:
        begun = time.perf_counter()
        print(f"{name} ...", file=sys.stderr, flush=True)
        try:
            body = step()
        except Exception as error:  # noqa: BLE001 - a missing requirement leaves its table saying so
            traceback.print_exc()
            body = f"Not measured in this run: {type(error).__name__}: {error}".replace("\n", " ")
        sections[name] = f"{body}\n\n{line}"
        print(f"{name}: {time.perf_counter() - begun:.0f} s", file=sys.stderr, flush=True)
    total = time.perf_counter() - started
    text = [
        "<!-- Generated by `python benches/performance_report.py`: do not edit; run it again. -->",
        f"<!-- One run, {total:.0f} s, {info['date']}. -->",
        "",
    ]
    for name in SECTIONS:
        text += [f"<!-- --8<-- [start:{name}] -->", sections[name], f"<!-- --8<-- [end:{name}] -->", ""]
    args.out.write_text("\n".join(text), encoding="utf-8")
    print(f"wrote {args.out} ({total:.0f} s)", file=sys.stderr)


if __name__ == "__main__":
    main()
