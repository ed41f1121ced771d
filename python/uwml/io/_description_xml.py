"""A robot description's XML as written, read before MuJoCo reads it (for uwml.io.descriptions).

MuJoCo reads URDF and MJCF well, but some files make it wait forever, take minutes, or change
what was written without a word. :func:`scan` reads the XML once with the standard library's
expat parser (streaming, no tree; external entities are not fetched, and expat bounds entity
expansion) and refuses, each with a :class:`DescriptionError` naming the file and the element:

- a file that is not a regular file (MuJoCo waits forever on a named pipe and reads a device
  forever): the description, every ``<include>``\\ d file, and every file an element names
  (meshes, textures, height fields, skins, model assets), wherever MuJoCo may look for it
  (beside the description or the file naming it, in ``meshdir``/``texturedir``/``assetdir``,
  or by its base name, as URDF ``package://`` paths are read);
- a description beyond uwml's limits (:data:`MAX_DESCRIPTION_BODIES` bodies, ``MAX_ROBOT_JOINTS``
  moving joints, :data:`MAX_DESCRIPTION_GEOMS` geoms), counted as written: ``<replicate>``
  multiplies its content and ``<include>`` adds the included file's, so a 300-byte MJCF that
  replicates into thousands of bodies is refused before MuJoCo expands it, and a 10,000-link
  URDF before MuJoCo's reader, which takes minutes on it;
- what MuJoCo would change silently or report without the name: a URDF link or joint name given
  twice (MuJoCo renames the second joint, and cuts the link's name off its message), a URDF
  ``<mimic>`` (uwml has no coupled joints), a number that is not finite (``nan``, ``inf``,
  ``1e400``);
- URDF joints uwml does not take (``planar``, ``floating``, an unknown type), named, before
  MuJoCo splits a planar joint into three;
- MJCF ``<composite>`` and ``<flexcomp>``, which generate bodies (deformable or not) at parse.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass, field
from pathlib import Path
from xml.parsers import expat

from .._checks import shown
from .._core import MAX_ROBOT_JOINTS, MAX_SEGMENTS
from ._description_io import DescriptionError, clipped, not_regular, read_regular

__all__ = ["MAX_DESCRIPTION_BODIES", "MAX_DESCRIPTION_GEOMS", "limits_exceeded", "scan"]

#: The most bodies (links) a description may have: its base, ``MAX_ROBOT_JOINTS`` moving links
#: and as many fixed ones as uwml takes segments (``MAX_SEGMENTS``).
MAX_DESCRIPTION_BODIES = 1 + MAX_ROBOT_JOINTS + MAX_SEGMENTS
#: The most geoms (visual and collision) a description may have: 8 per segment uwml takes.
MAX_DESCRIPTION_GEOMS = 8 * MAX_SEGMENTS
#: How deep ``<include>`` and ``<attach>`` may nest.
_MAX_NESTING = 16

_URDF_JOINTS = ("revolute", "continuous", "prismatic", "fixed")
_FOLDERS = ("meshdir", "texturedir", "assetdir")
# Attributes that hold names or words, never numbers ("inf" may be a link's name).
_WORD_ATTRIBUTES = (
    "name class childclass link joint joint1 joint2 body body1 body2 mesh material texture hfield type model prefix target objname reftype "
    "refname key content_type plugin instance actuator sensor camera light skin flex site site1 site2 geom geom1 geom2 tendon tendon1 tendon2 "
    "builtin mark gridlayout mode filename file version xmlns"
)
_WORDS = frozenset(_WORD_ATTRIBUTES.split())


def limits_exceeded(
    source: str, bodies: int, joints: int, geoms: int, *, urdf: bool, counted: str = "counted as written, before MuJoCo reads it"
) -> DescriptionError | None:
    """The error of a description with these counts, or None within uwml's limits."""
    problems = []
    if joints > MAX_ROBOT_JOINTS + (0 if urdf else 1):
        problems.append(
            f"{joints} moving joints, at most {MAX_ROBOT_JOINTS} (uwml.MAX_ROBOT_JOINTS)"
            if urdf
            else f"{joints} joints, at most {MAX_ROBOT_JOINTS + 1} (uwml.MAX_ROBOT_JOINTS moving joints and a free root)"
        )
    if bodies > MAX_DESCRIPTION_BODIES:
        problems.append(
            f"{bodies} {'links' if urdf else 'bodies'}, at most {MAX_DESCRIPTION_BODIES} "
            "(the base, uwml.MAX_ROBOT_JOINTS moving links and uwml.MAX_SEGMENTS fixed ones)"
        )
    if geoms > MAX_DESCRIPTION_GEOMS:
        problems.append(f"{geoms} geoms (visual and collision), at most {MAX_DESCRIPTION_GEOMS} (8 per segment of uwml.MAX_SEGMENTS)")
    if not problems:
        return None
    return DescriptionError(f"{source}: too large for uwml: {'; '.join(problems)} ({counted})")


