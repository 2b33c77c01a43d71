// The dashboard: pick a scenario and method, start a live run, watch it,
// change parameters, drag obstacles, steer a joystick task, replay stored runs.
import { api, openStream } from './api.js';
import { View2D } from './view2d.js';

const $ = (id) => document.getElementById(id);
const view = new View2D($('view'));
window.__rrlabView = view;  // browser tests map world points to the page
const state = { runId: null, replayId: null, socket: null, snapshot: null, frame: null, drag: null, methods: [] };

function fmt(v) {
  if (v === null || v === undefined) return '—';
  if (typeof v === 'boolean') return v ? 'yes' : 'no';
  if (Number.isInteger(v)) return String(v);
  return Math.abs(v) >= 1e4 || (Math.abs(v) < 1e-3 && v !== 0) ? v.toExponential(3) : v.toFixed(4);
}

function table(element, rows) {
  element.innerHTML = '';
  for (const [name, value, cls] of rows) {
    const tr = element.insertRow();
    tr.insertCell().textContent = name;
    const td = tr.insertCell();
    td.textContent = fmt(value);
    if (cls) td.className = cls;
  }
}

function showError(error) { $('status').textContent = `⚠ ${error.message}`; }

async function loadCatalogue() {
  const [scenarios, methods] = await Promise.all([api('GET', '/api/scenarios'), api('GET', '/api/methods')]);
  state.methods = methods;
  $('scenario').innerHTML = scenarios.map((s) => `<option value="${s.name}" title="${s.description.replace(/"/g, '&quot;')}">${s.name}</option>`).join('');
  $('method').innerHTML = '<option value="">(scenario\'s own)</option>' +
    methods.map((m) => `<option value="${m.name}" title="${m.description}">${m.name}</option>`).join('');
}

async function refreshRuns() {
  const runs = await api('GET', '/api/runs?limit=30');
  $('runs').innerHTML = '';
  for (const r of runs) {
    const li = document.createElement('li');
    li.innerHTML = `<span>#${r.id} ${r.scenario}<br><span class="muted">${r.method} · ${r.mode} · ${r.status} · ${r.frames} frames</span></span>`;
    if (r.frames > 0 && r.status !== 'running' && r.status !== 'paused') {
      const button = document.createElement('button');
      button.textContent = 'Replay';
      button.onclick = () => replay(r.id).catch(showError);
      li.appendChild(button);
    }
    $('runs').appendChild(li);
  }
}

function connect(path) {
  if (state.socket) state.socket.close();
  state.snapshot = null;
  state.frame = null;
  $('connection').textContent = `connecting ${path}`;
  state.socket = openStream(path, {
    onSnapshot: (snapshot) => {
      const first = !state.snapshot;
      state.snapshot = snapshot;
      if (first) view.fit(snapshot);
      if (snapshot.frame) state.frame = snapshot.frame;
      buildParams(snapshot);
      $('joystick-help').hidden = snapshot.task.trajectory !== 'joystick';
      $('connection').textContent = `${path} · ${snapshot.scenario} · ${snapshot.method}`;
      render();
    },
    onFrame: (frame) => { state.frame = frame; render(); },
    onMessage: (message) => { if (message.type === 'error') showError(new Error(message.error.message)); },
    onClose: () => { $('connection').textContent = 'disconnected'; refreshRuns().catch(() => {}); },
  });
}

function render() {
  view.draw(state.snapshot, state.frame, state.drag ? state.drag.index : null);
  const f = state.frame;
  if (!f || !state.snapshot) return;
  const m = f.metrics;
  $('status').textContent = `t = ${f.t.toFixed(2)} s · step ${f.step} · ${f.status}`;
  table($('metrics'), [
    ['task error (m)', m.task_error], ['min distance (m)', m.min_distance],
    ['nearest link', m.min_distance_link], ['collided', m.collided, m.collided ? 'collided' : ''],
    ['joint-limit margin', m.joint_limit_margin], ['manipulability', m.manipulability],
    ['condition number', m.condition_number], ['step (µs)', m.step_us],
  ]);
  table($('diagnostics'), state.snapshot.diagnostic_names.map((name, i) => [name, f.diagnostics[i]]));
}

// Sliders (or selects for enumerations) from the method's parameter specs.
function buildParams(snapshot) {
  const box = $('params');
  box.innerHTML = '';
  $('params-section').hidden = snapshot.param_specs.length === 0 || state.replayId !== null;
  for (const spec of snapshot.param_specs) {
    const div = document.createElement('div');
    div.className = 'param';
    const value = snapshot.params[spec.name];
    div.title = spec.help;
    if (spec.choices && spec.choices.length) {
      div.innerHTML = `<label>${spec.label}<select>${spec.choices.map((c, i) => `<option value="${i}" ${i === value ? 'selected' : ''}>${c}</option>`).join('')}</select></label>`;
      div.querySelector('select').onchange = (e) => setParam(spec.name, Number(e.target.value));
    } else {
      // a spec step that does not divide (max - min) from min would reject values: any value then
      const step = spec.step && Number.isInteger((spec.max - spec.min) / spec.step) ? spec.step : 'any';
      div.innerHTML = `${spec.label} <span class="value">${fmt(value)} ${spec.unit}</span>
        <input type="range" min="${spec.min}" max="${spec.max}" step="${step}" value="${value}">`;
      const input = div.querySelector('input');
      input.oninput = () => { div.querySelector('.value').textContent = `${fmt(Number(input.value))} ${spec.unit}`; };
      input.onchange = () => setParam(spec.name, Number(input.value));
    }
    box.appendChild(div);
  }
}

