"""MkDocs hooks of the documentation site (mkdocs.yml): the docstrings' Sphinx roles
(``:class:`uwml.Robot```, ``:meth:`hydro```, ...) rendered as the code they name."""

from __future__ import annotations

import re
from typing import Any

_ROLE = re.compile(r":(?:py:)?(?:class|meth|func|mod|attr|data|exc|obj|const):(<code>)")


def on_page_content(html: str, **_: Any) -> str:
    """The page's HTML with every ``:role:`` before inline code removed."""
    return _ROLE.sub(r"\1", html)