@dataclass
class _Counts:
    bodies: int = 0
    joints: int = 0
    geoms: int = 0
    attached: list[tuple[str, int]] = field(default_factory=list)  # (model asset, times)

    def add(self, other: _Counts, times: int) -> None:
        self.bodies += times * other.bodies
        self.joints += times * other.joints
        self.geoms += times * other.geoms
        self.attached += [(name, times * n) for name, n in other.attached]


@dataclass
class _Edge:
    """A URDF joint: its name, where it is written, its parent and child links."""

    name: str
    where: str
    parent: str | None = None
    child: str | None = None


@dataclass
class _Element:
    tag: str
    name: str
    times: int  # how many copies of its content <replicate> makes
    in_world: bool  # inside <worldbody> (bodies, joints, geoms count)
    in_default: bool  # inside <default> (class defaults, not elements)


def _quoted(text: str) -> str:
    return f"'{text}'" if len(text) <= 60 and text.isprintable() and "'" not in text else shown(text, 40)


class _Scan:
    def __init__(self, path: str | os.PathLike[str], what: str) -> None:
        self.main = Path(path)
        self.source = str(path)
        self.what = what
        self.format = ""
        self.references: list[tuple[str, Path, str, str]] = []  # (value, folder of its file, element, file's name)
        self.folders: set[str] = set()
        self.models: dict[str, tuple[str, Path]] = {}
        self.links: set[str] = set()
        self.joints: set[str] = set()
        self.tree: list[_Edge] = []
        self.limits: dict[str, dict[str, float]] = {}  # URDF joint name -> its positive <limit velocity effort>
        self.memo: dict[tuple[str, bool], _Counts] = {}
        self.active: list[str] = []

    def fail(self, where: str, message: str) -> DescriptionError:
        return DescriptionError(f"{where}: {message}")

    # --- one file --------------------------------------------------------------------------

    def document(self, path: Path, in_world: bool, label: str) -> _Counts:
        try:
            real = os.path.realpath(path)
        except ValueError:  # a NUL in the path: read_regular says so
            real = str(path)
        if (real, in_world) in self.memo:  # a file included many times is read once
            return self.memo[(real, in_world)]
        source = self.source if not self.active else str(path)
        if real in self.active or len(self.active) >= _MAX_NESTING:
            raise self.fail(source, f"included in itself, or includes nested more than {_MAX_NESTING} deep")
        data = read_regular(path, label)
        counts = _Counts()
        stack: list[_Element] = []
        parser = expat.ParserCreate()
        main = not self.active

        def start(tag: str, attrs: dict[str, str]) -> None:
            line = parser.CurrentLineNumber
            where = f"{source}, line {line}"
            parent = stack[-1] if stack else _Element("", "", 1, in_world, False)
            if not stack and main:
                if tag not in ("robot", "mujoco"):
                    raise self.fail(source, f"the root element <{clipped(tag, 40)}> is neither <robot> (URDF) nor <mujoco> (MJCF)")
                self.format = "URDF" if tag == "robot" else "MJCF"
            self.numbers(where, stack, tag, attrs)
            for key, value in attrs.items():
                if (key == "filename" or key.startswith("file")) and value.strip() and tag != "include":
                    self.references.append((value, path.parent, tag, source))
            if tag == "compiler":
                self.folders.update(attrs[k] for k in _FOLDERS if attrs.get(k, "").strip())
            element = _Element(tag, attrs.get("name", ""), parent.times, parent.in_world, parent.in_default)
            if self.format == "URDF":
                self.urdf(where, stack, tag, attrs, counts)
            else:
                self.mjcf(where, parent, element, tag, attrs, counts, path.parent)
            stack.append(element)

        parser.StartElementHandler = start
        parser.EndElementHandler = lambda tag: stack.pop()
        self.active.append(real)
        try:
            parser.Parse(data, True)
        except expat.ExpatError as exc:
            reason = expat.ErrorString(exc.code)
            raise self.fail(
                source,
                f"not a readable {self.format or self.what} file: not well-formed XML ({reason}) at line {exc.lineno}, column {exc.offset}",
            ) from None
        finally:
            self.active.pop()
        self.memo[(real, in_world)] = counts
        return counts

    def numbers(self, where: str, stack: list[_Element], tag: str, attrs: dict[str, str]) -> None:
        """Refuses an attribute of numbers of which one is not finite (nan, inf, 1e400)."""
        for key, value in attrs.items():
            if key in _WORDS:
                continue
            tokens = value.split()
            try:
                numbers = [float(t) for t in tokens]
            except ValueError:
                continue
            if numbers and not all(math.isfinite(x) for x in numbers):
                owner = next((e for e in reversed(stack) if e.name and e.tag in ("link", "joint", "body")), None)
                of = f"{owner.tag} {_quoted(owner.name)}, " if owner is not None else ""
                own = f" {_quoted(attrs['name'])}" if attrs.get("name") else ""
                raise self.fail(where, f"{of}<{tag}>{own} {key}={shown(value, 40)}: numbers must be finite")

    # --- URDF ------------------------------------------------------------------------------

    def urdf(self, where: str, stack: list[_Element], tag: str, attrs: dict[str, str], counts: _Counts) -> None:
        parent = stack[-1].tag if stack else ""
        name = attrs.get("name", "")
        if parent == "robot" and tag == "link":
            if name in self.links:
                raise self.fail(where, f"the link name {_quoted(name)} is given twice; a URDF names each link once")
            self.links.add(name)
            counts.bodies += 1
        elif parent == "robot" and tag == "joint":
            if name in self.joints:
                raise self.fail(
                    where, f"the joint name {_quoted(name)} is given twice (MuJoCo would rename the second); each joint needs its own name"
                )
            self.joints.add(name)
            kind = attrs.get("type", "")
            if kind in ("planar", "floating"):
                raise self.fail(
                    where,
                    f"joint {_quoted(name)} is a {kind} joint; uwml takes revolute, continuous and prismatic joints (fixed ones are fused)",
                )
            if kind not in _URDF_JOINTS:
                what = f"has type {_quoted(kind)}" if kind else "has no type"
                raise self.fail(where, f"joint {_quoted(name)} {what}; uwml takes revolute, continuous, prismatic and fixed")
            counts.joints += kind != "fixed"
            self.tree.append(_Edge(name, where))
        elif tag in ("parent", "child") and parent == "joint" and len(stack) == 2 and self.tree:
            setattr(self.tree[-1], tag, attrs.get("link", ""))
        elif tag == "limit" and parent == "joint" and len(stack) == 2:
            # MuJoCo keeps a URDF's range, not its velocity, and its effort only in some versions:
            # both read here (0, or absent: none given).
            for key in ("velocity", "effort"):
                try:
                    value = float(attrs.get(key, "0"))
                except ValueError:
                    raise self.fail(
                        where, f"joint {_quoted(stack[-1].name)}: <limit {key}={shown(attrs[key], 40)}> is not a number"
                    ) from None
                if value > 0.0:
                    self.limits.setdefault(stack[-1].name, {})[key] = value
        elif tag == "mimic" and parent == "joint" and len(stack) == 2:
            raise self.fail(
                where,
                f"joint {_quoted(stack[-1].name)} mimics joint {_quoted(attrs.get('joint', ''))} (<mimic>); uwml has no coupled joints: "
                "each joint is a coordinate of q of its own (remove the <mimic>)",
            )
        elif tag in ("visual", "collision") and parent == "link":
            counts.geoms += 1

    def check_tree(self) -> None:
        """Refuses what MuJoCo reports without a name: a joint's link missing, a link with two
        parents, links in a loop."""
        parents: dict[str, _Edge] = {}
        for edge in self.tree:
            for role in ("parent", "child"):
                link = getattr(edge, role)
                if link is None:
                    raise self.fail(edge.where, f"joint {_quoted(edge.name)} has no <{role} link=...>")
                if link not in self.links:
                    raise self.fail(edge.where, f"joint {_quoted(edge.name)}: its {role} {_quoted(link)} is not a link of this file")
            child = edge.child or ""
            if child in parents:
                first = parents[child]
                raise self.fail(
                    edge.where,
                    f"link {_quoted(child)} is the child of joints {_quoted(first.name)} and {_quoted(edge.name)}; "
                    "a URDF is a tree: each link has one parent",
                )
            parents[child] = edge
        children: dict[str, list[str]] = {}
        for edge in self.tree:
            children.setdefault(edge.parent or "", []).append(edge.child or "")
        reached: set[str] = set()
        todo = [link for link in self.links if link not in parents]
        while todo:
            link = todo.pop()
            if link not in reached:
                reached.add(link)
                todo += children.get(link, [])
        looped = sorted(self.links - reached)
        if looped:
            what = (
                f"links {', '.join(map(_quoted, looped))} form a loop"
                if len(looped) > 1
                else f"link {_quoted(looped[0])} is its own parent"
            )
            raise self.fail(self.source, f"{clipped(what)}; a URDF is a tree")

    # --- MJCF ------------------------------------------------------------------------------

    def mjcf(self, where: str, parent: _Element, element: _Element, tag: str, attrs: dict[str, str], counts: _Counts, folder: Path) -> None:
        times = parent.times
        if tag == "default":
            element.in_default = True
        elif tag == "worldbody":
            element.in_world = True
        elif tag == "model" and attrs.get("file", "").strip():
            self.models[attrs.get("name", "")] = (attrs["file"], folder)
        elif tag == "include":
            target = self.find(attrs.get("file", ""), folder)
            if target is not None:
                counts.add(self.document(target, element.in_world, "included file"), times)
        elif tag in ("composite", "flexcomp"):
            raise self.fail(where, f"<{tag}> generates bodies at parse time; uwml maps bodies written out, not generated ones")
        if not element.in_world or element.in_default:
            return
        if tag == "replicate":
            try:
                element.times = times * max(int(attrs.get("count", "1")), 1)
            except ValueError:
                pass  # MuJoCo says what is wrong with it
        elif tag == "body":
            counts.bodies += times
        elif tag in ("joint", "freejoint"):
            counts.joints += times
        elif tag == "geom":
            counts.geoms += times
        elif tag == "attach":
            counts.attached.append((attrs.get("model", ""), times))

    def find(self, value: str, folder: Path) -> Path | None:
        """Where MuJoCo reads an included file: beside the file naming it, or the main file."""
        if not value.strip():
            return None
        for candidate in (folder / value, self.main.parent / value):
            if os.path.lexists(candidate):
                return candidate
        return None

    def attached(self, counts: _Counts, depth: int = 0) -> None:
        """Adds to ``counts`` the model assets its ``<attach>`` elements bring in."""
        pending, counts.attached = counts.attached, []
        for name, times in pending:
            if name not in self.models:
                continue  # MuJoCo says so
            value, folder = self.models[name]
            target = self.find(value, folder)
            if target is None:
                continue
            if depth >= _MAX_NESTING:
                raise self.fail(self.source, f"<attach> nested more than {_MAX_NESTING} deep")
            sub = _Counts()
            sub.add(self.document(target, False, "model asset file"), 1)
            self.attached(sub, depth + 1)
            counts.add(sub, times)

    # --- the files it names ----------------------------------------------------------------

    def check_references(self) -> None:
        bases = [self.main.parent]
        for value, folder, tag, source in self.references:
            names = [value] + ([os.path.basename(value)] if os.path.basename(value) not in ("", value) else [])
            for base in [*bases, folder]:
                for sub in ["", *sorted(self.folders)]:
                    for name in names:
                        candidate = Path(base, sub, name)
                        why = not_regular(candidate)
                        if why is not None:
                            raise self.fail(
                                source,
                                f"<{tag}> names the file {_quoted(value)}, and {clipped(str(candidate), 80)} {why}; "
                                "uwml reads regular files only (MuJoCo would wait on a pipe, or read a device forever)",
                            )


def scan(path: str | os.PathLike[str], what: str) -> tuple[str, dict[str, dict[str, float]]]:
    """Reads the description at ``path`` as written (see the module docstring) and returns its
    format, ``"URDF"`` or ``"MJCF"`` (by its root element), and the limits of its joints by name:
    a URDF's positive ``<limit velocity effort>`` as ``{"velocity": ..., "effort": ...}`` (MuJoCo
    does not keep the velocity; an MJCF's limits are in the compiled model); ``what`` names the
    format expected in messages about a file that cannot be parsed."""
    state = _Scan(path, what)
    counts = state.document(Path(path), False, f"{what} file")
    state.attached(counts)
    error = limits_exceeded(str(path), counts.bodies, counts.joints, counts.geoms, urdf=state.format == "URDF")
    if error is not None:
        raise error
    if state.format == "URDF":
        state.check_tree()
    state.check_references()
    return state.format, state.limits
