"""The package's layout (docs/index.md, "What is inside"): layers, each a subpackage, importing only from
the layers below; every module in one layer; no module that only re-exports another's names, no
package that re-exports another package's; no two modules of one name; the numpy reference
standing alone and, with matplotlib, out of ``import uwml``; short modules; one
hydrostatic-pressure formula.

The rules hold for any module by where it sits and what it imports, not by a list of names; each
checker is a function of a graph or a text, and ``test_each_rule_can_fail`` shows it failing on a
made-up one.

Imports are read from the sources (``ast``). The import-time graph has the imports a module runs
when it is imported (at module level, in a class body, under ``if``/``try``/``with``), not those in
functions or under ``if TYPE_CHECKING:``: it must have no circle. The full graph has those in
functions too (a deferred import is a dependency all the same): its edges must point down.
Importing ``uwml.a.b`` from a module outside ``uwml.a`` also runs ``uwml/a/__init__.py``: that
edge is in both.
"""

from __future__ import annotations

import ast
import importlib
import shutil
import subprocess
import sys
import tomllib
import types
from collections.abc import Iterable, Iterator, Mapping
from functools import cache
from pathlib import Path

import numpy as np
import uwml
from uwml.sea import conditions

ROOT = Path(__file__).resolve().parents[1]
SOURCE = ROOT / "python" / "uwml"
REFERENCE = "uwml.reference"

#: The layers, lowest first. A module is in the layer of the name it is or lies under, and
#: imports only from its own layer (without a circle) and those below. The bottom layer is the
#: few modules every layer may use: the compiled core, the checks, the inputs' domains, the
#: errors and warnings, Ray and its watchdog. Then one subpackage a layer.
LAYERS: tuple[tuple[str, ...], ...] = (
    ("uwml._core", "uwml._checks", "uwml.domains", "uwml.errors", "uwml.plausibility", "uwml._ray", "uwml._watchdog"),
    ("uwml.sea",),
    ("uwml.model",),
    ("uwml.io",),
    ("uwml.robot",),
    ("uwml.examples",),
    ("uwml.jax",),
    ("uwml.fit",),
    ("uwml.viz",),
    ("uwml.sim",),
    ("uwml.paper",),
    ("uwml.study",),
    ("uwml.cli",),
)
#: Above every layer: the front door (``uwml/__init__.py``, the names most users need) and
#: ``python -m uwml``. The numpy reference stands apart: it imports nothing of uwml, and nothing
#: of uwml but the front door (lazily) imports it.
TOP = ("uwml", "uwml.__main__")
#: Where no layer or the top holds a module.
NOWHERE = -1


def _module_name(path: Path) -> str:
    parts = path.relative_to(SOURCE.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


@cache
def _modules() -> dict[str, Path]:
    """The package's modules: its ``.py`` files in folders that are packages (a script among an
    example's data files, ``uwml/examples/my_arm/make_logs.py``, is no module)."""
    return {_module_name(path): path for path in sorted(SOURCE.rglob("*.py")) if (path.parent / "__init__.py").exists()}


def _is_package(name: str) -> bool:
    return _modules()[name].name == "__init__.py"


def _known(name: str) -> bool:
    return name in _modules() or name == "uwml._core"


def _under(module: str, head: str) -> bool:
    return module == head or module.startswith(head + ".")


def _layer(module: str) -> int:
    """The index of ``module``'s layer; ``len(LAYERS)`` for the top; ``NOWHERE`` if none."""
    for index, heads in enumerate(LAYERS):
        if any(_under(module, head) for head in heads):
            return index
    return len(LAYERS) if module in TOP else NOWHERE


def _type_checking(node: ast.If) -> bool:
    test = node.test
    return (isinstance(test, ast.Name) and test.id == "TYPE_CHECKING") or (isinstance(test, ast.Attribute) and test.attr == "TYPE_CHECKING")


def _import_nodes(tree: ast.Module, deferred: bool) -> Iterator[ast.Import | ast.ImportFrom]:
    """The import statements of a module, not under ``if TYPE_CHECKING:``; with ``deferred``
    those in functions too."""
    stack: list[ast.AST] = list(tree.body)
    while stack:
        node = stack.pop()
        if isinstance(node, (ast.Import, ast.ImportFrom)):
            yield node
        elif isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda)) and not deferred:
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
def _graph(deferred: bool = False) -> dict[str, frozenset[str]]:
    """Module -> the uwml modules its imports run (with the packages above them it enters);
    ``deferred``: the imports in functions too."""
    graph: dict[str, frozenset[str]] = {}
    for module, path in _modules().items():
        edges: set[str] = set()
        for node in _import_nodes(ast.parse(path.read_text(encoding="utf-8")), deferred):
            for target in _imported(module, node):
                edges.add(target)
                # Importing uwml.a.b from outside uwml.a runs uwml/a/__init__.py first.
                parts = target.split(".")
                for k in range(2, len(parts)):
                    package = ".".join(parts[:k])
                    if not _under(module, package):
                        edges.add(package)
        graph[module] = frozenset(edges - {module})
    return graph


