// SPDX-License-Identifier: MIT
// check_live_view.mjs -- `streamclust live --foxglove --tracks` end to end:
// the live run fed by `streamclust replay` (a simulated Mid-360 in the office,
// its people walking) over real UDP on loopback, read by the reference client
// (@foxglove/ws-protocol's FoxgloveClient over `ws`, messages decoded from the
// advertised ros2msg schemas). Checks that the view advertises the four topics,
// and that every /streamclust/tracks update received shows exactly the
// confirmed and coasting tracks of the --tracks file's rows of its cycle: ids,
// box centres and sizes, the speed in the text, states, and a velocity arrow
// of the track's speed on moving ones; and that some track moved.
// Prints one JSON line of figures; exits 1 with the failed check otherwise.
// Usage: node check_live_view.mjs NPM_PREFIX TOOL WORK_DIR PORT

import fs from "node:fs";
import path from "node:path";
import { spawn } from "node:child_process";
import { createRequire } from "node:module";
import { checks } from "./node_checks.mjs";

const [prefix, tool, work, port] = process.argv.slice(2);
const require = createRequire(path.join(path.resolve(prefix), "package.json"));
const { FoxgloveClient } = require("@foxglove/ws-protocol");
const WebSocket = require("ws");
const { MessageReader } = require("@foxglove/rosmsg2-serialization");
const { parse } = require("@foxglove/rosmsg");

const { fail, need, sleep, until } = checks("live_view", 240);

// The live run: not quiet (its first lines name the view's port), no status line.
const url = `livox-sdk2://127.0.0.1:${port}`;
const tracksPath = path.join(work, "tracks.csv");
const live = spawn(tool, ["live", url, "--preset", "objects-mid360", "--idle-exit", "1", "--wait", "60",
                          "--foxglove", "127.0.0.1:0", "--tracks", tracksPath, "--no-status"],
                   { stdio: ["ignore", "ignore", "pipe"] });
let liveErr = "", liveExit;
live.stderr.on("data", (d) => (liveErr += d));
live.on("exit", (code, signal) => (liveExit = code ?? signal));
await until(() => /Foxglove live view on ws:\/\/[^:]+:(\d+)/.test(liveErr) || liveExit !== undefined, 30,
            "the live view's port");
need(liveExit === undefined, `live exited early (${liveExit}): ${liveErr}`);
const viewPort = Number(liveErr.match(/Foxglove live view on ws:\/\/[^:]+:(\d+)/)[1]);

// The reference client: every channel subscribed as advertised.
const seen = { channels: [], subscriptions: new Map(), tracks: [], received: {} };
const client = new FoxgloveClient({ ws: new WebSocket(`ws://127.0.0.1:${viewPort}`, [FoxgloveClient.SUPPORTED_SUBPROTOCOL]) });
client.on("error", (e) => fail(`client: ${e}`));
client.on("advertise", (channels) => {
  for (const channel of channels) {
    seen.channels.push(channel);
    const reader = new MessageReader(parse(channel.schema, { ros2: true }));
    seen.subscriptions.set(client.subscribe(channel.id), { channel, reader });
  }
});
client.on("message", ({ subscriptionId, timestamp, data }) => {
  const { channel, reader } = seen.subscriptions.get(subscriptionId);
  seen.received[channel.topic] = (seen.received[channel.topic] ?? 0) + 1;
  if (channel.topic !== "/streamclust/tracks") return;
  seen.tracks.push({ timestamp, message: reader.readMessage(new Uint8Array(data.buffer, data.byteOffset, data.byteLength)) });
});
const topics = ["/streamclust/points", "/streamclust/clusters", "/streamclust/raw", "/streamclust/tracks"];
await until(() => seen.subscriptions.size >= topics.length, 20, "the four topics' advertisements");
const byTopic = Object.fromEntries(seen.channels.map((ch) => [ch.topic, ch]));
need(topics.every((t) => byTopic[t]) && seen.channels.length === 4, "advertise: the four topics");
need(byTopic["/streamclust/tracks"].schemaName === "foxglove_msgs/msg/SceneUpdate", "advertise: tracks as SceneUpdate");

// The emulated LiDAR, once subscribed: 4 s of the office, people walking.
const replay = spawn(tool, ["replay", "--simulate", "--sensor", "mid360", "--scene", "office", "--seconds", "4",
                            "--to", url, "--device-address", "127.0.0.2", "-q"], { stdio: ["ignore", "ignore", "pipe"] });
