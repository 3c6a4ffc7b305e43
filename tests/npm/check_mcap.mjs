#!/usr/bin/env node
// Checks an MCAP file with the official readers (@mcap/core): node check_mcap.mjs FILE
//   [--expect-json F] [--counts-only]
// - McapIndexedReader (footer, summary CRC, chunk indexes, message indexes) reads every message with
//   CRC validation, zstd and lz4 decompression (@foxglove/wasm-zstd, @foxglove/wasm-lz4);
// - the summary's statistics and chunk indexes must agree with those messages (counts per channel,
//   start/end times, chunk, channel and schema counts) and the data section CRC with the bytes;
// - McapStreamReader reads the file again front to back (record structure, chunk CRCs) and must
//   find the same messages (channel, sequence, times, payload) as the indexed reader;
// - every message whose schema encoding is omgidl (message encoding cdr) is decoded with
//   @foxglove/omgidl-parser + @foxglove/omgidl-serialization, the decoder Foxglove uses; every
//   message of a jsonschema schema (message encoding json: --foxglove-scene) is parsed as JSON.
// Prints one JSON line per message ({topic, log_time, publish_time, value}; times as strings of
// ns) or, with --counts-only, one line of counts per topic. --expect-json F: F is a JSON array of
// such objects; the decoded messages must equal it, in log-time order.
// Exit 0 when everything agrees, 1 with one "check_mcap: FILE: reason" line otherwise, 2 on usage.
import { open, readFile } from "node:fs/promises";
import { isDeepStrictEqual } from "node:util";

import { McapIndexedReader, McapStreamReader } from "@mcap/core";
import { parseIDL } from "@foxglove/omgidl-parser";
import { MessageReader } from "@foxglove/omgidl-serialization";
import zstd from "@foxglove/wasm-zstd";
import lz4 from "@foxglove/wasm-lz4";

const args = process.argv.slice(2);
let file;
let expectPath;
let countsOnly = false;
for (let i = 0; i < args.length; ++i) {
  if (args[i] === "--expect-json") expectPath = args[++i];
  else if (args[i] === "--counts-only") countsOnly = true;
  else if (file === undefined && !args[i].startsWith("--")) file = args[i];
  else {
    console.error(`check_mcap: unknown argument '${args[i]}'`);
    process.exit(2);
  }
}
if (file === undefined || (expectPath === undefined && args.includes("--expect-json"))) {
  console.error("usage: node check_mcap.mjs FILE [--expect-json F] [--counts-only]");
  process.exit(2);
}

class Disagreement extends Error {}
const fail = (reason) => {
  throw new Disagreement(reason);
};

// CRC-32 (IEEE), for the data section CRC, which neither official reader checks.
const crcTable = new Uint32Array(256).map((_, n) => {
  let c = n;
  for (let k = 0; k < 8; ++k) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1;
  return c >>> 0;
});
function crc32(bytes) {
  let c = 0xffffffff;
  for (let i = 0; i < bytes.length; ++i) c = crcTable[(c ^ bytes[i]) & 0xff] ^ (c >>> 8);
  return (c ^ 0xffffffff) >>> 0;
}

// A message's identity for comparing the two readers: channel, sequence, times, payload CRC and size.
const messageKey = (m) => `${m.channelId}/${m.sequence}/${m.logTime}/${m.publishTime}/${crc32(m.data)}/${m.data.length}`;

// JSON-friendly values: typed arrays as arrays, bigints as numbers when exact, else strings.
function plain(value) {
  if (typeof value === "bigint") return Number.isSafeInteger(Number(value)) ? Number(value) : value.toString();
  if (ArrayBuffer.isView(value)) return Array.from(value, plain);
  if (Array.isArray(value)) return value.map(plain);
  if (value !== null && typeof value === "object") {
    return Object.fromEntries(Object.entries(value).map(([k, v]) => [k, plain(v)]));
  }
  return value;
}

