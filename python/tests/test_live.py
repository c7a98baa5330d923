# SPDX-License-Identifier: MIT
"""streamclust.live against the emulated LiDAR (``streamclust replay``) on
loopback: the points are the replayed input's, the labels are the module's
offline clustering of the same points, leaving the loop stops the LiDAR, and
bad sources and silence raise clear errors."""

import signal
import socket
import subprocess
import sys
import time

import numpy as np
import pytest

import streamclust

PRESET = dict(preset="carc-mid360", window_time=0.2)


def simulate_csv(tool, path, sensor, seconds):
    subprocess.run([tool, "simulate", "--sensor", sensor, "--scene", "office", "--seconds", str(seconds),
                    "--out", str(path), "-q"], check=True)
    return str(path)


def replay(tool, *args):
    """The emulated LiDAR as a subprocess (its summary and messages kept)."""
    return subprocess.Popen([tool, "replay", *args], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)


def finish(process, timeout=30):
    """Waits for the emulator; its output."""
    out, _ = process.communicate(timeout=timeout)
    assert process.returncode == 0, out
    return out


def collect(stream):
    retrievals = list(stream)
    assert retrievals, "no retrieval"
    return retrievals


def received(retrievals):
    """(xyz, t, intensity) of every point received: the retrievals' new points."""
    return tuple(np.concatenate([getattr(r, name) for r in retrievals])
                 for name in ("new_xyz", "new_t", "new_intensity"))


def check_points_and_offline_labels(retrievals, csv, quantum_m, **options):
    """The received points are the input's (within the data type's quantum,
    1 us of relative time); every cycle equals cluster_stream over them."""
    xyz, t, intensity = received(retrievals)
    given = streamclust.read(csv)
    finite = np.isfinite(given["x"]) & np.isfinite(given["y"]) & np.isfinite(given["z"])
    expected = np.stack([given["x"], given["y"], given["z"]], axis=1)[finite]
    assert len(xyz) == len(expected)
    assert np.abs(xyz - expected).max() <= quantum_m
    dt = (t - t[0]) - (given["t"][finite] - given["t"][finite][0])
    assert np.abs(dt).max() <= 1e-6
    assert np.array_equal(intensity, np.clip(given["intensity"][finite], 0, 255).astype(np.uint8).astype(np.float32))

    check_offline_labels(retrievals, **options)


def check_offline_labels(retrievals, **options):
    """Every cycle equals cluster_stream over the received points."""
    xyz, t, intensity = received(retrievals)
    offline = streamclust.cluster_stream(xyz, t, intensity, **options)
    assert [r.cycle for r in retrievals] == [r.cycle for r in offline]
    assert len(offline) >= 8  # many cycles
    for live_r, off in zip(retrievals, offline):
        assert live_r.time == off.time
        assert np.array_equal(live_r.index, off.index)
        assert np.array_equal(live_r.labels, off.labels)
        assert np.array_equal(live_r.components, off.components)
        # The window's points are the stream's at the rows' indices.
        assert np.array_equal(live_r.xyz, xyz[live_r.index])
        assert np.array_equal(live_r.t, t[live_r.index])
    assert np.any(np.concatenate([r.labels for r in retrievals]) >= 0)


def test_sdk2_passive_points_and_labels_equal_offline(tool, tmp_path):
    csv = simulate_csv(tool, tmp_path / "office.csv", "mid360", 1.2)
    url = "livox-sdk2://127.0.0.1:48301"
    with streamclust.live(url, idle_exit=0.5, **PRESET) as stream:  # the ports are bound: the replay may start
        sender = replay(tool, csv, "--to", url, "--device-address", "127.0.0.31", "--data-type", "1", "-q")
        retrievals = collect(stream)
        counters = stream.counters
        origin = stream.time_origin
    finish(sender)
    assert abs(origin + retrievals[-1].time - time.time()) < 30  # host clock, Unix time
    assert counters["lost"] == 0 and counters["queue_drops"] == 0 and counters["malformed"] == 0
    assert counters["end"] == "idle_exit: no packets"
    assert counters["lidar"] == "LiDAR at 127.0.0.31"
    assert counters["returns"] == sum(len(r.new_t) for r in retrievals)
    check_points_and_offline_labels(retrievals, csv, 0.0009, **PRESET)


