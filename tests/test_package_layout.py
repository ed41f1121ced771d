"""The package's layout (README, "What is inside"): one idea per subpackage, dependencies pointing
one way, the numpy reference and matplotlib out of ``import uwml``, no production use of the
reference, one hydrostatic-pressure formula.

The import graph is read from the sources (``ast``): every import a module runs when it is
imported (at module level, in a class body, under ``if``/``try``/``with``), not those inside
functions or under ``if TYPE_CHECKING:``. Importing ``uwml.a.b`` from a module outside ``uwml.a``
also runs ``uwml/a/__init__.py``: that edge is in the graph too.
"""

from __future__ import annotations

import ast
import importlib
import shutil
import subprocess
import sys
import tomllib
from functools import cache
from pathlib import Path

import numpy as np
import uwml
from uwml.robot.leg import Leg
from uwml.sea import conditions

ROOT = Path(__file__).resolve().parents[1]
SOURCE = ROOT / "python" / "uwml"
REFERENCE = "uwml.reference"

#: The layers, lowest first: a module imports (at module level) only from its own layer or lower
#: ones. Within a layer the graph must still be acyclic. The package itself (``uwml/__init__.py``)
#: comes last.
LAYERS = (
    ("uwml._core", "uwml._checks", "uwml.domains", "uwml.errors", "uwml._ray", "uwml.plausibility"),
    ("uwml.sea",),
    ("uwml.model",),
    ("uwml.io",),
    ("uwml.robot",),
    ("uwml.fit",),
    ("uwml.viz",),
    ("uwml.sim",),
    ("uwml.paper",),
    ("uwml.study",),
    ("uwml.cli", "uwml.__main__"),
)

#: What ``import uwml`` exposed before the subpackages (public names and modules), still there.
TOP_LEVEL = [
    "BaseMotion",
    "BaseWrench",
    "DescriptionError",
    "Drive",
    "EnvironmentJacobians",
    "EnvironmentTorques",
    "ExtrapolationWarning",
    "HydroRegressors",
    "HydroTorques",
    "Joint",
    "JointLosses",
    "Leg",
    "Link",
    "Log",
    "LossTorques",
    "MAX_JOINTS",
    "MAX_ROBOT_JOINTS",
    "MAX_SEGMENTS",
    "ModelError",
    "ModelFileError",
    "OilDrag",
    "Robot",
    "RobotEnvironment",
    "RobotJacobians",
    "RobotRegressors",
    "RobotTorques",
    "Seal",
    "Segment",
    "UwmlError",
    "WalkingGait",
    "Water",
    "domains",
    "errors",
    "hydrostatic_pressure_mpa",
    "model",
    "paper_leg_foot",
    "paper_leg_ik",
    "read_log",
    "robot",
    "write_log",
]


def _module_name(path: Path) -> str:
    parts = path.relative_to(SOURCE.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


@cache
def _modules() -> dict[str, Path]:
    return {_module_name(path): path for path in sorted(SOURCE.rglob("*.py"))}


def _is_package(name: str) -> bool:
    return _modules()[name].name == "__init__.py"


def _known(name: str) -> bool:
    return name in _modules() or name == "uwml._core"


def _type_checking(node: ast.If) -> bool:
    test = node.test
    return (isinstance(test, ast.Name) and test.id == "TYPE_CHECKING") or (isinstance(test, ast.Attribute) and test.attr == "TYPE_CHECKING")


def _import_time_nodes(tree: ast.Module):
    """The import statements a module runs when imported: not in functions, not under TYPE_CHECKING."""
    stack: list[ast.AST] = list(tree.body)
    while stack:
        node = stack.pop()
        if isinstance(node, (ast.Import, ast.ImportFrom)):
            yield node
        elif isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda)):
            continue
        elif isinstance(node, ast.If) and _type_checking(node):
            stack.extend(node.orelse)
        else:
            stack.extend(ast.iter_child_nodes(node))


def _imported(module: str, node: ast.Import | ast.ImportFrom) -> list[str]:
    """The uwml modules an import statement of ``module`` names (``from . import x``: the
    submodule ``x`` where there is one, else the package)."""
    if isinstance(node, ast.Import):
        return [alias.name for alias in node.names if alias.name.split(".")[0] == "uwml"]
    if node.level:
        package = module if _is_package(module) else module.rpartition(".")[0]
        for _ in range(node.level - 1):
            package = package.rpartition(".")[0]
        base = f"{package}.{node.module}" if node.module else package
    else:
        base = node.module or ""
    if base.split(".")[0] != "uwml":
        return []
    found = []
    for alias in node.names:
        candidate = f"{base}.{alias.name}"
        found.append(candidate if _known(candidate) else base)
    return found


