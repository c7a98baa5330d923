// SPDX-License-Identifier: MIT
// check_mcap.mjs -- reads an MCAP file with the reference implementation
// (@mcap/core: the stream reader with every CRC validated, and the indexed
// reader through the summary's chunk indexes), decodes every message from its
// schema's ros2msg text (@foxglove/rosmsg + @foxglove/rosmsg2-serialization)
// and prints what it found as JSON:
//   {"profile", "messages", "indexed", "topics": {topic: {"schema", "messages", "entities": [per
//    SceneUpdate], "arrows": arrows in all, "cubes_turned": cubes with a turn about z}},
//    "points": [points per PointCloud message], "entities": [entities per SceneUpdate],
//    "first_log_time", "last_log_time"}
// Usage: node check_mcap.mjs NPM_PREFIX FILE   (NPM_PREFIX holds node_modules with
// @mcap/core, @mcap/support, @foxglove/rosmsg, @foxglove/rosmsg2-serialization).
// Exits 1 on any error the readers raise.

import fs from "node:fs";
import path from "node:path";
import { createRequire } from "node:module";

const [prefix, file] = process.argv.slice(2);
const require = createRequire(path.join(path.resolve(prefix), "package.json"));
const { McapStreamReader, McapIndexedReader } = require("@mcap/core");
const { loadDecompressHandlers } = require("@mcap/support");
const { MessageReader } = require("@foxglove/rosmsg2-serialization");
const { parse } = require("@foxglove/rosmsg");

const bytes = fs.readFileSync(file);
const decompressHandlers = await loadDecompressHandlers();
const out = { profile: "", messages: 0, indexed: 0, topics: {}, points: [], entities: [] };
const schemas = new Map();
const channels = new Map();
const readers = new Map();
const stream = new McapStreamReader({ decompressHandlers, validateCrcs: true });
stream.append(bytes);
for (let r; (r = stream.nextRecord()); ) {
  if (r.type === "Header") out.profile = r.profile;
  if (r.type === "Schema") schemas.set(r.id, r);
  if (r.type === "Channel" && !channels.has(r.id)) {
    channels.set(r.id, r);
    const s = schemas.get(r.schemaId);
    readers.set(r.id, new MessageReader(parse(new TextDecoder().decode(s.data), { ros2: true })));
    out.topics[r.topic] ??= { schema: s.name, messages: 0, entities: [], arrows: 0, cubes_turned: 0 };  // the summary repeats the channels
  }
  if (r.type === "Message") {
    const channel = channels.get(r.channelId);
    const message = readers.get(r.channelId).readMessage(r.data);
    out.topics[channel.topic].messages += 1;
    out.messages += 1;
    if (out.first_log_time === undefined) out.first_log_time = r.logTime.toString();
    out.last_log_time = r.logTime.toString();
    if (message.point_stride !== undefined) out.points.push(message.data.length / message.point_stride);
    if (message.entities !== undefined) {
      const t = out.topics[channel.topic];
      t.entities.push(message.entities.length);
      for (const e of message.entities) {
        t.arrows += e.arrows.length;
        t.cubes_turned += e.cubes.filter((c) => Math.abs(c.pose.orientation.z) > 1e-9).length;
      }
      if (channel.topic === "/streamclust/clusters") out.entities.push(message.entities.length);
    }
  }
}
if (!stream.done()) throw new Error("the stream reader did not reach the end of the file");
const indexed = await McapIndexedReader.Initialize({
  readable: { size: async () => BigInt(bytes.length), read: async (o, n) => bytes.subarray(Number(o), Number(o + n)) },
  decompressHandlers,
});
for await (const m of indexed.readMessages()) out.indexed += m ? 1 : 0;
console.log(JSON.stringify(out));
