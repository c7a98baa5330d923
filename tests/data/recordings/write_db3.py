#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""write_db3.py -- rosbag2 SQLite fixtures (Python's sqlite3 module, no ROS needed).

Usage: /usr/bin/python3 write_db3.py <work_dir> <out_dir>

Reads the CDR payloads, definition texts and bag metadata that gen_fixtures.mjs serialized
(<work_dir>/db3_custom.json, <work_dir>/db3_pc2_old.json) and writes:

  ros2_custom_db3/                    a bag folder as rosbag2 (schema version 4, Iron and later)
    metadata.yaml                     writes it: metadata version 8
    ros2_custom_db3_0.db3             tables schema, metadata, topics (with offered_qos_profiles
                                      and type_description_hash), message_definitions, messages,
                                      index timestamp_idx; the CREATE statements are rosbag2's
                                      (rosbag2_storage_sqlite3/sqlite_storage.cpp)
  ros2_pc2_old.db3                    a single file in the first rosbag2 layout (Dashing/Eloquent,
                                      before rosbag2 PR #335): only tables topics(id, name, type,
                                      serialization_format) and messages, index timestamp_idx

messages.timestamp = header stamp in ns; rows inserted in timestamp order.
type_description_hash is stored as "" (the real RIHS01 hashes need the ROS type-description
tooling; rosbag2 also stores "" when the publisher offers none).
SQLite writes no time stamps into the file, so the output is byte-for-byte reproducible with the
same SQLite library version.  Page size 1024 instead of SQLite's default 4096 (see create()).
"""
import base64
import json
import os
import sqlite3
import sys

NEW_SCHEMA = [
    "CREATE TABLE schema(schema_version INTEGER PRIMARY KEY,ros_distro TEXT NOT NULL);",
    "CREATE TABLE metadata(id INTEGER PRIMARY KEY,metadata_version INTEGER NOT NULL,metadata TEXT NOT NULL);",
    "CREATE TABLE topics(id INTEGER PRIMARY KEY,name TEXT NOT NULL,type TEXT NOT NULL,"
    "serialization_format TEXT NOT NULL,offered_qos_profiles TEXT NOT NULL,type_description_hash TEXT NOT NULL);",
    "CREATE TABLE message_definitions(id INTEGER PRIMARY KEY,topic_type TEXT NOT NULL,encoding TEXT NOT NULL,"
    "encoded_message_definition TEXT NOT NULL,type_description_hash TEXT NOT NULL);",
    "CREATE TABLE messages(id INTEGER PRIMARY KEY,topic_id INTEGER NOT NULL,timestamp INTEGER NOT NULL, data BLOB NOT NULL);",
    "CREATE INDEX timestamp_idx ON messages (timestamp ASC);",
]

OLD_SCHEMA = [
    "CREATE TABLE topics(id INTEGER PRIMARY KEY,name TEXT NOT NULL,type TEXT NOT NULL,serialization_format TEXT NOT NULL);",
    "CREATE TABLE messages(id INTEGER PRIMARY KEY,topic_id INTEGER NOT NULL,timestamp INTEGER NOT NULL, data BLOB NOT NULL);",
    "CREATE INDEX timestamp_idx ON messages (timestamp ASC);",
]


def create(path, statements):
    if os.path.exists(path):
        os.remove(path)
    con = sqlite3.connect(path)
    # rosbag2 leaves SQLite's default page size (4096); 1024 only keeps these tiny fixtures small.
    # The page size is internal to SQLite and invisible to any reader that goes through libsqlite3.
    con.execute("PRAGMA page_size=1024;")
    for s in statements:
        con.execute(s)
    return con


def insert_messages(con, topic_ids, messages):
    for m in messages:
        con.execute("INSERT INTO messages (timestamp, topic_id, data) VALUES (?, ?, ?);",
                    (int(m["timestamp"]), topic_ids[m["topic"]], base64.b64decode(m["data"])))


def write_new(inp, bag_dir):
    os.makedirs(bag_dir, exist_ok=True)
    name = os.path.basename(bag_dir.rstrip("/"))
    con = create(os.path.join(bag_dir, name + "_0.db3"), NEW_SCHEMA)
    con.execute("INSERT INTO schema (schema_version, ros_distro) VALUES (?, ?)", (4, ""))
    topic_ids = {}
    for t in inp["topics"]:
        cur = con.execute("INSERT INTO topics(name, type, serialization_format, offered_qos_profiles, "
                          "type_description_hash) VALUES (?, ?, ?, ?, ?)",
                          (t["name"], t["type"], "cdr", inp["qos"], ""))
        topic_ids[t["name"]] = cur.lastrowid
        con.execute("INSERT INTO message_definitions (topic_type, encoding, encoded_message_definition, "
                    "type_description_hash) VALUES (?, ?, ?, ?)", (t["type"], "ros2msg", t["definition"], ""))
    insert_messages(con, topic_ids, inp["messages"])
    con.execute("INSERT INTO metadata (metadata_version, metadata) VALUES (?, ?)", (8, inp["metadata_body"]))
    con.commit()
    con.close()
    with open(os.path.join(bag_dir, "metadata.yaml"), "w") as f:
        f.write(inp["metadata_yaml"])


def write_old(inp, path):
    con = create(path, OLD_SCHEMA)
    topic_ids = {}
    for t in inp["topics"]:
        cur = con.execute("INSERT INTO topics (name, type, serialization_format) VALUES (?, ?, ?)",
                          (t["name"], t["type"], "cdr"))
        topic_ids[t["name"]] = cur.lastrowid
    insert_messages(con, topic_ids, inp["messages"])
    con.commit()
    con.close()


def main():
    work, out = sys.argv[1], sys.argv[2]
    with open(os.path.join(work, "db3_custom.json")) as f:
        write_new(json.load(f), os.path.join(out, "ros2_custom_db3"))
    with open(os.path.join(work, "db3_pc2_old.json")) as f:
        write_old(json.load(f), os.path.join(out, "ros2_pc2_old.db3"))
    print("write_db3.py: wrote ros2_custom_db3/ and ros2_pc2_old.db3 (SQLite %s)" % sqlite3.sqlite_version)


if __name__ == "__main__":
    main()
