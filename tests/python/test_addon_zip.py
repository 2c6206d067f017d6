"""The add-on zip stands alone: unpacked anywhere, its module imports by itself (no libspindrift, no GLEW
beside it), finds the shaders beside it and renders a frame."""

import pathlib
import subprocess
import sys
import zipfile

from spindrift_testing import BUILD, ROOT

SCRIPT = """
import importlib.util, sys
import numpy as np
spec = importlib.util.spec_from_file_location("_spindrift", sys.argv[1])
module = importlib.util.module_from_spec(spec)
spec.loader.exec_module(module)
sys.path.insert(0, sys.argv[2])
from spindrift_testing import scene_json, sphere_of_particles
with module.Renderer() as renderer:
    result = renderer.render(scene_json(), 1, particles=sphere_of_particles(count=50), layers=["liquid"])
alpha = np.frombuffer(result["layers"]["liquid"][1], np.float32)[3::4]
print("liquid pixels", int((alpha > 0).sum()))
"""


def test_zip_holds_module_shaders_and_python_and_renders_unpacked(tmp_path):
    archive = tmp_path / "spindrift-addon.zip"
    subprocess.run([sys.executable, str(ROOT / "scripts" / "package-addon.py"), "--build", str(BUILD), "--output",
                    str(archive)], check=True, capture_output=True, text=True, timeout=300)
    with zipfile.ZipFile(archive) as contents:
        names = set(contents.namelist())
        contents.extractall(tmp_path / "unpacked")
    assert "spindrift/_spindrift.abi3.so" in names
    assert "spindrift/shaders/refraction.frag" in names and "spindrift/shaders/lib/frame.glsl" in names
    for path in (ROOT / "addon" / "spindrift").rglob("*.py"):
        assert "spindrift/" + path.relative_to(ROOT / "addon" / "spindrift").as_posix() in names
    assert all(name.startswith("spindrift/") for name in names)
    assert not any("__pycache__" in name for name in names)

    module = tmp_path / "unpacked" / "spindrift" / "_spindrift.abi3.so"
    # No environment that points at the build tree: the shaders must be found beside the module.
    child = subprocess.run([sys.executable, "-c", SCRIPT, str(module), str(pathlib.Path(__file__).parent)],
                           capture_output=True, text=True, timeout=300, env={"PATH": "/usr/bin:/bin"})
    assert child.returncode == 0, child.stderr
    assert int(child.stdout.split()[-1]) > 50
