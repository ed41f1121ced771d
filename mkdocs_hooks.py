"""MkDocs hooks of the documentation site (mkdocs.yml): the docstrings' Sphinx roles
(``:class:`uwml.Robot```, ``:meth:`hydro```, ...) rendered as the code they name, and the Rust
snippets' hidden lines (rustdoc's ``# ``: what makes a snippet a doctest) left out."""

from __future__ import annotations

import re
from typing import Any

_ROLE = re.compile(r":(?:py:)?(?:class|meth|func|mod|attr|data|exc|obj|const):(<code>)")


_RUST_BLOCK = re.compile(r"^```rust\n.*?^```$", re.MULTILINE | re.DOTALL)


def _visible(block: re.Match[str]) -> str:
    """A Rust block without rustdoc's hidden lines (``# ...`` and a lone ``#``)."""
    return "\n".join(line for line in block.group(0).split("\n") if not (line == "#" or line.startswith("# ")))


def on_page_markdown(markdown: str, **_: Any) -> str:
    """The page's Markdown with its Rust snippets' hidden lines left out."""
    return _RUST_BLOCK.sub(_visible, markdown)


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
