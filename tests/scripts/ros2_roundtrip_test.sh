#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# CTest ros2_roundtrip: every message type `streamclust ros2` publishes, and
# every one `replay --to ros2://` sends (with the static transform of the
# objects preset's level frame), has the bytes the reference ROS 2
# serializer writes for the same message. A simulated Mid-360 is replayed
# (the driver's PointCloud2 and IMU, then its CustomMsg) to the node over DDS on loopback; the
# node records its input (--record) and what it published (--record-out);
# tests/scripts/check_ros2_roundtrip.mjs decodes each message of both files
# with @foxglove/rosmsg2-serialization and re-encodes it, byte for byte; the
# node's tracked objects (--tracks) are checked against its tracks file.
# Skipped (exit 77) without node or the npm packages (scripts/install-npm-tools.sh).
# Usage: ros2_roundtrip_test.sh TOOL SOURCE_DIR WORK_DIR
set -euo pipefail
tool=$1 src=$2 work=$3
prefix=${STREAMCLUST_NPM_PREFIX:-$src/build/npm}
if ! command -v node >/dev/null || [[ ! -d "$prefix/node_modules/@foxglove/rosmsg2-serialization" ]]; then
  echo "skipped: needs node and @foxglove/rosmsg2-serialization in $prefix (scripts/install-npm-tools.sh)"
  exit 77
fi
rm -rf "$work" && mkdir -p "$work"
domain=71
"$tool" ros2 --dds-loopback --domain $domain --input /points --imu /livox/imu --preset objects-mid360 \
  --idle-exit 1.5 --wait 60 --record "$work/in.mcap" --record-out "$work/out.mcap" --report "$work/node.json" \
  --tracks "$work/tracks.csv" -q &
node_pid=$!
"$tool" replay --simulate --sensor mid360 --seconds 1.5 --imu 0,0 --message pointcloud2 \
  --to ros2:///points --dds-loopback --domain $domain --wait 60 -q
wait $node_pid
# The driver's CustomMsg, on a domain of its own.
"$tool" ros2 --dds-loopback --domain $((domain + 1)) --preset carc-mid360 --idle-exit 1.5 --wait 60 \
  --record "$work/custom.mcap" -q &
node_pid=$!
"$tool" replay --simulate --sensor mid360 --seconds 1.5 --to ros2:///livox/lidar --dds-loopback \
  --domain $((domain + 1)) --wait 60 -q
wait $node_pid
for f in in out custom; do
  json=$(node "$src/tests/scripts/check_ros2_roundtrip.mjs" "$prefix" "$work/$f.mcap")
  echo "$f.mcap: $json"
  python3 - "$f" "$json" "$work/tracks.csv" <<'PY'
import csv, json, sys
which, r = sys.argv[1], json.loads(sys.argv[2])
want = {"in": {"/points": "sensor_msgs/msg/PointCloud2", "/livox/imu": "sensor_msgs/msg/Imu"},
        "custom": {"/livox/lidar": "livox_ros_driver2/msg/CustomMsg"},
        "out": {"/streamclust/points": "sensor_msgs/msg/PointCloud2",
                "/streamclust/clusters": "visualization_msgs/msg/MarkerArray",
                "/streamclust/detections": "vision_msgs/msg/Detection3DArray",
                "/streamclust/tracks": "visualization_msgs/msg/MarkerArray",
                "/streamclust/tracked_objects": "vision_msgs/msg/Detection3DArray",
                "/tf_static": "tf2_msgs/msg/TFMessage"}}[which]
for topic, schema in want.items():
    t = r["topics"].get(topic)
    if not t or t["schema"] != schema or t["messages"] < (1 if topic == "/tf_static" else 10):
        sys.exit("ros2_roundtrip: %s.mcap: expected messages of %s on %s, got %s" % (which, schema, topic, t))
if which == "out":
    # Each tracked_objects message holds the confirmed and coasting rows of
    # the --tracks file's cycle at its log time (the file's time text is
    # exact to the nanosecond): ids, centres, score 1 confirmed, 0.5 coasting.
    def ns(text):
        whole, _, fraction = text.partition(".")
        return str(int(whole) * 10**9 + int((fraction + "000000000")[:9]))
    rows = {}
    for row in csv.DictReader(open(sys.argv[3])):
        if row["state"] != "tentative":
            rows.setdefault(ns(row["time"]), {})[row["track_id"]] = row
    shown = 0
    for stamp, detections in r["tracked"].items():
        want = rows.get(stamp, {})
        if sorted(d[0] for d in detections) != sorted(want):
            sys.exit("ros2_roundtrip: tracked_objects at %s: ids %s, the file's %s" % (stamp, [d[0] for d in detections], sorted(want)))
        for id_, x, y, z, class_id, score in detections:
            row = want[id_]
            if max(abs(x - float(row["x"])), abs(y - float(row["y"])), abs(z - float(row["z"]))) > 1e-4:
                sys.exit("ros2_roundtrip: tracked_objects at %s: track %s at %s, the file's %s" % (stamp, id_, (x, y, z), row))
            if score != (1.0 if row["state"] == "confirmed" else 0.5) or class_id not in ("moving", "static"):
                sys.exit("ros2_roundtrip: tracked_objects at %s: track %s class %s score %s" % (stamp, id_, class_id, score))
            shown += 1
    if shown < 20:
        sys.exit("ros2_roundtrip: only %d tracked objects shown" % shown)
    print("ros2_roundtrip: %d tracked objects equal the --tracks rows" % shown)
print("ros2_roundtrip: %s.mcap ok, %d messages byte-identical" % (which, r["messages"]))
PY
done
