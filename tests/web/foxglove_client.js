// Foxglove's own WebSocket client (@foxglove/ws-protocol over ws) driving kame's foxglove_bridge,
// decoding what it receives with the ros1msg schema it was given (@foxglove/rosmsg and
// @foxglove/rosmsg-serialization, as the Foxglove app does). Each step of the plan (JSON, argv[2])
// prints one JSON line; the test reads them.
//   {"url": "ws://127.0.0.1:PORT", "steps": [
//     {"subscribe": "/topic", "count": 3},               -> {"topic", "schemaName", "messages": [...]}
//     {"publish": "/topic", "type": "pkg/T", "definition": "...", "message": {...}, "count": 5, "period_ms": 100}
//     {"call": "/service", "request": {...}}              -> {"service", "response"} or {"failure"}
//     {"getParameters": [names]}, {"setParameters": [{name, value, type?}]}, {"subscribeParameterUpdates": [names], "count": n}
//     {"graph": true}                                     -> the first connectionGraphUpdate
//     {"raw": "text"} / {"rawBinary": [bytes]}            -> the status it brings back
//     {"send": "text"}                                    -> (sent as it is; nothing is awaited)
//     {"rate": "/topic", "seconds": s}                    -> {"received", "fps", "bytes"}
//     {"time": n}                                         -> the first n server times (ns)
//   ]}
"use strict";
const { FoxgloveClient } = require("@foxglove/ws-protocol");
const { parse } = require("@foxglove/rosmsg");
const { MessageReader, MessageWriter } = require("@foxglove/rosmsg-serialization");
const WebSocket = require("ws");

const plan = JSON.parse(process.argv[2]);
const ws = new WebSocket(plan.url, [FoxgloveClient.SUPPORTED_SUBPROTOCOL]);
const client = new FoxgloveClient({ ws });
const channels = new Map(); // topic -> channel
const services = new Map(); // name -> service
const waiters = [];
let serverInfo = null;

function emit(obj) {
  process.stdout.write(JSON.stringify(obj, (k, v) => (typeof v === "bigint" ? v.toString() : v)) + "\n");
}
function waitFor(pred, what, ms = 20000) {
  return new Promise((resolve, reject) => {
    const found = pred();
    if (found) return resolve(found);
    const timer = setTimeout(() => reject(new Error(`timed out waiting for ${what}`)), ms);
    waiters.push(() => {
      const value = pred();
      if (value) {
        clearTimeout(timer);
        resolve(value);
        return true;
      }
      return false;
    });
  });
}
function wake() {
  for (let i = waiters.length - 1; i >= 0; i--) if (waiters[i]()) waiters.splice(i, 1);
}
// a decoded message as JSON: typed arrays become their length and a checksum of their bytes
function plain(value) {
  if (ArrayBuffer.isView(value)) {
    let sum = 0;
    const bytes = new Uint8Array(value.buffer, value.byteOffset, value.byteLength);
    for (let i = 0; i < bytes.length; i += 1) sum = (sum + bytes[i] * ((i % 251) + 1)) % 1000000007;
    return { length: bytes.length, checksum: sum };
  }
  if (Array.isArray(value)) return value.map(plain);
  if (value && typeof value === "object") {
    const out = {};
    for (const [k, v] of Object.entries(value)) out[k] = plain(v);
    return out;
  }
  return value;
}

client.on("serverInfo", (info) => { serverInfo = info; wake(); });
client.on("advertise", (list) => { for (const c of list) channels.set(c.topic, c); wake(); });
client.on("unadvertise", (ids) => { for (const [t, c] of channels) if (ids.includes(c.id)) channels.delete(t); wake(); });
client.on("advertiseServices", (list) => { for (const s of list) services.set(s.name, s); wake(); });
client.on("error", (err) => { emit({ error: String(err) }); process.exit(2); });

const inbox = { messages: new Map(), status: [], params: [], graph: [], responses: [], failures: [] };
client.on("message", (m) => {
  const list = inbox.messages.get(m.subscriptionId) || [];
  list.push(m);
  inbox.messages.set(m.subscriptionId, list);
  wake();
});
const times = [];
client.on("time", (t) => { times.push(t.timestamp); wake(); });
client.on("status", (s) => { inbox.status.push(s); wake(); });
client.on("parameterValues", (p) => { inbox.params.push(p); wake(); });
client.on("connectionGraphUpdate", (g) => { inbox.graph.push(g); wake(); });
client.on("serviceCallResponse", (r) => { inbox.responses.push(r); wake(); });
client.on("serviceCallFailure", (f) => { inbox.failures.push(f); wake(); });

