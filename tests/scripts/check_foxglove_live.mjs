// SPDX-License-Identifier: MIT
// check_foxglove_live.mjs -- the live view's WebSocket server read by the
// reference client (@foxglove/ws-protocol's FoxgloveClient over `ws`), its
// messages decoded from the advertised ros2msg schemas
// (@foxglove/rosmsg2-serialization). Starts SERVE (tests/live/foxglove_serve.cpp,
// known content) and checks:
//   1. the subprotocols: either name is accepted and echoed, another refused with 400;
//   2. two clients at once: serverInfo, advertise (topics, schema names,
//      encodings), subscribe, and decoded values (point count, a label's colour,
//      the box ids and centres, the raw intensity, the log time in the frame);
//   3. a client that subscribes and stops reading loses messages (the server's
//      drop counter grows, it gets a warning status) while the other client
//      keeps receiving and the publisher keeps its rate with short publish calls;
//   4. the server shuts down promptly with that client still stalled.
// Prints one JSON line of figures; exits 1 with the failed check otherwise.
// Usage: node check_foxglove_live.mjs NPM_PREFIX SERVE

import path from "node:path";
import readline from "node:readline";
import { spawn } from "node:child_process";
import { createRequire } from "node:module";
import { checks } from "./node_checks.mjs";

const [prefix, serve] = process.argv.slice(2);
const require = createRequire(path.join(path.resolve(prefix), "package.json"));
const { FoxgloveClient } = require("@foxglove/ws-protocol");
const WebSocket = require("ws");
const { MessageReader } = require("@foxglove/rosmsg2-serialization");
const { parse } = require("@foxglove/rosmsg");

const POINTS = 10000, RATE = 20;  // as passed to SERVE
const { fail, need, sleep, until } = checks("foxglove_live", 120);

const server = spawn(serve, ["--points", POINTS, "--rate", RATE, "--seconds", 90, "--limit", 1000000].map(String),
                     { stdio: ["pipe", "pipe", "inherit"] });
let exited = false;
server.on("exit", (code, signal) => {
  exited = true;
  need(code === 0, `foxglove_serve exited with ${code ?? signal}`);
});
const lines = [];
readline.createInterface({ input: server.stdout }).on("line", (l) => lines.push(JSON.parse(l)));
await until(() => lines.length > 0, 20, "the server's port");
const url = `ws://127.0.0.1:${lines[0].port}`;

// 1. Subprotocol negotiation.
async function handshake(protocols) {
  const ws = new WebSocket(url, protocols);
  const result = await new Promise((resolve) => {
    ws.on("open", () => resolve({ protocol: ws.protocol }));
    ws.on("unexpected-response", (_req, res) => resolve({ status: res.statusCode }));
    ws.on("error", (e) => resolve({ error: String(e) }));
  });
  ws.terminate();
  return result;
}
need((await handshake(["foxglove.sdk.v1"])).protocol === "foxglove.sdk.v1", "foxglove.sdk.v1 accepted and echoed");
need((await handshake(["foxglove.websocket.v1", "foxglove.sdk.v1"])).protocol === "foxglove.websocket.v1",
     "the client's first supported subprotocol chosen");
need((await handshake(["bogus.v1"])).status === 400, "an unknown subprotocol refused with HTTP 400");

// The writers' label colour (io::label_color: a splitmix64 hash to a hue), written again here.
function labelColor(label) {
  const M = (1n << 64n) - 1n;
  let z = (BigInt(label) + 0x9e3779b97f4a7c15n) & M;
  z = ((z ^ (z >> 30n)) * 0xbf58476d1ce4e5b9n) & M;
  z = ((z ^ (z >> 27n)) * 0x94d049bb133111ebn) & M;
  z ^= z >> 31n;
  const hue = Number(z % 1536n), f = hue & 255;
  const rising = 40 + Math.floor((f * 215) / 255), falling = 255 - Math.floor((f * 215) / 255);
  return [[255, rising, 40], [falling, 255, 40], [40, 255, rising], [40, falling, 255], [rising, 40, 255],
          [255, 40, falling]][hue >> 8];
}

// 2. Reference clients.
function referenceClient(name) {
  const c = { info: undefined, channels: [], subscriptions: new Map(), received: {}, last: {}, statuses: [] };
  const ws = new WebSocket(url, [FoxgloveClient.SUPPORTED_SUBPROTOCOL]);
  const client = new FoxgloveClient({ ws });
  client.on("error", (e) => fail(`${name}: ${e}`));
  client.on("serverInfo", (info) => (c.info = info));
  client.on("status", (s) => c.statuses.push(s));
  client.on("advertise", (channels) => {
    for (const channel of channels) {
      c.channels.push(channel);
      const reader = new MessageReader(parse(channel.schema, { ros2: true }));
      c.subscriptions.set(client.subscribe(channel.id), { channel, reader });
    }
  });
  client.on("message", ({ subscriptionId, timestamp, data }) => {
    const { channel, reader } = c.subscriptions.get(subscriptionId);
    const message = reader.readMessage(new Uint8Array(data.buffer, data.byteOffset, data.byteLength));
    const stamp = message.timestamp ?? message.deletions[0].timestamp;
    need(BigInt(stamp.sec) * 1000000000n + BigInt(stamp.nanosec ?? stamp.nsec) === timestamp,
         `${name}: the frame's log time equals the message's stamp on ${channel.topic}`);
    const previous = c.last[channel.topic];
    need(previous === undefined || timestamp > previous.timestamp, `${name}: log times increase on ${channel.topic}`);
    c.received[channel.topic] = (c.received[channel.topic] ?? 0) + 1;
    c.last[channel.topic] = { timestamp, message };
  });
  c.close = () => client.close();
  return c;
}
const topics = ["/streamclust/points", "/streamclust/clusters", "/streamclust/raw"];
const clients = [referenceClient("client 1"), referenceClient("client 2")];
for (const c of clients) await until(() => topics.every((t) => (c.received[t] ?? 0) >= 5), 30, "5 messages per topic");

