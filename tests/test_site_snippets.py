"""Every snippet of the documentation site's pages (``docs/``) and of the README is checked by
kind (README, "Documentation"; the README's own Python and command-line blocks run in
``tests/test_readme.py``):

- Python: each block runs on its own, as written, in a fresh interpreter with warnings as errors,
  in an empty folder (as after ``pip install uwml``: the examples are the package's,
  ``uwml.examples.path``);
- Rust: the pages that hold Rust blocks are doctests of uwml-core (``crates/uwml-core/src/lib.rs``
  includes them; ``cargo test`` compiles and runs every block, their ``# `` lines hidden on the
  site by ``mkdocs_hooks.py``);
- C: only docs/firmware.md holds C blocks, and uwml-ffi's ``firmware_doc_c_examples_compile``
  compiles each (``docs/reference/c.md`` is rendered from the header by ``mkdocs_c_api.py``);
- shell: every ``uwml`` command line is one the command line's parser takes as written (its
  files are a user's: they are not made here); any other command is one of the tools listed in
  ``ENVIRONMENT_COMMANDS`` (installers, compilers, a cluster's), which set up a machine and are
  not run by the tests;
- TOML: parses; a study configuration (``[scenario]``) is checked whole by ``uwml.study``;
- CMake: reads as CMake's command syntax (``tests/cmake_text.py``; cmake is not run);
- the API reference's docstring examples (their ``Examples`` sections) of ``uwml.Robot`` and
  ``uwml.Conditions`` run as doctests.

A block of any other language, or without one, fails the test: each kind has its check here.
"""

import re
import shlex
import subprocess
import sys
import textwrap
import tomllib
from pathlib import Path

import cmake_text
import pytest
import uwml
from uwml.cli import build_parser

ROOT = Path(__file__).resolve().parents[1]
PAGES = sorted((ROOT / "docs").rglob("*.md"))
#: Languages of blocks that are shown, not run: output, file contents checked elsewhere.
SHOWN = {"text", "xml"}
#: The programs of shell lines that set up a machine (install, build, serve, a cluster's).
ENVIRONMENT_COMMANDS = {
    "pip",
    "cargo",
    "make",
    "cc",
    "rustup",
    "arm-none-eabi-gcc",
    "mkdocs",
    "maturin",
    "bash",
    "ray",
    "srun",
    "sleep",
    "python",
}


def blocks(path: Path) -> list[tuple[str, int, str]]:
    """The fenced blocks of a Markdown file: (language, line, text)."""
    text = path.read_text(encoding="utf-8")
    return [
        (match.group(1), text[: match.start()].count("\n") + 1, match.group(2))
        for match in re.finditer(r"^```([^\n]*)\n(.*?)^```$", text, re.MULTILINE | re.DOTALL)
    ]


def snippets(language: str, pages: list[Path] = PAGES) -> list[tuple[str, str]]:
    return [
        (f"{path.relative_to(ROOT)}:{line}", body) for path in pages for lang, line, body in blocks(path) if lang in language.split("|")
    ]


@pytest.fixture(scope="module")
def folder(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """An empty folder: a snippet finds the examples where the package is installed."""
    return tmp_path_factory.mktemp("site")


def run_python(code: str, folder: Path) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, "-W", "error", "-c", code], cwd=folder, capture_output=True, text=True, timeout=600, check=False)


def test_every_block_has_a_kind_that_is_checked() -> None:
    checked = {"python", "rust", "c", "sh", "bash", "toml", "cmake"} | SHOWN
    for path in [ROOT / "README.md", *PAGES]:
        for language, line, _ in blocks(path):
            assert language in checked, f"{path.relative_to(ROOT)}:{line}: a ```{language} block: give it a language this test checks"


@pytest.mark.parametrize(("where", "code"), snippets("python"), ids=[w for w, _ in snippets("python")])
def test_each_python_block_of_the_site_runs_on_its_own(where: str, code: str, folder: Path) -> None:
    pytest.importorskip("mujoco")
    done = run_python(code, folder)
    assert done.returncode == 0, f"{where}:\n{code}\n{done.stderr[-3000:]}"


