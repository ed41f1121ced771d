"""CMake files read as text, where cmake itself is not installed (tests/test_dist.py reads the
firmware package's CMake files with it, tests/test_site_snippets.py the documentation's CMake
blocks): CMake's command syntax, a name and a parenthesized argument list per command, with
strings, comments and ``if`` blocks; not what the commands do."""

from __future__ import annotations

import re

_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")


def _line_end(text: str, i: int) -> int:
    end = text.find("\n", i)
    return len(text) if end < 0 else end


def commands(text: str) -> list[tuple[str, list[str]]]:
    """The commands of a CMake file, each ``(name, arguments)`` (quoted arguments without their
    quotes), in order; ``ValueError`` on what CMake's grammar refuses: text outside a command, a
    name without its ``(``, an unterminated string or argument list, unbalanced ``${``."""
    found: list[tuple[str, list[str]]] = []
    i, n = 0, len(text)

    def line(at: int) -> int:
        return text.count("\n", 0, at) + 1

    while i < n:
        if text[i].isspace():
            i += 1
        elif text[i] == "#":
            i = _line_end(text, i)
        else:
            name = _NAME.match(text, i)
            if name is None:
                raise ValueError(f"line {line(i)}: not a command: {text[i : i + 20]!r}")
            i = name.end()
            while i < n and text[i] in " \t":
                i += 1
            if i >= n or text[i] != "(":
                raise ValueError(f"line {line(i)}: {name.group()} without '('")
            i, depth, arguments, word = i + 1, 1, [], ""
            while depth:
                if i >= n:
                    raise ValueError(f"line {line(i)}: unterminated argument list of {name.group()}")
                c = text[i]
                if c == '"':
                    end = i + 1
                    while end < n and text[end] != '"':
                        end += 2 if text[end] == "\\" else 1
                    if end >= n:
                        raise ValueError(f"line {line(i)}: unterminated string")
                    arguments.append(text[i + 1 : end])
                    i = end + 1
                    continue
                if c == "#":
                    i = _line_end(text, i)
                    continue
                if c in "()" or c.isspace():
                    if word:
                        arguments.append(word)
                        word = ""
                    depth += {"(": 1, ")": -1}.get(c, 0)
                else:
                    word += c
                i += 1
            for argument in arguments:
                if argument.count("${") != argument.count("}"):
                    raise ValueError(f"{name.group()}: unbalanced ${{...}} in {argument!r}")
            found.append((name.group().lower(), arguments))
    blocks: list[str] = []
    for name, _ in found:
        if name == "if":
            blocks.append(name)
        elif name in ("elseif", "else", "endif") and blocks[-1:] != ["if"]:
            raise ValueError(f"{name} outside an if block")
        elif name == "endif":
            blocks.pop()
    if blocks:
        raise ValueError("an if block is not closed")
    return found
