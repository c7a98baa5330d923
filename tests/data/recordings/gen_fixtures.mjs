// SPDX-License-Identifier: MIT
// gen_fixtures.mjs -- Node part of make_fixtures.sh.
//
// Usage: node gen_fixtures.mjs <npm_prefix> <out_dir> <work_dir>
//   <npm_prefix>  directory where make_fixtures.sh installed the pinned npm packages
//   <out_dir>     this folder (tests/data/recordings): receives *.expected.csv and *.mcap
//   <work_dir>    temporary directory: receives JSON files that the Python writers read
//
// Writes:
//   *.expected.csv          expected points (see lib_stream.mjs), one file per distinct content
//   ros2_*.mcap             MCAP fixtures 6..12 (ROS 2 profile), written by @mcap/core's McapWriter
//                           with CDR payloads from @foxglove/rosmsg2-serialization; lz4 chunks are
//                           compressed with lz4js (LZ4 frame format), zstd chunks with zstd-codec
//   <work>/ros1_input.json  stream + PointCloud2 point blobs + IMU samples for write_ros1_bags.py
//   <work>/db3_*.json       CDR payloads + definition texts for write_db3.py
// Everything is deterministic: no wall-clock time, no randomness.

import fs from "node:fs";
import path from "node:path";
import { createRequire } from "node:module";
import {
  makeStream, stampSecNsec, packCloud, expectedCsv, ros2FullText, QOS_YAML,
  velodyneTimeF32, N_MSGS, rosbag2MetadataBody, metadataYamlFile,
} from "./lib_stream.mjs";

const [npmPrefix, outDir, workDir] = process.argv.slice(2);
if (!npmPrefix || !outDir || !workDir) {
  console.error("usage: node gen_fixtures.mjs <npm_prefix> <out_dir> <work_dir>");
  process.exit(2);
}
const require = createRequire(path.join(path.resolve(npmPrefix), "package.json"));
const { McapWriter } = require("@mcap/core");
const { MessageWriter } = require("@foxglove/rosmsg2-serialization");
const { parse } = require("@foxglove/rosmsg");
const lz4js = require("lz4js");
const { ZstdCodec } = require("zstd-codec");

const here = path.dirname(new URL(import.meta.url).pathname);
const MSG2 = path.join(here, "msg", "ros2");

// ---------------------------------------------------------------- stream and expected values
const stream = makeStream();

// Velodyne: make sure no expected time is near a rounding tie.
for (const p of stream[0].points) {
  const v = velodyneTimeF32(p) * 1e9;
  const frac = v - Math.floor(v);
  if (Math.abs(frac - 0.5) < 1e-3) throw new Error(`velodyne time of point ${p.i} is near a tie`);
}

const EXPECTED = {
  "custom.expected.csv": "custom",
  "pc2_livox.expected.csv": "livox",
  "pc2_offset_u32.expected.csv": "converter",
  "pc2_ouster.expected.csv": "ouster",
  "pc2_velodyne.expected.csv": "velodyne",
};
for (const [file, kind] of Object.entries(EXPECTED)) {
  fs.writeFileSync(path.join(outDir, file), expectedCsv(stream, kind));
}

// Second lidar for the two-topic bag (no expected file): only the first 12 points of each message,
// x mirrored, reflectivity 255 - r, stamps + 10 ms.
const rearStream = stream.map((m) => ({
  ...m,
  stamp_ns: m.stamp_ns + 10000000n,
  points: m.points.slice(0, 12).map((p) => ({ ...p, x: -p.x, refl: 255 - p.refl })),
}));

// IMU samples (readers must skip this topic): stamps 50 ms after lidar messages 0..2.
const imu = [0, 1, 2].map((k) => ({
  stamp_ns: stream[k].stamp_ns + 50000000n,
  orientation: { x: 0, y: 0, z: 0, w: 1 },
  angular_velocity: { x: 0.01 * (k + 1), y: -0.02, z: 0.03 },
  linear_acceleration: { x: 0.1, y: 0.0, z: 9.81 },
}));

