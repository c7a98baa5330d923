// SPDX-License-Identifier: MIT
// write_mcap.mjs -- write an MCAP (ROS 2 profile) from the CDR payloads csv_to_recordings.py framed,
// with @mcap/core's McapWriter, streaming, in bounded memory.
//
//   node write_mcap.mjs <npm_prefix> <STEM.mcap_input.json> <STEM.mcap_input.bin> <out.mcap> [zstd|lz4]
//
// <npm_prefix>: a folder where `npm install @mcap/core@2.2.2 zstd-codec@0.1.5 lz4js@0.2.0` was run
// (make_long_recordings.sh installs them into a temporary folder, never into the repository).
// Input: [u64 log_time_ns][u32 size][payload] records (CDR livox_ros_driver2/msg/CustomMsg).
// Output: one schema (ros2msg), one channel (cdr, rosbag2's channel metadata keys), the messages
// (log_time = publish_time = timebase), chunks of McapWriter's default 1 MiB compressed with zstd
// (level 3, zstd-codec) or lz4 (LZ4 frame, lz4js), message indexes, a full summary and a
// rosbag2-style "rosbag2" Metadata record.  The file is written as it goes (positioned writes).
import fs from "node:fs";
import path from "node:path";
import { createRequire } from "node:module";

const [npmPrefix, jsonPath, binPath, outPath, codec = "zstd"] = process.argv.slice(2);
if (!npmPrefix || !jsonPath || !binPath || !outPath || !["zstd", "lz4"].includes(codec)) {
  console.error("usage: node write_mcap.mjs <npm_prefix> <input.json> <input.bin> <out.mcap> [zstd|lz4]");
  process.exit(2);
}
const require = createRequire(path.join(path.resolve(npmPrefix), "package.json"));
const { McapWriter } = require("@mcap/core");

let compressChunk;
if (codec === "zstd") {
  const { ZstdCodec } = require("zstd-codec");
  const zstd = await new Promise((resolve) => ZstdCodec.run((z) => resolve(new z.Simple())));
  compressChunk = (data) => ({ compression: "zstd", compressedData: Uint8Array.from(zstd.compress(data, 3)) });
} else {
  const lz4js = require("lz4js");
  compressChunk = (data) => ({ compression: "lz4", compressedData: Uint8Array.from(lz4js.compress(data)) });
}

// IWritable over a file descriptor: bytes go to the file at once, nothing is kept.
class FileWritable {
  constructor(file) { this.fd = fs.openSync(file, "w"); this.size = 0n; }
  position() { return this.size; }
  async write(buf) {
    let done = 0;
    while (done < buf.byteLength) done += fs.writeSync(this.fd, buf, done, buf.byteLength - done);
    this.size += BigInt(buf.byteLength);
  }
  close() { fs.closeSync(this.fd); }
}

const meta = JSON.parse(fs.readFileSync(jsonPath, "utf8"));
const out = new FileWritable(outPath);
const writer = new McapWriter({ writable: out, compressChunk });
await writer.start({ profile: "ros2", library: "mcap-typescript/2.2.2 (streamclust bench)" });
const schemaId = await writer.registerSchema({
  name: meta.schema_name, encoding: "ros2msg", data: new TextEncoder().encode(meta.schema_text),
});
const channelId = await writer.registerChannel({
  schemaId, topic: meta.topic, messageEncoding: "cdr",
  metadata: new Map([["offered_qos_profiles", meta.qos], ["topic_type_hash", ""]]),
});

// Read the framed payloads one at a time.
const fd = fs.openSync(binPath, "r");
const head = Buffer.alloc(12);
let pos = 0;
let sequence = 0;
const readFully = (buf, len) => {
  let got = 0;
  while (got < len) {
    const n = fs.readSync(fd, buf, got, len - got, pos + got);
    if (n === 0) break;
    got += n;
  }
  return got;
};
for (;;) {
  const n = readFully(head, 12);
  if (n === 0) break;
  if (n !== 12) throw new Error(`${binPath}: truncated record header at ${pos}`);
  const time = head.readBigUInt64LE(0);
  const size = head.readUInt32LE(8);
  pos += 12;
  const data = Buffer.alloc(size);
  if (readFully(data, size) !== size) throw new Error(`${binPath}: truncated payload at ${pos}`);
  pos += size;
  await writer.addMessage({ channelId, sequence: sequence++, logTime: time, publishTime: time, data });
}
fs.closeSync(fd);
if (sequence !== meta.message_count) throw new Error(`read ${sequence} messages, expected ${meta.message_count}`);
await writer.addMetadata({ name: "rosbag2", metadata: new Map([["serialized_metadata", meta.rosbag2_metadata]]) });
await writer.end();
out.close();
console.log(`write_mcap.mjs: ${sequence} messages -> ${outPath} (${codec} chunks)`);
