// Reads an MCAP file as Foxglove does: @mcap/core's indexed reader, each channel's ros1msg
// schema parsed with @foxglove/rosmsg and its messages decoded with @foxglove/rosmsg-serialization.
// Prints one JSON line per message: topic, schema name, log time (ns), a checksum of its bytes
// and the decoded message (byte arrays as their length and checksum), then {"done": true}.
"use strict";
const fs = require("fs");
const { McapIndexedReader } = require("@mcap/core");
const { parse } = require("@foxglove/rosmsg");
const { MessageReader } = require("@foxglove/rosmsg-serialization");

function checksum(bytes) {
  let sum = 0;
  for (let i = 0; i < bytes.length; i += 1) sum = (sum + bytes[i] * ((i % 251) + 1)) % 1000000007;
  return sum;
}
function plain(value) {
  if (ArrayBuffer.isView(value)) {
    const bytes = new Uint8Array(value.buffer, value.byteOffset, value.byteLength);
    return { length: bytes.length, checksum: checksum(bytes) };
  }
  if (Array.isArray(value)) return value.map(plain);
  if (value && typeof value === "object") {
    const out = {};
    for (const [k, v] of Object.entries(value)) out[k] = plain(v);
    return out;
  }
  return value;
}

async function main() {
  const file = fs.readFileSync(process.argv[2]);
  const readable = {
    size: async () => BigInt(file.length),
    read: async (offset, length) => file.subarray(Number(offset), Number(offset + length)),
  };
  const reader = await McapIndexedReader.Initialize({ readable });
  const readers = new Map();
  for (const [id, channel] of reader.channelsById) {
    const schema = reader.schemasById.get(channel.schemaId);
    readers.set(id, { topic: channel.topic, schema,
      reader: new MessageReader(parse(new TextDecoder().decode(schema.data), { ros2: false })) });
  }
  for await (const message of reader.readMessages()) {
    const { topic, schema, reader: decoder } = readers.get(message.channelId);
    process.stdout.write(JSON.stringify({ topic, schemaName: schema.name, schemaEncoding: schema.encoding,
      logTime: message.logTime.toString(), checksum: checksum(message.data),
      message: plain(decoder.readMessage(message.data)) }) + "\n");
  }
  process.stdout.write(JSON.stringify({ done: true, profile: reader.header.profile }) + "\n");
}

main().catch((err) => { console.error(err); process.exit(1); });
