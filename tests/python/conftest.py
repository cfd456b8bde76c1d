"""pytest set-up for the Python module's tests (run by scripts/test.sh).

The module is imported from PYTHONPATH (scripts/test.sh sets <build>/python);
when run by hand without it, from $RHEODDA_BUILD_DIR/python or build/python.
Without a build the tests that need no module (test_docs_links.py) still run.
"""
import os
import pathlib
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]

try:
    import rheodda  # noqa: F401
except ImportError:
    build = pathlib.Path(os.environ.get("RHEODDA_BUILD_DIR", ROOT / "build"))
    sys.path.insert(0, str(build / "python"))
    try:
        import rheodda  # noqa: F401
    except ImportError:
        # Not built: the tests that need the module fail on their own import;
        # those that need no build (test_docs_links.py) run.
        pass


@pytest.fixture
def root():
    return ROOT


@pytest.fixture
def rheodda_binary():
    """The `rheodda` command of the same build (the module records its path)."""
    import rheodda as r
    path = r._rheodda._build_rheodda_binary
    if not os.path.exists(path):
        pytest.fail("the rheodda command of this build is missing: " + path)
    return path


# The seed's Table 1 row 1 Burgers parameters (MPa/mm, MPa*h/mm), as in examples/shear-creep-test.yaml.
TABLE1 = {"E1": 26.87, "E2": 192.43, "eta1": 34807.72, "eta2": 2141.23}