def test_sdk1_handshake_points_and_labels_equal_offline(tool, tmp_path):
    csv = simulate_csv(tool, tmp_path / "avia.csv", "avia", 1.2)
    url = "livox-sdk1://127.0.0.1:38000"
    sender = replay(tool, csv, "--to", url, "--device-address", "127.0.0.32", "--data-type", "2", "-q")
    options = dict(preset="carc-avia", window_time=0.2)
    with streamclust.live(url, idle_exit=0.5, wait=20, **options) as stream:  # waits for the broadcast
        retrievals = collect(stream)
        counters = stream.counters
    finish(sender)
    assert counters["lidar"].startswith("Avia ")
    assert counters["lost"] == 0 and counters["queue_drops"] == 0
    check_points_and_offline_labels(retrievals, csv, 0.0009, **options)


def test_sdk2_configure_finds_the_lidar_by_serial_objects_preset_equals_offline(tool):
    sender = replay(tool, "--simulate", "--sensor", "mid360", "--seconds", "0.6", "--to",
                    "livox-sdk2://127.0.0.39:1000", "--device-address", "127.0.0.38", "--serial", "EMUPYTHON",
                    "--wait-configure", "-q")
    # The objects preset: the mount and sensor height are estimated from the first window.
    options = dict(preset="objects-mid360", window_time=0.2)
    stream = streamclust.live("livox-sdk2://127.0.0.39:48401", configure=True, lidar="EMUPYTHON",
                              discovery_address="127.0.0.38", idle_exit=0.5, wait=20, **options)
    retrievals = collect(stream)
    finish(sender)
    counters = retrievals[-1].counters
    assert counters["lidar"].endswith(" EMUPYTHON")
    assert counters["point_packets"] > 1000 and counters["lost"] == 0
    assert sum(len(r.new_t) for r in retrievals) == counters["returns"]
    assert np.any(np.concatenate([r.labels for r in retrievals]) == streamclust.GROUND)
    check_offline_labels(retrievals, **options)


def test_tracks_equal_cluster_stream_tracks_over_the_received_points(tool):
    """live(tracks=True): every retrieval's tracks are cluster_stream's
    (tracks=True) over the same points, row for row."""
    url = "livox-sdk2://127.0.0.1:48451"
    options = dict(preset="objects-mid360", mount=(0, 0, 0), sensor_height=1.0)
    with streamclust.live(url, idle_exit=0.5, wait=20, tracks=True, **options) as stream:  # bound: replay may start
        sender = replay(tool, "--simulate", "--sensor", "mid360", "--scene", "office", "--seconds", "2.5", "--to",
                        url, "--device-address", "127.0.0.36", "-q")
        retrievals = collect(stream)
    finish(sender)
    xyz, t, intensity = received(retrievals)
    offline = streamclust.cluster_stream(xyz, t, intensity, tracks=True, **options)
    assert [r.cycle for r in retrievals] == [r.cycle for r in offline]
    for live_r, off in zip(retrievals, offline):
        assert live_r.tracks.dtype == streamclust.TRACK_DTYPE
        assert np.array_equal(live_r.tracks, off.tracks), f"cycle {live_r.cycle}"
    states = np.concatenate([r.tracks["state"] for r in retrievals])
    assert np.count_nonzero(states == streamclust.TRACK_STATES.index("confirmed")) > 100
    assert len(retrievals[-1].tracks) > 0


