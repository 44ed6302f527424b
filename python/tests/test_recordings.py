"""Recordings in from Python (issue 38): the frames the recordings fixture makes from the shared
Kinect frame (tests/data/make_recordings.py), as a ROS 1 bag, an MCAP file and a TUM RGB-D
folder, map as their PCD manifest does, cell for cell; every and topic choose frames."""

import os

import numpy as np
import pytest

import vantage as vt

RECORDINGS = os.environ.get("VANTAGE_RECORDINGS", "")


@pytest.fixture(scope="module")
def pcd_map():
    return vt.map_recorded(os.path.join(RECORDINGS, "pcd.yaml"), num_threads=2)


@pytest.mark.parametrize("manifest", ["bag.yaml", "mcap.yaml", "tum.yaml"])
def test_the_same_map_as_the_pcds(pcd_map, manifest):
    grid = vt.map_recorded(os.path.join(RECORDINGS, manifest), num_threads=2)
    assert np.array_equal(grid.log_odds(), pcd_map.log_odds())
    assert grid.counts()["occupied"] > 1000  # a map of the objects, not an empty one


def test_every_and_topic_choose_frames():
    bag = os.path.join(RECORDINGS, "bag.yaml")
    assert len(vt.read_manifest(bag)["clouds"]) == 3
    every2 = vt.read_manifest(bag, every=2, topic="/camera/depth/points")["clouds"]
    assert [c["pose_from"] for c in every2] == ["given", "given"]
    with pytest.raises(ValueError, match="no message on topic /nothing"):
        vt.read_manifest(bag, topic="/nothing")
