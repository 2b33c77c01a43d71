// The right-hand measurements: metrics (a column per lane in a compare),
// joint-limit bars of the focused lane, and its method's diagnostics. Drawn
// from the render loop at most 10 times a second, when a lane's snapshot or
// frame or the focus changed.
import { app } from './state.js';
import { fmt } from './dom.js';

const $ = (id) => document.getElementById(id);

const ROWS = [
  ['task error (m)', (m) => m.task_error],
  ['orientation error (rad)', (m) => m.orientation_error],
  ['min distance (m)', (m) => m.min_distance],
  ['nearest link', (m) => m.min_distance_link],
  ['collided', (m) => m.collided],
  // self-collision (frames from blob v3 on; older runs show —)
  ['min self distance (m)', (m) => m.min_self_distance],
  ['nearest self pair', (m) => (m.self_link_a > 0 ? `${m.self_link_a} · ${m.self_link_b}` : null)],
  ['self-collided', (m) => m.self_collided],
  ['joint-limit margin', (m) => m.joint_limit_margin],
  ['manipulability', (m) => m.manipulability],
  ['condition number', (m) => m.condition_number],
  ['step (µs)', (m) => m.step_us],
];

// Three significant digits where 3–4 lanes share the column's width (the
// full value in the tooltip): readable, not cut to "0.23…".
function fmtCompact(v) {
  if (typeof v !== 'number' || Number.isInteger(v) || !Number.isFinite(v)) return fmt(v);
  return Math.abs(v) >= 1e4 || (Math.abs(v) < 1e-3 && v !== 0) ? v.toExponential(1) : String(Number(v.toPrecision(3)));
}

function cell(row, value, compact) {
  const td = row.insertCell();
  td.textContent = compact ? fmtCompact(value) : fmt(value);
  if (compact) td.title = fmt(value);
  if (value === true) td.className = 'collided';
  return td;
}

// The panel: render(now) is called at the display rate; tables are text for
// people, so 10 updates a second are plenty and spare the layout work.
export class MetricsPanel {
  constructor() {
    this.dirty = false;
    this.last = 0;
    const touched = (lane) => { if (app.session && app.session.lanes.includes(lane)) this.dirty = true; };
    app.signals.snapshot.add(touched);
    app.signals.frame.add(touched);
    app.signals.focusChanged.add(() => { this.dirty = true; });
  }

  render(now) {
    if (!this.dirty || now - this.last < 100) return;
    this.dirty = false;
    this.last = now;
    showMetrics(app.session);
  }
}

function showMetrics(session) {
  const table = $('metrics');
  table.replaceChildren();
  if (!session) return;
  const lanes = session.lanes.filter((l) => l.frame);
  if (!lanes.length) return;
  const compact = session.compare && lanes.length >= 3;
  table.classList.toggle('compact', compact);
  if (session.compare) {
    const head = table.createTHead().insertRow();
    head.appendChild(document.createElement('th'));
    for (const lane of lanes) {
      const th = document.createElement('th');
      // break a narrow column's name after "_" and before "·", not inside a word
      th.textContent = compact ? lane.label.replace(/_/g, '_\u200b').replace(/ · /g, ' ·\u200b') : lane.label;
      th.style.color = lane.colour;
      head.appendChild(th);
    }
  }
  const body = table.createTBody();
  const time = body.insertRow();
  time.insertCell().textContent = 't (s) · step';
  for (const lane of lanes) time.insertCell().textContent = compact ? lane.frame.t.toFixed(2) : `${lane.frame.t.toFixed(2)} · ${lane.frame.step}`;
  if (compact) time.cells[0].textContent = 't (s)';
  for (const [name, get] of ROWS) {
    const row = body.insertRow();
    row.insertCell().textContent = name;
    for (const lane of lanes) cell(row, get(lane.frame.metrics), compact);
  }
  showLimits(session.focusLane);
  showDiagnostics(session.focusLane);
}

// One bar per joint with finite limits: the marker is q between lower and upper.
function showLimits(lane) {
  const box = $('limit-bars');
  if (!lane || !lane.snapshot || !lane.frame) { box.replaceChildren(); return; }
  const { lower, upper } = lane.snapshot.model.limits;
  const q = lane.frame.q;
  // an arm without position limits: say so rather than draw empty bars
  const bounded = (i) => lower && upper && lower[i] !== null && upper[i] !== null && upper[i] > lower[i];
  if (!q.some((_, i) => bounded(i))) {
    if (!box.querySelector('.no-limits')) box.innerHTML = '<p class="no-limits muted small">This arm has no joint position limits.</p>';
    return;
  }
  if (box.childElementCount !== q.length) {
    box.replaceChildren();
    for (let i = 0; i < q.length; ++i) {
      const row = document.createElement('div');
      row.className = 'limit-bar';
      row.innerHTML = `<span>q${i + 1}</span><span class="track"><span class="mark"></span></span><span class="mono"></span>`;
      box.appendChild(row);
    }
  }
  q.forEach((value, i) => {
    const row = box.children[i];
    const lo = lower ? lower[i] : null, hi = upper ? upper[i] : null;
    const bounded = lo !== null && hi !== null && hi > lo;
    const f = bounded ? (value - lo) / (hi - lo) : 0.5;
    row.querySelector('.mark').style.left = `calc(${Math.min(1, Math.max(0, f)) * 100}% - 1px)`;
    row.querySelector('.mark').style.display = bounded ? '' : 'none';
    row.querySelector('.mono').textContent = `${((value * 180) / Math.PI).toFixed(1)}°`;
    row.title = bounded ? `q${i + 1} = ${value.toFixed(4)} rad in [${lo.toFixed(3)}, ${hi.toFixed(3)}]` : `q${i + 1}: unbounded`;
    row.classList.toggle('out', bounded && (f < 0 || f > 1));
    row.classList.toggle('near', bounded && f >= 0 && f <= 1 && Math.min(f, 1 - f) < 0.05);
  });
}

function showDiagnostics(lane) {
  const table = $('diagnostics');
  table.replaceChildren();
  if (!lane || !lane.snapshot || !lane.frame) return;
  lane.snapshot.diagnostic_names.forEach((name, i) => {
    const row = table.insertRow();
    row.insertCell().textContent = name;
    cell(row, lane.frame.diagnostics[i]);
  });
}
