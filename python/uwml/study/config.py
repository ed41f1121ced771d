"""A study's configuration (``uwml study CONFIG.toml``, :func:`uwml.study.load`): a scenario and
the parameters that vary, checked whole before anything runs.

::

    # uwml study: the paper's leg tracking its gait, SI units
    [scenario]
    kind = "paper_leg"          # the only kind so far: uwml.paper.control_study.run
    cycles = 0.5                # gait cycles per run (a parameter below may vary it)

    [parameters]                # a list is a grid; a table is a random distribution
    depth = [0.0, 3000.0, 6000.0]
    controller = ["land", "hydro", "hydro_losses"]
    coefficient_scale = { distribution = "uniform", low = 0.7, high = 1.3 }
    payload = { distribution = "normal", mean = 1.0, std = 0.2, low = 0.0 }

    [sampling]
    samples = 4                 # random draws per point of the grid (1 without distributions)
    seed = 0

The runs are every point of the grid (the product of the lists, in the order given) times
``samples`` draws of the distributions, numbered from 0; the draws come from ``seed``
(``numpy.random.default_rng``), so the same file gives the same runs, and a resumed study the
runs it lacks. They are made one by one as the study takes them (:meth:`StudyConfig.iter_runs`):
a study of :data:`MAX_RUNS` runs starts at once, in little memory. A distribution is ``uniform``
(``low`` < ``high``), ``normal`` (``mean``, ``std``, clipped to ``low`` < ``high``, by default
the parameter's bounds) or ``choice`` (``values``). Every error names the file and the key.

A file setting (the ``robot`` scenario's description and hydro file) is read for its digest
(SHA-256 of its bytes, :attr:`StudyConfig.inputs`) as well as its path: the study's fingerprint
covers both, so a study does not resume over a robot that changed.

A scenario of one's own (``kind = "custom"``, :mod:`uwml.study.custom`) names its function
(``function = "package.module:function"``, imported here to check it; its module's file is a
file setting, ``function_file``) and its ``metrics``: a list of names, or a table of each
metric's unit (``metrics = { peak_tension = "N", energy = "J" }``, the axes of the study's
figures); its other settings and
its parameters take any names, each a finite number or a string (a grid's values all one or the
other; a distribution ``uniform`` or ``normal`` over any finite numbers, or ``choice``).
"""

from __future__ import annotations

import hashlib
import itertools
import json
import math
import tomllib
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import UwmlError
from .custom import OWN_SETTINGS, RESERVED, check_metrics, function_file, resolve
from .scenarios import DEFAULTS, PARAMETERS, PATH, REQUIRED, SCENARIOS, metric_units
from .vehicle import check_vehicle

__all__ = ["MAX_RUNS", "ConfigError", "Distribution", "StudyConfig", "load", "loads"]

#: The most runs a study may have.
MAX_RUNS = 10_000_000
#: The kind of a custom scenario's settings and parameters: a finite number or a string.
ANY = "any"


class ConfigError(UwmlError):
    """A study configuration that cannot run (the message names the file and the key)."""


@dataclass(frozen=True)
class Distribution:
    """A random parameter (module docstring)."""

    kind: str
    arguments: dict[str, Any]

    def draw(self, rng: np.random.Generator) -> Any:
        a = self.arguments
        if self.kind == "uniform":
            return float(rng.uniform(a["low"], a["high"]))
        if self.kind == "normal":  # clipped, as np.clip would
            return min(max(float(rng.normal(a["mean"], a["std"])), a.get("low", -math.inf)), a.get("high", math.inf))
        values = a["values"]
        return values[int(rng.integers(len(values)))]


