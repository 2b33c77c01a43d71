// The frames of a WebM file, counted by walking its EBML elements: every
// SimpleBlock (0xA3) or Block (0xA1) of the video track is one encoded frame.
// Segments and clusters may have an unknown size (MediaRecorder streams them).
const MASTERS = new Set([0x18538067 /* Segment */, 0x1f43b675 /* Cluster */, 0xa0 /* BlockGroup */]);
const BLOCKS = new Set([0xa3, 0xa1]);

function vint(bytes, at, keepMarker) {
  const first = bytes[at];
  let length = 1;
  while (length <= 8 && !(first & (0x80 >> (length - 1)))) ++length;
  if (length > 8) throw new Error(`bad EBML number at byte ${at}`);
  let value = keepMarker ? first : first & (0xff >> length);
  let unknown = (first & (0xff >> length)) === (0xff >> length);
  for (let i = 1; i < length; ++i) { value = value * 256 + bytes[at + i]; unknown = unknown && bytes[at + i] === 0xff; }
  return { value, length, unknown };
}

// {frames, width, height} of a WebM in `bytes` (a Uint8Array or Buffer).
export function webmFrames(bytes) {
  let frames = 0, width = null, height = null;
  let at = 0;
  while (at < bytes.length) {
    const id = vint(bytes, at, true);
    const size = vint(bytes, at + id.length, false);
    const body = at + id.length + size.length;
    if (id.value === 0xb0) width = readUint(bytes, body, size.value);      // PixelWidth
    if (id.value === 0xba) height = readUint(bytes, body, size.value);     // PixelHeight
    if (BLOCKS.has(id.value)) ++frames;
    // descend into masters, and into the Tracks → TrackEntry → Video path for the size
    if (MASTERS.has(id.value) || size.unknown || [0x1654ae6b, 0xae, 0xe0].includes(id.value)) { at = body; continue; }
    at = body + size.value;
  }
  return { frames, width, height };
}

function readUint(bytes, at, length) {
  let v = 0;
  for (let i = 0; i < length; ++i) v = v * 256 + bytes[at + i];
  return v;
}