async function main() {
  await zstd.isLoaded;
  await lz4.isLoaded;
  const decompressHandlers = {
    zstd: (buffer, size) => zstd.decompress(buffer, Number(size)),
    lz4: (buffer, size) => lz4(buffer, Number(size)),
  };
  const handle = await open(file, "r");
  try {
    const size = BigInt((await handle.stat()).size);
    const readable = {
      size: async () => size,
      read: async (offset, length) => {
        if (offset + length > size) fail(`read of ${length} bytes at ${offset} past the end (${size})`);
        const buffer = new Uint8Array(Number(length));
        await handle.read(buffer, 0, buffer.length, Number(offset));
        return buffer;
      },
    };
    const reader = await McapIndexedReader.Initialize({ readable, decompressHandlers });
    const stats = reader.statistics;
    if (!stats) fail("the summary has no Statistics record");

    // Every message through the indexes, CRCs validated.
    const counts = new Map();
    let total = 0n;
    let first;
    let last;
    let previous = -1n;
    const decoded = [];
    const indexed = []; // messageKey() of each message read through the indexes
    const readers = new Map(); // schema id -> MessageReader
    for await (const m of reader.readMessages({ validateCrcs: true })) {
      if (m.logTime < previous) fail(`messages out of log-time order at ${m.logTime}`);
      previous = m.logTime;
      total += 1n;
      indexed.push(messageKey(m));
      counts.set(m.channelId, (counts.get(m.channelId) ?? 0n) + 1n);
      first = first === undefined || m.logTime < first ? m.logTime : first;
      last = last === undefined || m.logTime > last ? m.logTime : last;
      const channel = reader.channelsById.get(m.channelId);
      if (!channel) fail(`message on channel ${m.channelId}, which the summary does not define`);
      const schema = reader.schemasById.get(channel.schemaId);
      if (schema?.encoding === "jsonschema") {  // a derived channel (--foxglove-scene): JSON text
        if (channel.messageEncoding !== "json") fail(`channel ${channel.topic}: message encoding '${channel.messageEncoding}', expected json`);
        let value;
        try {
          value = JSON.parse(new TextDecoder().decode(m.data));
        } catch (error) {
          fail(`channel ${channel.topic}, log time ${m.logTime}: not JSON: ${error.message}`);
        }
        decoded.push({ topic: channel.topic, log_time: m.logTime.toString(), publish_time: m.publishTime.toString(), value });
        continue;
      }
      if (schema?.encoding !== "omgidl") continue;
      if (channel.messageEncoding !== "cdr") fail(`channel ${channel.topic}: message encoding '${channel.messageEncoding}', expected cdr`);
      let messageReader = readers.get(schema.id);
      if (!messageReader) {
        const idl = new TextDecoder().decode(schema.data);
        messageReader = new MessageReader(schema.name, parseIDL(idl));
        readers.set(schema.id, messageReader);
      }
      let value;
      try {
        value = plain(messageReader.readMessage(m.data));
      } catch (error) {
        fail(`channel ${channel.topic}, log time ${m.logTime}: does not decode as ${schema.name}: ${error.message}`);
      }
      decoded.push({ topic: channel.topic, log_time: m.logTime.toString(), publish_time: m.publishTime.toString(), value });
    }

    // The summary must describe those messages.
    const expectEqual = (what, stated, counted) => {
      if (stated !== counted) fail(`Statistics ${what} ${stated}, the messages read give ${counted}`);
    };
    expectEqual("messageCount", stats.messageCount, total);
    expectEqual("chunkCount", stats.chunkCount, reader.chunkIndexes.length);
    expectEqual("channelCount", stats.channelCount, reader.channelsById.size);
    expectEqual("schemaCount", stats.schemaCount, reader.schemasById.size);
    if (total > 0n) {
      expectEqual("messageStartTime", stats.messageStartTime, first);
      expectEqual("messageEndTime", stats.messageEndTime, last);
    }
    for (const id of new Set([...stats.channelMessageCounts.keys(), ...counts.keys()])) {
      expectEqual(`channelMessageCounts[${id}]`, stats.channelMessageCounts.get(id) ?? 0n, counts.get(id) ?? 0n);
    }
    let chunkStart;
    let chunkEnd;
    for (const c of reader.chunkIndexes) {
      if (c.messageStartTime > c.messageEndTime) fail(`chunk at ${c.chunkStartOffset}: start time after end time`);
      chunkStart = chunkStart === undefined || c.messageStartTime < chunkStart ? c.messageStartTime : chunkStart;
      chunkEnd = chunkEnd === undefined || c.messageEndTime > chunkEnd ? c.messageEndTime : chunkEnd;
    }
    if (total > 0n) {
      expectEqual("messageStartTime (chunk indexes)", chunkStart, first);
      expectEqual("messageEndTime (chunk indexes)", chunkEnd, last);
    }

    // The data section CRC.
    if (reader.dataSectionCrc !== undefined && reader.dataSectionCrc !== 0) {
      const dataSection = await readable.read(0n, reader.dataEndOffset);
      const crc = crc32(dataSection);
      if (crc !== reader.dataSectionCrc) fail(`data section CRC mismatch (Data End says ${reader.dataSectionCrc}, bytes give ${crc})`);
    }

    // Front to back with the streaming reader: same messages.
    const stream = new McapStreamReader({ decompressHandlers, validateCrcs: true });
    stream.append(await readFile(file));
    let streamed = 0n;
    let footer = false;
    const inFile = [];
    for (let record; (record = stream.nextRecord()); ) {
      if (record.type === "Message") {
        streamed += 1n;
        inFile.push(messageKey(record));
      }
      if (record.type === "Footer") footer = true;
    }
    if (!stream.done() || !footer) fail("the streaming reader did not reach the footer and closing magic");
    if (streamed !== total) fail(`the streaming reader found ${streamed} messages, the indexed reader ${total}`);
    // The message indexes led to the records themselves: the same messages, field for field.
    indexed.sort();
    inFile.sort();
    for (let i = 0; i < inFile.length; ++i) {
      if (indexed[i] !== inFile[i]) fail(`the indexes lead to message ${indexed[i]}, the records hold ${inFile[i]}`);
    }

    if (expectPath !== undefined) {
      const expected = JSON.parse(await readFile(expectPath, "utf8"));
      if (expected.length !== decoded.length) fail(`${decoded.length} omgidl messages, ${expectPath} expects ${expected.length}`);
      for (let i = 0; i < expected.length; ++i) {
        if (!isDeepStrictEqual(decoded[i], expected[i])) {
          fail(`omgidl message ${i} decodes to ${JSON.stringify(decoded[i])}, ${expectPath} expects ${JSON.stringify(expected[i])}`);
        }
      }
    }
    if (countsOnly) {
      const topics = {};
      for (const [id, n] of counts) topics[reader.channelsById.get(id).topic] = Number(n);
      console.log(JSON.stringify({ file, messages: Number(total), chunks: reader.chunkIndexes.length, topics, decoded: decoded.length }));
    } else {
      for (const d of decoded) console.log(JSON.stringify(d));
    }
  } finally {
    await handle.close();
  }
}

main().catch((error) => {
  // Errors of the official reader (bad CRC, bad magic, ...) and our disagreements: one line.
  const reason = error instanceof Disagreement ? error.message : `${error.name}: ${error.message}`;
  console.error(`check_mcap: ${file}: ${reason.split("\n")[0]}`);
  process.exit(1);
});