@dataclass(frozen=True)
class StudyConfig:
    """A checked study: its scenario's settings, its grid and distributions, draws and seed."""

    source: str
    kind: str
    settings: dict[str, Any]
    grid: dict[str, list[Any]]
    distributions: dict[str, Distribution]
    samples: int
    seed: int
    #: The metrics of its runs (the results' columns).
    metrics: tuple[str, ...] = ()
    #: Each file setting's digest (SHA-256 of the file's bytes when loaded), by setting.
    inputs: dict[str, str] = field(default_factory=dict)
    #: Each metric's unit (:func:`uwml.study.scenarios.metric_units`; ``""``: a custom
    #: scenario's metric declared without one). Not in the fingerprint: the runs do not depend on it.
    units: dict[str, str] = field(default_factory=dict)

    @property
    def n_runs(self) -> int:
        return math.prod(len(values) for values in self.grid.values()) * self.samples

    @property
    def parameter_names(self) -> list[str]:
        return [*self.grid, *self.distributions]

    def runs(self) -> list[dict[str, Any]]:
        """Every run's parameters, numbered (``run``) as the module docstring says (a list: for a
        small study; a study takes them one by one, :meth:`iter_runs`)."""
        return list(self.iter_runs())

    def iter_runs(self, wanted: np.ndarray | None = None) -> Iterator[dict[str, Any]]:
        """The runs of :meth:`runs`, made one by one; with ``wanted`` (a boolean per run), only
        those it marks, the others' draws made and dropped (so each run gets its own draws)."""
        rng = np.random.default_rng(self.seed)
        names = list(self.grid)
        distributions = list(self.distributions.items())
        run = 0
        for point in itertools.product(*self.grid.values()):
            for _ in range(self.samples):
                if wanted is None or wanted[run]:
                    parameters = dict(zip(names, point, strict=True))
                    parameters |= {name: d.draw(rng) for name, d in distributions}
                    yield {"run": run, **parameters}
                else:
                    for _, d in distributions:
                        d.draw(rng)
                run += 1

    def fingerprint(self, inputs: dict[str, str] | None = None) -> str:
        """A digest of what the runs are (not of the file's layout): a resumed study must be
        this one. It covers the file settings' content (:attr:`inputs`, or the digests given)."""
        what: dict[str, Any] = {
            "kind": self.kind,
            "settings": self.settings,
            "grid": self.grid,
            "distributions": {k: [d.kind, d.arguments] for k, d in self.distributions.items()},
            "samples": self.samples,
            "seed": self.seed,
        }
        inputs = self.inputs if inputs is None else inputs
        if inputs:  # none for the scenarios without files: their fingerprints are as before
            what["inputs"] = inputs
        return hashlib.sha256(json.dumps(what, sort_keys=True).encode()).hexdigest()[:16]

    def changed_inputs(self) -> list[str]:
        """The file settings' paths whose content is no longer the one loaded (or is gone)."""
        changed = []
        for key, digest in self.inputs.items():
            try:
                now = _digest(Path(self.settings[key]))
            except OSError:
                now = None
            if now != digest:
                changed.append(str(self.settings[key]))
        return changed


def load(path: str | Path) -> StudyConfig:
    """A study from its TOML file (module docstring)."""
    source = str(path)
    try:
        text = Path(path).read_text(encoding="utf-8")
    except FileNotFoundError:
        raise ConfigError(f"{source}: no such file") from None
    except (OSError, UnicodeDecodeError) as exc:
        raise ConfigError(f"{source}: cannot be read ({exc})") from None
    return loads(text, source, Path(path).parent)


