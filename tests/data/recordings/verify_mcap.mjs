// SPDX-License-Identifier: MIT
// verify_mcap.mjs -- check the MCAP fixtures (and the db3 CDR blobs) with the MCAP reference
// readers and the ROS 2 CDR deserializer.
//
// Usage: node verify_mcap.mjs <npm_prefix> [db3_dump.json]      (exit status 1 on any mismatch)
//   <npm_prefix>    directory with @mcap/core, @mcap/support, @foxglove/rosmsg2-serialization,
//                   @foxglove/rosmsg installed (verify_fixtures.sh does that)
//   db3_dump.json   written by verify_db3.py: CDR blobs of the db3 fixtures to decode as well
//
// For every MCAP file: McapStreamReader reads the whole file (validateCrcs on; chunks decompressed
// by @mcap/support's WebAssembly builds of liblz4 / libzstd, not by the compressors that wrote
// them); files with a summary are also opened with McapIndexedReader and read through the chunk
// indexes.  Messages are decoded with MessageReader built from the schema's own definition text,
// points are extracted with the PointField decoder below, and compared with the expected CSV.

import fs from "node:fs";
import path from "node:path";
import { createRequire } from "node:module";

const [npmPrefix, db3Dump] = process.argv.slice(2);
const require = createRequire(path.join(path.resolve(npmPrefix), "package.json"));
const { McapStreamReader, McapIndexedReader } = require("@mcap/core");
const { loadDecompressHandlers } = require("@mcap/support");
const { MessageReader } = require("@foxglove/rosmsg2-serialization");
const { parse } = require("@foxglove/rosmsg");

const here = path.dirname(new URL(import.meta.url).pathname);
const decompressHandlers = await loadDecompressHandlers();

class Mismatch extends Error {}

function loadExpected(file) {
  const lines = fs.readFileSync(path.join(here, file), "utf8").trim().split("\n");
  if (lines[0] !== "x,y,z,intensity,t") throw new Mismatch(`${file}: bad header`);
  return lines.slice(1).map((l) => {
    const [x, y, z, i, t] = l.split(",");
    const c = (s) => (s === "nan" ? NaN : Math.fround(Number(s)));
    return [c(x), c(y), c(z), Number(i), BigInt(t)];
  });
}

function compare(label, got, exp) {
  if (got.length !== exp.length) throw new Mismatch(`${label}: ${got.length} points, expected ${exp.length}`);
  got.forEach((g, n) => {
    const e = exp[n];
    for (let a = 0; a < 3; a++) {
      if (!(Object.is(g[a], e[a]) || (Number.isNaN(g[a]) && Number.isNaN(e[a])))) {
        throw new Mismatch(`${label}: point ${n} coord ${a}: ${g[a]} != ${e[a]}`);
      }
    }
    if (g[3] !== e[3]) throw new Mismatch(`${label}: point ${n} intensity ${g[3]} != ${e[3]}`);
    if (g[4] !== e[4]) throw new Mismatch(`${label}: point ${n} t ${g[4]} != ${e[4]}`);
  });
}

const stampNs = (h) => BigInt(h.stamp.sec) * 1000000000n + BigInt(h.stamp.nanosec);