@cache
def _graph() -> dict[str, set[str]]:
    """Module -> the uwml modules importing it runs (with the packages above them it enters)."""
    graph: dict[str, set[str]] = {}
    for module, path in _modules().items():
        edges: set[str] = set()
        for node in _import_time_nodes(ast.parse(path.read_text(encoding="utf-8"))):
            for target in _imported(module, node):
                edges.add(target)
                # Importing uwml.a.b from outside uwml.a runs uwml/a/__init__.py first.
                parts = target.split(".")
                for k in range(2, len(parts)):
                    package = ".".join(parts[:k])
                    if not (module == package or module.startswith(package + ".")):
                        edges.add(package)
        graph[module] = edges - {module}
    return graph


def _cycle(graph: dict[str, set[str]]) -> list[str] | None:
    """One cycle of ``graph`` (its modules in order, the first repeated at the end), or None."""
    state: dict[str, int] = {}  # 1: on the current path, 2: done
    path: list[str] = []

    def visit(node: str) -> list[str] | None:
        state[node] = 1
        path.append(node)
        for nxt in sorted(graph.get(node, ())):
            if state.get(nxt) == 1:
                return path[path.index(nxt) :] + [nxt]
            if nxt not in state:
                found = visit(nxt)
                if found:
                    return found
        path.pop()
        state[node] = 2
        return None

    for node in sorted(graph):
        if node not in state:
            found = visit(node)
            if found:
                return found
    return None


def _layer(module: str) -> int:
    for index, heads in enumerate(LAYERS):
        if any(module == head or module.startswith(head + ".") for head in heads):
            return index
    return len(LAYERS)  # the package itself and the former flat modules


# --------------------------------------------------------------------------------------------
# The import graph
# --------------------------------------------------------------------------------------------


def test_the_graph_reader_sees_relative_imports_and_skips_deferred_ones() -> None:
    graph = _graph()
    assert "uwml.robot.tree" in graph["uwml.robot.leg"]  # from .tree import Robot
    assert "uwml._core" in graph["uwml.robot.leg"]  # from .. import _core
    assert "uwml.paper.synthetic" in graph["uwml.paper.control_study"]  # from . import synthetic
    assert "uwml.model" in graph["uwml.io.modelfile"]  # entering uwml/model/__init__.py
    assert "uwml.viz.plot" not in graph["uwml.paper.analysis"]  # imported in a function (matplotlib)
    assert _cycle({"a": {"b"}, "b": {"c"}, "c": {"a"}}) == ["a", "b", "c", "a"]


def test_no_import_circle() -> None:
    cycle = _cycle(_graph())
    assert cycle is None, "import circle: " + " -> ".join(cycle or ())


def test_dependencies_point_one_way() -> None:
    upward = [
        f"{module} (layer {_layer(module)}) imports {target} (layer {_layer(target)})"
        for module, targets in _graph().items()
        if not module.startswith(REFERENCE)
        for target in sorted(targets)
        if _layer(target) > _layer(module)
    ]
    assert not upward, "\n".join(upward)


def test_the_reference_stands_alone_and_production_code_does_not_use_it() -> None:
    # Every import, deferred ones too: the reference is for tests and checks only.
    users, outside = [], []
    for module, path in _modules().items():
        tree = ast.parse(path.read_text(encoding="utf-8"))
        for node in ast.walk(tree):
            if not isinstance(node, (ast.Import, ast.ImportFrom)):
                continue
            for target in _imported(module, node):
                if module.startswith(REFERENCE) and not target.startswith(REFERENCE):
                    outside.append(f"{module} imports {target}")
                if not module.startswith(REFERENCE) and module != "uwml" and target.startswith(REFERENCE):
                    users.append(f"{module} imports {target}")
    assert not outside, outside
    assert not users, users


def test_import_uwml_loads_neither_the_reference_nor_matplotlib() -> None:
    code = (
        "import sys, uwml; "
        "loaded = sorted(m for m in sys.modules if m == 'matplotlib' or m.startswith(('matplotlib.', 'uwml.reference'))); "
        "print(loaded)"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=False, timeout=120)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == "[]"


def test_modules_stay_short() -> None:
    long = {
        name: n
        for name, path in _modules().items()
        if not name.startswith(REFERENCE) and (n := len(path.read_text(encoding="utf-8").splitlines())) > 600
    }
    assert not long, long


# --------------------------------------------------------------------------------------------
# The hydrostatic pressure
# --------------------------------------------------------------------------------------------


def _names_in(node: ast.AST) -> set[str]:
    return {n.id.lower() if isinstance(n, ast.Name) else n.attr.lower() for n in ast.walk(node) if isinstance(n, (ast.Name, ast.Attribute))}


def test_one_hydrostatic_pressure_formula() -> None:
    """No product of a depth with a density or gravity outside :func:`uwml.sea.conditions.hydrostatic_pressure`."""
    found = []
    for module, path in _modules().items():
        if module.startswith(REFERENCE):
            continue
        tree = ast.parse(path.read_text(encoding="utf-8"))
        allowed = {
            id(node)
            for fn in ast.walk(tree)
            if isinstance(fn, ast.FunctionDef) and module == "uwml.sea.conditions" and fn.name == "hydrostatic_pressure"
            for node in ast.walk(fn)
        }
        for node in ast.walk(tree):
            if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Mult) and id(node) not in allowed:
                names = _names_in(node)
                if any("depth" in n for n in names) and any(k in n for n in names for k in ("density", "gravity", "rho")):
                    found.append(f"{module}:{node.lineno}: {ast.unparse(node)}")
    assert not found, found


