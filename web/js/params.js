// The parameter panel of the focused lane: a slider (or a select for an
// enumeration) per parameter spec, its help as a tooltip, a reset to the
// default, and the method switch. Changes go to the lane's own run.
import { app } from './state.js';
import { escapeHtml as escape } from './dom.js';

const $ = (id) => document.getElementById(id);

export function fmt(v) {
  if (v === null || v === undefined) return '—';
  if (typeof v === 'boolean') return v ? 'yes' : 'no';
  if (typeof v !== 'number') return String(v);
  if (Number.isInteger(v)) return String(v);
  return Math.abs(v) >= 1e4 || (Math.abs(v) < 1e-3 && v !== 0) ? v.toExponential(3) : v.toFixed(4);
}


// A slider's step must divide (max - min) from min, or the browser rejects
// values in between: then any value.
function sliderStep(spec) {
  return spec.step && Number.isInteger(Math.round(((spec.max - spec.min) / spec.step) * 1e9) / 1e9) ? spec.step : 'any';
}

// A slider's value as text, beside its name.
function showValue(div, spec, value) {
  div.querySelector('.value').textContent = `${fmt(value)} ${spec.unit || ''}`;
}

// Whether the value differs from the default: marked, and the reset enabled.
function markChanged(div, spec, value) {
  const changed = value !== spec.default;
  div.classList.toggle('changed', changed);
  div.querySelector('button.reset').disabled = !changed;
}

function paramControl(spec, value, setParam) {
  const div = document.createElement('div');
  div.className = 'param';
  div.title = spec.help || '';
  const id = `param-${spec.name}`;
  const head = `<div class="head"><label class="name" for="${id}">${escape(spec.label || spec.name)}</label>
    <span class="value"></span>
    <button type="button" class="reset" title="reset to the default (${escape(fmt(spec.default))})" aria-label="reset ${escape(spec.name)} to its default">↺</button></div>`;
  if (spec.choices && spec.choices.length) {
    div.innerHTML = `${head}<select id="${id}">${spec.choices.map((c, i) => `<option value="${i}" ${i === value ? 'selected' : ''}>${escape(c)}</option>`).join('')}</select>`;
    div.querySelector('select').onchange = (e) => setParam(spec.name, Number(e.target.value));
  } else {
    div.innerHTML = `${head}<input id="${id}" type="range" min="${spec.min}" max="${spec.max}" step="${sliderStep(spec)}" value="${value}">`;
    const input = div.querySelector('input');
    showValue(div, spec, value);
    input.oninput = () => showValue(div, spec, Number(input.value));
    input.onchange = () => setParam(spec.name, Number(input.value));
  }
  markChanged(div, spec, value);
  div.querySelector('button.reset').onclick = () => setParam(spec.name, spec.default);
  return div;
}


// Rebuilds the panel from the focused lane's snapshot.
export function buildParams(session) {
  const lane = session.focusLane;
  const live = session.kind === 'live';
  $('params-section').hidden = !lane || !lane.snapshot;
  if (!lane || !lane.snapshot) return;
  const snapshot = lane.snapshot;
  $('params-lane').textContent = `${snapshot.method}${session.compare ? ` · run #${lane.runId}` : ''}`;
  const box = $('params');
  box.replaceChildren();
  if (!snapshot.param_specs.length) box.innerHTML = '<p class="muted">This method has no parameters.</p>';
  for (const spec of snapshot.param_specs) {
    const setParam = (name, value) => session.input('params', { [name]: value }, lane.runId).catch((e) => app.error(e));
    const control = paramControl(spec, snapshot.params[spec.name], setParam);
    if (!live) for (const el of control.querySelectorAll('input, select, button')) el.disabled = true;
    box.appendChild(control);
  }
  buildLaneTabs(session);
  // the switch shows the lane's method when it changes, not on every snapshot
  // (a snapshot after a parameter change must not undo what the user is choosing)
  const select = $('switch-method');
  if (select.options.length !== app.methods.length) select.innerHTML = app.methods.map((m) => `<option value="${escape(m.name)}" title="${escape(m.description)}">${escape(m.name)}</option>`).join('');
  const shown = `${lane.runId}:${snapshot.method}`;
  if (select.dataset.shown !== shown) { select.value = snapshot.method; select.dataset.shown = shown; }
}

// New values for the focused lane's parameters (a params message): each
// control shows its value in place, except a slider the user is dragging.
export function updateParams(session) {
  const lane = session.focusLane;
  if (!lane || !lane.snapshot) return;
  for (const spec of lane.snapshot.param_specs) {
    const div = $(`param-${spec.name}`)?.closest('.param');
    if (!div) return buildParams(session);  // not the panel of this method: build it
    const value = lane.snapshot.params[spec.name];
    const control = div.querySelector('input, select');
    if (!control.matches(':active')) {  // not while the user drags it
      control.value = String(value);
      if (control.tagName === 'INPUT') showValue(div, spec, value);
    }
    markChanged(div, spec, value);
  }
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
    b.onclick = () => { session.focus = lane.index; buildParams(session); app.signals.frame.dispatch(lane); };
    tabs.appendChild(b);
  }
}

export function setupMethodSwitch(getSession) {
  $('switch-method-go').onclick = async () => {
    const session = getSession();
    if (!session || session.kind !== 'live') return;
    const name = $('switch-method').value;
    await session.input('method', { name }, session.focusLane.runId).catch((e) => app.error(e));
    session.focusLane.label = name;
  };
}