def loads(text: str, source: str = "<study>", folder: str | Path = ".") -> StudyConfig:
    """A study from TOML text (module docstring); file settings relative to ``folder``."""
    try:
        table = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise ConfigError(f"{source}: not TOML ({exc})") from None
    for key in table:
        if key not in ("scenario", "parameters", "sampling"):
            raise ConfigError(f"{source}: key {key!r}: unknown table (a study has [scenario], [parameters] and [sampling])")
    scenario = _table(table, "scenario", source)
    kind = scenario.get("kind", "paper_leg")
    if kind not in SCENARIOS:
        raise ConfigError(f"{source}: key 'scenario.kind': must be one of {', '.join(SCENARIOS)}, got {kind!r}")
    allowed = PARAMETERS[kind]
    settings: dict[str, Any] = {}
    inputs: dict[str, str] = {}
    custom = kind == "custom"
    for key, value in scenario.items():
        if key == "kind" or (custom and key == "metrics"):  # the metrics: once the parameters are known
            continue
        if custom and key == "function":
            settings[key] = _function(value, inputs, settings, source)
            continue
        if custom:
            _custom_name(key, f"scenario.{key}", source)
            settings[key] = _value(value, ANY, f"scenario.{key}", source)
            continue
        if key not in allowed:
            raise ConfigError(f"{source}: key 'scenario.{key}': unknown setting (a {kind} run takes {', '.join(allowed)})")
        if allowed[key] == PATH:
            settings[key] = _path(value, Path(folder), f"scenario.{key}", source)
            try:
                inputs[key] = _digest(Path(settings[key]))
            except OSError as exc:
                raise ConfigError(f"{source}: key 'scenario.{key}': {settings[key]}: cannot be read ({exc.strerror or exc})") from None
        else:
            settings[key] = _value(value, allowed[key], f"scenario.{key}", source)
    for key in REQUIRED[kind]:
        if key not in settings and not (custom and key == "metrics" and key in scenario):
            raise ConfigError(f"{source}: key 'scenario.{key}': missing (a {kind} run needs it)")
    grid: dict[str, list[Any]] = {}
    distributions: dict[str, Distribution] = {}
    for key, value in _table(table, "parameters", source).items():
        where = f"parameters.{key}"
        if custom:
            _custom_name(key, where, source)
        elif key not in allowed:
            raise ConfigError(f"{source}: key '{where}': unknown parameter (a {kind} run takes {', '.join(allowed)})")
        if key in settings:
            raise ConfigError(f"{source}: key '{where}': also set in [scenario]; give it once")
        value_kind = ANY if custom else allowed[key]
        if value_kind == PATH:
            raise ConfigError(f"{source}: key '{where}': a file is a setting of [scenario], not a parameter")
        if isinstance(value, list):
            if not value:
                raise ConfigError(f"{source}: key '{where}': an empty grid")
            grid[key] = _alike([_value(v, value_kind, f"{where}[{i}]", source) for i, v in enumerate(value)], where, source)
        elif isinstance(value, dict):
            distributions[key] = _distribution(value, value_kind, where, source)
        else:
            grid[key] = [_value(value, value_kind, where, source)]
    declared: dict[str, str] = {}
    if custom:
        try:
            settings["metrics"] = list(check_metrics(scenario["metrics"], [*settings, *grid, *distributions]))
            declared = dict(scenario["metrics"]) if isinstance(scenario["metrics"], dict) else {}
        except ValueError as exc:
            raise ConfigError(f"{source}: key 'scenario.metrics': {exc}") from None
    if kind == "vehicle":
        _check_vehicle(settings, grid, distributions, source)
    sampling = _table(table, "sampling", source)
    for key in sampling:
        if key not in ("samples", "seed"):
            raise ConfigError(f"{source}: key 'sampling.{key}': unknown setting (samples, seed)")
    samples = sampling.get("samples", 1)
    seed = sampling.get("seed", 0)
    if not isinstance(samples, int) or isinstance(samples, bool) or not 1 <= samples <= MAX_RUNS:
        raise ConfigError(f"{source}: key 'sampling.samples': must be an integer from 1 to {MAX_RUNS}, got {samples!r}")
    if samples > 1 and not distributions:
        raise ConfigError(f"{source}: key 'sampling.samples': {samples} draws of no random parameter would repeat each run")
    if not isinstance(seed, int) or isinstance(seed, bool) or not 0 <= seed < 2**63:
        raise ConfigError(f"{source}: key 'sampling.seed': must be a non-negative integer, got {seed!r}")
    try:
        units = metric_units(kind, settings, declared)
    except (ValueError, OSError) as exc:
        raise ConfigError(f"{source}: key 'scenario.robot': {exc}") from None
    config = StudyConfig(source, kind, settings, grid, distributions, samples, seed, tuple(units), inputs, units)
    if config.n_runs > MAX_RUNS:
        raise ConfigError(f"{source}: key 'parameters': {config.n_runs} runs, more than {MAX_RUNS}")
    return config


