#!/usr/bin/env python3
"""Packs the Blender add-on zip from a build tree: spindrift/ = addon/spindrift/* (Python files, the manifest),
_spindrift.abi3.so (debug information stripped) and shaders/. Refuses a module that needs a library Debian's
blender package does not bring (docs/python-module.md). Used by scripts/build-addon and the
tests (tests/python/test_addon_zip.py)."""

import argparse
import pathlib
import subprocess
import sys
import tempfile
import zipfile

ROOT = pathlib.Path(__file__).resolve().parent.parent
# What the module must not need: the library and GLEW are linked in statically, EGL is opened at run time
# (Debian's blender package brings neither GLEW, EGL nor libOpenGL; docs/python-module.md).
FORBIDDEN = ("libspindrift", "libGLEW", "libEGL", "libOpenGL.so")


def needed_libraries(module):
    output = subprocess.run(["objdump", "-p", str(module)], check=True, capture_output=True, text=True).stdout
    return [line.split()[1] for line in output.splitlines() if line.strip().startswith("NEEDED")]


def package(build, output):
    module = build / "lib" / "_spindrift.abi3.so"
    shaders = ROOT / "shaders"
    addon = ROOT / "addon" / "spindrift"
    if not module.is_file():
        sys.exit(f"package-addon: {module} is missing (run scripts/build)")
    bad = [name for name in needed_libraries(module) if name.startswith(FORBIDDEN)]
    if bad:
        sys.exit(f"package-addon: {module} needs {', '.join(bad)}, which the add-on does not carry")
    output.parent.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory() as scratch:
        stripped = pathlib.Path(scratch) / module.name
        subprocess.run(["objcopy", "--strip-debug", str(module), str(stripped)], check=True)
        partial = output.with_suffix(".zip.partial")
        with zipfile.ZipFile(partial, "w", zipfile.ZIP_DEFLATED) as archive:
            if addon.is_dir():
                for path in sorted(addon.rglob("*")):
                    if path.is_file() and "__pycache__" not in path.parts and path.suffix != ".pyc":
                        archive.write(path, "spindrift/" + path.relative_to(addon).as_posix())
            archive.write(stripped, "spindrift/_spindrift.abi3.so")
            for path in sorted(shaders.rglob("*")):
                if path.is_file():
                    archive.write(path, "spindrift/shaders/" + path.relative_to(shaders).as_posix())
        partial.replace(output)  # A failed run never leaves a half-written zip under the real name.
    return output


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--build", type=pathlib.Path, default=ROOT / "build")
    parser.add_argument("--output", type=pathlib.Path, default=ROOT / "build" / "spindrift-addon.zip")
    arguments = parser.parse_args()
    path = package(arguments.build.resolve(), arguments.output.resolve())
    print(f"package-addon: wrote {path} ({path.stat().st_size / 1e6:.1f} MB)")


if __name__ == "__main__":
    main()
