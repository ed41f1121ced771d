"""Reading the tables of a uwml model file or a hydro file (TOML, read by ``tomllib``): typed access
to one table (:class:`_Reader`) whose errors name the file, the table and the key, and the
tables of bodies, segments, lumped models, joint losses and the water (:mod:`uwml.io.modelfile`
and :mod:`uwml.io.hydrofile` read with them)."""

from __future__ import annotations

import dataclasses
import functools
import math
from collections.abc import Callable, Sequence
from typing import Any, Literal, NoReturn, TypeVar, overload

from .._checks import shown
from ..errors import ModelFileError
from ..model.joint_losses import JointLosses
from ..model.losses import Drive, OilDrag, Seal
from ..model.lumped import LumpedModel
from ..model.parts import Link, Segment, Water
from ..model.thrusters import ThrustCurve, Thruster

_T = TypeVar("_T")

#: The water of a model file or a hydro file must lie in these ranges (SI units; a value outside
#: is taken for a unit mistake, such as a density in g/cm³ or a gravity in g or ft/s²). Other
#: fluids or planets: construct :class:`uwml.Water` in code.
WATER_DENSITY_RANGE = (900.0, 1300.0)
WATER_GRAVITY_RANGE = (9.7, 9.9)
_DENSITY_HINT = "fresh water is 1000, sea water about 1025 (a density in g/cm³ or t/m³ is 1000 times too small)"
_GRAVITY_HINT = "the Earth's is 9.78 to 9.83 (not in g, not in ft/s²)"
#: The longest message a model file's error quotes from the library's own checks [characters].
_MESSAGE_LIMIT = 300


class _Reader:
    """Typed access to one table of the file, with errors naming the file, table and key."""

    def __init__(self, source: str, where: str, table: object, error: type[ValueError] = ModelFileError) -> None:
        self.source, self.where, self.error = source, where, error
        if not isinstance(table, dict):
            self.fail(None, f"must be a table, got {type(table).__name__}")
        self.table: dict[str, Any] = table

    def fail(self, key: str | None, message: str) -> NoReturn:
        at = self.where if key is None else f"{self.where}, key {shown(key, 40)}"
        raise self.error(f"{self.source}: {at}: {message}")

    def check_keys(self, allowed: Sequence[str]) -> None:
        for key in self.table:
            if key not in allowed:
                self.fail(key, f"is not a key of this table (allowed: {', '.join(allowed)})")

    @overload
    def get(self, key: str, convert: Callable[[Any], _T], what: str) -> _T: ...
    @overload
    def get(self, key: str, convert: Callable[[Any], _T], what: str, *, required: Literal[False], default: _T) -> _T: ...
    @overload
    def get(self, key: str, convert: Callable[[Any], _T], what: str, *, required: Literal[False]) -> _T | None: ...

    def get(self, key: str, convert: Callable[[Any], _T], what: str, *, required: bool = True, default: _T | None = None) -> _T | None:
        """The value of ``key`` converted by ``convert``; a missing key is an error if
        ``required``, else ``default``."""
        if key not in self.table:
            if required:
                self.fail(key, f"is missing ({what})")
            return default
        value = self.table[key]
        try:
            return convert(value)
        except (TypeError, ValueError) as exc:
            self.fail(key, f"must be {what}, got {shown(value)} ({_clipped(str(exc))})")

    def build(self, make: Callable[[], _T]) -> _T:
        """``make()``, its ValueError or TypeError (from the model's checks) named here."""
        try:
            return make()
        except (TypeError, ValueError) as exc:
            self.fail(None, _clipped(str(exc)))


def _clipped(message: str) -> str:
    """A message of the model's own checks, which may quote a whole value (a name), made short."""
    return message if len(message) <= _MESSAGE_LIMIT else f"{message[:_MESSAGE_LIMIT]}... ({len(message)} characters)"


def _float(value: Any) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise TypeError("not a number")
    return float(value)


def _vec3(value: Any) -> tuple[float, float, float]:
    if not isinstance(value, list) or len(value) != 3:
        raise TypeError("not an array of 3 numbers")
    x, y, z = (_float(v) for v in value)
    return (x, y, z)