// ---------------------------------------------------------------- CDR (ROS 2) messages
const FULL = {
  custom: ros2FullText(MSG2, "livox_ros_driver2/msg/CustomMsg"),
  pc2: ros2FullText(MSG2, "sensor_msgs/msg/PointCloud2"),
  imu: ros2FullText(MSG2, "sensor_msgs/msg/Imu"),
};
const TYPE = {
  custom: "livox_ros_driver2/msg/CustomMsg",
  pc2: "sensor_msgs/msg/PointCloud2",
  imu: "sensor_msgs/msg/Imu",
};
const WRITER = Object.fromEntries(Object.entries(FULL).map(([k, t]) => [k, new MessageWriter(parse(t, { ros2: true }))]));

const header = (ns, frame_id) => ({ stamp: stampSecNsec(ns), frame_id });

function cdrCustom(msg, frame_id) {
  return WRITER.custom.writeMessage({
    header: header(msg.stamp_ns, frame_id),
    timebase: msg.stamp_ns + 1000n,
    point_num: msg.points.length,
    lidar_id: 192,
    rsvd: new Uint8Array([0, 0, 0]),
    points: msg.points.map((p) => ({
      offset_time: Number(p.offset_ns), x: p.x, y: p.y, z: p.z,
      reflectivity: p.refl, tag: p.tag, line: p.line,
    })),
  });
}

function cdrPc2(layout, msg, frame_id, littleEndian = true) {
  const c = packCloud(layout, msg, littleEndian);
  return WRITER.pc2.writeMessage({ header: header(msg.stamp_ns, frame_id), ...c });
}

const ZERO9 = new Array(9).fill(0);
function cdrImu(s) {
  return WRITER.imu.writeMessage({
    header: header(s.stamp_ns, "livox_frame"),
    orientation: s.orientation, orientation_covariance: ZERO9,
    angular_velocity: s.angular_velocity, angular_velocity_covariance: ZERO9,
    linear_acceleration: s.linear_acceleration, linear_acceleration_covariance: ZERO9,
  });
}

// ---------------------------------------------------------------- compression
const zstd = await new Promise((resolve) => ZstdCodec.run((z) => resolve(new z.Simple())));
const COMPRESS = {
  none: undefined,
  lz4: (data) => ({ compression: "lz4", compressedData: Uint8Array.from(lz4js.compress(data)) }),
  zstd: (data) => ({ compression: "zstd", compressedData: Uint8Array.from(zstd.compress(data, 3)) }),
};

// ---------------------------------------------------------------- MCAP writer
class MemWritable {
  chunks = [];
  size = 0n;
  position() { return this.size; }
  async write(buf) { this.chunks.push(Uint8Array.from(buf)); this.size += BigInt(buf.byteLength); }
  bytes() { return Buffer.concat(this.chunks); }
}

// channels: [{topic, kind ('custom'|'pc2'|'imu'), noSchema?}]; messages: [{topic, time_ns, data}]
async function writeMcap(file, { chunked, compression = "none", chunkSize = 4096, summary = true, channels, messages, rosbag2Metadata }) {
  const w = new MemWritable();
  const writer = new McapWriter({
    writable: w,
    useChunks: chunked,
    chunkSize,
    compressChunk: COMPRESS[compression],
    useStatistics: summary,
    useSummaryOffsets: summary,
    repeatSchemas: summary,
    repeatChannels: summary,
    useAttachmentIndex: summary,
    useMetadataIndex: summary,
    useMessageIndex: chunked,
    useChunkIndex: summary && chunked,
  });
  await writer.start({ profile: "ros2", library: "mcap-typescript/2.2.2" });
  const schemaIds = {};
  const channelIds = {};
  for (const ch of channels) {
    let schemaId = 0;
    if (!ch.noSchema) {
      if (schemaIds[ch.kind] === undefined) {
        schemaIds[ch.kind] = await writer.registerSchema({
          name: TYPE[ch.kind], encoding: "ros2msg", data: new TextEncoder().encode(FULL[ch.kind]),
        });
      }
      schemaId = schemaIds[ch.kind];
    }
    channelIds[ch.topic] = await writer.registerChannel({
      schemaId, topic: ch.topic, messageEncoding: "cdr",
      // keys rosbag2's MCAP storage plugin writes
      metadata: new Map([["offered_qos_profiles", QOS_YAML], ["topic_type_hash", ""]]),
    });
  }
  if (rosbag2Metadata) {
    // rosbag2 stores its bag metadata in an MCAP Metadata record named "rosbag2"
    await writer.addMetadata({ name: "rosbag2", metadata: new Map([["serialized_metadata", rosbag2Metadata]]) });
  }
  const seq = {};
  const sorted = [...messages].sort((a, b) => (a.time_ns < b.time_ns ? -1 : a.time_ns > b.time_ns ? 1 : 0));
  for (const m of sorted) {
    seq[m.topic] = (seq[m.topic] ?? -1) + 1;
    await writer.addMessage({
      channelId: channelIds[m.topic], sequence: seq[m.topic],
      logTime: m.time_ns, publishTime: m.time_ns, data: m.data,
    });
  }
  await writer.end();
  fs.writeFileSync(path.join(outDir, file), w.bytes());
}