# --------------------------------------------------------------------------------------------
# The rules, each a function of a graph, the modules' names or a module's text
# --------------------------------------------------------------------------------------------


def _cycle(graph: Mapping[str, Iterable[str]]) -> list[str] | None:
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


def _without_a_layer(modules: Iterable[str]) -> list[str]:
    """The modules outside every layer, the top and the reference."""
    return [m for m in modules if _layer(m) == NOWHERE and not _under(m, REFERENCE)]


def _upward(graph: Mapping[str, Iterable[str]]) -> list[str]:
    """Every import of a module (the reference's aside) from a layer above its own."""
    return [
        f"{module} (layer {_layer(module)}) imports {target} (layer {_layer(target)})"
        for module, targets in sorted(graph.items())
        if not _under(module, REFERENCE)
        for target in sorted(targets)
        if not _under(target, REFERENCE) and _layer(target) > _layer(module)
    ]


def _shared_names(modules: Iterable[str]) -> dict[str, list[str]]:
    """The names that more than one module or package has (a leading underscore aside: ``_files``
    and ``files`` read alike), with the modules that have them."""
    by_name: dict[str, list[str]] = {}
    for module in modules:
        last = module.rpartition(".")[2]
        if module != "uwml" and not (last.startswith("__") and last.endswith("__")):  # __main__ is a role, not a name
            by_name.setdefault(last.lstrip("_"), []).append(module)
    return {name: sorted(found) for name, found in sorted(by_name.items()) if len(found) > 1}


def _only_re_exports(text: str) -> bool:
    """Whether a module's text defines nothing: only a docstring, imports and ``__all__``."""
    for node in ast.parse(text).body:
        if isinstance(node, (ast.Import, ast.ImportFrom)):
            continue
        if isinstance(node, ast.Expr) and isinstance(node.value, ast.Constant) and isinstance(node.value.value, str):
            continue
        if isinstance(node, (ast.Assign, ast.AnnAssign)):
            targets = node.targets if isinstance(node, ast.Assign) else [node.target]
            if all(isinstance(t, ast.Name) and t.id == "__all__" for t in targets):
                continue
        return False
    return True


def _foreign_imports(package: str, text: str) -> list[str]:
    """The imports of a package's ``__init__`` from outside the package (``from ..x import``, an
    absolute ``uwml`` import): a package exports its own modules' names, not another's."""
    found = []
    for node in ast.parse(text).body:
        if isinstance(node, ast.ImportFrom) and node.level > 1:
            found.append(f"{package}: from {'.' * node.level}{node.module or ''} import ...")
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and (node.module or "").split(".")[0] == "uwml":
            found.append(f"{package}: from {node.module} import ...")
        elif isinstance(node, ast.Import) and any(a.name.split(".")[0] == "uwml" for a in node.names):
            found.append(f"{package}: import uwml...")
    return found


# --------------------------------------------------------------------------------------------
# The layers
# --------------------------------------------------------------------------------------------


def test_the_graph_reader_sees_relative_imports_and_tells_deferred_ones() -> None:
    graph, full = _graph(), _graph(deferred=True)
    assert "uwml.sim.mujoco" in graph["uwml.sim.control"]  # from .mujoco import Simulation
    assert "uwml._core" in graph["uwml.sim.mujoco"]  # from .. import _core
    assert "uwml.paper.synthetic" in graph["uwml.paper.control_study"]  # from . import synthetic
    assert "uwml.model" in graph["uwml.io.modelfile"]  # entering uwml/model/__init__.py
    # Imported in a function (matplotlib): not at import time, a dependency all the same.
    assert "uwml.viz.plot" not in graph["uwml.paper.analysis"] and "uwml.viz.plot" in full["uwml.paper.analysis"]


def test_every_module_is_in_a_layer() -> None:
    """A new module sits in a subpackage (its layer); a flat module at the top of the package,
    beside the bottom layer's few, has no layer."""
    assert not _without_a_layer(_modules()), "in no layer (put each in the subpackage of its idea): " + ", ".join(
        _without_a_layer(_modules())
    )
    subpackages = {m for m in _modules() if m.count(".") == 1 and _is_package(m)}
    assert subpackages == {heads[0] for heads in LAYERS[1:]} | {REFERENCE}, "a layer without its subpackage, or the reverse"


def test_no_import_circle() -> None:
    cycle = _cycle(_graph())
    assert cycle is None, "import circle: " + " -> ".join(cycle or ())


def test_dependencies_point_down() -> None:
    """Every import, deferred ones too, from the module's own layer or one below."""
    upward = _upward(_graph(deferred=True))
    assert not upward, "\n".join(upward)


def test_no_module_only_re_exports_and_packages_export_their_own() -> None:
    """No shims: every module defines something of its own (a package's ``__init__`` may gather its
    own modules' names, not another package's; the front door gathers the layers' names)."""
    shims = [m for m, path in _modules().items() if path.name != "__init__.py" and _only_re_exports(path.read_text(encoding="utf-8"))]
    assert not shims, f"modules that only re-export: {shims}"
    foreign = [
        finding
        for m, path in _modules().items()
        if path.name == "__init__.py" and m != "uwml"
        for finding in _foreign_imports(m, path.read_text(encoding="utf-8"))
    ]
    assert not foreign, foreign


