// SPDX-License-Identifier: MIT
// lib_stream.mjs -- the ONE definition of the point stream stored in every recording fixture,
// of the PointCloud2 point layouts, of the expected-values CSV format, and of the ROS 2
// message-definition text (built the way rosbag2 builds it).  Imported by gen_fixtures.mjs
// (writer) and verify_mcap.mjs (reader).  No npm package is needed here.
//
// Stream: 4 messages k = 0..3, 120 points i = 0..119 each.
//   header stamp  stamp_ns(k) = 1700000000 s + k * 100 ms
//   i % 3 == 0 -> cluster A around (5, 0, 0)
//   i % 3 == 1 -> cluster B around (0, 8, 1)
//   i % 3 == 2 -> isolated point on a circle of radius 20 m, z = 2 (about 3 m from its neighbours)
//   cluster offsets: +-0.2 m per axis from the LCG below (no Math.random)
//   every coordinate is first rounded to whole millimetres (short CSV text, and the trigonometry
//   of the circle cannot leak into the files), then to float32 (Math.fround) before anything is
//   written
//   reflectivity = (7*i + k) % 256, tag = 16, line = i % 4, offset_ns = i * 800000

import fs from "node:fs";
import path from "node:path";

export const N_MSGS = 4;
export const N_POINTS = 120;
export const STAMP0_NS = 1700000000000000000n;
export const PERIOD_NS = 100000000n; // 100 ms
export const POINT_DT_NS = 800000n; // 0.8 ms between points
export const CUSTOM_TIMEBASE_OFFSET_NS = 1000n; // CustomMsg: timebase = stamp + 1000 ns

export const stampNs = (k) => STAMP0_NS + BigInt(k) * PERIOD_NS;
export const stampSecNsec = (ns) => ({ sec: Number(ns / 1000000000n), nanosec: Number(ns % 1000000000n) });

// 32-bit LCG (Numerical Recipes constants), seed 12345.  Returns a float in (-0.2, 0.2).
export function makeLcg(seed = 12345) {
  let s = seed >>> 0;
  return () => {
    s = (Math.imul(s, 1664525) + 1013904223) >>> 0;
    return ((s >>> 8) / 16777216 - 0.5) * 0.4; // top 24 bits -> [0,1) -> [-0.2, 0.2)
  };
}

// The stream: array of N_MSGS messages {k, stamp_ns, points:[{i,x,y,z,refl,tag,line,offset_ns}]}.
export function makeStream() {
  const rnd = makeLcg(12345);
  const msgs = [];
  for (let k = 0; k < N_MSGS; k++) {
    const points = [];
    for (let i = 0; i < N_POINTS; i++) {
      let x, y, z;
      if (i % 3 === 0) {
        x = 5 + rnd(); y = 0 + rnd(); z = 0 + rnd();
      } else if (i % 3 === 1) {
        x = 0 + rnd(); y = 8 + rnd(); z = 1 + rnd();
      } else {
        const a = (2 * Math.PI * ((i - 2) / 3 + 0.25 * k)) / 40;
        x = 20 * Math.cos(a); y = 20 * Math.sin(a); z = 2;
      }
      const mm = (v) => Math.fround(Math.round(v * 1000) / 1000) + 0; // "+ 0": no negative zero
      points.push({
        i,
        x: mm(x), y: mm(y), z: mm(z),
        refl: (7 * i + k) % 256, tag: 16, line: i % 4,
        offset_ns: BigInt(i) * POINT_DT_NS,
      });
    }
    msgs.push({ k, stamp_ns: stampNs(k), points });
  }
  return msgs;
}

// ---------------------------------------------------------------------------------------------
// PointCloud2 layouts.  Each layout: fields (PointField name/offset/datatype/count), point_step,
// height/width, is_dense, pack(dv, off, p, msg, littleEndian) writing one point record, and
// expectedT(p, msg) -> BigInt absolute time in ns (what a reader must report).
// PointField datatypes: INT8=1 UINT8=2 INT16=3 UINT16=4 INT32=5 UINT32=6 FLOAT32=7 FLOAT64=8
export const DT = { INT8: 1, UINT8: 2, INT16: 3, UINT16: 4, INT32: 5, UINT32: 6, FLOAT32: 7, FLOAT64: 8 };
const F = (name, offset, datatype) => ({ name, offset, datatype, count: 1 });

