// The parameter panel of the focused lane: a slider (or a select for an
// enumeration) per parameter spec, its help as a tooltip, a reset to the
// default, and the method switch. Changes go to the lane's own run, as
// input commands. The panel follows the focused lane's snapshots.
import { app } from './state.js';
import { escapeHtml as escape, fmt } from './dom.js';
import { typedNumber } from './typed_number.js';

const $ = (id) => document.getElementById(id);

// A slider's step must divide (max - min) from min, or the browser rejects
// values in between: then any value.
function sliderStep(spec) {
  return spec.step && Number.isInteger(Math.round(((spec.max - spec.min) / spec.step) * 1e9) / 1e9) ? spec.step : 'any';
}

// A log slider moves in twentieths of a decade (a step is ×1.12) and sets two
// significant digits (1.0, 1.1, 1.3, … 8.9): fine enough to choose, coarse
// enough that the keyboard's steps land on the same values both ways.
const STEPS_PER_DECADE = 20;

// How a slider maps a parameter's range: linear, or logarithmic where the
// range spans two decades or more (0.001–10 m, 0–1000), so every decade gets
// the same travel; a range from 0 keeps 0 at the left end. `anchors`: values
// (the run's starting value, the value the control opened with) that their
// own positions give back exactly, so steps out and back return to them.
// Exported for tests.
export function sliderScale(spec, anchors = []) {
  const lo = spec.min > 0 ? spec.min : Math.max(spec.step || 0, spec.max * 1e-4);
  const log = spec.min >= 0 && spec.max > 0 && lo > 0 && spec.max / lo >= 100;
  if (!log) return { log: false, min: spec.min, max: spec.max, step: sliderStep(spec), toPosition: (v) => v, fromPosition: (p) => p };
  const zero = spec.min === 0;  // position 0 is the value 0
  const first = zero ? 1 : 0;
  const span = Math.max(1, Math.round(STEPS_PER_DECADE * Math.log10(spec.max / lo)));
  const toPosition = (v) => {
    if (zero && v <= 0) return 0;
    const x = Math.min(spec.max, Math.max(lo, v));
    return first + Math.round((span * Math.log(x / lo)) / Math.log(spec.max / lo));
  };
  const exact = new Map();  // position -> anchor value
  for (const a of anchors) if (typeof a === 'number' && Number.isFinite(a) && a >= spec.min && a <= spec.max) exact.set(toPosition(a), a);
  const fromPosition = (p) => {
    if (exact.has(p)) return exact.get(p);
    if (zero && p <= 0) return 0;
    if (p - first >= span) return spec.max;
    const value = lo * Math.pow(spec.max / lo, (p - first) / span);
    return Math.min(spec.max, Math.max(lo, Number(value.toPrecision(2))));  // type for more digits
  };
  return { log: true, min: 0, max: first + span, step: 1, toPosition, fromPosition };
}

// A change made with the keyboard is sent once the keys rest this long, as
// one recorded event (a drag sends one on release).
const KEYS_SETTLE_MS = 400;

// Whether the value differs from the run's starting value (the scenario's):
// marked, and the reset (back to it) enabled.
function markChanged(div, value, start) {
  const changed = value !== start;
  div.classList.toggle('changed', changed);
  div.querySelector('button.reset').disabled = !changed;
}

