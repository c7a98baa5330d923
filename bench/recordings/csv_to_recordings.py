#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""csv_to_recordings.py -- turn a simulated point CSV into a ROS 1 bag, a rosbag2 SQLite bag and
the input of write_mcap.mjs, streaming, in bounded memory.

Usage: /usr/bin/python3 csv_to_recordings.py CSV OUTDIR STEM [--period-ms 100] [--block-mb 8]

Run with Debian's /usr/bin/python3 (python3-rosbag, python3-genpy, python3-genmsg, python3-roslz4,
python3-numpy; sqlite3 is in the standard library).  Never uses the project's C++ code.

Input: the CSV `streamclust simulate --out X.csv --start-time S` writes (header
x,y,z,intensity,t,label; t in seconds, Unix time).  Points are cut into messages of --period-ms
of stream time, counted from the first point: message k holds the points with
t - t_first in [k, k+1) * period.  For each message:
  timebase        = time of its first point, integer ns
  offset_time     = point time - timebase, ns (uint32)
  reflectivity    = intensity rounded, clamped to 0..255; tag = 0; line = 0; lidar_id = 192
  header.stamp    = timebase; frame_id "livox_frame"; record / log time = timebase
Outputs (in OUTDIR):
  STEM.bag                ROS 1 bag v2.0, livox_ros_driver/CustomMsg on /livox/lidar, lz4 chunks
                          (rosbag.Bag, raw serialized messages)
  STEM_db3/               rosbag2 bag folder: metadata.yaml + STEM_db3_0.db3 (schema version 4,
                          livox_ros_driver2/msg/CustomMsg in CDR)
  STEM.mcap_input.bin     the same CDR payloads framed as [u64 log_time_ns][u32 size][payload]
  STEM.mcap_input.json    schema text, topic, rosbag2 metadata for write_mcap.mjs
Memory: one block of CSV text (--block-mb) plus the points of the message being cut; every
payload is written out as soon as it is complete.