async function setParam(name, value) {
  if (!state.runId) return;
  await api('PATCH', `/api/runs/${state.runId}/params`, { [name]: value }).catch(showError);
}

async function startRun(mode) {
  const body = { scenario: $('scenario').value, mode, rate: Number($('rate').value) };
  if ($('method').value) body.method = $('method').value;
  if (mode === 'batch') {
    $('status').textContent = 'running…';
    const result = await api('POST', '/api/runs', body);
    $('status').textContent = `batch run #${result.id}: ${result.summary.steps} steps, max tracking error ${fmt(result.summary.max_tracking_error)} m, ${result.summary.collided ? 'collided' : 'no collision'}`;
    await refreshRuns();
    return;
  }
  const run = await api('POST', '/api/runs', body);
  state.runId = run.id;
  state.replayId = null;
  $('run-id').textContent = `#${run.id}`;
  $('controls').hidden = false;
  connect(run.ws);
  refreshRuns().catch(() => {});
}

async function replay(id) {
  const player = await api('POST', `/api/runs/${id}/replay`, { mode: 'frames', speed: 1 });
  state.runId = null;
  state.replayId = player.replay;
  $('controls').hidden = true;
  connect(player.ws);
}

async function control(action) {
  if (!state.runId) return;
  await api('POST', `/api/runs/${state.runId}/control`, { action }).catch(showError);
}

// Dragging an obstacle moves it live (PUT, at most 20 times a second).
function pointer(event) {
  const rect = view.canvas.getBoundingClientRect();
  return [(event.clientX - rect.left) * (view.canvas.width / rect.width), (event.clientY - rect.top) * (view.canvas.height / rect.height)];
}
view.canvas.addEventListener('pointerdown', (event) => {
  if (!state.runId) return;
  const [x, y] = pointer(event);
  const index = view.hit(state.snapshot, state.frame, x, y);
  if (index === null) return;
  state.drag = { index, start: view.toWorld(x, y), from: state.frame.obstacles[index].slice(), last: 0 };
  view.canvas.setPointerCapture(event.pointerId);
});
view.canvas.addEventListener('pointermove', (event) => {
  const drag = state.drag;
  if (!drag) return;
  const [x, y] = pointer(event);
  const [wx, wy] = view.toWorld(x, y);
  const position = [drag.from[0] + wx - drag.start[0], drag.from[1] + wy - drag.start[1], drag.from[2]];
  state.frame.obstacles[drag.index] = position;
  render();
  const now = performance.now();
  if (now - drag.last < 50) return;
  drag.last = now;
  const id = state.snapshot.obstacles[drag.index].id;
  api('PUT', `/api/runs/${state.runId}/obstacles/${encodeURIComponent(id)}`, { position }).catch(showError);
});
view.canvas.addEventListener('pointerup', () => { state.drag = null; });

// Keyboard joystick: held keys set a velocity; releasing all stops it.
const held = new Set();
const keys = { ArrowUp: [0, 1], ArrowDown: [0, -1], ArrowLeft: [-1, 0], ArrowRight: [1, 0], w: [0, 1], s: [0, -1], a: [-1, 0], d: [1, 0] };
function joystick() {
  if (!state.runId || !state.snapshot || state.snapshot.task.trajectory !== 'joystick') return;
  const speed = 0.2 * Math.max(0.25, state.snapshot.model.reach / 3);
  let vx = 0, vy = 0;
  for (const k of held) { vx += keys[k][0]; vy += keys[k][1]; }
  api('POST', `/api/runs/${state.runId}/joystick`, { linear: [vx * speed, vy * speed] }).catch(showError);
}
window.addEventListener('keydown', (e) => {
  if (!(e.key in keys) || held.has(e.key) || e.target.tagName === 'SELECT') return;
  held.add(e.key);
  e.preventDefault();
  joystick();
});
window.addEventListener('keyup', (e) => { if (held.delete(e.key)) joystick(); });

$('start-live').onclick = () => startRun('live').catch(showError);
$('start-batch').onclick = () => startRun('batch').catch(showError);
for (const button of document.querySelectorAll('[data-action]')) button.onclick = () => control(button.dataset.action);

loadCatalogue().then(refreshRuns).catch(showError);
view.draw(null, null);
