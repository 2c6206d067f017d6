import pytest

from spindrift_testing import import_module


@pytest.fixture(scope="session")
def spindrift():
    return import_module()


@pytest.fixture(scope="session")
def renderer(spindrift):
    with spindrift.Renderer() as shared:
        yield shared