async function subscribeStep(step) {
  const channel = await waitFor(() => channels.get(step.subscribe), `channel ${step.subscribe}`);
  const reader = new MessageReader(parse(channel.schema, { ros2: false }));
  const id = client.subscribe(channel.id);
  const count = step.count || 1;
  const got = await waitFor(() => { const l = inbox.messages.get(id); return l && l.length >= count && l; },
    `${count} messages on ${step.subscribe}`);
  client.unsubscribe(id);
  emit({ topic: step.subscribe, schemaName: channel.schemaName, encoding: channel.encoding,
    schemaEncoding: channel.schemaEncoding, schema: channel.schema,
    messages: got.slice(0, count).map((m) => plain(reader.readMessage(m.data))) });
}

async function rateStep(step) {
  const channel = await waitFor(() => channels.get(step.rate), `channel ${step.rate}`);
  const id = client.subscribe(channel.id);
  await waitFor(() => inbox.messages.get(id), `a first message on ${step.rate}`);
  inbox.messages.set(id, []);
  const start = process.hrtime.bigint();
  const cpuStart = process.cpuUsage();
  await new Promise((r) => setTimeout(r, step.seconds * 1000));
  const got = inbox.messages.get(id);
  const elapsed = Number(process.hrtime.bigint() - start) / 1e9;
  const cpu = process.cpuUsage(cpuStart);
  client.unsubscribe(id);
  emit({ topic: step.rate, received: got.length, fps: got.length / elapsed, seconds: elapsed,
    bytes: got.reduce((n, m) => n + m.data.byteLength, 0), clientCpu: (cpu.user + cpu.system) / 1e6 / elapsed });
  inbox.messages.set(id, []);
}

async function publishStep(step) {
  const writer = new MessageWriter(parse(step.definition, { ros2: false }));
  const id = client.advertise({ topic: step.publish, encoding: "ros1", schemaName: step.type });
  const data = writer.writeMessage(step.message);
  for (let i = 0; i < (step.count || 1); i++) {
    client.sendMessage(id, data);
    await new Promise((r) => setTimeout(r, step.period_ms || 100));
  }
  emit({ published: step.publish, count: step.count || 1, bytes: data.length });
}

let callIds = 1;
async function callStep(step) {
  const service = await waitFor(() => services.get(step.call), `service ${step.call}`);
  const request = service.request ? service.request.schema : service.requestSchema;
  const response = service.response ? service.response.schema : service.responseSchema;
  const writer = new MessageWriter(parse(request, { ros2: false }));
  const reader = new MessageReader(parse(response, { ros2: false }));
  const callId = callIds++;
  client.sendServiceCallRequest({ serviceId: service.id, callId, encoding: "ros1",
    data: new DataView(writer.writeMessage(step.request).buffer) });
  const answer = await waitFor(() => inbox.responses.find((r) => r.callId === callId)
    || inbox.failures.find((f) => f.callId === callId), `the answer of ${step.call}`);
  if (answer.message !== undefined) emit({ service: step.call, type: service.type, failure: answer.message });
  else emit({ service: step.call, type: service.type, response: plain(reader.readMessage(answer.data)) });
}

async function paramStep(step, key) {
  const before = inbox.params.length;
  const id = `req${before}`;
  if (key === "getParameters") client.getParameters(step.getParameters, id);
  else if (key === "setParameters") client.setParameters(step.setParameters, id);
  else client.subscribeParameterUpdates(step.subscribeParameterUpdates);
  const want = key === "subscribeParameterUpdates" ? step.count || 1 : 1;
  const got = await waitFor(() => inbox.params.length >= before + want && inbox.params.slice(before),
    `parameterValues after ${key}`);
  emit({ [key]: got.slice(0, want) });
}

async function rawStep(step) {
  const before = inbox.status.length;
  if (step.raw !== undefined) ws.send(step.raw);
  else ws.send(Uint8Array.from(step.rawBinary));
  const status = await waitFor(() => inbox.status.length > before && inbox.status[before], "a status");
  emit({ status });
}

async function main() {
  await waitFor(() => serverInfo, "serverInfo");
  emit({ serverInfo, subprotocol: ws.protocol });
  for (const step of plan.steps) {
    if (step.subscribe) await subscribeStep(step);
    else if (step.rate) await rateStep(step);
    else if (step.publish) await publishStep(step);
    else if (step.call) await callStep(step);
    else if (step.getParameters) await paramStep(step, "getParameters");
    else if (step.setParameters) await paramStep(step, "setParameters");
    else if (step.subscribeParameterUpdates) await paramStep(step, "subscribeParameterUpdates");
    else if (step.graph) {
      client.subscribeConnectionGraph();
      const g = await waitFor(() => inbox.graph[0], "a connection graph");
      emit({ graph: g });
    } else if (step.raw !== undefined || step.rawBinary) await rawStep(step);
    else if (step.send !== undefined) ws.send(step.send);
    else if (step.time) {
      const got = await waitFor(() => times.length >= step.time && times.slice(0, step.time), "time messages");
      emit({ time: got });
    }
  }
  emit({ done: true });
  client.close();
}

main().catch((err) => { emit({ error: String(err && err.stack || err) }); process.exit(1); });