def test_the_pressures_are_the_one_formula_bit_for_bit() -> None:
    depth = np.array([0.0, 0.1, 1.0, 123.456, 1000.0, 3333.3, 10_999.9])
    pascal = conditions.hydrostatic_pressure(depth, 1025.0, 9.81)
    assert np.array_equal(pascal, 1025.0 * 9.81 * depth)  # the core's order: density · gravity · depth
    assert np.array_equal(uwml.hydrostatic_pressure_mpa(depth), pascal / 1e6)
    pressure, temperature = conditions.loss_conditions(depth, 4.0, 1025.0, 9.81, len(depth))
    assert np.array_equal(pressure, pascal) and np.array_equal(temperature, np.full(len(depth), 4.0))
    # A batch (pressure from Python) and one state at a time (pressure from the core) agree in every bit.
    leg, losses = Leg.paper(), uwml.JointLosses()
    q = np.tile([0.1, -0.4, 0.7], (len(depth), 1))
    qd = np.tile([0.3, 0.2, -0.5], (len(depth), 1))
    batch = leg.environment(q, qd, np.zeros_like(q), depth=depth, temperature_c=4.0, losses=losses)
    for i, z in enumerate(depth):
        one = leg.environment(list(q[i]), list(qd[i]), [0.0, 0.0, 0.0], depth=float(z), temperature_c=4.0, losses=losses)
        for field in ("visc", "seal", "current"):
            assert np.array_equal(getattr(one, field), getattr(batch, field)[i]), (field, z)


# --------------------------------------------------------------------------------------------
# The front door and the command line
# --------------------------------------------------------------------------------------------


def test_the_top_level_namespace_is_unchanged() -> None:
    """Every name it had, and the ones added since on purpose (the lumped model of
    docs/model.md section 12.1: ``LumpedModel``, ``MAX_LUMPED_BODIES``; the warning of likely
    unit mistakes, ``PlausibilityWarning``)."""
    assert uwml.__all__ == [
        "MAX_JOINTS", "MAX_LUMPED_BODIES", "MAX_ROBOT_JOINTS", "MAX_SEGMENTS", "BaseMotion", "BaseWrench", "DescriptionError",
        "Drive", "EnvironmentJacobians", "EnvironmentTorques", "ExtrapolationWarning", "HydroRegressors", "HydroTorques", "Joint",
        "JointLosses", "Leg", "Link", "Log", "LossTorques", "LumpedModel", "ModelError", "ModelFileError", "OilDrag", "PlausibilityWarning", "Robot",
        "RobotEnvironment", "RobotJacobians", "RobotRegressors", "RobotTorques", "Seal", "Segment", "UwmlError",
        "WalkingGait", "Water", "hydrostatic_pressure_mpa", "paper_leg_foot", "paper_leg_ik", "read_log", "write_log",
    ]  # fmt: skip
    # After a bare `import uwml`, in a fresh interpreter: every name it had, the modules included.
    code = f"import uwml; missing = [n for n in {TOP_LEVEL!r} if not hasattr(uwml, n)]; print(missing)"
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=False, timeout=120)
    assert done.returncode == 0 and done.stdout.strip() == "[]", done.stdout + done.stderr


def test_the_command_line_entry_points() -> None:
    scripts = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]["scripts"]
    module, _, function = scripts["uwml"].partition(":")
    assert callable(getattr(importlib.import_module(module), function))
    done = subprocess.run([sys.executable, "-m", "uwml", "--help"], capture_output=True, text=True, check=False, timeout=120)
    assert done.returncode == 0 and "usage: uwml" in done.stdout, done.stderr


# --------------------------------------------------------------------------------------------
# The pure-Python modules
# --------------------------------------------------------------------------------------------


def test_the_pure_modules_import_without_the_compiled_core(tmp_path: Path) -> None:
    """What tests/pure.py loads imports from a copy of the sources without the extension."""
    copy = tmp_path / "uwml"
    shutil.copytree(SOURCE, copy, ignore=shutil.ignore_patterns("*.so", "*.pyd", "__pycache__"))
    code = (
        "import importlib, sys, types\n"
        f"package = types.ModuleType('bare'); package.__path__ = [{str(copy)!r}]; sys.modules['bare'] = package\n"
        "for name in ('model', 'model.parts', 'model.losses', 'sea', 'sea.conditions', 'sea.oil', 'sea.seawater', 'reference'):\n"
        "    importlib.import_module('bare.' + name)\n"
        "assert 'bare._core' not in sys.modules and not any(m == 'uwml' or m.startswith('uwml.') for m in sys.modules)\n"
        "print('ok')\n"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=False, timeout=120)
    assert done.returncode == 0 and done.stdout.strip() == "ok", done.stderr
