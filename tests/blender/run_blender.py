#!/usr/bin/python3
"""Runs one Blender test script with the add-on installed from its zip into a fresh, temporary user directory.

    run_blender.py --zip build/spindrift-addon.zip [--xvfb [--screen WxH]] SCRIPT [-- ARGS...]

Blender runs with --factory-startup and BLENDER_USER_CONFIG / BLENDER_USER_SCRIPTS pointing at a temporary
directory, so nothing of the machine's own Blender set-up (or an add-on installed there) takes part. The
script receives its arguments after `--`, and SPINDRIFT_ADDON_ZIP, SPINDRIFT_TEST_DIR (a scratch directory)
and SPINDRIFT_SOURCE_DIR in its environment. The exit code is Blender's (--python-exit-code 1 makes an
uncaught exception fail the test).
"""

import argparse
import os
import pathlib
import shutil
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parents[2]


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--zip", required=True)
    parser.add_argument("--blender", default=shutil.which("blender") or "blender")
    parser.add_argument("--xvfb", action="store_true", help="run the interface under xvfb-run (1280x800)")
    parser.add_argument("--screen", default="1280x800", help="Xvfb screen size (default 1280x800)")
    parser.add_argument("--keep", action="store_true", help="keep the scratch directory")
    parser.add_argument("script")
    parser.add_argument("args", nargs=argparse.REMAINDER)
    options = parser.parse_args()
    zip_path = os.path.abspath(options.zip)
    if not os.path.isfile(zip_path):
        print(f"run_blender: {zip_path} does not exist; build it with scripts/build-addon", file=sys.stderr)
        return 1
    scratch = tempfile.mkdtemp(prefix="spindrift_blender_test_")
    environment = dict(os.environ)
    environment.update(BLENDER_USER_CONFIG=os.path.join(scratch, "config"),
                       BLENDER_USER_SCRIPTS=os.path.join(scratch, "scripts"),
                       SPINDRIFT_ADDON_ZIP=zip_path, SPINDRIFT_TEST_DIR=os.path.join(scratch, "work"),
                       SPINDRIFT_SOURCE_DIR=str(ROOT))
    os.makedirs(environment["SPINDRIFT_TEST_DIR"])
    script = os.path.abspath(options.script)
    args = options.args[1:] if options.args[:1] == ["--"] else options.args
    command = [options.blender, "--factory-startup", "--python-exit-code", "1", "--python", script, "--", *args]
    if options.xvfb:
        command = ["xvfb-run", "-a", "-s", f"-screen 0 {options.screen}x24", *command]
    else:
        command.insert(1, "-b")
    print("run_blender:", " ".join(command), flush=True)
    try:
        return subprocess.call(command, env=environment, cwd=environment["SPINDRIFT_TEST_DIR"])
    finally:
        if options.keep:
            print(f"run_blender: kept {scratch}")
        else:
            shutil.rmtree(scratch, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
