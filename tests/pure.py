"""Load uwml's pure-Python modules straight from the source tree, without the compiled extension.

``uwml/__init__.py`` imports the Rust extension, so ``import uwml.fit`` needs a built package.
The loss modules (``losses``, ``reference``, ``oil``, ``seawater``, ``synthetic``, ``fit``,
``plot``) do not: :func:`load` imports them as submodules of a bare package ``uwml_pure`` whose
path is ``python/uwml``, so their relative imports resolve to the sources under test.
"""

import importlib
import sys
from pathlib import Path
from types import ModuleType

_PACKAGE = "uwml_pure"
_SOURCE = Path(__file__).resolve().parents[1] / "python" / "uwml"


def load(name: str) -> ModuleType:
    """The module ``python/uwml/<name>.py``, imported without running ``uwml/__init__.py``."""
    if _PACKAGE not in sys.modules:
        package = ModuleType(_PACKAGE)
        package.__path__ = [str(_SOURCE)]
        sys.modules[_PACKAGE] = package
    return importlib.import_module(f"{_PACKAGE}.{name}")