// livox_ros_driver2 PointXYZRTLT: timestamp = absolute ns as float64.  stamp_ns ~ 1.7e18 lies in
// [2^60, 2^61) where doubles are spaced 256 ns apart, so the per-point time is rounded (half up)
// to a multiple of 256 ns; the double then holds that integer exactly.
export const livoxTimeNs = (p, msg) => ((msg.stamp_ns + p.offset_ns + 128n) / 256n) * 256n;

// Ouster: 5 points per message are invalid (NaN x,y,z): i = 5 + 24*j + 3*k, j = 0..4
// (all isolated points, i % 3 == 2).
export function ousterIsNan(p, msg) {
  const r = p.i - 5 - 3 * msg.k;
  return r >= 0 && r % 24 === 0 && r / 24 < 5;
}

// Velodyne: time = float32(i * 0.0008) seconds relative to the stamp;
// expected t = stamp + Math.round(double(time) * 1e9) (round half up; no value is near a tie,
// checked in gen_fixtures.mjs).
export const velodyneTimeF32 = (p) => Math.fround(p.i * 0.0008);
export const velodyneTimeNs = (p, msg) => msg.stamp_ns + BigInt(Math.round(velodyneTimeF32(p) * 1e9));

export const LAYOUTS = {
  // livox_ros_driver2 xfer_format 0 (formats.md 1.3)
  livox: {
    fields: [F("x", 0, 7), F("y", 4, 7), F("z", 8, 7), F("intensity", 12, 7), F("tag", 16, 2), F("line", 17, 2), F("timestamp", 18, 8)],
    point_step: 26, height: 1, is_dense: true,
    pack(dv, o, p, msg, le) {
      dv.setFloat32(o, p.x, le); dv.setFloat32(o + 4, p.y, le); dv.setFloat32(o + 8, p.z, le);
      dv.setFloat32(o + 12, p.refl, le); dv.setUint8(o + 16, p.tag); dv.setUint8(o + 17, p.line);
      dv.setFloat64(o + 18, Number(livoxTimeNs(p, msg)), le);
    },
    expectedT: livoxTimeNs,
    nan: () => false,
  },
  // koide3/livox_to_pointcloud2 converter layout (formats.md 2.7): t = u32 ns relative to stamp
  converter: {
    fields: [F("x", 0, 7), F("y", 4, 7), F("z", 8, 7), F("t", 12, 6), F("intensity", 16, 7), F("tag", 20, 2), F("line", 21, 2)],
    point_step: 22, height: 1, is_dense: true,
    pack(dv, o, p, msg, le) {
      dv.setFloat32(o, p.x, le); dv.setFloat32(o + 4, p.y, le); dv.setFloat32(o + 8, p.z, le);
      dv.setUint32(o + 12, Number(p.offset_ns), le); dv.setFloat32(o + 16, p.refl, le);
      dv.setUint8(o + 20, p.tag); dv.setUint8(o + 21, p.line);
    },
    expectedT: (p, msg) => msg.stamp_ns + p.offset_ns,
    nan: () => false,
  },
  // Ouster (ouster_ros PointOS0-style): organized 2 x 60, 48-byte records with padding
  ouster: {
    fields: [F("x", 0, 7), F("y", 4, 7), F("z", 8, 7), F("intensity", 16, 7), F("t", 20, 6), F("reflectivity", 24, 4), F("ring", 26, 4), F("ambient", 28, 4), F("range", 32, 6)],
    point_step: 48, height: 2, is_dense: false,
    pack(dv, o, p, msg, le) {
      const nan = ousterIsNan(p, msg);
      const x = nan ? NaN : p.x, y = nan ? NaN : p.y, z = nan ? NaN : p.z;
      dv.setFloat32(o, x, le); dv.setFloat32(o + 4, y, le); dv.setFloat32(o + 8, z, le);
      // bytes 12..15 and 36..47: padding, left zero
      dv.setFloat32(o + 16, p.refl, le); dv.setUint32(o + 20, Number(p.offset_ns), le);
      dv.setUint16(o + 24, p.refl, le); dv.setUint16(o + 26, p.line, le);
      dv.setUint16(o + 28, (3 * p.i) % 1000, le);
      dv.setUint32(o + 32, nan ? 0 : Math.round(1000 * Math.sqrt(p.x * p.x + p.y * p.y + p.z * p.z)), le);
    },
    expectedT: (p, msg) => msg.stamp_ns + p.offset_ns,
    nan: ousterIsNan,
  },
  // Velodyne (velodyne_pointcloud PointXYZIRT-style, packed): time = float32 seconds rel. to stamp
  velodyne: {
    fields: [F("x", 0, 7), F("y", 4, 7), F("z", 8, 7), F("intensity", 12, 7), F("ring", 16, 4), F("time", 18, 7)],
    point_step: 22, height: 1, is_dense: true,
    pack(dv, o, p, msg, le) {
      dv.setFloat32(o, p.x, le); dv.setFloat32(o + 4, p.y, le); dv.setFloat32(o + 8, p.z, le);
      dv.setFloat32(o + 12, p.refl, le); dv.setUint16(o + 16, p.line, le);
      dv.setFloat32(o + 18, velodyneTimeF32(p), le);
    },
    expectedT: velodyneTimeNs,
    nan: () => false,
  },
};

