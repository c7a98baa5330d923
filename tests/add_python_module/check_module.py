# SPDX-License-Identifier: MIT
"""The add_python_module test's checks (PYTHONPATH: the module built by
streamclust_add_python_module in tests/add_python_module): the researcher's linkage is
a choice of the `linkage` keyword, its option a keyword, a bad value the usual
ValueError naming it, and its gate decides the labels that come back."""

import numpy as np

import streamclust
from streamclust import _streamclust

assert "intensity-gated" in _streamclust.policy_names("linkage"), _streamclust.policy_names("linkage")

# One row of points 2 cm apart, 5 m ahead, in 10 ms: the first half at
# intensity 10, the second at 60. Gated at 20 the halves are two
# components; at 80, one.
n = 200
xyz = np.zeros((n, 3), dtype=np.float32)
xyz[:, 0] = 5.0
xyz[:, 1] = np.linspace(-2.0, 2.0, n, dtype=np.float32)
t = np.linspace(0.0, 0.01, n)
intensity = np.where(np.arange(n) < n // 2, 10.0, 60.0).astype(np.float32)


def components(gap):
    c = streamclust.Clusterer("carc", linkage="intensity-gated", intensity_gap=gap, distance=0.1, grid=(64, 256))
    assert c.insert(xyz, t, intensity) == n
    r = c.retrieve(0.01)
    assert len(r.labels) == n and (r.labels >= 0).all(), r.labels
    return len(np.unique(r.labels))


assert components(20) == 2, components(20)
assert components(80) == 1, components(80)

try:
    streamclust.Clusterer("carc", linkage="intensity-gated", intensity_gap=-3)
    raise AssertionError("intensity_gap=-3 was accepted")
except ValueError as e:
    assert "intensity_gap" in str(e), str(e)
print("streamclust_add_python_module: intensity-gated selectable, intensity_gap parsed and applied")
