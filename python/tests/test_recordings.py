# SPDX-License-Identifier: MIT
"""streamclust.read on recordings: the same arrays as the source stream's CSV,
topic choice by keyword, and the reader's errors as ValueError."""

import pathlib

import numpy as np
import pytest

import streamclust

DATA = pathlib.Path(__file__).resolve().parents[2] / "tests" / "data" / "recordings"


@pytest.mark.parametrize("name", ["ros1_custom_lz4.bag", "ros2_custom_zstd.mcap", "ros2_custom_db3"])
def test_recording_reads_as_its_csv(name):
    got = streamclust.read(DATA / name)
    want = streamclust.read(DATA / "custom.expected.csv", time_unit="ns")
    for key in ("x", "y", "z", "intensity", "t"):
        np.testing.assert_array_equal(got[key], want[key])
    assert got["time_origin"] == want["time_origin"] == 1700000000


def test_topic_keyword():
    path = DATA / "ros1_pc2_two_topics.bag"
    with pytest.raises(ValueError, match="2 point-cloud topics: /lidar_front"):
        streamclust.read(path)
    assert len(streamclust.read(path, topic="/lidar_rear")["x"]) == 48
    with pytest.raises(ValueError, match="topic"):
        streamclust.read(path, topic=3)
