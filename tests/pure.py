"""Load uwml's pure-Python modules straight from the source tree, without the compiled extension.

``uwml/__init__.py`` imports the Rust extension, so ``import uwml.sea`` needs a built package.
The pure modules (``model.losses``, ``model.parts`` and the package ``model``, ``sea.oil``,
``sea.seawater``, ``sea.conditions``, ``reference``) do not: :func:`load` imports them as
submodules of a bare package ``uwml_pure`` whose path is ``python/uwml`` (``load("sea.oil")``),
so their relative imports resolve to the sources under test. ``fit``, ``paper.synthetic`` and
``viz.plot`` evaluate the joint losses with the Rust core (``uwml.model.joint_losses``): their
tests import them from the built package.
"""

import importlib
import importlib.util
import sys
from pathlib import Path
from types import ModuleType

_PACKAGE = "uwml_pure"
_SOURCE = Path(__file__).resolve().parents[1] / "python" / "uwml"
#: The numpy reference package, which stands alone (numpy and the standard library only).
REFERENCE_DIR = _SOURCE / "reference"


def load(name: str) -> ModuleType:
    """The module ``python/uwml/<name>.py`` (dots for subpackages: ``"sea.oil"`` is
    ``python/uwml/sea/oil.py``), imported without running ``uwml/__init__.py``."""
    if _PACKAGE not in sys.modules:
        package = ModuleType(_PACKAGE)
        package.__path__ = [str(_SOURCE)]
        sys.modules[_PACKAGE] = package
    return importlib.import_module(f"{_PACKAGE}.{name}")


def load_reference() -> ModuleType:
    """The package ``python/uwml/reference/`` on its own, without ``uwml/__init__.py`` (which
    imports the compiled extension): registered under a name of its own so that its relative
    imports resolve to its own submodules."""
    name = "uwml_reference_standalone"
    if name in sys.modules:
        return sys.modules[name]
    spec = importlib.util.spec_from_file_location(name, REFERENCE_DIR / "__init__.py", submodule_search_locations=[str(REFERENCE_DIR)])
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module
    try:
        spec.loader.exec_module(module)
    except BaseException:
        del sys.modules[name]
        raise
    return module