def test_no_two_modules_share_a_name() -> None:
    shared = _shared_names(_modules())
    assert not shared, shared


def test_each_rule_can_fail() -> None:
    """The checkers above, on made-up modules that break each rule."""
    assert _cycle({"a": {"b"}, "b": {"c"}, "c": {"a"}}) == ["a", "b", "c", "a"]
    assert _upward({"uwml.sea.conditions": {"uwml.robot.tree"}, "uwml.cli.common": {"uwml.robot.tree"}}) == [
        "uwml.sea.conditions (layer 1) imports uwml.robot.tree (layer 4)"
    ]
    assert _upward({"uwml.robot.tree": {"uwml.paper.gait"}})  # a deferred import counts as much
    assert _upward({"uwml.domains": {"uwml"}})  # nothing imports the front door
    assert _without_a_layer(["uwml.gait", "uwml.sim.gait", "uwml.reference.chain"]) == ["uwml.gait"]
    assert _shared_names(["uwml.fit.losses", "uwml.model.losses", "uwml.io._files", "uwml.robot.files", "uwml.sim.__main__"]) == {
        "files": ["uwml.io._files", "uwml.robot.files"],
        "losses": ["uwml.fit.losses", "uwml.model.losses"],
    }
    shim = '"""The former module."""\n\nfrom .paper.gait import WalkingGait\n\n__all__ = ["WalkingGait"]\n'
    assert _only_re_exports(shim) and not _only_re_exports(shim + "\nX = 1\n")
    assert _foreign_imports("uwml.robot", "from .tree import Robot\nfrom ..model.parts import Joint\n") == [
        "uwml.robot: from ..model.parts import ..."
    ]


def test_the_reference_stands_alone_and_production_code_does_not_use_it() -> None:
    # Every import, deferred ones too: the reference is for tests and checks only.
    users, outside = [], []
    for module, targets in _graph(deferred=True).items():
        for target in targets:
            if _under(module, REFERENCE) and not _under(target, REFERENCE):
                outside.append(f"{module} imports {target}")
            if not _under(module, REFERENCE) and module != "uwml" and _under(target, REFERENCE):
                users.append(f"{module} imports {target}")
    assert not outside, outside
    assert not users, users


def test_import_uwml_loads_neither_the_reference_nor_matplotlib_nor_jax() -> None:
    code = (
        "import sys, uwml; "
        "loaded = sorted(m for m in sys.modules if m in ('matplotlib', 'jax') or m.startswith(('matplotlib.', 'jax.', 'uwml.reference', 'uwml.jax'))); "
        "print(loaded)"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=False, timeout=120)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == "[]"


def test_modules_stay_short() -> None:
    long = {
        name: n
        for name, path in _modules().items()
        if not _under(name, REFERENCE) and (n := len(path.read_text(encoding="utf-8").splitlines())) > 600
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
    # The joint losses' pressure is the core's (`pressure_at_depth`), for a batch and one state
    # at a time alike: their losses agree in every bit.
    leg, losses = uwml.paper_leg(), uwml.JointLosses()
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


def test_the_front_door_gives_the_layers_names() -> None:
    """Each name of ``uwml.__all__`` is there, is no module, and is the object of the layer that
    defines it (a class or function: its module is in a layer); the modules ``import uwml`` sets
    as its attributes are its layers' (the numpy reference comes on first use, apart)."""
    assert uwml.__all__ == sorted(uwml.__all__, key=lambda n: (not n.isupper(), n)), "__all__: constants first, then sorted"
    for name in uwml.__all__:
        value = getattr(uwml, name)
        assert not isinstance(value, types.ModuleType), f"uwml.{name} is a module"
        home = getattr(value, "__module__", None)
        if getattr(uwml._core, name, None) is value:
            continue  # the compiled core's (its classes say module "uwml")
        if isinstance(value, type) or callable(value):
            assert home is not None and _layer(home) not in (NOWHERE, len(LAYERS)), f"uwml.{name} comes from {home}"
    # After a bare ``import uwml``, in a fresh interpreter: the modules it has loaded as attributes.
    code = "import types, uwml; print(sorted(n for n, v in vars(uwml).items() if isinstance(v, types.ModuleType)))"
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=False, timeout=120)
    assert done.returncode == 0, done.stderr
    modules = ast.literal_eval(done.stdout.strip())
    assert modules and all(_layer(f"uwml.{n}") not in (NOWHERE, len(LAYERS)) for n in modules), modules


def test_the_command_line_entry_points() -> None:
    scripts = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]["scripts"]
    module, _, function = scripts["uwml"].partition(":")
    assert callable(getattr(importlib.import_module(module), function))
    for program in ("uwml", "uwml.cli"):
        done = subprocess.run([sys.executable, "-m", program, "--help"], capture_output=True, text=True, check=False, timeout=120)
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
