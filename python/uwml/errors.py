"""The exceptions of uwml, under one base.

Every exception uwml defines derives from :class:`UwmlError`, which extends :class:`ValueError`
(each is a bad value, model or file), so ``except uwml.UwmlError`` catches any of them and code
that catches ``ValueError`` keeps working. Plain ``ValueError`` and ``TypeError`` still report a
bad argument of one call; :class:`uwml.ExtrapolationWarning` is a warning, not an error.
"""

from __future__ import annotations

from ._core import ModelError, UwmlError

__all__ = ["DescriptionError", "ModelError", "ModelFileError", "UwmlError"]


class ModelFileError(UwmlError):
    """A uwml model file that cannot be read: names the file, the table and the key."""


class DescriptionError(UwmlError):
    """A robot description or hydro file that cannot be mapped: names the file and the element."""