@pytest.mark.parametrize("name", ["Robot", "Conditions"])
def test_the_api_references_docstring_examples_run(name: str, folder: Path) -> None:
    assert ">>> " in (getattr(uwml, name).__doc__ or ""), f"uwml.{name}'s docstring has no example"
    code = textwrap.dedent(f"""\
        import doctest, uwml
        (test,) = doctest.DocTestFinder(recurse=False).find(uwml.{name}, "uwml.{name}", globs={{}})
        runner = doctest.DocTestRunner()
        runner.run(test)
        raise SystemExit(runner.failures or not runner.tries)
        """)
    done = run_python(code, folder)
    assert done.returncode == 0, f"uwml.{name}'s example:\n{done.stdout[-3000:]}\n{done.stderr[-3000:]}"


def test_the_pages_with_rust_blocks_are_doctests() -> None:
    lib = (ROOT / "crates/uwml-core/src/lib.rs").read_text(encoding="utf-8")
    included = set(re.findall(r'#\[cfg\(doctest\)\]\n#\[doc = include_str!\("\.\./\.\./\.\./([^"]+)"\)\]', lib))
    pages = {where.split(":")[0] for where, _ in snippets("rust", [ROOT / "README.md", *PAGES])}
    assert pages and pages <= included, f"pages with Rust blocks that are not doctests: {sorted(pages - included)}"
    # The site hides rustdoc's hidden lines; the doctest needs them.
    sys.path.insert(0, str(ROOT))
    try:
        import mkdocs_hooks
    finally:
        sys.path.remove(str(ROOT))
    shown = mkdocs_hooks.on_page_markdown("```rust\nuse a;\n# let hidden = 1;\n#\nlet b = 2;\n# Ok::<(), E>(())\n```\n")
    assert shown == "```rust\nuse a;\nlet b = 2;\n```\n"


def test_the_c_blocks_are_the_firmware_pages_which_are_compiled() -> None:
    pages = {where.split(":")[0] for where, _ in snippets("c", [ROOT / "README.md", *PAGES])}
    assert pages == {"docs/firmware.md"}
    program = (ROOT / "crates/uwml-ffi/tests/c_program.rs").read_text(encoding="utf-8")
    assert "fn firmware_doc_c_examples_compile()" in program and 'join("../../docs/firmware.md")' in program


def shell_commands(code: str) -> list[str]:
    """The commands of a shell block: continuation lines joined, comments dropped, ``&&``
    chains split (a line of a batch script's syntax is kept: the caller skips it)."""
    joined = re.sub(r"\\\n\s*", " ", code)
    commands = []
    for line in joined.splitlines():
        line = re.sub(r"(^|\s)#.*$", "", line).strip()
        commands += [part.strip() for part in line.split("&&") if part.strip()]
    return commands


SHELL = snippets("sh|bash", [ROOT / "README.md", *PAGES])


@pytest.mark.parametrize(("where", "code"), SHELL, ids=[w for w, _ in SHELL])
def test_each_shell_block_is_commands_the_tools_take(where: str, code: str) -> None:
    parser = build_parser()
    for command in shell_commands(code):
        if re.match(r"^((export )?\w+=\S*$|\w+=\(|for |done$|#!|#SBATCH)", command):
            continue  # shell syntax of a batch script
        command = re.split(r"\s[>|]\s", command)[0].removesuffix("&").strip()  # a redirection, a pipe, a background job
        words = shlex.split(command)
        while words and re.match(r"^\w+=", words[0]):
            words = words[1:]  # VAR=value before a command
        program = words[0]
        if program == "uwml":
            try:
                parser.parse_args(words[1:])
            except SystemExit as exc:
                pytest.fail(f"{where}: `{command}`: the command line refuses it (exit {exc.code})")
        else:
            assert program in ENVIRONMENT_COMMANDS, f"{where}: `{command}`: {program} is neither uwml nor a listed tool"


@pytest.mark.parametrize(("where", "code"), snippets("cmake"), ids=[w for w, _ in snippets("cmake")])
def test_each_cmake_block_reads_as_cmake(where: str, code: str) -> None:
    try:
        cmake_text.commands(code)
    except ValueError as exc:
        pytest.fail(f"{where}: {exc}")


@pytest.mark.parametrize(("where", "code"), snippets("toml"), ids=[w for w, _ in snippets("toml")])
def test_each_toml_block_parses_and_a_study_is_a_valid_study(where: str, code: str) -> None:
    document = tomllib.loads(code)
    if "scenario" in document:
        pytest.importorskip("mujoco")
        from uwml.study import config

        config.loads(code, where, folder=ROOT / "examples" / "bluerov2")
