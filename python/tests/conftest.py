import os
import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))


@pytest.fixture(scope="session")
def root():
    return ROOT


@pytest.fixture(scope="session")
def cli():
    """The mechkin executable the package is compared with (MECHKIN_BINARY, else build/mechkin)."""
    path = os.environ.get("MECHKIN_BINARY", os.path.join(ROOT, "build", "mechkin"))
    if not os.path.exists(path):
        pytest.fail("mechkin executable not found at %s: build it or set MECHKIN_BINARY" % path)
    return path