def _pair(value: Any) -> tuple[float, float]:
    if not isinstance(value, list) or len(value) != 2:
        raise TypeError("not an array of 2 numbers")
    a, b = (_float(v) for v in value)
    return (a, b)


def _normals(value: Any) -> tuple[tuple[float, float, float], tuple[float, float, float]]:
    if not isinstance(value, list) or len(value) != 2:
        raise TypeError("not an array of 2 vectors")
    return (_vec3(value[0]), _vec3(value[1]))


def _text(value: Any) -> str:
    if not isinstance(value, str):
        raise TypeError("not a string")
    return value


def _integer(value: Any) -> int:
    if isinstance(value, bool) or not isinstance(value, int):
        raise TypeError("not an integer")
    return value


_SEGMENT_KEYS = ("section", "start", "axis", "length", "diameter", "normals", "widths", "area", "cd", "cm", "cd_axial", "axial_area")
#: The keys of one kind of section only, beside the keys of every segment (the other refuses them).
_SECTION_ONLY_KEYS = {"circular": ("diameter",), "rectangular": ("normals", "widths")}
_BODY_KEYS = ("name", "mass", "com", "volume", "cob", "segments", "lumped", "thrusters")
_THRUSTER_KEYS = ("name", "position", "direction", "curve", "max_forward", "max_reverse", "time_constant")
_CURVE_KEYS = ("kind", "commands", "thrusts", "forward", "reverse", "dead_band")
#: The most thrusters one body may carry in a file.
MAX_THRUSTERS = 64
_LUMPED_KEYS = ("point", "axes", "added_mass", "linear_damping", "quadratic_damping")


def _matrix3(value: Any) -> tuple[tuple[float, ...], ...]:
    if not isinstance(value, list) or len(value) != 3:
        raise TypeError("not an array of 3 rows")
    return tuple(_vec3(row) for row in value)


def _six(value: Any) -> tuple[float, ...]:
    if not isinstance(value, list) or len(value) != 6:
        raise TypeError("not an array of 6 numbers")
    return tuple(_float(v) for v in value)


def _matrix6(value: Any) -> tuple[tuple[float, ...], ...]:
    if not isinstance(value, list) or len(value) != 6:
        raise TypeError("not an array of 6 rows")
    return tuple(_six(row) for row in value)


def _lumped(source: str, where: str, table: object, error: type[ValueError] = ModelFileError) -> LumpedModel:
    r = _Reader(source, where, table, error)
    r.check_keys(_LUMPED_KEYS)
    point = r.get("point", _vec3, "an array of 3 numbers [m]", required=False)
    identity: tuple[tuple[float, ...], ...] = ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))
    axes = r.get("axes", _matrix3, "3 rows of 3 numbers (a rotation)", required=False, default=identity)
    zero: tuple[tuple[float, ...], ...] = tuple((0.0,) * 6 for _ in range(6))
    no_quadratic: tuple[float, ...] = (0.0,) * 6
    added_mass = r.get("added_mass", _matrix6, "6 rows of 6 numbers", required=False, default=zero)
    damping = r.get("linear_damping", _matrix6, "6 rows of 6 numbers", required=False, default=zero)
    quadratic = r.get("quadratic_damping", _six, "6 numbers", required=False, default=no_quadratic)
    return r.build(lambda: LumpedModel(point, added_mass, damping, quadratic, axes=axes))


