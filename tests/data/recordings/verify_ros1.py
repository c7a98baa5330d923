#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""verify_ros1.py -- check the ROS 1 bag fixtures with independent readers.

Usage: /usr/bin/python3 verify_ros1.py        (exit status 1 on any mismatch)

1. rosbag (python3-rosbag) reads every message back; points are compared with the expected CSV.
2. A byte-level walk over the bag records (ROS bag v2.0 format: u32 header_len, header fields
   name=value, u32 data_len, data) lists each chunk's compression string and decompresses lz4
   chunks with python3-lz4's lz4.frame (liblz4) and bz2 chunks with Python's bz2 module, to show
   whether a plain LZ4-frame / bzip2 decoder reads them.
"""
import bz2
import struct
import sys

import rosbag

sys.dont_write_bytecode = True  # keep the source tree free of __pycache__
from fixture_check import HERE, Mismatch, compare, decode_cloud, load_expected

try:
    import lz4.frame as lz4frame
except ImportError:  # python3-lz4 not installed: skip that cross-check
    lz4frame = None

BAGS = {
    # bag: (lidar topic, expected type, expected CSV, other topics {topic: (type, count)})
    "ros1_custom.bag": ("/livox/lidar", "livox_ros_driver/CustomMsg", "custom.expected.csv",
                        {"/livox/imu": ("sensor_msgs/Imu", 3)}),
    "ros1_custom_bz2.bag": ("/livox/lidar", "livox_ros_driver2/CustomMsg", "custom.expected.csv",
                            {"/livox/imu": ("sensor_msgs/Imu", 3)}),
    "ros1_custom_lz4.bag": ("/livox/lidar", "livox_ros_driver2/CustomMsg", "custom.expected.csv",
                            {"/livox/imu": ("sensor_msgs/Imu", 3)}),
    "ros1_pc2_livox.bag": ("/livox/lidar", "sensor_msgs/PointCloud2", "pc2_livox.expected.csv",
                           {"/livox/imu": ("sensor_msgs/Imu", 3)}),
    "ros1_pc2_two_topics.bag": ("/lidar_front", "sensor_msgs/PointCloud2", "pc2_livox.expected.csv",
                                {"/lidar_rear": ("sensor_msgs/PointCloud2", 4), "/livox/imu": ("sensor_msgs/Imu", 3)}),
}
EXPECTED_COMPRESSION = {"ros1_custom_bz2.bag": "bz2", "ros1_custom_lz4.bag": "lz4"}


def read_points(msg, type_name):
    if type_name.endswith("/CustomMsg"):
        if msg.point_num != len(msg.points):
            raise Mismatch("point_num")
        return [(p.x, p.y, p.z, p.reflectivity, msg.timebase + p.offset_time) for p in msg.points]
    fields = [(f.name, f.offset, f.datatype, f.count) for f in msg.fields]
    return decode_cloud(msg.header.stamp.to_nsec(), msg.height, msg.width, fields, msg.is_bigendian,
                        msg.point_step, msg.row_step, msg.data)


def check_with_rosbag(name, spec):
    topic, type_name, csv, others = spec
    bag = rosbag.Bag(f"{HERE}/{name}")
    info = bag.get_type_and_topic_info().topics
    want = {topic: (type_name, 4), **others}
    got = {t: (v.msg_type, v.message_count) for t, v in info.items()}
    if got != want:
        raise Mismatch(f"{name}: topics {got} != {want}")
    points = []
    for t, msg, _ in bag.read_messages(topics=[topic]):
        points += read_points(msg, type_name)
    compare(name, points, load_expected(csv))
    n_chunks = len(bag._chunks)
    if n_chunks < 2:
        raise Mismatch(f"{name}: only {n_chunks} chunk")
    bag.close()
    return n_chunks


def fields(header):
    out, o = {}, 0
    while o < len(header):
        n = struct.unpack_from("<I", header, o)[0]
        k, v = header[o + 4:o + 4 + n].split(b"=", 1)
        out[k.decode()] = v
        o += 4 + n
    return out


def walk(name):
    """Raw record walk; returns [(compression, size, decompressed ok)] per chunk."""
    b = open(f"{HERE}/{name}", "rb").read()
    if not b.startswith(b"#ROSBAG V2.0\n"):
        raise Mismatch(f"{name}: bad magic")
    o, chunks = 13, []
    while o < len(b):
        hl = struct.unpack_from("<I", b, o)[0]
        h = fields(b[o + 4:o + 4 + hl])
        dl = struct.unpack_from("<I", b, o + 4 + hl)[0]
        data = b[o + 8 + hl:o + 8 + hl + dl]
        op = h["op"][0]
        if op == 0x05:
            comp = h["compression"].decode()
            size = struct.unpack("<I", h["size"])[0]
            if comp == "none":
                raw = data
            elif comp == "bz2":
                raw = bz2.decompress(data)
            elif comp == "lz4":
                raw = lz4frame.decompress(data) if lz4frame else None
                if data[:4] != b"\x04\x22\x4d\x18":
                    raise Mismatch(f"{name}: lz4 chunk without LZ4 frame magic")
            else:
                raise Mismatch(f"{name}: unknown compression {comp}")
            if raw is not None and len(raw) != size:
                raise Mismatch(f"{name}: chunk size {len(raw)} != header size {size}")
            chunks.append((comp, size, len(data), raw is not None))
        o += 8 + hl + dl
    return chunks


def main():
    ok = True
    for name, spec in BAGS.items():
        try:
            n = check_with_rosbag(name, spec)
            chunks = walk(name)
            comps = {c[0] for c in chunks}
            want = EXPECTED_COMPRESSION.get(name, "none")
            if comps != {want} or len(chunks) != n:
                raise Mismatch(f"{name}: chunk compressions {comps}, {len(chunks)} chunks")
            print(f"ok   {name}: {n} chunks, compression '{want}', sizes (uncompressed/stored) "
                  + ", ".join(f"{c[1]}/{c[2]}" for c in chunks)
                  + ("" if all(c[3] for c in chunks) else " (lz4 cross-check skipped: no python3-lz4)"))
        except Exception as e:  # noqa: BLE001 -- report every failure, then exit non-zero
            ok = False
            print(f"FAIL {name}: {type(e).__name__}: {e}")
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