// current(): the run's value now (a refused typed value gives way to it)
function paramControl(spec, value, start, setParam, current) {
  const div = document.createElement('div');
  div.className = 'param';
  div.title = spec.help || '';
  const id = `param-${spec.name}`;
  const head = `<div class="head"><label class="name" for="${id}">${escape(spec.label || spec.name)}</label>
    <span class="value"></span>
    <button type="button" class="reset" title="back to the run's starting value (${escape(fmt(start))}); the method's default is ${escape(fmt(spec.default))}" aria-label="reset ${escape(spec.name)} to its starting value">↺</button></div>`;
  if (spec.choices && spec.choices.length) {
    div.innerHTML = `${head}<select id="${id}">${spec.choices.map((c, i) => `<option value="${i}" ${i === value ? 'selected' : ''}>${escape(c)}</option>`).join('')}</select>`;
    div.querySelector('select').onchange = (e) => setParam(spec.name, Number(e.target.value));
  } else {
    const scale = sliderScale(spec, [start, value]);
    div.innerHTML = `${head}<div class="slider-row"><input id="${id}" type="range" min="${scale.min}" max="${scale.max}" step="${scale.step}" value="${scale.toPosition(value)}"${scale.log ? ' data-scale="log"' : ''}>
      <span class="scale-mark" title="${scale.log ? 'logarithmic: each step is ×1.12, a twentieth of a decade' : 'linear'}">${scale.log ? 'log' : 'lin'}</span></div>`;
    div.querySelector('.value').innerHTML = `<input type="text" inputmode="decimal" class="typed" aria-label="${escape(spec.name)}, typed"> <span class="unit">${escape(spec.unit || '')}</span>`;
    const slider = div.querySelector('input[type=range]');
    const typed = div.querySelector('input.typed');
    typed.value = String(value);
    slider.oninput = () => { typed.value = String(scale.fromPosition(Number(slider.value))); };
    // one event per settled change: a drag on release, keys once they rest
    let keyed = false;
    const send = () => {
      clearTimeout(div.pendingSend);
      div.pendingSend = null;
      const chosen = scale.fromPosition(Number(slider.value));
      if (chosen !== current()) setParam(spec.name, chosen);  // steps out and back: nothing to record
    };
    slider.onkeydown = () => { keyed = true; };
    slider.onpointerdown = () => { keyed = false; };
    slider.onchange = () => {
      if (!keyed) return send();
      clearTimeout(div.pendingSend);
      div.pendingSend = setTimeout(send, KEYS_SETTLE_MS);
    };
    slider.onblur = () => { if (div.pendingSend) send(); };
    // "0,3" is 0.3; text read two ways or out of range is refused at the field
    typedNumber(typed, {
      min: spec.min, max: spec.max, unit: spec.unit,
      current: () => { typed.dataset.committed = String(current()); return typed.dataset.committed; },
      after: div.querySelector('.head'),
      onValue: (v) => { typed.dataset.committed = typed.value; setParam(spec.name, v); },
    });
    div.scale = scale;
  }
  markChanged(div, value, start);
  div.querySelector('button.reset').onclick = () => setParam(spec.name, start);
  return div;
}

// The run's starting values per method (the first snapshot of that method).
const startValues = (lane) => lane.startParams[lane.snapshot.method];

// In a replay the panel shows the values recorded at the playhead
// (session.js showRecordedAt), and says so: as of which recorded input.
function showRecordedNote(session) {
  const note = $('params-recorded');
  const lane = session.focusLane;
  note.hidden = session.kind !== 'replay' || !lane || !lane.snapshot;
  if (note.hidden) return;
  const r = lane.recorded;
  const dt = lane.snapshot.dt;
  note.textContent = !r ? 'recorded values' : r.seq === null
    ? 'recorded: the starting values (no input yet at this frame)'
    : `recorded at t = ${(r.seq * dt).toFixed(2)} s (frame ${r.seq})`;
  note.title = 'a replay shows the method and parameters as they were at the frame on screen';
}