const imuMsgs = () => imu.map((s) => ({ topic: "/livox/imu", time_ns: s.stamp_ns, data: cdrImu(s) }));
const lidarMsgs = (fn) => stream.map((m) => ({ topic: "/livox/lidar", time_ns: m.stamp_ns, data: fn(m) }));
const LIDAR_IMU = (kind) => [{ topic: "/livox/lidar", kind }, { topic: "/livox/imu", kind: "imu" }];

// 6: CustomMsg, frame_id livox_frame, LZ4 chunks, full summary, plus a rosbag2-style Metadata record
await writeMcap("ros2_custom_lz4.mcap", {
  chunked: true, compression: "lz4", channels: LIDAR_IMU("custom"),
  messages: [...lidarMsgs((m) => cdrCustom(m, "livox_frame")), ...imuMsgs()],
  rosbag2Metadata: rosbag2MetadataBody({
    storage: "mcap", file: "ros2_custom_lz4.mcap", start_ns: stream[0].stamp_ns, end_ns: stream[N_MSGS - 1].stamp_ns,
    topics: [{ name: "/livox/lidar", type: TYPE.custom, count: N_MSGS }, { name: "/livox/imu", type: TYPE.imu, count: imu.length }],
  }),
});
// 7: CustomMsg, frame_id "lidar" (6 pad bytes before timebase), zstd chunks
await writeMcap("ros2_custom_zstd.mcap", {
  chunked: true, compression: "zstd", channels: LIDAR_IMU("custom"),
  messages: [...lidarMsgs((m) => cdrCustom(m, "lidar")), ...imuMsgs()],
});
// 8: converter layout, unchunked, no summary section (footer summary_start = 0)
await writeMcap("ros2_pc2_converter.mcap", {
  chunked: false, summary: false, channels: LIDAR_IMU("pc2"),
  messages: [...lidarMsgs((m) => cdrPc2("converter", m, "livox_frame")), ...imuMsgs()],
});
// 9: Ouster layout, organized 2 x 60, NaN points, uncompressed chunks
await writeMcap("ros2_pc2_ouster.mcap", {
  chunked: true, compression: "none", chunkSize: 8192, channels: LIDAR_IMU("pc2"),
  messages: [...lidarMsgs((m) => cdrPc2("ouster", m, "os_sensor")), ...imuMsgs()],
});
// 10: Velodyne layout, LZ4 chunks
await writeMcap("ros2_pc2_velodyne.mcap", {
  chunked: true, compression: "lz4", channels: LIDAR_IMU("pc2"),
  messages: [...lidarMsgs((m) => cdrPc2("velodyne", m, "velodyne")), ...imuMsgs()],
});
// 11: converter layout with big-endian point data (CDR encapsulation stays CDR_LE), zstd chunks
await writeMcap("ros2_pc2_bigendian.mcap", {
  chunked: true, compression: "zstd", channels: LIDAR_IMU("pc2"),
  messages: [...lidarMsgs((m) => cdrPc2("converter", m, "livox_frame", false)), ...imuMsgs()],
});
// 12: /livox/lidar channel with schema_id 0 (no schema) carrying CDR CustomMsg (messages 0 and 1
// only, to keep it small); uncompressed chunks, with summary
await writeMcap("ros2_no_schema.mcap", {
  chunked: true, compression: "none", summary: true,
  channels: [{ topic: "/livox/lidar", kind: "custom", noSchema: true }, { topic: "/livox/imu", kind: "imu" }],
  messages: [...lidarMsgs((m) => cdrCustom(m, "livox_frame")).slice(0, 2), ...imuMsgs().slice(0, 1)],
});