Times are kept exact to the nanosecond: the CSV's t text is parsed with its leading digits of
whole seconds removed (a double of a Unix time resolves only 0.24 us), which needs every t of the
file to start with the same first digits (whole seconds S..S+duration inside one block of 1000 s:
the script checks it and stops otherwise).
"""
import argparse
import json
import os
import sqlite3
import struct
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
# The message definitions of the recording fixtures (the driver's .msg files).
FIXTURES = os.path.normpath(os.path.join(HERE, "..", "..", "tests", "data", "recordings"))
MSG_ROOT = os.path.join(FIXTURES, "msg")
# The rosbag2 SQLite schema (version 4), as the .db3 fixtures are written.
sys.path.insert(0, FIXTURES)
from write_db3 import NEW_SCHEMA  # noqa: E402

TOPIC = "/livox/lidar"
FRAME_ID = "livox_frame"
LIDAR_ID = 192
ROS1_TYPE = "livox_ros_driver/CustomMsg"
ROS2_TYPE = "livox_ros_driver2/msg/CustomMsg"
# QoS string rosbag2 (metadata version 8) stores for a reliable/volatile publisher (as the fixtures).
QOS_YAML = ("- history: 3\n  depth: 0\n  reliability: 1\n  durability: 2\n  deadline:\n    sec: 9223372036\n"
            "    nsec: 854775807\n  lifespan:\n    sec: 9223372036\n    nsec: 854775807\n  liveliness: 1\n"
            "  liveliness_lease_duration:\n    sec: 9223372036\n    nsec: 854775807\n"
            "  avoid_ros_namespace_conventions: false")

_POINT_FIELDS = dict(names=["offset_time", "x", "y", "z", "reflectivity", "tag", "line"],
                     formats=["<u4", "<f4", "<f4", "<f4", "u1", "u1", "u1"],
                     offsets=[0, 4, 8, 12, 16, 17, 18])
ROS1_POINT = np.dtype(dict(_POINT_FIELDS, itemsize=19))  # ROS 1: packed, 19 bytes
CDR_POINT = np.dtype(dict(_POINT_FIELDS, itemsize=20))   # CDR: the next point's u32 is 4-aligned


# ------------------------------------------------------------------ message definitions
def ros1_class():
    """(message class, md5sum) as genmsg / catkin compute them from the .msg files."""
    import genmsg
    import genmsg.gentools
    import genmsg.msg_loader
    import genpy.dynamic
    root = os.path.join(MSG_ROOT, "ros1")
    search_path = {p: [os.path.join(root, p, "msg")] for p in os.listdir(root)}
    ctx = genmsg.msg_loader.MsgContext.create_default()
    spec = genmsg.msg_loader.load_msg_by_type(ctx, ROS1_TYPE, search_path)
    genmsg.msg_loader.load_depends(ctx, spec, search_path)
    text, md5 = genmsg.gentools.compute_full_text(ctx, spec), genmsg.gentools.compute_md5(ctx, spec)
    cls = genpy.dynamic.generate_dynamic(ROS1_TYPE, text)[ROS1_TYPE]
    assert cls._md5sum == md5
    return cls, md5


def ros2_full_text(root_type):
    """ros2msg schema text: the .msg, then each dependency after a '=' * 80 line and 'MSG: pkg/Type'
    (dependencies sorted, depth first), as tests/data/recordings/lib_stream.mjs ros2FullText."""
    import re
    primitives = {"bool", "byte", "char", "float32", "float64", "int8", "uint8", "int16", "uint16", "int32",
                  "uint32", "int64", "uint64", "string", "wstring", "time", "duration"}
    field_type = re.compile(r"^\s*([a-zA-Z0-9_/]+)(?:<=\d+)?(?:\[[^\]]*\])?\s+[a-zA-Z0-9_]+", re.M)
    seen = set()

    def read(t):
        pkg, name = re.fullmatch(r"([a-zA-Z0-9_]+)/(?:msg/)?([a-zA-Z0-9_]+)", t).groups()
        with open(os.path.join(MSG_ROOT, "ros2", pkg, "msg", name + ".msg")) as f:
            return pkg, f.read()

    def rec(t):
        pkg, text = read(t)
        deps = sorted({(m if "/" in m else pkg + "/" + m) for m in field_type.findall(text)
                       if m not in primitives})
        out = text
        for d in deps:
            if d in seen:
                continue
            seen.add(d)
            out += "\n" + "=" * 80 + "\n" + "MSG: " + d + "\n" + rec(d)
        return out

    return rec(root_type)


def rosbag2_metadata_body(storage, file, start_ns, end_ns, count):
    """rosbag2 metadata version 8, without the rosbag2_bagfile_information: wrapper."""
    dur = end_ns - start_ns
    lines = ["version: 8", "storage_identifier: " + storage, "duration:", "  nanoseconds: %d" % dur,
             "starting_time:", "  nanoseconds_since_epoch: %d" % start_ns, "message_count: %d" % count,
             "topics_with_message_count:", "  - topic_metadata:", "      name: " + TOPIC,
             "      type: " + ROS2_TYPE, "      serialization_format: cdr",
             "      offered_qos_profiles: " + json.dumps(QOS_YAML), '      type_description_hash: ""',
             "    message_count: %d" % count, 'compression_format: ""', 'compression_mode: ""',
             "relative_file_paths:", "  - " + file, "files:", "  - path: " + file, "    starting_time:",
             "      nanoseconds_since_epoch: %d" % start_ns, "    duration:", "      nanoseconds: %d" % dur,
             "    message_count: %d" % count, "custom_data: ~", 'ros_distro: ""']
    return "\n".join(lines)


# ------------------------------------------------------------------ serialization
def fill_points(dtype, off, x, y, z, refl):
    a = np.zeros(len(off), dtype=dtype)
    a["offset_time"], a["x"], a["y"], a["z"], a["reflectivity"] = off, x, y, z, refl
    return a


def ros1_payload(seq, timebase, off, x, y, z, refl):
    sec, nsec = divmod(timebase, 1000000000)
    fid = FRAME_ID.encode()
    head = struct.pack("<III I%ds Q I B 3B I" % len(fid), seq, sec, nsec, len(fid), fid, timebase,
                       len(off), LIDAR_ID, 0, 0, 0, len(off))
    return head + fill_points(ROS1_POINT, off, x, y, z, refl).tobytes()


def cdr_payload(timebase, off, x, y, z, refl):
    sec, nsec = divmod(timebase, 1000000000)
    fid = FRAME_ID.encode() + b"\0"
    head = b"\x00\x01\x00\x00" + struct.pack("<iII", sec, nsec, len(fid)) + fid
    rel = len(head) - 4                      # CDR alignment counts from after the encapsulation
    head += b"\0" * (-rel % 8)               # u64 timebase is 8-aligned
    head += struct.pack("<QIB3BI", timebase, len(off), LIDAR_ID, 0, 0, 0, len(off))
    pts = fill_points(CDR_POINT, off, x, y, z, refl).tobytes()
    return head + pts[:-1] if len(off) else head   # no padding after the last point


# ------------------------------------------------------------------ writers
class Ros1Writer:
    def __init__(self, path):
        import genpy
        import rosbag
        self.genpy = genpy
        self.cls, self.md5 = ros1_class()
        if os.path.exists(path):
            os.remove(path)
        self.bag = rosbag.Bag(path, "w", compression=rosbag.Compression.LZ4)

    def write(self, seq, timebase, off, x, y, z, refl):
        data = ros1_payload(seq, timebase, off, x, y, z, refl)
        t = self.genpy.Time(timebase // 1000000000, timebase % 1000000000)
        self.bag.write(TOPIC, (ROS1_TYPE, data, self.md5, None, self.cls), t=t, raw=True)

    def close(self, *_):
        self.bag.close()


class Db3Writer:
    COMMIT_EVERY = 50  # messages per transaction

    def __init__(self, folder, definition):
        os.makedirs(folder, exist_ok=True)
        self.folder = folder
        self.file = os.path.basename(folder.rstrip("/")) + "_0.db3"
        path = os.path.join(folder, self.file)
        for p in (path, os.path.join(folder, "metadata.yaml")):
            if os.path.exists(p):
                os.remove(p)
        self.con = sqlite3.connect(path)
        self.con.execute("PRAGMA synchronous=OFF;")
        for s in NEW_SCHEMA:
            self.con.execute(s)
        self.con.execute("INSERT INTO schema (schema_version, ros_distro) VALUES (?, ?)", (4, ""))
        cur = self.con.execute("INSERT INTO topics(name, type, serialization_format, offered_qos_profiles, "
                               "type_description_hash) VALUES (?, ?, ?, ?, ?)", (TOPIC, ROS2_TYPE, "cdr", QOS_YAML, ""))
        self.topic_id = cur.lastrowid
        self.con.execute("INSERT INTO message_definitions (topic_type, encoding, encoded_message_definition, "
                         "type_description_hash) VALUES (?, ?, ?, ?)", (ROS2_TYPE, "ros2msg", definition, ""))
        self.con.commit()
        self.pending = 0

    def write(self, timebase, payload):
        self.con.execute("INSERT INTO messages (timestamp, topic_id, data) VALUES (?, ?, ?);",
                         (timebase, self.topic_id, payload))
        self.pending += 1
        if self.pending >= self.COMMIT_EVERY:
            self.con.commit()
            self.pending = 0

    def close(self, start_ns, end_ns, count):
        body = rosbag2_metadata_body("sqlite3", self.file, start_ns, end_ns, count)
        self.con.execute("INSERT INTO metadata (metadata_version, metadata) VALUES (?, ?)", (8, body))
        self.con.commit()
        self.con.close()
        with open(os.path.join(self.folder, "metadata.yaml"), "w") as f:
            f.write("rosbag2_bagfile_information:\n" + "".join("  " + l + "\n" for l in body.split("\n")))


class FramedWriter:
    """CDR payloads for write_mcap.mjs: [u64 log_time_ns][u32 size][payload] ..."""

    def __init__(self, stem, definition):
        self.stem, self.definition = stem, definition
        self.f = open(stem + ".mcap_input.bin", "wb")

    def write(self, timebase, payload):
        self.f.write(struct.pack("<QI", timebase, len(payload)))
        self.f.write(payload)

    def close(self, start_ns, end_ns, count):
        self.f.close()
        with open(self.stem + ".mcap_input.json", "w") as f:
            json.dump({"topic": TOPIC, "schema_name": ROS2_TYPE, "schema_text": self.definition,
                       "qos": QOS_YAML, "message_count": count,
                       "rosbag2_metadata": rosbag2_metadata_body("mcap", os.path.basename(self.stem) + ".mcap",
                                                                 start_ns, end_ns, count)}, f)


# ------------------------------------------------------------------ CSV in blocks
def csv_blocks(path, block_bytes):
    """Yields (ns_abs int64, x, y, z float32, reflectivity uint8) per block of CSV text."""
    with open(path, "rb") as f:
        header = f.readline().decode().strip().split(",")
        col = {n: i for i, n in enumerate(header)}
        for n in ("x", "y", "z", "intensity", "t"):
            if n not in col:
                sys.exit("csv_to_recordings.py: %s lacks column %s" % (path, n))
        if col["t"] == 0:
            sys.exit("csv_to_recordings.py: t must not be the first column")
        ncol = len(header)
        first = f.readline()
        t_text = first.decode().strip().split(",")[col["t"]]
        whole = t_text.split(".")[0]
        if not whole.isdigit() or len(whole) < 4:
            sys.exit("csv_to_recordings.py: first t %r: expected Unix time in seconds" % t_text)
        # t texts are "<prefix><3 digits>[.fraction]"; the prefix is removed before parsing.
        prefix, base = whole[:-3], int(whole[-3:])
        whole_s = int(whole) - base              # whole seconds of the prefix
        pattern = ("," + prefix).encode()
        rest = first
        while True:
            data = f.read(block_bytes)
            buf = rest + data
            if not data:
                cut = len(buf)
            else:
                cut = buf.rfind(b"\n") + 1
                if cut == 0:
                    rest = buf
                    continue
            block, rest = buf[:cut], buf[cut:]
            block = block.strip(b"\n")
            if block:
                nlines = block.count(b"\n") + 1
                if block.count(pattern) != nlines:
                    sys.exit("csv_to_recordings.py: not every t starts with %s (times must stay within "
                             "[%d, %d) s)" % (prefix, whole_s, whole_s + 1000))
                vals = np.fromstring(block.replace(pattern, b",").replace(b"\n", b","), sep=",")
                if vals.size != nlines * ncol:
                    sys.exit("csv_to_recordings.py: malformed CSV block (%d values for %d lines)" % (vals.size, nlines))
                vals = vals.reshape(nlines, ncol)
                t_rel = vals[:, col["t"]]        # seconds after whole_s, exact decimal -> double
                ns = np.rint(t_rel * 1e9).astype(np.int64) + np.int64(whole_s) * 1000000000
                refl = np.clip(np.rint(vals[:, col["intensity"]]), 0, 255).astype(np.uint8)
                yield (ns, vals[:, col["x"]].astype(np.float32), vals[:, col["y"]].astype(np.float32),
                       vals[:, col["z"]].astype(np.float32), refl)
            if not data:
                return


# ------------------------------------------------------------------ main
def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("csv")
    ap.add_argument("outdir")
    ap.add_argument("stem")
    ap.add_argument("--period-ms", type=float, default=100.0)
    ap.add_argument("--block-mb", type=float, default=8.0)
    a = ap.parse_args()
    period = int(round(a.period_ms * 1e6))
    stem = os.path.join(a.outdir, a.stem)
    definition = ros2_full_text(ROS2_TYPE)

    ros1 = Ros1Writer(stem + ".bag")
    db3 = Db3Writer(stem + "_db3", definition)
    framed = FramedWriter(stem, definition)

    t0 = None
    seq = 0
    npoints = 0
    first_ns = last_ns = None
    pend = None  # points of the message not yet complete
    started = time.time()

    def emit(ns, x, y, z, refl):
        nonlocal seq, npoints, first_ns, last_ns
        timebase = int(ns[0])
        off = ns - timebase
        if off[-1] >= 2 ** 32:
            sys.exit("csv_to_recordings.py: a message spans more than 4.29 s")
        ros1.write(seq, timebase, off, x, y, z, refl)
        payload = cdr_payload(timebase, off, x, y, z, refl)
        db3.write(timebase, payload)
        framed.write(timebase, payload)
        if first_ns is None:
            first_ns = timebase
        last_ns = timebase
        seq += 1
        npoints += len(ns)

    for cols in csv_blocks(a.csv, int(a.block_mb * 1024 * 1024)):
        if pend is not None:
            cols = tuple(np.concatenate((p, c)) for p, c in zip(pend, cols))
        ns = cols[0]
        if t0 is None:
            t0 = int(ns[0])
        if np.any(np.diff(ns) < 0):  # pend's points precede the block's: checks across blocks too
            sys.exit("csv_to_recordings.py: times decrease; the CSV must be in time order")
        k = (ns - t0) // period
        # every message but the last one of the block is complete
        bounds = np.flatnonzero(np.diff(k)) + 1
        starts = np.concatenate(([0], bounds))
        ends = np.concatenate((bounds, [len(k)]))
        for s, e in zip(starts[:-1], ends[:-1]):
            emit(*(c[s:e] for c in cols))
        s = starts[-1]
        pend = tuple(c[s:].copy() for c in cols)
    if pend is not None and len(pend[0]):
        emit(*pend)

    count = seq
    ros1.close()
    db3.close(first_ns, last_ns, count)
    framed.close(first_ns, last_ns, count)
    print("csv_to_recordings.py: %d points in %d messages of %g ms -> %s.bag, %s_db3/, %s.mcap_input.* (%.1f s)"
          % (npoints, count, a.period_ms, stem, stem, stem, time.time() - started))


if __name__ == "__main__":
    main()