// PointField decoder (datatypes 1..8), honouring is_bigendian and unaligned offsets.
function cloudPoints(m) {
  const le = !m.is_bigendian;
  const dv = new DataView(m.data.buffer, m.data.byteOffset, m.data.byteLength);
  const f = Object.fromEntries(m.fields.map((x) => [x.name, x]));
  const get = (o, name) => {
    const { offset, datatype } = f[name];
    const p = o + offset;
    switch (datatype) {
      case 1: return dv.getInt8(p);
      case 2: return dv.getUint8(p);
      case 3: return dv.getInt16(p, le);
      case 4: return dv.getUint16(p, le);
      case 5: return dv.getInt32(p, le);
      case 6: return dv.getUint32(p, le);
      case 7: return dv.getFloat32(p, le);
      case 8: return dv.getFloat64(p, le);
      default: throw new Mismatch(`datatype ${datatype}`);
    }
  };
  if (m.data.byteLength !== m.row_step * m.height || m.row_step !== m.point_step * m.width) {
    throw new Mismatch("cloud size fields");
  }
  const stamp = stampNs(m.header);
  const out = [];
  for (let r = 0; r < m.height; r++) {
    for (let c = 0; c < m.width; c++) {
      const o = r * m.row_step + c * m.point_step;
      let t;
      if (f.timestamp) t = BigInt(get(o, "timestamp")); // absolute ns as float64 (exact integers)
      else if (f.t) t = stamp + BigInt(get(o, "t"));
      else if (f.time) t = stamp + BigInt(Math.round(get(o, "time") * 1e9));
      else throw new Mismatch("no time field");
      out.push([get(o, "x"), get(o, "y"), get(o, "z"), get(o, "intensity"), t]);
    }
  }
  return out;
}

function customPoints(m) {
  if (m.point_num !== m.points.length) throw new Mismatch("point_num");
  return m.points.map((p) => [p.x, p.y, p.z, p.reflectivity, m.timebase + BigInt(p.offset_time)]);
}

const pointsOf = (type, m) => (type.endsWith("CustomMsg") ? customPoints(m) : cloudPoints(m));

const FIXTURES = {
  // file: [lidar type, expected CSV (null: no schema, decoding must be impossible), chunk compression or null]
  "ros2_custom_lz4.mcap": ["livox_ros_driver2/msg/CustomMsg", "custom.expected.csv", "lz4"],
  "ros2_custom_zstd.mcap": ["livox_ros_driver2/msg/CustomMsg", "custom.expected.csv", "zstd"],
  "ros2_pc2_converter.mcap": ["sensor_msgs/msg/PointCloud2", "pc2_offset_u32.expected.csv", null],
  "ros2_pc2_ouster.mcap": ["sensor_msgs/msg/PointCloud2", "pc2_ouster.expected.csv", ""],
  "ros2_pc2_velodyne.mcap": ["sensor_msgs/msg/PointCloud2", "pc2_velodyne.expected.csv", "lz4"],
  "ros2_pc2_bigendian.mcap": ["sensor_msgs/msg/PointCloud2", "pc2_offset_u32.expected.csv", "zstd"],
  "ros2_no_schema.mcap": [null, null, ""],
};