let replayErr = "", replayExit;
replay.stderr.on("data", (d) => (replayErr += d));
replay.on("exit", (code, signal) => (replayExit = code ?? signal));
await until(() => replayExit !== undefined && liveExit !== undefined, 180, "the replay and the live run to end");
need(replayExit === 0, `replay exited with ${replayExit}: ${replayErr}`);
need(liveExit === 0, `live exited with ${liveExit}: ${liveErr}`);
await sleep(200);
client.close();

// The file's rows by cycle time [ns], the view's log time (the file's time
// text is exact to the nanosecond: seconds, a point, nine digits at most).
const nanoseconds = (text) => {
  const [whole, fraction = ""] = text.split(".");
  return (BigInt(whole) * 1000000000n + BigInt(fraction.padEnd(9, "0").slice(0, 9))).toString();
};
const rows = fs.readFileSync(tracksPath, "utf8").trim().split("\n");
need(rows[0] === "cycle,time,track_id,cluster_id,x,y,z,vx,vy,vz,length,width,height,yaw,points,state", "the CSV header");
const cycles = new Map();
for (const line of rows.slice(1)) {
  const f = line.split(",");
  const key = nanoseconds(f[1]);
  if (!cycles.has(key)) cycles.set(key, []);
  const [x, y, z, vx, vy, vz, length, width, height] = f.slice(4, 13).map(Number);
  cycles.get(key).push({ id: f[2], cluster: f[3], x, y, z, vx, vy, length, width, height, points: f[14], state: f[15] });
}
const close = (a, b, what) => need(Math.abs(a - b) <= 1e-5 * Math.max(1, Math.abs(b)), `${what}: ${a} against ${b}`);
let compared = 0, boxes = 0, arrows = 0, confirmed = 0;
for (const { timestamp, message } of seen.tracks) {
  const key = timestamp.toString();
  const want = (cycles.get(key) ?? []).filter((r) => r.state !== "tentative");
  const got = message.entities;
  const what = `the update at ${timestamp} ns`;
  need(cycles.has(key) || got.length === 0, `${what}: a cycle of the --tracks file`);
  need(got.map((e) => e.id).sort().join() === want.map((r) => "track " + r.id).sort().join(),
       `${what}: the confirmed and coasting tracks of its cycle (${got.map((e) => e.id).join()} against ` +
       `${want.map((r) => r.id).join()})`);
  for (const e of got) {
    const r = want.find((w) => "track " + w.id === e.id);
    const cube = e.cubes[0];
    close(cube.pose.position.x, r.x, `${e.id} x`);
    close(cube.pose.position.y, r.y, `${e.id} y`);
    close(cube.pose.position.z, r.z, `${e.id} z`);
    close(cube.size.x, r.length, `${e.id} length`);
    close(cube.size.y, r.width, `${e.id} width`);
    close(cube.size.z, r.height, `${e.id} height`);
    const speed = Math.hypot(r.vx, r.vy);
    need(e.texts[0].text === `${r.id} ${speed.toFixed(1)} m/s`, `${e.id}: its id and speed above it (${e.texts[0].text})`);
    const meta = Object.fromEntries(e.metadata.map((kv) => [kv.key, kv.value]));
    need(meta.state === r.state && meta.cluster === r.cluster && meta.points === r.points,
         `${e.id}: state, cluster and points as in the file`);
    need(e.arrows.length <= 1, `${e.id}: at most one arrow`);
    if (e.arrows.length === 1) {
      const a = e.arrows[0];
      close(a.shaft_length + a.head_length, speed, `${e.id}: the arrow's length (1 s of travel)`);
      ++arrows;
    }
    if (r.state === "confirmed") ++confirmed;
    ++boxes;
  }
  ++compared;
}
const fileCycles = [...new Set(rows.slice(1).map((l) => l.split(",")[0]))].length;
need(compared >= 40, `track updates received and compared: ${compared} (cycles in the file: ${fileCycles})`);
need(confirmed > 0 && arrows > 0, `confirmed tracks (${confirmed}) and moving ones with arrows (${arrows})`);
console.log(JSON.stringify({ updates: compared, file_cycles_with_tracks: fileCycles, boxes, confirmed, arrows,
                             received: seen.received }));
process.exit(0);
