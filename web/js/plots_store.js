// One lane's time series, column by column: t, the step metrics and every
// diagnostic of the lane's method (kept even when its chart is not shown, so
// ticking a diagnostic fills its chart at once). Live lanes keep a rolling
// window with a hard cap; replay lanes hold a whole stored run.

// The metrics a lane keeps: the frame field table's numeric metrics that
// frames carry (GET /api/frame-fields, app.frameFields), in the table's
// order, so a metric added to the table is charted without a change here.
export function chartedMetrics(fields) {
  return fields
    .filter((f) => f.metric && f.kind === 'number' && Array.isArray(f.outputs) && f.outputs.includes('json'))
    .map((f) => f.name);
}

// Metrics drawn on a log axis keep only positive values.
const LOG_METRICS = new Set(['condition_number']);

export const diagnosticKey = (name) => `diag:${name}`;

// A hard cap per live lane whatever the window: 100 steps/s over 20 s.
const LIVE_CAP = 2000;

// null for anything a chart cannot place (null, NaN, ±Infinity, strings).
function finite(v) {
  return typeof v === 'number' && Number.isFinite(v) ? v : null;
}

// The condition number goes on a log axis: only positive values fit there.
function positive(v) {
  const x = finite(v);
  return x !== null && x > 0 ? x : null;
}

export class LaneSeries {
  constructor(diagnosticNames, metricKeys) {
    this.diagnosticNames = diagnosticNames.slice();
    this.metricKeys = metricKeys.slice();
    this.keys = [...this.metricKeys, ...this.diagnosticNames.map(diagnosticKey)];
    this.index = new Map(this.keys.map((k, i) => [k, i]));
    this.clear();
  }

  clear() {
    this.t = [];
    this.columns = this.keys.map(() => []);
    this.orientationSeen = false;  // any non-zero orientation error (pose tasks)
  }

  column(key) {
    const i = this.index.get(key);
    return i === undefined ? null : this.columns[i];
  }

  get length() { return this.t.length; }

  // One WebSocket frame. A repeated t is skipped (the display timer may
  // resend the newest frame); an earlier t means the run was reset: start over.
  // Returns whether the lane changed.
  appendLive(frame, windowSeconds) {
    const t = finite(frame.t);
    if (t === null) return false;
    const last = this.t.length ? this.t[this.t.length - 1] : null;
    if (last !== null && t === last) return false;
    if (last !== null && t < last) this.clear();
    this.appendFrame(t, frame);
    this.dropBefore(t - windowSeconds);
    return true;
  }

  // Stored frames from api.frames (a run's frames route), in the stream's shape
  // (step_us is not stored: its column holds nulls).
  setStored(frames) {
    this.clear();
    for (const f of frames) {
      const t = finite(f.t);
      if (t !== null) this.appendFrame(t, f);
    }
  }

  // A frame's row, live or stored (docs/api.md, Frames): metrics inside
  // `metrics`, diagnostics an array in the order of the lane's names.
  appendFrame(t, frame) {
    this.t.push(t);
    const c = this.columns;
    const m = frame.metrics && typeof frame.metrics === 'object' ? frame.metrics : {};
    this.metricKeys.forEach((key, i) => c[i].push(LOG_METRICS.has(key) ? positive(m[key]) : finite(m[key])));
    const orientation = finite(m.orientation_error);
    if (orientation !== null && orientation !== 0) this.orientationSeen = true;
    const d = Array.isArray(frame.diagnostics) ? frame.diagnostics : [];
    const n = this.metricKeys.length;
    this.diagnosticNames.forEach((name, i) => c[n + i].push(finite(d[i])));
  }

  // Keeps one point older than the window so the line reaches the left edge.
  dropBefore(tMin) {
    let cut = 0;
    while (cut + 1 < this.t.length && this.t[cut + 1] < tMin) ++cut;
    cut = Math.max(cut, this.t.length - LIVE_CAP);
    if (cut <= 0) return;
    this.t.splice(0, cut);
    for (const col of this.columns) col.splice(0, cut);
  }
}
