#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""write_ros1_bags.py -- ROS 1 bag fixtures, written by the reference ROS 1 tooling.

Usage: /usr/bin/python3 write_ros1_bags.py <work_dir>/ros1_input.json <out_dir>

Run with Debian's /usr/bin/python3 (packages python3-rosbag, python3-genpy, python3-genmsg,
python3-roslz4).  Message classes are generated at run time with genpy.dynamic.generate_dynamic
from the full definition text that genmsg computes from the .msg files in msg/ros1/ (the same
text and md5sum catkin-generated classes carry), so no ROS workspace is needed.

Writes (bag format v2.0, topic /livox/lidar unless noted, plus /livox/imu sensor_msgs/Imu):
  ros1_custom.bag           livox_ros_driver/CustomMsg, uncompressed chunks
  ros1_custom_bz2.bag       livox_ros_driver2/CustomMsg, bz2 chunks
  ros1_custom_lz4.bag       livox_ros_driver2/CustomMsg, lz4 chunks
  ros1_pc2_livox.bag        sensor_msgs/PointCloud2, livox_ros_driver2 PointXYZRTLT layout
  ros1_pc2_two_topics.bag   PointCloud2 on /lidar_front and /lidar_rear (no /livox/lidar)
The point stream and PointCloud2 point bytes come from gen_fixtures.mjs (ros1_input.json).
Bag record times = header stamps; nothing depends on the wall clock.
"""
import base64
import json
import os
import sys

import genmsg
import genmsg.gentools
import genmsg.msg_loader
import genpy
import genpy.dynamic
import rosbag

HERE = os.path.dirname(os.path.abspath(__file__))
MSG_ROOT = os.path.join(HERE, "msg", "ros1")
CHUNK_THRESHOLD = 4096  # bytes; small so that every bag has several chunks


def full_text(msg_type):
    """Definition text + md5 exactly as genmsg (catkin's generator) computes them."""
    search_path = {p: [os.path.join(MSG_ROOT, p, "msg")] for p in os.listdir(MSG_ROOT)}
    ctx = genmsg.msg_loader.MsgContext.create_default()
    spec = genmsg.msg_loader.load_msg_by_type(ctx, msg_type, search_path)
    genmsg.msg_loader.load_depends(ctx, spec, search_path)
    return genmsg.gentools.compute_full_text(ctx, spec), genmsg.gentools.compute_md5(ctx, spec)


def msg_classes(msg_type):
    text, md5 = full_text(msg_type)
    classes = genpy.dynamic.generate_dynamic(msg_type, text)
    assert classes[msg_type]._md5sum == md5, msg_type
    return classes


def ros_time(ns):
    ns = int(ns)
    return genpy.Time(ns // 1000000000, ns % 1000000000)


def main():
    inp, out_dir = sys.argv[1], sys.argv[2]
    with open(inp) as f:
        data = json.load(f)

    imu_cls = msg_classes("sensor_msgs/Imu")
    Imu = imu_cls["sensor_msgs/Imu"]

    def imu_msgs():
        for seq, s in enumerate(data["imu"]):
            m = Imu()
            m.header.seq = seq
            m.header.stamp = ros_time(s["stamp_ns"])
            m.header.frame_id = "livox_frame"
            for part in ("orientation", "angular_velocity", "linear_acceleration"):
                obj = getattr(m, part)
                for key, val in s[part].items():
                    setattr(obj, key, val)
            yield "/livox/imu", m, m.header.stamp

    def custom_msgs(pkg):
        cls = msg_classes(pkg + "/CustomMsg")
        CustomMsg, CustomPoint = cls[pkg + "/CustomMsg"], cls[pkg + "/CustomPoint"]
        for msg in data["stream"]:
            m = CustomMsg()
            m.header.seq = msg["k"]
            m.header.stamp = ros_time(msg["stamp_ns"])
            m.header.frame_id = "livox_frame"
            m.timebase = int(msg["stamp_ns"]) + 1000
            m.point_num = len(msg["points"])
            m.lidar_id = 192
            m.rsvd = [0, 0, 0]
            m.points = [CustomPoint(offset_time=p["offset_time"], x=p["x"], y=p["y"], z=p["z"],
                                    reflectivity=p["reflectivity"], tag=p["tag"], line=p["line"])
                        for p in msg["points"]]
            yield "/livox/lidar", m, m.header.stamp

    pc2_cls = msg_classes("sensor_msgs/PointCloud2")
    PointCloud2, PointField = pc2_cls["sensor_msgs/PointCloud2"], pc2_cls["sensor_msgs/PointField"]

    def pc2_msgs(topic, clouds):
        for seq, c in enumerate(clouds):
            m = PointCloud2()
            m.header.seq = seq
            m.header.stamp = ros_time(c["stamp_ns"])
            m.header.frame_id = "livox_frame"
            m.height, m.width = c["height"], c["width"]
            m.fields = [PointField(name=f["name"], offset=f["offset"], datatype=f["datatype"], count=f["count"])
                        for f in c["fields"]]
            m.is_bigendian = c["is_bigendian"]
            m.point_step, m.row_step = c["point_step"], c["row_step"]
            m.data = base64.b64decode(c["data"])
            m.is_dense = c["is_dense"]
            yield topic, m, m.header.stamp

    def write(name, compression, *sources):
        items = [it for src in sources for it in src]
        items.sort(key=lambda it: (it[2].to_nsec(), it[0]))
        path = os.path.join(out_dir, name)
        if os.path.exists(path):
            os.remove(path)
        with rosbag.Bag(path, "w", compression=compression, chunk_threshold=CHUNK_THRESHOLD) as bag:
            for topic, msg, t in items:
                bag.write(topic, msg, t)

    write("ros1_custom.bag", rosbag.Compression.NONE, custom_msgs("livox_ros_driver"), imu_msgs())
    write("ros1_custom_bz2.bag", rosbag.Compression.BZ2, custom_msgs("livox_ros_driver2"), imu_msgs())
    write("ros1_custom_lz4.bag", rosbag.Compression.LZ4, custom_msgs("livox_ros_driver2"), imu_msgs())
    write("ros1_pc2_livox.bag", rosbag.Compression.NONE, pc2_msgs("/livox/lidar", data["clouds"]["livox"]), imu_msgs())
    write("ros1_pc2_two_topics.bag", rosbag.Compression.NONE,
          pc2_msgs("/lidar_front", data["clouds"]["livox"]),
          pc2_msgs("/lidar_rear", data["clouds"]["livox_rear"]), imu_msgs())
    print("write_ros1_bags.py: wrote 5 bags")


if __name__ == "__main__":
    main()
