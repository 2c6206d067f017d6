"""Every bad argument raises ValueError, TypeError or _spindrift.Error with a message naming it, and never
crashes: the cases run in a child process (validation_cases.py), one JSON line each, so a crash fails the case
that caused it instead of this test run."""

import json
import pathlib
import subprocess
import sys
import tempfile

import pytest

from validation_cases import CASES, N

HERE = pathlib.Path(__file__).resolve().parent


@pytest.fixture(scope="module")
def outcomes():
    child = subprocess.run([sys.executable, str(HERE / "validation_cases.py")], cwd=HERE, capture_output=True,
                           text=True, timeout=300)
    results, started = {}, None
    for line in child.stdout.splitlines():
        record = json.loads(line)
        if record.get("started"):
            started = record["case"]
        else:
            results[record["case"]] = record
            started = None
    if started is not None:
        results[started] = {"crashed": f"the process ended with {child.returncode} in this case:\n{child.stderr}"}
    return results, child


@pytest.mark.parametrize("name", list(CASES))
def test_case(outcomes, name):
    results, child = outcomes
    assert name in results, f"not run (exit {child.returncode}):\n{child.stderr}"
    outcome = results[name]
    assert "crashed" not in outcome, outcome.get("crashed")
    _, expected, fragment = CASES[name]
    assert outcome["exception"] == expected, outcome["message"]
    assert fragment in outcome["message"]


def test_nan_positions_are_dropped_and_counted(outcomes):
    outcome = outcomes[0]["nan_positions_dropped"]
    assert outcome["dropped"] == 5
    assert outcome["liquid"] == N - 5


def test_radii_not_positive_are_dropped_and_counted(outcomes):
    outcome = outcomes[0]["radii_not_positive_dropped"]
    assert outcome["dropped"] == 3
    assert outcome["liquid"] == N - 3


def test_memory_limits_name_what_is_available(outcomes):
    """Both memory refusals say how much the frame needs against what is available, and where that comes
    from; the particle case names the limit this test set."""
    particles = outcomes[0]["particles_over_memory"]["message"]
    assert "more than the 64 MiB available (SPINDRIFT_MEMORY_LIMIT_MB" in particles, particles
    resolution = outcomes[0]["resolution_over_memory"]["message"]
    assert "MiB available" in resolution or "larger than this OpenGL allows" in resolution, resolution


def test_render_after_close_raises(outcomes):
    outcome = outcomes[0]["render_after_close"]
    assert outcome["exception"] == "Error" and "closed" in outcome["message"]


def test_child_exits_cleanly(outcomes):
    assert outcomes[1].returncode == 0, outcomes[1].stderr


def test_shader_directory_errors_are_python_exceptions(spindrift):
    with pytest.raises(spindrift.Error, match="not a directory"):
        spindrift.Renderer("/nonexistent/shaders")
    with tempfile.TemporaryDirectory() as empty, pytest.raises(spindrift.Error, match="cannot read shader"):
        spindrift.Renderer(empty)


def test_error_is_a_runtime_error(spindrift):
    assert issubclass(spindrift.Error, RuntimeError)


def test_parameter_table_matches_the_library(spindrift):
    rows = spindrift.parameter_table()
    assert rows, "the table is empty"
    names = {(row["group"], row["name"]) for row in rows}
    assert len(names) == len(rows)
    for row in rows:
        assert set(row) == {"group", "name", "type", "default", "min", "max", "choices", "doc"}
        assert row["group"] in ("liquid", "foam", "light")
        assert row["type"] in ("float", "int", "bool", "color", "vec3", "choice")
        if row["type"] in ("color", "vec3"):
            assert isinstance(row["default"], tuple) and len(row["default"]) == 3
        if row["type"] == "choice":
            assert row["default"] in row["choices"]
        if row["type"] in ("float", "int"):
            assert row["min"] <= row["default"] <= row["max"], row
    # docs/parameters.md is generated from the same table (a native test keeps it current).
    page = (HERE.parents[1] / "docs" / "parameters.md").read_text()
    for row in rows:
        assert f"{row['group']}.{row['name']}" in page


def test_version(spindrift):
    assert isinstance(spindrift.__version__, str) and spindrift.__version__.count(".") == 2