def _function(value: Any, inputs: dict[str, str], settings: dict[str, Any], source: str) -> str:
    """A custom scenario's ``function`` (:mod:`uwml.study.custom`), checked by importing it; its
    module's source file recorded as a file setting (``function_file``), for its digest."""
    where = f"{source}: key 'scenario.function'"
    try:
        resolve(value)  # its name checked (parse) before anything is imported
    except ValueError as exc:
        raise ConfigError(f"{where}: {exc}") from None
    except Exception as exc:  # noqa: BLE001 (the module's own import error, whatever it is)
        raise ConfigError(f"{where}: cannot import {value.split(':')[0]} ({type(exc).__name__}: {exc})") from None
    path = function_file(value)
    if path is not None:
        settings["function_file"] = path
        try:
            inputs["function_file"] = _digest(Path(path))
        except OSError as exc:
            raise ConfigError(f"{where}: {path}: cannot be read ({exc.strerror or exc})") from None
    return str(value)


def _custom_name(key: str, where: str, source: str) -> None:
    """A custom scenario's setting or parameter name: an identifier, not one of its own keys
    nor a result column's."""
    if not (key.isidentifier() and key.isascii()) or key in RESERVED or key in OWN_SETTINGS or key == "kind":
        raise ConfigError(
            f"{source}: key '{where}': a parameter's name must be an identifier other than {', '.join(sorted({*RESERVED, *OWN_SETTINGS, 'kind'}))}"
        )


def _alike(values: list[Any], where: str, source: str) -> list[Any]:
    """A grid's values, all numbers or all strings (a column of the results has one type)."""
    if len({isinstance(v, str) for v in values}) > 1:
        raise ConfigError(f"{source}: key '{where}': mixes numbers and strings; a parameter's values are all one or the other")
    return values


def _check_vehicle(settings: dict[str, Any], grid: dict[str, list[Any]], distributions: dict[str, Distribution], source: str) -> None:
    """The vehicle scenario's description checked (:func:`uwml.study.vehicle.check_vehicle`),
    and a trajectory file not given with the sines' amplitude or period."""
    if "trajectory" in settings:
        for key in ("amplitude", "period"):
            if key in settings or key in grid or key in distributions:
                raise ConfigError(f"{source}: key 'scenario.trajectory': the arm follows the log; {key} is the sines' (drop it)")
    if "station_keeping" in settings:
        keeping = [settings["station_keeping"]]
    elif "station_keeping" in grid:
        keeping = grid["station_keeping"]
    elif "station_keeping" in distributions:
        keeping = distributions["station_keeping"].arguments["values"]
    else:
        keeping = [DEFAULTS["vehicle"]["station_keeping"]]
    try:
        check_vehicle(settings, keeping)
    except (ValueError, OSError) as exc:
        raise ConfigError(f"{source}: key 'scenario.robot': {exc}") from None


def _table(table: dict[str, Any], key: str, source: str) -> dict[str, Any]:
    value = table.get(key, {})
    if not isinstance(value, dict):
        raise ConfigError(f"{source}: key {key!r}: must be a table")
    return value


def _digest(path: Path) -> str:
    """SHA-256 of a file's bytes, in hex."""
    return hashlib.sha256(path.read_bytes()).hexdigest()