async function checkMcap(file, [lidarType, csv, compression]) {
  const bytes = new Uint8Array(fs.readFileSync(path.join(here, file)));
  const reader = new McapStreamReader({ decompressHandlers, validateCrcs: true });
  reader.append(bytes);
  const schemas = new Map(), channels = new Map(), msgs = [];
  let header, footer, nChunks = 0;
  const chunkCompressions = new Set();
  for (let rec; (rec = reader.nextRecord()); ) {
    if (rec.type === "Header") header = rec;
    else if (rec.type === "Schema") schemas.set(rec.id, rec);
    else if (rec.type === "Channel") channels.set(rec.id, rec);
    else if (rec.type === "Message") msgs.push(rec);
    else if (rec.type === "Footer") footer = rec;
  }
  if (!reader.done()) throw new Mismatch("stream reader not done");
  if (header.profile !== "ros2") throw new Mismatch(`profile ${header.profile}`);
  const lidar = [...channels.values()].find((c) => c.topic === "/livox/lidar");
  if (!lidar || lidar.messageEncoding !== "cdr") throw new Mismatch("no cdr /livox/lidar channel");
  const facts = [];
  if (csv === null) {
    if (lidar.schemaId !== 0) throw new Mismatch("schemaId should be 0");
    facts.push("lidar channel schemaId 0 (no definition: decoding impossible)");
  } else {
    const schema = schemas.get(lidar.schemaId);
    if (schema.name !== lidarType || schema.encoding !== "ros2msg") throw new Mismatch(`schema ${schema.name}/${schema.encoding}`);
    const mr = new MessageReader(parse(new TextDecoder().decode(schema.data), { ros2: true }));
    const pts = [];
    for (const m of msgs.filter((x) => x.channelId === lidar.id)) {
      const dec = mr.readMessage(m.data);
      if (mr.lastReadHadTrailingBytes()) throw new Mismatch("trailing bytes after message");
      if (stampNs(dec.header) !== m.logTime) throw new Mismatch("logTime != header stamp");
      pts.push(...pointsOf(lidarType, dec));
    }
    compare(file, pts, loadExpected(csv));
    // imu channel present and decodable
    const imuCh = [...channels.values()].find((c) => c.topic === "/livox/imu");
    const imuReader = new MessageReader(parse(new TextDecoder().decode(schemas.get(imuCh.schemaId).data), { ros2: true }));
    for (const m of msgs.filter((x) => x.channelId === imuCh.id)) imuReader.readMessage(m.data);
  }
  if (footer.summaryStart !== 0n) {
    // indexed reader: summary, chunk indexes, statistics
    const readable = {
      size: async () => BigInt(bytes.byteLength),
      read: async (off, len) => bytes.subarray(Number(off), Number(off + len)),
    };
    const ir = await McapIndexedReader.Initialize({ readable, decompressHandlers });
    nChunks = ir.chunkIndexes.length;
    for (const ci of ir.chunkIndexes) chunkCompressions.add(ci.compression);
    let n = 0;
    for await (const m of ir.readMessages()) n++;
    if (nChunks > 0 && n !== msgs.length) throw new Mismatch(`indexed reader: ${n} messages, stream reader ${msgs.length}`);
    if (ir.statistics && ir.statistics.messageCount !== BigInt(msgs.length)) throw new Mismatch("statistics.messageCount");
    facts.push(`indexed reader ok (${n} messages, statistics ${ir.statistics ? "yes" : "no"}, ${ir.metadataIndexes.length} metadata)`);
  } else {
    facts.push("no summary");
  }
  if (compression === null) {
    if (nChunks !== 0) throw new Mismatch("expected no chunks");
  } else if (nChunks < 2 || chunkCompressions.size !== 1 || !chunkCompressions.has(compression)) {
    throw new Mismatch(`chunks: ${nChunks} ${[...chunkCompressions]}`);
  } else {
    facts.push(`${nChunks} chunks, compression "${compression}"`);
  }
  return facts.join("; ");
}

let ok = true;
for (const [file, spec] of Object.entries(FIXTURES)) {
  try {
    console.log(`ok   ${file}: ${await checkMcap(file, spec)}`);
  } catch (e) {
    ok = false;
    console.log(`FAIL ${file}: ${e.message}`);
  }
}

if (db3Dump) {
  for (const entry of JSON.parse(fs.readFileSync(db3Dump, "utf8"))) {
    try {
      // old-layout bags carry no definition: use the one from an MCAP fixture of the same type
      let def = entry.definition;
      if (!def) {
        const src = entry.type.endsWith("PointCloud2") ? "ros2_pc2_converter.mcap" : "ros2_custom_lz4.mcap";
        const r = new McapStreamReader({ decompressHandlers });
        r.append(new Uint8Array(fs.readFileSync(path.join(here, src))));
        for (let rec; (rec = r.nextRecord()); ) {
          if (rec.type === "Schema" && rec.name === entry.type) def = new TextDecoder().decode(rec.data);
        }
      }
      const mr = new MessageReader(parse(def, { ros2: true }));
      const pts = [];
      for (const b64 of entry.messages) {
        const dec = mr.readMessage(Buffer.from(b64, "base64"));
        if (mr.lastReadHadTrailingBytes()) throw new Mismatch("trailing bytes");
        pts.push(...pointsOf(entry.type, dec));
      }
      compare(entry.file, pts, loadExpected(entry.expected));
      console.log(`ok   ${entry.file}: ${entry.messages.length} CDR blobs decoded by MessageReader match ${entry.expected}`);
    } catch (e) {
      ok = false;
      console.log(`FAIL ${entry.file}: ${e.message}`);
    }
  }
}
process.exit(ok ? 0 : 1);
