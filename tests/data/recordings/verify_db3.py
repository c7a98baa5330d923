#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""verify_db3.py -- check the rosbag2 SQLite fixtures.

Usage: /usr/bin/python3 verify_db3.py [dump.json]      (exit status 1 on any mismatch)

Opens each .db3 with Python's sqlite3, checks the table layout (new: schema version 4 with
message_definitions; old: only topics(id,name,type,serialization_format) + messages), reads the
messages with rosbag2's reader query (JOIN topics, ORDER BY timestamp, id), decodes the CDR blobs
with the hand-written decoder of fixture_check.py and compares with the expected CSV.  With a
dump.json argument it also writes every blob + definition text there, so that verify_mcap.mjs can
decode them a second time with @foxglove/rosmsg2-serialization's MessageReader.
"""
import base64
import json
import os
import sqlite3
import sys

sys.dont_write_bytecode = True  # keep the source tree free of __pycache__
from fixture_check import HERE, Mismatch, cdr_custom, cdr_pc2, compare, load_expected

FIXTURES = {
    # path: (layout, lidar type, decoder, expected CSV)
    "ros2_custom_db3/ros2_custom_db3_0.db3": ("new", "livox_ros_driver2/msg/CustomMsg", "custom", "custom.expected.csv"),
    "ros2_pc2_old.db3": ("old", "sensor_msgs/msg/PointCloud2", "pc2", "pc2_livox.expected.csv"),
}
NEW_TABLES = {
    "schema": ["schema_version", "ros_distro"],
    "metadata": ["id", "metadata_version", "metadata"],
    "topics": ["id", "name", "type", "serialization_format", "offered_qos_profiles", "type_description_hash"],
    "message_definitions": ["id", "topic_type", "encoding", "encoded_message_definition", "type_description_hash"],
    "messages": ["id", "topic_id", "timestamp", "data"],
}
OLD_TABLES = {
    "topics": ["id", "name", "type", "serialization_format"],
    "messages": ["id", "topic_id", "timestamp", "data"],
}


def tables(con):
    names = [r[0] for r in con.execute("SELECT name FROM sqlite_master WHERE type='table' ORDER BY name")]
    return {n: [r[1] for r in con.execute(f"PRAGMA table_info({n})")] for n in names}


def check(path, layout, lidar_type, kind, csv, dump):
    con = sqlite3.connect(f"file:{os.path.join(HERE, path)}?mode=ro", uri=True)
    want = NEW_TABLES if layout == "new" else OLD_TABLES
    got = tables(con)
    if got != want:
        raise Mismatch(f"tables {got}")
    topics = {r[1]: r[2] for r in con.execute("SELECT id, name, type, serialization_format FROM topics")}
    if topics != {"/livox/lidar": lidar_type, "/livox/imu": "sensor_msgs/msg/Imu"}:
        raise Mismatch(f"topics {topics}")
    defs = {}
    if layout == "new":
        if list(con.execute("SELECT schema_version FROM schema")) != [(4,)]:
            raise Mismatch("schema_version")
        for t, enc, text in con.execute("SELECT topic_type, encoding, encoded_message_definition FROM message_definitions"):
            if enc != "ros2msg":
                raise Mismatch(f"encoding {enc}")
            defs[t] = text
        if set(defs) != set(topics.values()):
            raise Mismatch(f"message_definitions {set(defs)}")
    rows = list(con.execute(
        "SELECT messages.data, messages.timestamp, topics.name, topics.type FROM messages "
        "JOIN topics ON messages.topic_id = topics.id ORDER BY messages.timestamp, messages.id"))
    points, n_lidar, pads = [], 0, None
    for data, ts, name, typ in rows:
        if name != "/livox/lidar":
            continue
        n_lidar += 1
        if kind == "custom":
            stamp, frame, _, pts, c = cdr_custom(data)
        else:
            stamp, frame, pts, _, c = cdr_pc2(data)
        if stamp != ts:
            raise Mismatch(f"timestamp column {ts} != header stamp {stamp}")
        pads = pads or c.pads[:4]
        points += pts
    if n_lidar != 4 or len(rows) != 7:
        raise Mismatch(f"{n_lidar} lidar rows, {len(rows)} rows")
    compare(path, points, load_expected(csv))
    if dump is not None:
        dump.append({"file": path, "type": lidar_type, "definition": defs.get(lidar_type),
                     "expected": csv,
                     "messages": [base64.b64encode(d).decode() for d, _, n, _ in rows if n == "/livox/lidar"]})
    con.close()
    return pads


def main():
    dump_path = sys.argv[1] if len(sys.argv) > 1 else None
    dump = [] if dump_path else None
    ok = True
    for path, spec in FIXTURES.items():
        try:
            pads = check(path, *spec, dump)
            print(f"ok   {path}: {spec[0]} layout, 4 lidar + 3 imu rows; first CDR pad gaps (abs offset, bytes) {pads}")
        except Exception as e:  # noqa: BLE001
            ok = False
            print(f"FAIL {path}: {type(e).__name__}: {e}")
    meta = os.path.join(HERE, "ros2_custom_db3", "metadata.yaml")
    text = open(meta).read()
    for needle in ("rosbag2_bagfile_information:", "storage_identifier: sqlite3", "- ros2_custom_db3_0.db3",
                   "message_count: 7", "name: /livox/lidar", "type: livox_ros_driver2/msg/CustomMsg"):
        if needle not in text:
            ok = False
            print(f"FAIL metadata.yaml lacks {needle!r}")
    try:
        import yaml  # python3-yaml, optional
    except ImportError:
        yaml = None
    if yaml is not None:
        info = yaml.safe_load(text)["rosbag2_bagfile_information"]
        if (info["version"] != 8 or info["relative_file_paths"] != ["ros2_custom_db3_0.db3"]
                or info["starting_time"]["nanoseconds_since_epoch"] != 1700000000000000000
                or {t["topic_metadata"]["name"]: t["message_count"] for t in info["topics_with_message_count"]}
                != {"/livox/lidar": 4, "/livox/imu": 3}):
            ok = False
            print("FAIL metadata.yaml content")
    if dump_path:
        with open(dump_path, "w") as f:
            json.dump(dump, f)
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