def _path(value: Any, folder: Path, where: str, source: str) -> str:
    """A file setting: a string naming an existing file, relative to the study file's folder."""
    if not isinstance(value, str) or not value:
        raise ConfigError(f"{source}: key '{where}': must be a file name, got {value!r}")
    path = folder / value
    if not path.is_file():
        raise ConfigError(f"{source}: key '{where}': {path}: no such file")
    return str(path)


def _value(value: Any, kind: Any, where: str, source: str) -> Any:
    """A setting's value checked against its kind: ``float`` (finite, with its bounds), a tuple
    of allowed strings, or :data:`ANY` (a finite number, as a float, or a string)."""
    if kind == ANY:
        if isinstance(value, str):
            return value
        if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
            raise ConfigError(f"{source}: key '{where}': must be a finite number or a string, got {value!r}")
        return float(value)
    if isinstance(kind, tuple) and len(kind) == 2 and all(isinstance(k, float) for k in kind):
        low, high = kind
        if isinstance(value, bool) or not isinstance(value, int | float) or not (math.isfinite(value) and low <= value <= high):
            raise ConfigError(f"{source}: key '{where}': must be a number from {low:g} to {high:g}, got {value!r}")
        return float(value)
    if value not in kind:
        raise ConfigError(f"{source}: key '{where}': must be one of {', '.join(kind)}, got {value!r}")
    return value


def _distribution(table: dict[str, Any], kind: Any, where: str, source: str) -> Distribution:
    name = table.get("distribution")
    if kind == ANY:  # a custom parameter: any finite number drawn, or a choice of numbers or strings
        if name == "choice" and isinstance(table.get("values"), list):
            _alike(table["values"], f"{where}.values", source)
        else:
            kind = (-math.inf, math.inf)
    numeric = isinstance(kind, tuple) and len(kind) == 2 and all(isinstance(k, float) for k in kind)
    shapes = {"uniform": ("low", "high"), "normal": ("mean", "std"), "choice": ("values",)}
    if name not in shapes or (name != "choice" and not numeric):
        allowed = "uniform, normal or choice" if numeric else "choice"
        raise ConfigError(f"{source}: key '{where}.distribution': must be {allowed}, got {name!r}")
    extra = set(table) - {"distribution", *shapes[name], *(("low", "high") if name == "normal" else ())}
    if extra:
        raise ConfigError(f"{source}: key '{where}.{min(extra)}': unknown for a {name} distribution")
    for key in shapes[name]:
        if key not in table:
            raise ConfigError(f"{source}: key '{where}.{key}': missing (a {name} distribution has {', '.join(shapes[name])})")
    if name == "choice":
        values = table["values"]
        if not isinstance(values, list) or not values:
            raise ConfigError(f"{source}: key '{where}.values': must be a non-empty list")
        return Distribution(name, {"values": [_value(v, kind, f"{where}.values[{i}]", source) for i, v in enumerate(values)]})
    arguments = {key: _value(table[key], kind, f"{where}.{key}", source) for key in table if key != "distribution"}
    if name == "uniform" and not arguments["low"] < arguments["high"]:
        raise ConfigError(f"{source}: key '{where}.high': must be above low ({arguments['low']:g}), got {arguments['high']:g}")
    if name == "normal":
        low, high = kind
        std = table["std"]
        if isinstance(std, bool) or not isinstance(std, int | float) or not (math.isfinite(std) and 0.0 < std <= high - low):
            raise ConfigError(f"{source}: key '{where}.std': must be positive and at most {high - low:g}, got {table['std']!r}")
        arguments["std"] = float(table["std"])
        arguments.setdefault("low", low)
        arguments.setdefault("high", high)
        if not arguments["low"] < arguments["high"]:  # else every draw would be one of them
            if "high" in table:
                raise ConfigError(f"{source}: key '{where}.high': must be above low ({arguments['low']:g}), got {arguments['high']:g}")
            raise ConfigError(
                f"{source}: key '{where}.low': must be below high ({arguments['high']:g}, the parameter's bound), got {arguments['low']:g}"
            )
    return Distribution(name, arguments)
