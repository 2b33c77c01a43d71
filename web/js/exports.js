// Pictures and videos to take away: a view or a chart as a PNG at a chosen
// size (drawn afresh at that size, not a screenshot), a figure for a paper
// (the views, the main charts, a legend and the run's metadata in one PNG),
// and a replay as a WebM video with exactly one encoded frame per stored
// frame of the chosen range, at the chosen rate (encoded with the browser's
// WebCodecs and written as WebM by webm_writer.js).
import { WebmWriter } from './webm_writer.js';
import { figureLayout } from './figure_layout.js';

export const LIMITS = { minSide: 16, maxSide: 4096, maxFrames: 20000, maxFps: 120 };

// Checks an export's numbers; throws an Error naming the field.
export function checkSize(width, height) {
  for (const [name, v] of [['width', width], ['height', height]]) {
    if (!Number.isInteger(v) || v < LIMITS.minSide || v > LIMITS.maxSide) throw new Error(`${name} must be a whole number of pixels in [${LIMITS.minSide}, ${LIMITS.maxSide}], not ${v}`);
  }
}

export function checkRange(from, to, last, fps) {
  if (!Number.isInteger(from) || !Number.isInteger(to) || from < 0 || to > last || from > to) throw new Error(`frames must satisfy 0 ≤ from ≤ to ≤ ${last}, not ${from}–${to}`);
  if (to - from + 1 > LIMITS.maxFrames) throw new Error(`at most ${LIMITS.maxFrames} frames per video`);
  if (!(fps > 0 && fps <= LIMITS.maxFps)) throw new Error(`the rate must be in (0, ${LIMITS.maxFps}] frames per second`);
}

export function download(blob, name) {
  const a = document.createElement('a');
  a.href = URL.createObjectURL(blob);
  a.download = name;
  document.body.appendChild(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(a.href), 60000);
}

const toBlob = (canvas, type = 'image/png') => new Promise((resolve, reject) => canvas.toBlob((b) => (b ? resolve(b) : reject(new Error('the browser could not encode the image'))), type));

// The lanes' views side by side (one row) in a width × height canvas, or the
// one view of an overlaid compare.
export function viewsCanvas(session, width, height, into = null) {
  const lanes = session.lanes.filter((l) => l.view);
  const out = into || document.createElement('canvas');
  out.width = width;
  out.height = height;
  const c = out.getContext('2d');
  c.fillStyle = '#fff';
  c.fillRect(0, 0, width, height);
  const gap = lanes.length > 1 ? Math.round(width * 0.006) : 0;
  const cell = Math.floor((width - gap * (lanes.length - 1)) / Math.max(1, lanes.length));
  lanes.forEach((lane, i) => {
    const w = i === lanes.length - 1 ? width - (cell + gap) * i : cell;
    c.drawImage(lane.view.renderAt(w, height), (cell + gap) * i, 0);
  });
  return out;
}

export async function viewPng(session, width, height) {
  checkSize(width, height);
  return toBlob(viewsCanvas(session, width, height));
}

// One chart with its title above, exactly width × height pixels.
export async function chartPng(plots, id, width, height) {
  checkSize(width, height);
  const ratio = window.devicePixelRatio || 1;
  const title = Math.round(height * 0.12);
  const image = await plots.chartImage(id, Math.round(width / ratio), Math.round((height - title) / ratio));
  if (!image) throw new Error(`no chart "${id}" on the page`);
  const out = document.createElement('canvas');
  out.width = width;
  out.height = height;
  const c = out.getContext('2d');
  c.fillStyle = '#fff';
  c.fillRect(0, 0, width, height);
  c.fillStyle = '#37474f';
  c.font = `600 ${Math.round(title * 0.6)}px system-ui, sans-serif`;
  c.fillText(image.title, Math.round(width * 0.01), Math.round(title * 0.75));
  c.drawImage(image.canvas, 0, title, width, height - title);
  return toBlob(out);
}