// Rebuilds the panel from the focused lane's snapshot.
function buildParams(session) {
  const lane = session.focusLane;
  const live = session.kind === 'live' && !session.ended;  // an ended run takes no inputs
  $('params-section').hidden = !lane || !lane.snapshot;
  if (!lane || !lane.snapshot) return;
  const snapshot = lane.snapshot;
  $('params-lane').textContent = `${lane.label}${session.compare ? ` · run #${lane.runId}` : ''}`;
  const box = $('params');
  box.replaceChildren();
  if (!snapshot.param_specs.length) box.innerHTML = '<p class="muted">This method has no parameters.</p>';
  const start = startValues(lane);
  for (const spec of snapshot.param_specs) {
    const setParam = (name, value) => app.execute({ type: 'input', kind: 'params', payload: { [name]: value }, runId: lane.runId });
    const control = paramControl(spec, snapshot.params[spec.name], start[spec.name], setParam, () => lane.snapshot.params[spec.name]);
    if (!live) for (const el of control.querySelectorAll('input, select, button')) el.disabled = true;
    box.appendChild(control);
  }
  buildLaneTabs(session);
  showRecordedNote(session);
  // the switch shows the lane's method when it changes, not on every snapshot
  // (a snapshot after a parameter change must not undo what the user is choosing)
  const select = $('switch-method');
  if (select.options.length !== app.methods.length) select.innerHTML = app.methods.map((m) => `<option value="${escape(m.name)}" title="${escape(m.description)}">${escape(m.name)}</option>`).join('');
  const shown = `${lane.runId}:${snapshot.method}`;
  if (select.dataset.shown !== shown) { select.value = snapshot.method; select.dataset.shown = shown; }
}

// New values for the focused lane's parameters (a params message): each
// control shows its value in place, except a slider the user is dragging.
function updateParams(session) {
  const lane = session.focusLane;
  if (!lane || !lane.snapshot) return;
  const start = startValues(lane);
  for (const spec of lane.snapshot.param_specs) {
    const div = $(`param-${spec.name}`)?.closest('.param');
    if (!div) return buildParams(session);  // not the panel of this method: build it
    const value = lane.snapshot.params[spec.name];
    const control = div.querySelector('input[type=range], select');
    // not while the user drags it or has a keyboard change waiting to be sent
    if (!control.matches(':active') && !div.pendingSend) control.value = String(div.scale ? div.scale.toPosition(value) : value);
    const typed = div.querySelector('input.typed');
    // not over a number being typed (focused, and changed since it was last sent)
    if (typed && (document.activeElement !== typed || typed.value === typed.dataset.committed)) {
      typed.value = String(value);
      typed.dataset.committed = typed.value;
    }
    markChanged(div, value, start[spec.name]);
  }
  showRecordedNote(session);
}

function buildLaneTabs(session) {
  const tabs = $('lane-tabs');
  tabs.hidden = !session.compare;
  tabs.replaceChildren();
  if (!session.compare) return;
  for (const lane of session.lanes) {
    const b = document.createElement('button');
    b.type = 'button';
    b.setAttribute('role', 'tab');
    b.setAttribute('aria-selected', String(lane.index === session.focus));
    b.style.borderColor = lane.colour;
    b.style.color = lane.colour;
    b.textContent = lane.label;
    b.onclick = () => app.execute({ type: 'focus', lane: lane.index });
    tabs.appendChild(b);
  }
}

// The panel's subscriptions and the method switch (the focused lane's run
// takes the method; its next snapshot renames the lane).
export function setupParams() {
  const current = (lane) => app.session && app.session.lanes.includes(lane);
  app.signals.snapshot.add((lane) => { if (current(lane) && lane.index === app.session.focus) buildParams(app.session); });
  app.signals.params.add((lane) => { if (current(lane) && lane.index === app.session.focus) updateParams(app.session); });
  app.signals.focusChanged.add((session) => buildParams(session));
  app.signals.sessionEnded.add((session) => buildParams(session));  // its parameters read-only
  app.signals.sessionChanged.add((session) => { if (!session) $('params-section').hidden = true; });
  // a replay's parameters follow its playhead (the values recorded at that frame)
  app.signals.playhead.add((seq) => { if (app.session && app.session.kind === 'replay') app.session.showRecordedAt(seq); });
  $('switch-method-go').onclick = () => {
    const session = app.session;
    if (!session || session.kind !== 'live') return;
    app.execute({ type: 'input', kind: 'method', payload: { name: $('switch-method').value }, runId: session.focusLane.runId });
  };
}
