"""MkDocs hooks of the documentation site (mkdocs.yml): the docstrings' Sphinx roles
(``:class:`uwml.Robot```, ``:meth:`hydro```, ...) rendered as the code they name."""

from __future__ import annotations

import re
from typing import Any

_ROLE = re.compile(r":(?:py:)?(?:class|meth|func|mod|attr|data|exc|obj|const):(<code>)")


def on_page_content(html: str, **_: Any) -> str:
    """The page's HTML with every ``:role:`` before inline code removed."""
    return _ROLE.sub(r"\1", html)


def on_post_build(config: Any, **_: Any) -> None:
    """The Rust core's reference, ``cargo doc`` of uwml-core, copied into the site as ``rust/``
    (where cargo is; without it the Rust page says how to build it)."""
    import json
    import shutil
    import subprocess
    from pathlib import Path

    cargo = shutil.which("cargo")
    root = Path(config["config_file_path"]).parent
    if cargo is None:
        return
    # rustdoc's notes on the units written in brackets ("[m]") are not the site's: kept out.
    subprocess.run([cargo, "doc", "-q", "-p", "uwml-core", "--no-deps"], cwd=root, check=True, capture_output=True)
    metadata = subprocess.run(
        [cargo, "metadata", "--format-version", "1", "--no-deps"], cwd=root, check=True, capture_output=True, text=True
    )
    target = Path(json.loads(metadata.stdout)["target_directory"]) / "doc"
    shutil.copytree(target, Path(config["site_dir"]) / "rust", dirs_exist_ok=True)