for (const c of clients) {
  need(c.info.name === "streamclust-test" && Array.isArray(c.info.capabilities) && c.info.capabilities.length === 0 &&
       typeof c.info.sessionId === "string", "serverInfo: name, no capabilities, a session id");
  const byTopic = Object.fromEntries(c.channels.map((ch) => [ch.topic, ch]));
  need(topics.every((t) => byTopic[t]) && c.channels.length === 3, "advertise: the three topics");
  need(c.channels.every((ch) => ch.encoding === "cdr" && ch.schemaEncoding === "ros2msg"), "advertise: cdr, ros2msg");
  need(byTopic["/streamclust/points"].schemaName === "foxglove_msgs/msg/PointCloud" &&
       byTopic["/streamclust/raw"].schemaName === "foxglove_msgs/msg/PointCloud" &&
       byTopic["/streamclust/clusters"].schemaName === "foxglove_msgs/msg/SceneUpdate", "advertise: schema names");

  const cloud = c.last["/streamclust/points"].message;
  need(cloud.frame_id === "streamclust" && cloud.point_stride === 20, "points: frame and stride");
  need(cloud.data.length / cloud.point_stride === POINTS, "points: the window's point count");
  const view = new DataView(cloud.data.buffer, cloud.data.byteOffset, cloud.data.byteLength);
  const rgb = (i) => [0, 1, 2].map((k) => cloud.data[i * 20 + 16 + k]);
  need(view.getFloat32(0, true) === 10 && view.getInt32(12, true) === 0, "points: the first point (x 10, label 0)");
  need(rgb(0).join() === labelColor(0).join(), "points: label 0 in its colour");
  need(view.getInt32((POINTS / 2) * 20 + 12, true) === -2 && rgb(POINTS / 2).join() === "140,105,70",
       "points: ground (-2) in brown");

  const scene = c.last["/streamclust/clusters"].message;
  need(scene.entities.map((e) => e.id).join() === "0,1", "clusters: the box ids 0 and 1");
  need(scene.entities.every((e) => e.texts[0].text === e.id && e.metadata[0].value === String(POINTS / 4)),
       "clusters: each box labelled with its id and point count");
  const centre = scene.entities.map((e) => e.cubes[0].pose.position);
  need(Math.abs(centre[0].x - 10.5) < 0.01 && Math.abs(centre[1].y - 20.5) < 0.01, "clusters: the boxes' centres");

  const raw = c.last["/streamclust/raw"].message;
  const rawView = new DataView(raw.data.buffer, raw.data.byteOffset, raw.data.byteLength);
  need(raw.data.length / raw.point_stride === POINTS && raw.fields.map((f) => f.name).join() === "x,y,z,intensity",
       "raw: every point, x y z intensity");
  need(rawView.getFloat32(3 * 16 + 12, true) === 3, "raw: the intensity of point 3");
}

// 3. A client that subscribes, then stops reading.
const slow = { statuses: [], paused: false };
const slowWs = new WebSocket(url, ["foxglove.websocket.v1"]);
slowWs.on("message", (data, isBinary) => {
  if (isBinary) return;
  const op = JSON.parse(data.toString());
  if (op.op === "advertise" && !slow.paused) {
    slowWs.send(JSON.stringify({ op: "subscribe", subscriptions: op.channels.map((ch, i) => ({ id: i, channelId: ch.id })) }));
    slowWs._socket.pause();  // nothing more is read: the kernel buffers fill, then the server's
    slow.paused = true;
  }
  if (op.op === "status") slow.statuses.push(op);
});
await until(() => slow.paused, 10, "the slow client's subscription");
const before = clients[0].received["/streamclust/points"];
const stall = 8;  // [s]
await sleep(stall * 1000);
const during = clients[0].received["/streamclust/points"] - before;
need(during >= 0.5 * RATE * stall, `the other client keeps receiving while one stalls (${during} in ${stall} s)`);
slowWs._socket.resume();
await until(() => slow.statuses.some((s) => s.level === 1 && /dropped/.test(s.message)), 30,
            "the slow client's warning status about dropped messages");
slowWs._socket.pause();
await sleep(2000);

// 4. Shutdown with the slow client stalled.
for (const c of clients) c.close();
server.stdin.end();
await until(() => lines.length > 1, 20, "the server's final figures");
const figures = lines[1];
await until(() => exited, 20, "the server's exit");
slowWs.terminate();
need(figures.messages_dropped > 0, "the server counted dropped messages");
need(figures.rate >= 0.9 * RATE, `the publisher kept its rate (${figures.rate} Hz of ${RATE})`);
need(figures.publish_us_median < 1000 && figures.publish_us_p99 < 50000,
     `publish() calls stay short (median ${figures.publish_us_median} us, P99 ${figures.publish_us_p99} us)`);
need(figures.shutdown_ms < 3000, `shutdown with a stalled client is prompt (${figures.shutdown_ms} ms)`);
console.log(JSON.stringify({ ...figures, other_client_during_stall: during }));
process.exit(0);