// Point-data bytes of one message in a layout.  littleEndian=false writes every multi-byte field
// big-endian (for is_bigendian = true clouds).
export function packCloud(layoutName, msg, littleEndian = true) {
  const L = LAYOUTS[layoutName];
  const n = msg.points.length;
  const buf = new Uint8Array(n * L.point_step);
  const dv = new DataView(buf.buffer);
  msg.points.forEach((p, idx) => L.pack(dv, idx * L.point_step, p, msg, littleEndian));
  const height = L.height;
  const width = n / height;
  return {
    height, width, fields: L.fields, is_bigendian: !littleEndian, point_step: L.point_step,
    row_step: width * L.point_step, data: buf, is_dense: L.is_dense,
  };
}

// ---------------------------------------------------------------------------------------------
// Expected CSV: header x,y,z,intensity,t; one row per point, message order then point order.
// Coordinates: shortest decimal (<= 9 significant digits) that parses back to the same float32
// both with strtof and with strtod followed by a cast to float (the decimal must lie strictly
// inside the float's rounding interval by more than a double's rounding error).
export function f32str(v) {
  if (Number.isNaN(v)) return "nan";
  if (v === 0) return Object.is(v, -0) ? "-0" : "0";
  const a = Math.abs(v);
  const e = Math.floor(Math.log2(a));
  const ulp = Math.pow(2, Math.max(e, -126) - 23);
  for (let prec = 1; prec <= 9; prec++) {
    const s = v.toPrecision(prec);
    const d = Number(s);
    if (Math.fround(d) === v && Math.abs(d - v) < ulp * (0.5 - 2 ** -28)) return String(d);
  }
  return v.toPrecision(9);
}

export function expectedCsv(stream, kind) {
  const rows = ["x,y,z,intensity,t"];
  for (const msg of stream) {
    for (const p of msg.points) {
      let x = p.x, y = p.y, z = p.z, t;
      if (kind === "custom") {
        t = msg.stamp_ns + CUSTOM_TIMEBASE_OFFSET_NS + p.offset_ns;
      } else {
        const L = LAYOUTS[kind];
        if (L.nan(p, msg)) x = y = z = NaN;
        t = L.expectedT(p, msg);
      }
      rows.push(`${f32str(x)},${f32str(y)},${f32str(z)},${p.refl},${t}`);
    }
  }
  return rows.join("\n") + "\n";
}