// ---------------------------------------------------------------- inputs for the Python writers
const b64 = (u8) => Buffer.from(u8).toString("base64");
const jsonStream = (s) => s.map((m) => ({
  k: m.k, stamp_ns: String(m.stamp_ns),
  points: m.points.map((p) => ({
    i: p.i, x: p.x, y: p.y, z: p.z, reflectivity: p.refl, tag: p.tag, line: p.line,
    offset_time: Number(p.offset_ns),
  })),
}));
const jsonClouds = (s, layout) => s.map((m) => {
  const c = packCloud(layout, m, true);
  return { stamp_ns: String(m.stamp_ns), ...c, data: b64(c.data) };
});
const jsonImu = imu.map((s) => ({ ...s, stamp_ns: String(s.stamp_ns) }));
fs.writeFileSync(path.join(workDir, "ros1_input.json"), JSON.stringify({
  stream: jsonStream(stream),
  clouds: { livox: jsonClouds(stream, "livox"), livox_rear: jsonClouds(rearStream, "livox") },
  imu: jsonImu,
}));

function db3Json(file, lidarKind, lidarData, bagFile) {
  const messages = [
    ...stream.map((m) => ({ topic: "/livox/lidar", timestamp: String(m.stamp_ns), data: b64(lidarData(m)) })),
    ...imu.map((s) => ({ topic: "/livox/imu", timestamp: String(s.stamp_ns), data: b64(cdrImu(s)) })),
  ].sort((a, b) => (BigInt(a.timestamp) < BigInt(b.timestamp) ? -1 : 1));
  fs.writeFileSync(path.join(workDir, file), JSON.stringify({
    topics: [
      { name: "/livox/lidar", type: TYPE[lidarKind], definition: FULL[lidarKind] },
      { name: "/livox/imu", type: TYPE.imu, definition: FULL.imu },
    ],
    qos: QOS_YAML,
    metadata_body: rosbag2MetadataBody({
      storage: "sqlite3", file: bagFile, start_ns: stream[0].stamp_ns, end_ns: stream[N_MSGS - 1].stamp_ns,
      topics: [{ name: "/livox/lidar", type: TYPE[lidarKind], count: N_MSGS }, { name: "/livox/imu", type: TYPE.imu, count: imu.length }],
    }),
    metadata_yaml: metadataYamlFile(rosbag2MetadataBody({
      storage: "sqlite3", file: bagFile, start_ns: stream[0].stamp_ns, end_ns: stream[N_MSGS - 1].stamp_ns,
      topics: [{ name: "/livox/lidar", type: TYPE[lidarKind], count: N_MSGS }, { name: "/livox/imu", type: TYPE.imu, count: imu.length }],
    })),
    messages,
  }));
}
// frame_id "mid360_front" (12 chars): the string ends at CDR offset 25, so 7 pad bytes precede the
// 8-aligned timebase and every point sits 8 bytes later than with "livox_frame" or "lidar".
db3Json("db3_custom.json", "custom", (m) => cdrCustom(m, "mid360_front"), "ros2_custom_db3_0.db3");
db3Json("db3_pc2_old.json", "pc2", (m) => cdrPc2("livox", m, "livox_frame"), "ros2_pc2_old.db3");

console.log(`gen_fixtures.mjs: wrote ${Object.keys(EXPECTED).length} expected files, 7 MCAP files, Python inputs (${N_MSGS} lidar messages each)`);