def _segment(source: str, where: str, table: object, error: type[ValueError] = ModelFileError) -> Segment:
    r = _Reader(source, where, table, error)
    r.check_keys(_SEGMENT_KEYS)
    section = r.get("section", _text, 'a string, "rectangular" or "circular"')
    start = r.get("start", _vec3, "an array of 3 numbers [m]")
    axis = r.get("axis", _vec3, "a unit vector")
    length = r.get("length", _float, "a length [m]")
    cd = r.get("cd", _pair, "[Cd along normal 0, along normal 1]")
    cm = r.get("cm", _pair, "[Cm along normal 0, along normal 1]")
    cd_axial = r.get("cd_axial", _float, "an axial drag coefficient", required=False, default=0.0)
    axial_area = r.get("axial_area", _float, "an area [m²]", required=False)
    # A key of the other kind of section would be ignored: refused, so that a section's kind and
    # its dimensions cannot disagree unseen.
    if section in _SECTION_ONLY_KEYS:
        for key in (key for kind, keys in _SECTION_ONLY_KEYS.items() if kind != section for key in keys if key in r.table):
            r.fail(key, f"is not a key of a {section} section (a {section} section takes {' and '.join(_SECTION_ONLY_KEYS[section])})")
    if section == "circular":
        diameter = r.get("diameter", _float, "a diameter [m]")
        area = r.get("area", _float, "a section area [m²]")
        for key, pair in (("cd", cd), ("cm", cm)):
            if pair[0] != pair[1]:
                r.fail(key, f"of a circular section must have two equal entries, got {list(pair)}")
        return r.build(
            lambda: Segment(
                start,
                axis,
                length,
                section="circular",
                diameter=diameter,
                area=area,
                cd=cd[0],
                cm=cm[0],
                cd_axial=cd_axial,
                axial_area=axial_area,
            )
        )
    normals = r.get("normals", _normals, "two unit vectors [[...], [...]]")
    widths = r.get("widths", _pair, "[width along normal 0, along normal 1] [m]")
    area = r.get("area", _float, "a section area [m²]")
    return r.build(
        lambda: Segment(
            start,
            axis,
            length,
            section=section,
            normals=normals,
            widths=widths,
            area=area,
            cd=cd,
            cm=cm,
            cd_axial=cd_axial,
            axial_area=axial_area,
        )
    )


def _numbers(value: Any) -> tuple[float, ...]:
    if not isinstance(value, list):
        raise TypeError("not an array")
    return tuple(_float(x) for x in value)


def _curve(source: str, where: str, table: object, error: type[ValueError] = ModelFileError) -> ThrustCurve:
    r = _Reader(source, where, table, error)
    r.check_keys(_CURVE_KEYS)
    kind = r.get("kind", _text, 'a string, "table" or "polynomial"')
    if kind == "table":
        commands = r.get("commands", _numbers, "an array of commands, increasing")
        thrusts = r.get("thrusts", _numbers, "an array of thrusts [N], one per command")
        return r.build(lambda: ThrustCurve.table(commands, thrusts))
    forward = r.get("forward", _numbers, "the forward coefficients, lowest degree first")
    reverse = r.get("reverse", _numbers, "the reverse coefficients, lowest degree first", required=False)
    dead_band = r.get("dead_band", _float, "a command", required=False, default=0.0)
    if kind != "polynomial":
        r.fail("kind", f'must be "table" or "polynomial", got {shown(kind)}')
    return r.build(lambda: ThrustCurve.polynomial(forward, reverse, dead_band))


def thrusters(source: str, where: str, value: object, error: type[ValueError] = ModelFileError) -> tuple[Thruster, ...]:
    """A body's ``[[...thrusters]]`` (docs/model.md section 13.1), each with its optional
    ``curve`` table (default: :meth:`uwml.ThrustCurve.t200`)."""
    if not isinstance(value, list):
        raise error(f"{source}: {where}: thrusters must be an array of tables [[...thrusters]], got {shown(value)}")
    if len(value) > MAX_THRUSTERS:
        raise error(f"{source}: {where}: at most {MAX_THRUSTERS} thrusters per body, got {len(value)}")
    out = []
    for i, table in enumerate(value):
        r = _Reader(source, f"{where}, thrusters[{i}]", table, error)
        r.check_keys(_THRUSTER_KEYS)
        name = r.get("name", _text, "a string", required=False)
        position = r.get("position", _vec3, "an array of 3 numbers [m]")
        direction = r.get("direction", _vec3, "an array of 3 numbers (normalized)")
        raw_curve = r.get("curve", lambda table: table, "a table", required=False)
        curve = ThrustCurve.t200() if raw_curve is None else _curve(source, f"{where}, thrusters[{i}], curve", raw_curve, error)
        limits = [r.get(key, _float, "a thrust [N]", required=False, default=math.inf) for key in ("max_forward", "max_reverse")]
        lag = r.get("time_constant", _float, "a time [s]", required=False, default=0.0)
        out.append(r.build(lambda: Thruster(position, direction, curve, limits[0], limits[1], lag, name)))  # noqa: B023 (built at once)
    return tuple(out)


