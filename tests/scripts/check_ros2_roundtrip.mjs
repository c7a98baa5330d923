// SPDX-License-Identifier: MIT
// check_ros2_roundtrip.mjs -- checks the CDR bytes of every message of an MCAP
// file against the reference ROS 2 serializer: each message is read with
// @mcap/core (every CRC validated), decoded with
// @foxglove/rosmsg2-serialization's MessageReader from its schema's ros2msg
// text (parsed by @foxglove/rosmsg with ros2: true), re-encoded with that
// package's MessageWriter, and the result must equal the message's bytes.
// Prints {"topics": {topic: {"schema", "messages"}}, "messages", "tracked"} as
// JSON; "tracked" maps the log time [ns] of each /streamclust/tracked_objects
// message to its detections as [id, x, y, z, class_id, score].
// Usage: node check_ros2_roundtrip.mjs NPM_PREFIX FILE   (NPM_PREFIX holds
// node_modules with @mcap/core, @mcap/support, @foxglove/rosmsg and
// @foxglove/rosmsg2-serialization).
// Exits 1 naming topic, message index (from 0 per topic) and the first
// differing byte for each message that does not round-trip (or that the
// reader refuses), 2 on bad usage.

import fs from "node:fs";
import path from "node:path";
import { createRequire } from "node:module";

const [prefix, file] = process.argv.slice(2);
if (prefix === undefined || file === undefined) {
  console.error("usage: node check_ros2_roundtrip.mjs NPM_PREFIX FILE.mcap");
  process.exit(2);
}
const require = createRequire(path.join(path.resolve(prefix), "package.json"));
const { McapStreamReader } = require("@mcap/core");
const { loadDecompressHandlers } = require("@mcap/support");
const { MessageReader, MessageWriter } = require("@foxglove/rosmsg2-serialization");
const { parse } = require("@foxglove/rosmsg");

const hex = (b) => (b === undefined ? "end" : "0x" + b.toString(16).padStart(2, "0"));

/// Index of the first byte where `a` and `b` differ, or -1 when they are equal.
function firstDifference(a, b) {
  const n = Math.min(a.length, b.length);
  for (let i = 0; i < n; i++) if (a[i] !== b[i]) return i;
  return a.length === b.length ? -1 : n;
}

const bytes = fs.readFileSync(file);
const out = { topics: {}, messages: 0, tracked: {} };
const failures = [];
const schemas = new Map();
const channels = new Map();  // id -> { topic, reader, writer, count }
const stream = new McapStreamReader({ decompressHandlers: await loadDecompressHandlers(), validateCrcs: true });
stream.append(bytes);
for (let r; (r = stream.nextRecord()); ) {
  if (r.type === "Schema") schemas.set(r.id, r);
  if (r.type === "Channel" && !channels.has(r.id)) {  // the summary repeats the channels
    const s = schemas.get(r.schemaId);
    if (s === undefined) throw new Error(`channel ${r.topic}: schema ${r.schemaId} is not defined before it`);
    if (s.encoding !== "ros2msg" || r.messageEncoding !== "cdr") {
      throw new Error(`channel ${r.topic}: schema encoding ${s.encoding}, message encoding ${r.messageEncoding};` +
                      ` expected ros2msg and cdr`);
    }
    const definitions = parse(new TextDecoder().decode(s.data), { ros2: true });
    channels.set(r.id, {
      topic: r.topic, reader: new MessageReader(definitions), writer: new MessageWriter(definitions), count: 0,
    });
    out.topics[r.topic] ??= { schema: s.name, messages: 0 };
  }
  if (r.type === "Message") {
    const c = channels.get(r.channelId);
    if (c === undefined) throw new Error(`message on channel ${r.channelId}, which is not defined before it`);
    const index = c.count++;
    out.topics[c.topic].messages += 1;
    out.messages += 1;
    let again;
    try {
      const message = c.reader.readMessage(r.data);
      if (c.topic === "/streamclust/tracked_objects") {
        out.tracked[r.logTime.toString()] = message.detections.map((d) => {
          const p = d.bbox.center.position;
          return [d.id, p.x, p.y, p.z, d.results[0].hypothesis.class_id, d.results[0].hypothesis.score];
        });
      }
      again = c.writer.writeMessage(message);
    } catch (e) {
      failures.push(`${c.topic} message ${index}: ${e.message}`);
      continue;
    }
    const at = firstDifference(r.data, again);
    if (at >= 0) {
      failures.push(`${c.topic} message ${index}: first difference at byte ${at} of ${r.data.length}` +
                    ` (file ${hex(r.data[at])}, re-encoded ${hex(again[at])}; re-encoded length ${again.length})`);
    }
  }
}
if (!stream.done()) throw new Error("the stream reader did not reach the end of the file");
console.log(JSON.stringify(out));
if (failures.length > 0) {
  for (const f of failures.slice(0, 20)) console.error(f);
  if (failures.length > 20) console.error(`... and ${failures.length - 20} more`);
  console.error(`${failures.length} of ${out.messages} messages do not round-trip byte for byte`);
  process.exit(1);
}
