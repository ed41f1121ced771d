"""A study of a scenario of one's own (``kind = "custom"``, :mod:`uwml.study.scenarios`): a Python
function named in the study file, called once per run with the run's parameters, returning its
metrics (docs/scale.md, "A scenario of your own").

The name is untrusted input and is never evaluated: ``function = "package.module:function"``
must be a dotted module path of identifiers, a colon and one identifier (no attribute path,
no name starting with an underscore, no keyword), outside Python's standard library (checked
before anything is imported: ``os:system``, ``subprocess:run`` or ``antigravity:x`` are refused
unimported). The module is imported by that name (``importlib.import_module``: it must be
importable where the runs are made; on Ray, by every worker: installed, or on ``PYTHONPATH``),
and the name must be a plain Python function (``def``; not a class nor a built-in) that takes
one positional argument: on Ray it travels by reference, as its module and name.

A run calls ``function(parameters)`` with one dict: the ``[scenario]`` table's own settings
(besides ``kind``, ``function`` and ``metrics``) and the run's ``[parameters]`` (numbers as
floats, strings as strings). It returns a dict holding exactly the ``metrics`` the study file
declares, each a finite real number; anything else (another type, a metric missing or extra,
NaN, a bool, an exception, ``sys.exit``) is that run's error, recorded in its row as the
runner records any run's failure.
"""

from __future__ import annotations

import importlib
import importlib.util
import inspect
import keyword
import math
import numbers
import sys
from collections.abc import Callable, Sequence
from typing import Any

__all__ = ["RESERVED", "check_metrics", "custom_run", "function_file", "resolve"]

#: Names a custom study's parameters and metrics may not take: the results' own columns.
RESERVED = frozenset(("run", "error", "error_kind"))
#: The ``[scenario]`` settings of a custom study that are not the function's parameters.
OWN_SETTINGS = ("function", "metrics", "function_file")


def _identifier(name: str) -> bool:
    return name.isidentifier() and name.isascii() and not keyword.iskeyword(name)


def parse(value: object) -> tuple[str, str]:
    """``(module, function)`` of a ``"package.module:function"`` string, or a ValueError."""
    if not isinstance(value, str) or value.count(":") != 1:
        raise ValueError(f'must be "package.module:function" (a dotted module path, a colon, a function name), got {value!r}')
    module, name = value.split(":")
    parts = module.split(".")
    if not all(_identifier(p) for p in parts) or not _identifier(name):
        raise ValueError(f'must be "package.module:function", each part a Python identifier, got {value!r}')
    if name.startswith("_") or any(p.startswith("_") for p in parts):
        raise ValueError(f"names a private module or function (a leading underscore): {value!r}")
    if parts[0] in sys.stdlib_module_names:
        raise ValueError(f"names a module of Python's standard library ({parts[0]}), not a scenario of one's own: {value!r}")
    return module, name


def resolve(value: str) -> Callable[[dict[str, Any]], Any]:
    """The function ``value`` names (module docstring), imported; a ValueError (or the import's
    ImportError) if it is not a plain Python function."""
    module_name, name = parse(value)
    module = importlib.import_module(module_name)
    function = getattr(module, name, None)
    if function is None:
        raise ValueError(f"module {module_name} has no {name!r}")
    if not inspect.isfunction(function):
        kind = "a built-in function" if inspect.isbuiltin(function) else f"a {type(function).__name__}"
        raise ValueError(f"{value} is {kind}, not a Python function (def) of the run's parameters returning its metrics")
    try:
        inspect.signature(function).bind({})
    except TypeError:
        raise ValueError(f"{value} does not take one argument (the run's parameters, a dict)") from None
    return function


def function_file(value: str) -> str | None:
    """The source file of the module ``value`` names (its digest keeps a resumed study on the
    same code), or None if it has none."""
    module_name, _ = parse(value)
    spec = importlib.util.find_spec(module_name)
    origin = None if spec is None else spec.origin
    return origin if origin and origin.endswith(".py") else None


def check_metrics(value: object, parameters: Sequence[str]) -> tuple[str, ...]:
    """The declared metrics' names, or a ValueError: a non-empty list of distinct identifiers,
    none a parameter's or a result column's; or a table of such names, each giving its metric's
    unit (a string, ``""`` for none: ``{ peak_tension = "N", energy = "J" }``)."""
    if isinstance(value, dict):
        units = [unit for unit in value.values() if not isinstance(unit, str)]
        if not value or units:
            raise ValueError(f'a table of metrics must give each one\'s unit as a string (peak_tension = "N"), got {value!r}')
        value = list(value)
    if not isinstance(value, list) or not value or not all(isinstance(v, str) for v in value):
        raise ValueError(f"must be a non-empty list of metric names (or a table of their units), got {value!r}")
    for name in value:
        if not _identifier(name):
            raise ValueError(f"{name!r} is not a name (a Python identifier)")
        if name in RESERVED or name in parameters:
            raise ValueError(f"{name!r} is a {'result column' if name in RESERVED else 'parameter'} already")
    if len(set(value)) != len(value):
        raise ValueError(f"names a metric twice: {value!r}")
    return tuple(value)


def custom_run(settings: dict[str, Any], parameters: dict[str, Any]) -> dict[str, float]:
    """One run of a custom scenario: the function of ``settings["function"]`` called with the
    run's parameters, its metrics checked (module docstring)."""
    function = resolve(settings["function"])
    metrics = tuple(settings["metrics"])
    arguments = {k: v for k, v in settings.items() if k not in OWN_SETTINGS} | parameters
    try:
        result = function(arguments)
    except SystemExit as exc:  # the study goes on: the run's failure, not the process's
        raise RuntimeError(f"{settings['function']} called exit({exc.code!r})") from None
    if not isinstance(result, dict):
        raise TypeError(f"{settings['function']} returned {type(result).__name__}, not a dict of its metrics {', '.join(metrics)}")
    missing = [m for m in metrics if m not in result]
    extra = sorted(str(k) for k in result if k not in metrics)
    if missing or extra:
        said = (
            (f"lacks {', '.join(missing)}" if missing else "")
            + ("; " if missing and extra else "")
            + (f"has {', '.join(extra)} undeclared" if extra else "")
        )
        raise ValueError(f"{settings['function']} returned metrics that do not match the study's ({', '.join(metrics)}): it {said}")
    out = {}
    for name in metrics:
        value = result[name]
        if isinstance(value, bool) or not isinstance(value, numbers.Real) or not math.isfinite(float(value)):
            raise ValueError(f"{settings['function']} returned metric {name} = {value!r}: a metric must be a finite real number")
        out[name] = float(value)
    return out
