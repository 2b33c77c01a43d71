// A minimal WebM (Matroska) writer for one video track of encoded chunks from
// WebCodecs' VideoEncoder: EBML header, Segment with Info and Tracks, and a
// Cluster per key frame holding SimpleBlocks with their own timestamps, so the
// video's timing is the one asked for, not the wall clock's. Pure: no DOM.

const te = new TextEncoder();

// An EBML element ID (its marker bits included) as bytes.
function idBytes(id) {
  const out = [];
  for (let v = id; v > 0; v = Math.floor(v / 256)) out.unshift(v & 0xff);
  return out;
}

// A data size as an 8-byte EBML number (simple, and never too short).
function sizeBytes(size) {
  const out = [0x01];
  for (let i = 6; i >= 0; --i) out.push(Math.floor(size / 2 ** (8 * i)) & 0xff);
  return out;
}

function uintBytes(v) {
  const out = [];
  do { out.unshift(v & 0xff); v = Math.floor(v / 256); } while (v > 0);
  return out;
}

function concat(parts) {
  const length = parts.reduce((n, p) => n + p.length, 0);
  const out = new Uint8Array(length);
  let at = 0;
  for (const p of parts) { out.set(p, at); at += p.length; }
  return out;
}

// An element from its id and body (bytes, or a list of child elements).
export function element(id, body) {
  const data = Array.isArray(body) && body.length && body[0] instanceof Uint8Array ? concat(body) : body instanceof Uint8Array ? body : new Uint8Array(body);
  return concat([new Uint8Array(idBytes(id)), new Uint8Array(sizeBytes(data.length)), data]);
}

const uint = (id, v) => element(id, new Uint8Array(uintBytes(v)));
const text = (id, s) => element(id, te.encode(s));
function float64(id, v) {
  const b = new Uint8Array(8);
  new DataView(b.buffer).setFloat64(0, v);
  return element(id, b);
}

// {codecId: 'V_VP8' | 'V_VP9', width, height, fps}; add(chunk bytes, timestamp µs, key) in order; finish() → Uint8Array.
export class WebmWriter {
  constructor({ codecId, width, height, fps }) {
    this.head = { codecId, width, height, fps };
    this.clusters = [];
    this.cluster = null;
    this.lastUs = 0;
  }

  add(bytes, timestampUs, key) {
    const ms = Math.round(timestampUs / 1000);
    // a new cluster at each key frame (and before a block's relative time would overflow 16 bits)
    if (!this.cluster || key || ms - this.cluster.ms > 30000) {
      this.cluster = { ms, blocks: [] };
      this.clusters.push(this.cluster);
    }
    const relative = ms - this.cluster.ms;
    const header = new Uint8Array([0x81, (relative >> 8) & 0xff, relative & 0xff, key ? 0x80 : 0x00]);  // track 1, time, flags
    this.cluster.blocks.push(element(0xa3, concat([header, bytes])));
    this.lastUs = timestampUs;
  }

  finish() {
    const { codecId, width, height, fps } = this.head;
    const ebml = element(0x1a45dfa3, [uint(0x4286, 1), uint(0x42f7, 1), uint(0x42f2, 4), uint(0x42f3, 8), text(0x4282, 'webm'), uint(0x4287, 4), uint(0x4285, 2)]);
    const durationMs = this.lastUs / 1000 + 1000 / fps;
    const info = element(0x1549a966, [uint(0x2ad7b1, 1000000), float64(0x4489, durationMs), text(0x4d80, 'rrlab'), text(0x5741, 'rrlab')]);
    const video = element(0xe0, [uint(0xb0, width), uint(0xba, height)]);
    const track = element(0xae, [uint(0xd7, 1), uint(0x73c5, 1), uint(0x83, 1), text(0x86, codecId), uint(0x23e383, Math.round(1e9 / fps)), video]);
    const tracks = element(0x1654ae6b, [track]);
    const clusters = this.clusters.map((c) => element(0x1f43b675, [uint(0xe7, c.ms), ...c.blocks]));
    const segment = element(0x18538067, [info, tracks, ...clusters]);
    return concat([ebml, segment]);
  }
}