def test_leaving_the_loop_stops_the_receiver_and_the_lidar(tool):
    # SDK1: breaking out stops sampling; the emulated LiDAR then stops sending long before its 20 s end.
    url = "livox-sdk1://127.0.0.1:36000"
    sender = replay(tool, "--simulate", "--sensor", "avia", "--seconds", "20", "--to", url, "--device-address",
                    "127.0.0.33")
    for r in streamclust.live(url, wait=20, preset="carc-avia", window_time=0.2):
        if r.cycle == 3:
            break  # the stream is garbage now: closed
    left = time.monotonic()
    said = finish(sender, timeout=10)
    assert time.monotonic() - left < 5.0
    assert "the host went away" in said

    # SDK2: close() frees the ports at once (the receiver thread is joined).
    url = "livox-sdk2://127.0.0.1:48551"
    sender = replay(tool, "--simulate", "--sensor", "mid360", "--seconds", "20", "--to", url, "--device-address",
                    "127.0.0.34", "-q")
    stream = streamclust.live(url, **PRESET)
    try:
        for r in stream:
            if r.cycle == 3:
                start = time.monotonic()
                stream.close()
                assert time.monotonic() - start < 0.5
                break
        with pytest.raises(StopIteration):
            next(stream)
        with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as s:
            s.bind(("127.0.0.1", 48551))  # free again
    finally:
        sender.kill()
        sender.communicate()


def test_bad_sources_and_options_raise_value_error_before_connecting():
    for source, text in [("http://127.0.0.1", "source: expected livox-sdk2://"),
                         ("livox-sdk2://1.2.3", "host '1.2.3' is not a dotted IPv4 address"),
                         ("livox-sdk2://:70000", "port '70000' is not 1-65535"),
                         ("livox-sdk1://127.0.0.1:65000", "leaves no room for the derived ports")]:
        with pytest.raises(ValueError, match=text.replace("(", r"\(").replace(".", r"\.")):
            streamclust.live(source)
    with pytest.raises(ValueError, match="configure: an SDK2 option"):
        streamclust.live("livox-sdk1://", configure=True)
    with pytest.raises(ValueError, match="wait: expected seconds > 0"):
        streamclust.live("livox-sdk2://", wait=0)
    with pytest.raises(ValueError, match="discovery_address: expected a dotted IPv4 address"):
        streamclust.live("livox-sdk2://", configure=True, discovery_address="lidar")
    with pytest.raises(ValueError, match="window_time"):
        streamclust.live("livox-sdk2://127.0.0.1:48601", window_time=-1)
    with pytest.raises(ValueError, match="time_origin"):
        streamclust.live("livox-sdk2://127.0.0.1:48601", time_origin=0)
    with pytest.raises(ValueError, match="tracks: expected True or False"):
        streamclust.live("livox-sdk2://127.0.0.1:48601", tracks=1)
    with pytest.raises(ValueError, match="tracks: tracking follows the continuous engine"):
        streamclust.live("livox-sdk2://127.0.0.1:48601", mode="frame", tracks=True)


def test_silence_past_wait_raises_timeout_error_naming_the_endpoint():
    stream = streamclust.live("livox-sdk2://127.0.0.1:48701", wait=0.3)
    start = time.monotonic()
    with pytest.raises(TimeoutError, match=r"no SDK2 point packet on UDP 127\.0\.0\.1:48701 within 0\.3 s"):
        next(stream)
    assert time.monotonic() - start < 2.0
    stream.close()
    with pytest.raises(ConnectionError, match=r"SDK1: no LiDAR broadcast to 127\.0\.0\.1:34000 within"):
        streamclust.live("livox-sdk1://127.0.0.1:34000", wait=0.3)


def test_ctrl_c_while_waiting_raises_keyboard_interrupt():
    script = ("import streamclust\n"
              "stream = streamclust.live('livox-sdk2://127.0.0.1:48801', wait=30)\n"
              "print('waiting', flush=True)\n"
              "try:\n"
              "    next(stream)\n"
              "except KeyboardInterrupt:\n"
              "    print('interrupted', flush=True)\n")
    process = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE, text=True)
    assert process.stdout.readline().strip() == "waiting"
    time.sleep(0.3)  # inside next(), the GIL released
    start = time.monotonic()
    process.send_signal(signal.SIGINT)
    out, _ = process.communicate(timeout=10)
    assert time.monotonic() - start < 2.0
    assert "interrupted" in out
