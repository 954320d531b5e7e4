// The independent MAVLink decoder of trnkit's tests: node-mavlink's splitter (framing, CRC with the
// CRC_EXTRA of mavlink-mappings, generated from the MAVLink XML) and parser, never trnkit's code.
//   node decode_mavlink.js FILE                 decode a file of concatenated frames
//   node decode_mavlink.js --udp IDLE_MS        listen on 127.0.0.1 (port printed first as {"port": N});
//                                               stop IDLE_MS after the last datagram (or 120 s without any)
// Prints one JSON line per packet: header, payload length, message name and every field by its XML
// name (64-bit integers as decimal strings, NaN as "NaN"), then {"end": true, packets, crc_errors, ...}.
'use strict';
const dgram = require('dgram');
const fs = require('fs');
const { PassThrough } = require('stream');
const { MavLinkPacketSplitter, MavLinkPacketParser } = require('node-mavlink');
// The definitions from mavlink-mappings 1.0.22 (package.json), not node-mavlink's own older copy:
// the first with GLOBAL_POSITION_SENSOR (296) in common.
const { minimal, common } = require('mavlink-mappings');

const registry = { ...minimal.REGISTRY, ...common.REGISTRY };
// The checksum seeds of the classes we decode with (the package's default table merges dialects).
const magicNumbers = {};
for (const [id, clazz] of Object.entries(registry)) magicNumbers[id] = clazz.MAGIC_NUMBER;

const counts = { packets: 0, crc_errors: 0, unknown: 0, datagrams: 0 };

function plain(value) {
  if (typeof value === 'bigint') return value.toString();
  if (typeof value === 'number' && Number.isNaN(value)) return 'NaN';
  if (Array.isArray(value)) return value.map(plain);
  return value;
}

function decoder() {
  const input = new PassThrough();
  const packets = input
    .pipe(new MavLinkPacketSplitter({}, { magicNumbers, onCrcError: () => { counts.crc_errors += 1; } }))
    .pipe(new MavLinkPacketParser());
  packets.on('data', (packet) => {
    counts.packets += 1;
    const h = packet.header;
    const line = { msgid: h.msgid, seq: h.seq, sysid: h.sysid, compid: h.compid, magic: h.magic,
                   incompat: h.incompatibilityFlags, compat: h.compatibilityFlags, len: h.payloadLength };
    const clazz = registry[h.msgid];
    if (!clazz) {
      counts.unknown += 1;
    } else {
      const data = packet.protocol.data(packet.payload, clazz);
      line.name = clazz.MSG_NAME;
      line.fields = {};
      for (const field of clazz.FIELDS) line.fields[field.source] = plain(data[field.name]);
    }
    process.stdout.write(JSON.stringify(line) + '\n');
  });
  return { input, packets };
}

function finish(d) {
  d.packets.on('end', () => process.stdout.write(JSON.stringify({ end: true, ...counts }) + '\n'));
  d.input.end();
}

const args = process.argv.slice(2);
if (args.length === 2 && args[0] === '--udp') {
  const idleMs = Number(args[1]);
  const d = decoder();
  const socket = dgram.createSocket('udp4');
  let timer = setTimeout(() => { socket.close(); finish(d); }, 120000);
  socket.on('message', (msg) => {
    counts.datagrams += 1;
    d.input.write(msg);
    clearTimeout(timer);
    timer = setTimeout(() => { socket.close(); finish(d); }, idleMs);
  });
  socket.bind(0, '127.0.0.1', () => process.stdout.write(JSON.stringify({ port: socket.address().port }) + '\n'));
} else if (args.length === 1) {
  const d = decoder();
  d.input.write(fs.readFileSync(args[0]));
  finish(d);
} else {
  process.stderr.write('usage: decode_mavlink.js FILE | --udp IDLE_MS\n');
  process.exit(2);
}
