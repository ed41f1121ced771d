"""The C ABI without Rust (docs/firmware.md, "Without Rust"): the header the Python package ships
(``uwml.get_include()``) is the crate's, and ``make dist`` makes a host package that a C compiler
alone builds against, through pkg-config, with its CMake files well formed (read here as text:
cmake itself runs only where it is installed) and a header of ``uwml export --c`` taken by it.

The package test needs cargo, make, a C compiler and pkg-config: it is skipped where cargo is
absent (the wheel's test run). .ci/dist holds the same package, and the Cortex-M one, in CI.
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import tomllib
from pathlib import Path

import pytest
import uwml
from cmake_text import commands
from uwml.io.export import to_c

ROOT = Path(__file__).resolve().parents[1]
HEADER = ROOT / "crates/uwml-ffi/include/uwml.h"
VERSION = tomllib.loads((ROOT / "Cargo.toml").read_text(encoding="utf-8"))["workspace"]["package"]["version"]


def test_get_include_is_the_packages_folder_holding_the_crates_header() -> None:
    folder = Path(uwml.get_include())
    assert folder.is_dir() and folder.is_absolute()
    assert Path(uwml.__file__).resolve().parent in folder.resolve().parents, f"{folder} is not inside the installed package"
    assert (folder / "uwml.h").read_bytes() == HEADER.read_bytes(), (
        "the shipped header differs from crates/uwml-ffi/include/uwml.h: UWML_BLESS=1 cargo test -p uwml-ffi --test header"
    )


# --------------------------------------------------------------------------------------------
# CMake files as text (tests/cmake_text.py): cmake runs only where it is installed.
# --------------------------------------------------------------------------------------------

#: The commands the package's CMake files may use (a misspelt one is an error only cmake sees).
CMAKE_COMMANDS = {"get_filename_component", "if", "elseif", "else", "endif", "add_library", "set_target_properties", "set", "unset", "math"}


def test_the_cmake_reader_refuses_what_cmake_refuses() -> None:
    assert commands('set(A "x;y") # c\nif(A)\n  unset(A)\nendif()\n') == [
        ("set", ["A", "x;y"]),
        ("if", ["A"]),
        ("unset", ["A"]),
        ("endif", []),
    ]
    for bad in ("set(A", 'set(A "x)', "set A", "if(A)\n", "endif()", 'set(A "${B")', "x = 1"):
        with pytest.raises(ValueError):
            commands(bad)


def check_cmake_package(package: Path) -> None:
    """The package's CMake files: well formed, only known commands, every template field filled,
    the imported target ``uwml::uwml`` at the package's own library and header, this version."""
    folder = package / "lib/cmake/uwml"
    config = commands((folder / "uwmlConfig.cmake").read_text(encoding="utf-8"))
    version = commands((folder / "uwmlConfigVersion.cmake").read_text(encoding="utf-8"))
    for name, arguments in config + version:
        assert name in CMAKE_COMMANDS, name
        assert not any(re.search(r"@\w+@", a) for a in arguments), (name, arguments)
    assert ("add_library", ["uwml::uwml", "STATIC", "IMPORTED"]) in config
    (root,) = [a for n, a in config if n == "get_filename_component"]
    assert root[1] == "${CMAKE_CURRENT_LIST_DIR}/../../.." and (folder / "../../..").resolve() == package.resolve()
    (properties,) = [dict(zip(a[2::2], a[3::2], strict=True)) for n, a in config if n == "set_target_properties"]
    assert properties["IMPORTED_LOCATION"] == "${_uwml_root}/lib/libuwml.a" and (package / "lib/libuwml.a").is_file()
    assert properties["INTERFACE_INCLUDE_DIRECTORIES"] == "${_uwml_root}/include" and (package / "include/uwml.h").is_file()
    assert ("set", ["PACKAGE_VERSION", VERSION]) in version


# --------------------------------------------------------------------------------------------
# make dist for the host, used without cargo
# --------------------------------------------------------------------------------------------


def _run(command: list[str], cwd: Path, env: dict[str, str] | None = None, timeout: float = 120) -> str:
    done = subprocess.run(command, cwd=cwd, env=env, capture_output=True, text=True, timeout=timeout, check=False)
    assert done.returncode == 0, f"{command} failed ({done.returncode}):\n{done.stdout[-3000:]}\n{done.stderr[-3000:]}"
    return done.stdout


def _without_rust() -> dict[str, str]:
    """The environment with no folder holding cargo or rustc on the PATH."""
    folders = [f for f in os.environ.get("PATH", "").split(os.pathsep) if f and not any((Path(f) / t).exists() for t in ("cargo", "rustc"))]
    env = {**os.environ, "PATH": os.pathsep.join(folders)}
    assert shutil.which("cargo", path=env["PATH"]) is None
    return env


