// The official Foxglove WebSocket client (@foxglove/ws-protocol's FoxgloveClient on the `ws`
// package) against `robodds bridge`, as integration.bridge_ws runs it:
//   A (FoxgloveClient): waits for the advertisement of TOPIC (checks schema encoding omgidl,
//     message encoding cdr, schema name SCHEMA), subscribes, decodes every message with
//     @foxglove/omgidl-parser + @foxglove/omgidl-serialization from the advertised schema, and
//     writes one JSON line per message to OUT ({receive_time, value}); its rate is measured before
//     and while B stalls; then it unsubscribes and must get nothing after the ack window.
//   B (FoxgloveClient): subscribes to every advertised channel, takes a few messages, then stops
//     reading its socket (paused) until the end: a stalled client.
//   C (raw `ws`): sends garbage text, a binary frame, malformed JSON, a subscribe to an unknown
//     channel and an unsubscribe of an unknown subscription, and must get one error status each.
//   D (FoxgloveClient): when foxglove/robot_poses is advertised (--foxglove-scene), takes 50 of its
//     JSON messages (foxglove.PosesInFrame).
// Prints one JSON line of figures on stdout; exits 1 with one line on the first failure.
// Usage: node bridge_client.mjs URL TOPIC SCHEMA OUT [STALL_S]
import { createRequire } from "node:module";
import { writeFileSync } from "node:fs";
import { parseIDL } from "@foxglove/omgidl-parser";
import { MessageReader } from "@foxglove/omgidl-serialization";
import WebSocket from "ws";

const require = createRequire(import.meta.url);
const { FoxgloveClient } = require("@foxglove/ws-protocol");  // its ESM build lacks file extensions node needs

const [url, topic, schemaName, outPath, stallArg] = process.argv.slice(2);
const stallS = Number(stallArg ?? 6);
const fail = (why) => {
  console.error(`bridge_client: ${why}`);
  process.exit(1);
};
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));
const within = (promise, ms, what) => {
  let timer;
  const timeout = new Promise(() => { timer = setTimeout(() => fail(`timed out after ${ms} ms waiting for ${what}`), ms); });
  return Promise.race([promise, timeout]).finally(() => clearTimeout(timer));
};
const plain = (v) => {
  if (typeof v === "bigint") return Number.isSafeInteger(Number(v)) ? Number(v) : v.toString();
  if (ArrayBuffer.isView(v)) return Array.from(v, plain);
  if (Array.isArray(v)) return v.map(plain);
  if (v && typeof v === "object") return Object.fromEntries(Object.entries(v).map(([k, x]) => [k, plain(x)]));
  return v;
};

function connect(name) {
  const ws = new WebSocket(url, [FoxgloveClient.SUPPORTED_SUBPROTOCOL]);
  const client = new FoxgloveClient({ ws });
  const channels = new Map();
  const advertised = new Promise((resolve) => {
    client.on("advertise", (list) => {
      for (const c of list) channels.set(c.id, c);
      resolve();
    });
  });
  const info = new Promise((resolve) => client.on("serverInfo", resolve));
  client.on("error", (e) => fail(`client ${name}: ${e.message}`));
  return { ws, client, channels, info, advertised };
}

// --- A: the live view -------------------------------------------------------------------------
const a = connect("A");
const serverInfo = await within(a.info, 10000, "serverInfo");
if (serverInfo.name !== "robodds bridge") fail(`serverInfo name ${JSON.stringify(serverInfo.name)}`);
const channelOf = () => [...a.channels.values()].find((c) => c.topic === topic);
const t0 = Date.now();
while (!channelOf()) {
  if (Date.now() - t0 > 20000) fail(`no advertisement of ${topic} within 20 s: ${[...a.channels.values()].map((c) => c.topic)}`);
  await sleep(50);
}
const channel = channelOf();
if (channel.schemaEncoding !== "omgidl" || channel.encoding !== "cdr" || channel.schemaName !== schemaName)
  fail(`${topic} advertised as ${channel.schemaEncoding}/${channel.encoding}/${channel.schemaName}`);
