"""Every uwml exception derives from ``uwml.UwmlError`` (a ``ValueError``), so one ``except``
catches them all; the warnings stay warnings."""

from __future__ import annotations

import copy
import importlib
import inspect
import pkgutil
from collections.abc import Callable
from pathlib import Path

import pytest
import uwml
from uwml import _core, study
from uwml.cli import common as cli_common
from uwml.robot.files import loads


def _classes_defined_in_uwml() -> set[type]:
    """The exception and warning classes of every module of the package, the native one included."""
    found: set[type] = set()
    for info in pkgutil.walk_packages(uwml.__path__, "uwml."):
        if info.name.rpartition(".")[2] == "__main__":  # running it is the command line
            continue
        module = importlib.import_module(info.name)
        for _, value in inspect.getmembers(module, inspect.isclass):
            if issubclass(value, BaseException) and value.__module__.split(".")[0] == "uwml":
                found.add(value)
    return found


def _exceptions() -> list[type]:
    return sorted((c for c in _classes_defined_in_uwml() if not issubclass(c, Warning)), key=lambda c: c.__qualname__)


def test_the_package_defines_the_exceptions_this_test_knows() -> None:
    # A new exception class shows up here, so the test below cannot miss it.
    names = {c.__qualname__ for c in _exceptions()}
    assert names == {"UwmlError", "ModelError", "ModelFileError", "DescriptionError", "_UsageError", "ConfigError", "StudyError"}


@pytest.mark.parametrize("error", _exceptions(), ids=lambda c: c.__qualname__)
def test_every_exception_is_a_uwml_error_and_a_value_error(error: type) -> None:
    assert issubclass(error, uwml.UwmlError)
    assert issubclass(error, ValueError)


def test_the_public_names_are_the_classes_raised() -> None:
    assert uwml.UwmlError is _core.UwmlError
    assert uwml.ModelError is _core.ModelError
    assert uwml.ModelFileError is uwml.errors.ModelFileError
    assert uwml.UwmlError.__mro__[1] is ValueError
    assert "UwmlError" in uwml.__all__


def test_warnings_stay_warnings() -> None:
    warnings = {c for c in _classes_defined_in_uwml() if issubclass(c, Warning)}
    assert uwml.ExtrapolationWarning in warnings
    assert not any(issubclass(c, uwml.UwmlError) for c in warnings)


def _negative_mass() -> None:
    leg = uwml.paper_leg()
    link = copy.copy(leg.links[0])
    object.__setattr__(link, "mass", -1.0)  # past the dataclass's own check, to the core's
    uwml.Robot(leg.joints, [link, *leg.links[1:]])


def _bad_model_file() -> None:
    loads("format = [", source="bad.toml")


def _bad_urdf(tmp_path: Path) -> None:
    bad = tmp_path / "bad.urdf"
    bad.write_text('<robot name="x"><link name="a"></robot>')
    uwml.Robot.from_urdf(bad)


def _output_into_a_directory(tmp_path: Path) -> None:
    cli_common._check_output(str(tmp_path), "--out")


def _a_study_over_another(tmp_path: Path) -> None:
    (tmp_path / "study.json").write_text("{}")
    study.run_study(study.loads(""), tmp_path, serial=True)


RAISERS: dict[str, tuple[type, Callable[[Path], None]]] = {
    "ModelError": (uwml.ModelError, lambda _: _negative_mass()),
    "ModelFileError": (uwml.ModelFileError, lambda _: _bad_model_file()),
    "DescriptionError": (uwml.DescriptionError, _bad_urdf),
    "_UsageError": (cli_common._UsageError, _output_into_a_directory),
    "ConfigError": (study.ConfigError, lambda _: study.loads("[parameters]\ndepth = -1\n")),
    "StudyError": (study.StudyError, _a_study_over_another),
}


def test_each_exception_has_a_real_error_below() -> None:
    assert set(RAISERS) | {"UwmlError"} == {c.__qualname__ for c in _exceptions()}


@pytest.mark.parametrize("name", sorted(RAISERS))
def test_one_real_error_of_each_kind_is_caught_as_a_uwml_error(name: str, tmp_path: Path) -> None:
    kind, raiser = RAISERS[name]
    with pytest.raises(uwml.UwmlError) as caught:
        raiser(tmp_path)
    assert type(caught.value) is kind