@pytest.mark.skipif(
    any(shutil.which(t) is None for t in ("cargo", "rustc", "make", "cc", "pkg-config")),
    reason="needs cargo and rustc (to make the package), make, cc and pkg-config",
)
def test_make_dist_makes_a_host_package_a_c_compiler_alone_builds_against(tmp_path: Path) -> None:
    host = re.search(r"^host: (\S+)$", _run(["rustc", "-vV"], ROOT), re.MULTILINE)
    assert host is not None
    name = f"uwml-{VERSION}-{host.group(1)}"
    _run(["make", "-s", "dist", f"TARGETS={host.group(1)}", f"DIST={tmp_path / 'dist'}"], ROOT, timeout=900)
    unpacked = tmp_path / "unpacked"  # a clean folder, away from the checkout
    unpacked.mkdir()
    _run(["tar", "-xzf", str(tmp_path / "dist" / f"{name}.tar.gz"), "-C", str(unpacked)], tmp_path)
    package = unpacked / name
    files = sorted(str(p.relative_to(package)) for p in package.rglob("*") if p.is_file())
    assert files == [
        "README.md",
        "examples/CMakeLists.txt",
        "examples/Makefile",
        "examples/minimal.c",
        "include/uwml.h",
        "lib/cmake/uwml/uwmlConfig.cmake",
        "lib/cmake/uwml/uwmlConfigVersion.cmake",
        "lib/libuwml.a",
        "lib/pkgconfig/uwml.pc",
    ]
    assert (package / "include/uwml.h").read_bytes() == HEADER.read_bytes()
    check_cmake_package(package)

    env = _without_rust()
    pkg_config = {**env, "PKG_CONFIG_PATH": str(package / "lib/pkgconfig")}
    assert _run(["pkg-config", "--modversion", "uwml"], tmp_path, pkg_config).strip() == VERSION
    # The example, through its Makefile (pkg-config), and its output: the published torques.
    _run(["make", "-s"], package / "examples", env)
    ran = _run(["./minimal"], package / "examples", env)
    assert ran.splitlines()[-1] == "the published torques, to 1e-4", ran

    # A header of `uwml export --c`, in double and float, taken by the package's library.
    robot = uwml.Robot.from_urdf(str(ROOT / "examples/bluerov2/bluerov2_arm.urdf"), str(ROOT / "examples/bluerov2/bluerov2_arm.hydro.toml"))
    (tmp_path / "arm64.h").write_text(to_c(robot, "f64", prefix="ARM"), encoding="utf-8")
    (tmp_path / "arm32.h").write_text(to_c(robot, "f32", prefix="ARM32"), encoding="utf-8")
    (tmp_path / "arm.c").write_text(EXPORTED_ARM, encoding="utf-8")
    flags = _run(["pkg-config", "--cflags", "--libs", "uwml"], tmp_path, pkg_config).split()
    _run(["cc", "-std=c11", "-Wall", "-Wextra", "-Werror", "-pedantic", "arm.c", "-o", "arm", *flags], tmp_path, env)
    assert _run(["./arm"], tmp_path, env).strip() == "f64 0, f32 0"

    if shutil.which("cmake") is not None:  # not on every machine: the text check above stands for it
        _run(["cmake", "-S", ".", "-B", "build"], package / "examples", env)
        _run(["cmake", "--build", "build"], package / "examples", env)
        assert _run(["build/minimal"], package / "examples", env).splitlines()[-1] == "the published torques, to 1e-4"


#: Builds the BlueROV2's arm from the two exported headers and sets its lumped model.
EXPORTED_ARM = r"""#include <stdio.h>
#include "arm64.h"
#include "arm32.h"

int main(void) {
    static UwmlRobotF64 robot64;
    static UwmlRobotF32 robot32;
    UwmlError error;
    int32_t f64 = uwml_robot_new_f64(&robot64, ARM_JOINTS, ARM_N_JOINTS, ARM_LINKS, ARM_BASE, ARM_SEGMENTS,
                                     ARM_N_SEGMENTS, ARM_WATER_DENSITY, ARM_GRAVITY, &error);
    if (f64 == UWML_OK) f64 = uwml_robot_set_lumped_f64(&robot64, ARM_LUMPED, ARM_N_LUMPED, &error);
    int32_t f32 = uwml_robot_new_f32(&robot32, ARM32_JOINTS, ARM32_N_JOINTS, ARM32_LINKS, ARM32_BASE, ARM32_SEGMENTS,
                                     ARM32_N_SEGMENTS, ARM32_WATER_DENSITY, ARM32_GRAVITY, &error);
    if (f32 == UWML_OK) f32 = uwml_robot_set_lumped_f32(&robot32, ARM32_LUMPED, ARM32_N_LUMPED, &error);
    printf("f64 %d, f32 %d\n", (int)f64, (int)f32);
    return f64 != UWML_OK || f32 != UWML_OK;
}
"""