def _body(source: str, where: str, table: object) -> Link:
    r = _Reader(source, where, table)
    r.check_keys(_BODY_KEYS)
    raw_segments: list[object] = r.get("segments", _table_array, "[[...segments]]", required=False, default=[])
    segments = tuple(_segment(source, f"{where}, segments[{i}]", s) for i, s in enumerate(raw_segments))
    name = r.get("name", _text, "a string", required=False)
    mass = r.get("mass", _float, "a mass [kg]")
    com = r.get("com", _vec3, "an array of 3 numbers [m]")
    volume = r.get("volume", _float, "a volume [m³]")
    cob = r.get("cob", _vec3, "an array of 3 numbers [m]")
    raw_lumped = r.get("lumped", lambda table: table, "a table", required=False)
    lumped = None if raw_lumped is None else _lumped(source, f"{where}, lumped", raw_lumped)
    raw_thrusters: object = r.get("thrusters", lambda value: value, "[[...thrusters]]", required=False, default=[])
    carried = thrusters(source, where, raw_thrusters)
    return r.build(lambda: Link(mass, com, volume, cob=cob, segments=segments, name=name, lumped=lumped, thrusters=carried))


def _losses(source: str, where: str, table: object, error: type[ValueError] = ModelFileError) -> JointLosses:
    """A joint's losses from a table with ``epsilon`` and the tables ``drive``, ``oil``, ``seal``
    (each with its dataclass's fields; an absent oil or seal is none, an absent drive the
    default one, an absent ``epsilon`` :class:`JointLosses`'s default)."""
    r = _Reader(source, where, table, error)
    r.check_keys(("epsilon", "drive", "oil", "seal"))
    parts: dict[str, Any] = {}
    for name, kind in (("drive", Drive), ("oil", OilDrag), ("seal", Seal)):
        if name not in r.table:
            continue
        part = _Reader(source, f"{where}, {name}", r.table[name], error)
        keys = [f.name for f in dataclasses.fields(kind)]
        part.check_keys(keys)
        values = {key: part.get(key, _float, f"a number ({kind.__name__}.{key})") for key in keys}
        parts[name] = part.build(functools.partial(kind, **values))
    epsilon = r.get("epsilon", _float, "the smooth sign's width [rad/s]", required=False, default=JointLosses.epsilon)
    # A part the file does not give is absent (oil, seal), or the default drive.
    return r.build(lambda: JointLosses(drive=parts.get("drive", Drive()), oil=parts.get("oil"), seal=parts.get("seal"), epsilon=epsilon))


def _within(low: float, high: float, unit: str, hint: str) -> Callable[[Any], float]:
    """A converter to a number from ``low`` to ``high``, else a ValueError with ``hint``."""

    def check(value: Any) -> float:
        x = _float(value)
        if not (math.isfinite(x) and low <= x <= high):
            raise ValueError(f"outside {low:g} to {high:g} {unit}; {hint}")
        return x

    return check


def _water(source: str, where: str, table: object, error: type[ValueError] = ModelFileError) -> Water:
    """The water of a ``[water]`` table of a model file or a hydro file: ``density`` [kg/m³]
    within :data:`WATER_DENSITY_RANGE` and ``gravity`` [m/s²] within :data:`WATER_GRAVITY_RANGE`,
    each defaulting to :class:`uwml.Water`'s."""
    r = _Reader(source, where, table, error)
    r.check_keys(("density", "gravity"))

    def ranged(key: str, bounds: tuple[float, float], what: str, unit: str, hint: str, default: float) -> float:
        low, high = bounds
        return r.get(key, _within(low, high, unit, hint), f"{what} [{unit}], {low:g} to {high:g}", required=False, default=default)

    density = ranged("density", WATER_DENSITY_RANGE, "a density", "kg/m³", _DENSITY_HINT, Water.density)
    gravity = ranged("gravity", WATER_GRAVITY_RANGE, "an acceleration", "m/s²", _GRAVITY_HINT, Water.gravity)
    return r.build(lambda: Water(density=density, gravity=gravity))


def _fail_type(what: str) -> NoReturn:
    raise TypeError(f"not {what}")


def _table_array(value: Any) -> list[object]:
    if not isinstance(value, list):
        _fail_type("an array of tables")
    return value