const reader = new MessageReader(channel.schemaName, parseIDL(channel.schema));
const received = [];  // {t: arrival ms, line}
let subscription = null;
a.client.on("message", ({ subscriptionId, timestamp, data }) => {
  if (subscriptionId !== subscription) fail(`A got subscription ${subscriptionId}, subscribed ${subscription}`);
  const bytes = new Uint8Array(data.buffer, data.byteOffset, data.byteLength);
  received.push({ t: Date.now(), line: JSON.stringify({ receive_time: plain(timestamp), value: plain(reader.readMessage(bytes)) }) });
});
subscription = a.client.subscribe(channel.id);
await sleep(2000);
const beforeStall = received.length;
const rateBefore = beforeStall / 2.0;

// --- B: subscribes to everything, then stalls ----------------------------------------------------
const b = connect("B");
await within(b.advertised, 10000, "B's advertisements");
let bMessages = 0;
b.client.on("message", () => ++bMessages);
for (const id of b.channels.keys()) b.client.subscribe(id);
await within((async () => { while (bMessages < 10) await sleep(20); })(), 10000, "B's first messages");
b.ws.pause();  // B reads nothing from now on (ws's own pause: it never resumes the socket itself)
const bPort = b.ws._socket.localPort;

// --- C: bad input, while B stalls ----------------------------------------------------------------
const c = new WebSocket(url, [FoxgloveClient.SUPPORTED_SUBPROTOCOL]);
const statuses = [];
c.on("message", (data, isBinary) => {
  if (isBinary) return;
  const m = JSON.parse(data.toString());
  if (m.op === "status") statuses.push(m);
});
await within(new Promise((r) => c.on("open", r)), 10000, "C's connection");
const bad = [
  "hello garbage",
  Buffer.from([0x01, 0x02, 0x03]),
  '{"op":"subscribe"',
  JSON.stringify({ op: "subscribe", subscriptions: [{ id: 1, channelId: 9999 }] }),
  JSON.stringify({ op: "unsubscribe", subscriptionIds: [4242] }),
];
for (const m of bad) c.send(m);
await within((async () => { while (statuses.length < bad.length) await sleep(20); })(), 10000, "C's statuses");
c.close();

// A's rate while B stalls.
const stallStart = received.length;
await sleep(stallS * 1000);
const rateDuring = (received.length - stallStart) / stallS;

// --- A unsubscribes: nothing after the ack window -------------------------------------------------
a.client.unsubscribe(subscription);
await sleep(300);  // the ack window: frames already on the wire may still arrive
const afterUnsubscribe = received.length;
await sleep(1000);
const lateMessages = received.length - afterUnsubscribe;

// --- D: the derived foxglove.PosesInFrame channel (robodds bridge --foxglove-scene) ---------------
const d = connect("D");
await within(d.advertised, 10000, "D's advertisements");
const scene = [...d.channels.values()].find((ch) => ch.topic === "foxglove/robot_poses");
const sceneMessages = [];
if (scene) {
  const decoder = new TextDecoder();
  d.client.on("message", ({ data }) => sceneMessages.push(JSON.parse(decoder.decode(data))));
  d.client.subscribe(scene.id);
  await within((async () => { while (sceneMessages.length < 50) await sleep(20); })(), 10000, "50 scene messages");
  d.client.close();
}

// The run ends: its writers go, and the bridge unadvertises the topic.
const unadvertised = new Promise((resolve) => a.client.on("unadvertise", (ids) => { if (ids.includes(channel.id)) resolve(true); }));
const gone = await Promise.race([unadvertised, sleep(30000).then(() => false)]);

writeFileSync(outPath, received.map((r) => r.line).join("\n") + "\n");
console.log(JSON.stringify({
  advertised: [...a.channels.values()].map((ch) => ({ topic: ch.topic, schemaName: ch.schemaName, schemaEncoding: ch.schemaEncoding, encoding: ch.encoding })),
  decoded: received.length,
  rate_before_hz: rateBefore,
  rate_during_stall_hz: rateDuring,
  late_after_unsubscribe: lateMessages,
  unadvertised_when_the_run_ended: gone,
  b_port: bPort,
  b_messages_before_stall: bMessages,
  statuses: statuses.map((s) => ({ level: s.level, message: s.message })),
  scene: scene ? { schemaName: scene.schemaName, schemaEncoding: scene.schemaEncoding, encoding: scene.encoding,
                   messages: sceneMessages.slice(0, 50) } : null,
}));
b.ws.terminate();
a.client.close();
process.exit(0);
