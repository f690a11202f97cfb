// Reads a backlash_monitor MCAP bag the way Foxglove does (@mcap/core indexed reader, chunk
// decompression from @mcap/support, ros2msg schemas parsed by @foxglove/rosmsg, CDR decoded by
// @foxglove/rosmsg2-serialization) and prints ONE JSON object:
//   {header, statistics, schemas, channels, metadata, messages: [{topic, logTime, publishTime,
//    sequence, message}]}
// uint64/int64 values are printed as decimal strings, NaN/Infinity as the strings "NaN"/"Infinity",
// typed arrays as plain arrays.
//
//   node read_bag.mjs BAG.mcap
import { open } from "node:fs/promises";

import { parse } from "@foxglove/rosmsg";
import { MessageReader } from "@foxglove/rosmsg2-serialization";
import { McapIndexedReader } from "@mcap/core";
import { loadDecompressHandlers } from "@mcap/support";

const path = process.argv[2];
if (!path) {
  console.error("usage: node read_bag.mjs BAG.mcap");
  process.exit(2);
}

const handle = await open(path, "r");
const size = (await handle.stat()).size;
const readable = {
  size: async () => BigInt(size),
  read: async (offset, length) => {
    const buf = new Uint8Array(Number(length));
    await handle.read(buf, 0, Number(length), Number(offset));
    return buf;
  },
};

const reader = await McapIndexedReader.Initialize({
  readable,
  decompressHandlers: await loadDecompressHandlers(),
});

const decoders = new Map();
const textDecoder = new TextDecoder();
for (const [id, schema] of reader.schemasById) {
  if (schema.encoding !== "ros2msg") {
    throw new Error(`schema ${schema.name}: encoding ${schema.encoding} is not ros2msg`);
  }
  const defs = parse(textDecoder.decode(schema.data), { ros2: true });
  decoders.set(id, new MessageReader(defs));
}

function plain(value) {
  if (typeof value === "bigint") return value.toString();
  if (typeof value === "number") {
    if (Number.isNaN(value)) return "NaN";
    if (!Number.isFinite(value)) return value > 0 ? "Infinity" : "-Infinity";
    return value;
  }
  if (ArrayBuffer.isView(value)) return Array.from(value, plain);
  if (Array.isArray(value)) return value.map(plain);
  if (value && typeof value === "object") {
    const out = {};
    for (const [k, v] of Object.entries(value)) out[k] = plain(v);
    return out;
  }
  return value;
}

const messages = [];
for await (const msg of reader.readMessages()) {
  const channel = reader.channelsById.get(msg.channelId);
  const decoder = decoders.get(channel.schemaId);
  messages.push({
    topic: channel.topic,
    logTime: msg.logTime.toString(),
    publishTime: msg.publishTime.toString(),
    sequence: msg.sequence,
    message: plain(decoder.readMessage(msg.data)),
  });
}

const metadata = [];
for (const [name] of reader.metadataIndexes.map((m) => [m.name])) {
  for await (const rec of reader.readMetadata({ name })) {
    metadata.push({ name: rec.name, metadata: Object.fromEntries(rec.metadata) });
  }
}

const stats = reader.statistics;
const out = {
  header: { profile: reader.header.profile, library: reader.header.library },
  statistics: stats && {
    messageCount: stats.messageCount.toString(),
    chunkCount: stats.chunkCount,
    channelMessageCounts: Object.fromEntries(
      [...stats.channelMessageCounts].map(([k, v]) => [k, v.toString()])),
  },
  schemas: [...reader.schemasById.values()].map((s) => ({ id: s.id, name: s.name, encoding: s.encoding })),
  channels: [...reader.channelsById.values()].map((c) => ({
    id: c.id, topic: c.topic, messageEncoding: c.messageEncoding, schemaId: c.schemaId,
    metadata: Object.fromEntries(c.metadata),
  })),
  chunkCompression: [...new Set(reader.chunkIndexes.map((c) => c.compression))],
  metadata,
  messages,
};
await handle.close();
process.stdout.write(JSON.stringify(out));