// A figure for a paper: the views, the task-error and distance charts, a
// legend of the lanes and the run's metadata, `width` pixels wide.
export async function figurePng(session, plots, { width, meta }) {
  checkSize(width, Math.round(width * 0.5));
  const ratio = window.devicePixelRatio || 1;
  const viewHeight = Math.round(width * (session.lanes.length > 1 && session.layout !== 'overlay' ? 0.5 / Math.min(2, session.lanes.length - 0.5) : 0.55));
  const chartHeight = Math.round(width * 0.2);
  const charts = [];
  for (const id of ['error', 'distance']) {
    const image = await plots.chartImage(id, Math.round(width / ratio), Math.round(chartHeight / ratio));
    if (image) charts.push(image);
  }
  const out = document.createElement('canvas');
  const c = out.getContext('2d');
  const measure = (text, font) => { c.font = font; return c.measureText(text).width; };
  const layout = figureLayout({ width, viewHeight, chartHeight, charts: charts.map((image) => ({ title: image.title, image })), lanes: session.lanes, meta }, measure);
  checkSize(width, layout.height);
  out.width = width;
  out.height = layout.height;
  c.fillStyle = '#fff';
  c.fillRect(0, 0, out.width, out.height);
  for (const box of layout.boxes) {
    if (box.kind === 'views') c.drawImage(viewsCanvas(session, box.w, box.h), box.x, box.y);
    else if (box.kind === 'chart') c.drawImage(box.chart.image.canvas, box.x, box.y, box.w, box.h);
    else if (box.kind === 'swatch') { c.fillStyle = box.colour; c.fillRect(box.x, box.y, box.w, box.h); }
    else { c.font = box.font; c.fillStyle = box.colour; c.fillText(box.text, box.x, box.y + box.h * 0.8); }
  }
  figurePng.lastLayout = layout;  // what went where: the browser test checks its boxes
  return toBlob(out);
}

// The first encoder configuration this browser supports (VP9, else VP8).
async function videoConfig(width, height, fps) {
  if (!window.VideoEncoder) throw new Error('this browser cannot encode video (no WebCodecs VideoEncoder)');
  const bitrate = Math.min(20e6, Math.max(5e5, width * height * fps * 0.15));
  for (const [codec, codecId] of [['vp09.00.10.08', 'V_VP9'], ['vp8', 'V_VP8']]) {
    const config = { codec, width, height, bitrate, framerate: fps };
    const { supported } = await VideoEncoder.isConfigSupported(config).catch(() => ({ supported: false }));
    if (supported) return { config, codecId };
  }
  throw new Error(`this browser cannot encode a ${width}×${height} VP8 or VP9 video`);
}

// A replay's frames from..to (every `stride`-th) as a WebM of width × height
// at `fps`: each frame is shown on every lane (showFrame resolves when all
// lanes show it), drawn into a canvas and encoded once with the timestamp
// i / fps (WebCodecs, written as WebM here), so the video holds exactly one
// frame per stored frame and its timing is the chosen rate. onProgress(done, total).
export async function recordVideo(session, showFrame, { from, to, stride = 1, fps, width, height, onProgress = () => {}, cancelled = () => false }) {
  checkSize(width, height);
  const { config, codecId } = await videoConfig(width, height, fps);
  const writer = new WebmWriter({ codecId, width, height, fps });
  let failure = null;
  const encoder = new VideoEncoder({
    output: (chunk) => {
      const bytes = new Uint8Array(chunk.byteLength);
      chunk.copyTo(bytes);
      writer.add(bytes, chunk.timestamp, chunk.type === 'key');
    },
    error: (e) => { failure = e; },
  });
  encoder.configure(config);
  const canvas = document.createElement('canvas');
  const seqs = [];
  for (let k = from; k <= to; k += stride) seqs.push(k);
  const period = 1e6 / fps;  // µs
  try {
    for (let i = 0; i < seqs.length; ++i) {
      if (cancelled()) throw new Error('the video export was cancelled');
      if (failure) throw failure;
      await showFrame(seqs[i]);
      viewsCanvas(session, width, height, canvas);
      const frame = new VideoFrame(canvas, { timestamp: Math.round(i * period), duration: Math.round(period) });
      encoder.encode(frame, { keyFrame: i % 60 === 0 });
      frame.close();
      while (encoder.encodeQueueSize > 4) await new Promise((resolve) => setTimeout(resolve, 1));
      onProgress(i + 1, seqs.length);
    }
    await encoder.flush();
    if (failure) throw failure;
  } finally {
    if (encoder.state !== 'closed') encoder.close();
  }
  return { blob: new Blob([writer.finish()], { type: 'video/webm' }), frames: seqs.length };
}
