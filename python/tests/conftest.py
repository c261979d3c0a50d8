"""Finds the package (an in-place build in python/, or an installed one) and
the command line (build/softrast, or $SOFTRAST_BIN) the comparisons run."""
import os
import subprocess
import sys

import pytest

PYTHON_DIR = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ROOT = os.path.dirname(PYTHON_DIR)
sys.path.insert(0, PYTHON_DIR)


@pytest.fixture
def cli():
    """Runs `softrast ARGS...`; fails with its stderr."""
    binary = os.environ.get("SOFTRAST_BIN", os.path.join(ROOT, "build", "softrast"))
    if not os.path.exists(binary):
        pytest.skip(f"{binary} not built (make build/softrast)")

    def run(*args):
        r = subprocess.run([binary, *map(str, args)], capture_output=True, text=True)
        assert r.returncode == 0, r.stderr
        return r

    return run


@pytest.fixture
def root():
    return ROOT


@pytest.fixture
def png():
    """tools/pinhole_sheet.py's PNG reader and writer (zlib alone, no PIL)."""
    sys.path.insert(0, os.path.join(ROOT, "tools"))
    import pinhole_sheet
    return pinhole_sheet
