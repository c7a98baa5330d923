# SPDX-License-Identifier: MIT
"""Shared fixtures: the built `streamclust` tool and small helpers.

Run from a build tree: ``PYTHONPATH=<build>/python STREAMCLUST_TOOL=<build>/tools/streamclust
python3 -m pytest python/tests`` (CTest's ``python_pytest`` sets both).
"""

import os
import pathlib

import numpy as np
import pytest


def _find_tool():
    given = os.environ.get("STREAMCLUST_TOOL")
    if given:
        return pathlib.Path(given)
    # Beside the module: <build>/python/streamclust -> <build>/tools/streamclust
    import streamclust
    candidate = pathlib.Path(streamclust.__file__).resolve().parents[2] / "tools" / "streamclust"
    return candidate


@pytest.fixture(scope="session")
def tool():
    path = _find_tool()
    if not path.is_file():
        pytest.fail(f"the streamclust tool was not found at {path}: build the target streamclust_tool "
                    "or set STREAMCLUST_TOOL")
    return str(path)


def same_partition(a, b):
    """True when label arrays a and b group the same points, negative codes
    (-1 unlabelled, -2 ground, -3 ceiling) matched exactly."""
    a = np.asarray(a, dtype=np.int64)
    b = np.asarray(b, dtype=np.int64)
    if a.shape != b.shape:
        return False
    if not np.array_equal(a < 0, b < 0) or not np.array_equal(a[a < 0], b[b < 0]):
        return False
    pos = a >= 0
    pairs = np.unique(np.stack([a[pos], b[pos]], axis=1), axis=0)
    # a bijection: each label of a maps to one label of b and back
    return len(pairs) == len(np.unique(a[pos])) == len(np.unique(b[pos]))