// ---------------------------------------------------------------------------------------------
// ROS 2 message definition text as rosbag2 stores it (rosbag2_cpp
// LocalMessageDefinitionSource::get_full_text): root .msg text, then for each dependency (std::set
// order = sorted, depth first, each type once) "\n" + 80 '=' + "\nMSG: pkg/Type\n" + its text.
// Dependencies are found with rosbag2's own regex over the .msg text.
const MSG_FIELD_TYPE_REGEX = /(?:^|\n)\s*([a-zA-Z0-9_/]+)(?:\[[^\]]*\])?\s+/g;
const PRIMITIVES = new Set(["bool", "byte", "char", "float32", "float64", "int8", "uint8", "int16", "uint16", "int32", "uint32", "int64", "uint64", "string"]);

export function ros2FullText(msgRoot, rootType) {
  const read = (type) => {
    const m = /^([a-zA-Z0-9_]+)\/(?:msg\/)?([a-zA-Z0-9_]+)$/.exec(type);
    if (!m) throw new Error(`bad type ${type}`);
    return { pkg: m[1], text: fs.readFileSync(path.join(msgRoot, m[1], "msg", `${m[2]}.msg`), "utf8") };
  };
  const deps = (text, pkg) => {
    const out = new Set();
    for (const m of text.matchAll(MSG_FIELD_TYPE_REGEX)) {
      const t = m[1];
      if (PRIMITIVES.has(t)) continue;
      out.add(t.includes("/") ? t : `${pkg}/${t}`);
    }
    return [...out].sort();
  };
  const seen = new Set();
  const rec = (type) => {
    const { pkg, text } = read(type);
    let result = text;
    for (const d of deps(text, pkg)) {
      if (seen.has(d)) continue;
      seen.add(d);
      result += "\n" + "=".repeat(80) + "\n" + `MSG: ${d}\n` + rec(d);
    }
    return result;
  };
  return rec(rootType);
}

// QoS string rosbag2 (metadata version 8) stores for a reliable/volatile publisher.
export const QOS_YAML = "- history: 3\n  depth: 0\n  reliability: 1\n  durability: 2\n  deadline:\n    sec: 9223372036\n    nsec: 854775807\n  lifespan:\n    sec: 9223372036\n    nsec: 854775807\n  liveliness: 1\n  liveliness_lease_duration:\n    sec: 9223372036\n    nsec: 854775807\n  avoid_ros_namespace_conventions: false";

// rosbag2 bag metadata (metadata version 8, the layout yaml-cpp's YAML::Dump gives in rosbag2's own
// test bags).  Returns the body WITHOUT the "rosbag2_bagfile_information:" wrapper (as stored in the
// db3 `metadata` table and in MCAP's "rosbag2" Metadata record); metadataYamlFile() wraps it for
// metadata.yaml.  topics: [{name, type, count}], times are BigInt ns.
export function rosbag2MetadataBody({ storage, file, start_ns, end_ns, topics }) {
  const count = topics.reduce((a, t) => a + t.count, 0);
  const dur = end_ns - start_ns;
  const L = [
    "version: 8",
    `storage_identifier: ${storage}`,
    "duration:", `  nanoseconds: ${dur}`,
    "starting_time:", `  nanoseconds_since_epoch: ${start_ns}`,
    `message_count: ${count}`,
    "topics_with_message_count:",
  ];
  for (const t of topics) {
    L.push("  - topic_metadata:", `      name: ${t.name}`, `      type: ${t.type}`, "      serialization_format: cdr",
      `      offered_qos_profiles: ${JSON.stringify(QOS_YAML)}`, '      type_description_hash: ""',
      `    message_count: ${t.count}`);
  }
  L.push('compression_format: ""', 'compression_mode: ""', "relative_file_paths:", `  - ${file}`,
    "files:", `  - path: ${file}`, "    starting_time:", `      nanoseconds_since_epoch: ${start_ns}`,
    "    duration:", `      nanoseconds: ${dur}`, `    message_count: ${count}`,
    "custom_data: ~", 'ros_distro: ""');
  return L.join("\n");
}
export const metadataYamlFile = (body) =>
  "rosbag2_bagfile_information:\n" + body.split("\n").map((l) => "  " + l).join("\n") + "\n";
