// Compare: pick 2–4 methods (each with optional parameters, `name=value, …`)
// and start them as one live group on the chosen scenario; at the end, a
// summary table of every lane's run.
import { api, ApiError } from './api.js';
import { app, LANE_COLOURS } from './state.js';
import { DEFAULT_CRITERION, compareVerdict } from './compare_verdict.js';
import { failureTimes } from './first_failure.js';
import { escapeHtml, fmt } from './dom.js';
import { parseTypedNumber, refuse, accept, mark } from './typed_number.js';

const $ = (id) => document.getElementById(id);
const MAX_LANES = 4;

export class CompareSetup {
  constructor() {
    $('compare-add').onclick = () => this.addRow();
    $('start-compare').onclick = () => this.submit().catch((e) => app.error(e));
    // the layout applies to the group on screen too
    $('compare-layout').addEventListener('change', () => app.execute({ type: 'setLayout', layout: $('compare-layout').value }));
    app.signals.methodsChanged.add(() => this.init());
    app.signals.scenariosChanged.add(() => {
      const chosen = app.choice.scenario;
      $('compare-scenario').innerHTML = app.scenarios.map((s) => `<option value="${escapeHtml(s.name)}" ${s.name === chosen ? 'selected' : ''}>${escapeHtml(s.name)}</option>`).join('');
    });
    // a session on screen: its controls come first, the pickers fold away
    app.signals.sessionChanged.add((session) => { if (session) $('compare-setup').open = false; });
  }

  // Two rows to begin with: the plain pseudoinverse against an avoidance
  // method (on the opening demo scenario the first collides, the second keeps clear).
  init() {
    $('compare-rows').replaceChildren();
    this.addRow('pinv');
    const second = ['closest_point', 'dls'].find((name) => app.methods.some((m) => m.name === name));
    this.addRow(second || app.methods[1].name);
  }

  addRow(method) {
    const rows = $('compare-rows');
    if (rows.childElementCount >= MAX_LANES) return;
    const i = rows.childElementCount;
    const row = document.createElement('div');
    row.className = 'compare-row';
    // colours are set through the DOM, not style="" (the Content-Security-Policy refuses inline styles)
    row.innerHTML = `<span class="swatch"></span>
      <span class="fields"><select aria-label="method ${i + 1}">${app.methods.map((m) => `<option ${m.name === method ? 'selected' : ''}>${escapeHtml(m.name)}</option>`).join('')}</select>
      <input type="text" aria-label="parameters of method ${i + 1}" placeholder="name=value, …" title="parameters, e.g. lambda=0.05, gain=8 (defaults otherwise)">
      <button type="button" aria-label="remove method ${i + 1}">×</button></span>`;
    row.querySelector('.swatch').style.background = LANE_COLOURS[i];
    row.querySelector('button').onclick = () => { if (rows.childElementCount > 2) { row.remove(); this.recolour(); } };
    rows.appendChild(row);
    $('compare-add').disabled = rows.childElementCount >= MAX_LANES;
  }

  recolour() {
    [...$('compare-rows').children].forEach((row, i) => { row.querySelector('.swatch').style.background = LANE_COLOURS[i]; });
    $('compare-add').disabled = $('compare-rows').childElementCount >= MAX_LANES;
  }

  methods() {
    return [...$('compare-rows').children].map((row, i) => {
      const name = row.querySelector('select').value;
      const params = {};
      for (const part of row.querySelector('input').value.split(',').map((s) => s.trim()).filter(Boolean)) {
        const [key, value] = part.split('=').map((s) => s.trim());
        if (!key || value === undefined || value === '') throw new ApiError(400, { message: `write parameters as name=value, separated by commas, with a decimal point ("${part}")`, path: `methods[${i}].params` });
        params[key] = Number.isFinite(Number(value)) ? Number(value) : value;
      }
      return Object.keys(params).length ? { name, params } : name;
    });
  }

  // The group starts as one live compare (the rate of the new-run pickers).
  // A refused method or parameter is marked at its row, in its words.
  async submit() {
    const rows = [...$('compare-rows').children];
    for (const row of rows) accept(row.querySelector('input'));
    try {
      const body = { scenario: $('compare-scenario').value, methods: this.methods(), mode: 'live', rate: app.choice.rate };
      await app.execute({ type: 'startCompare', body, layout: $('compare-layout').value, report: false });
    } catch (e) {
      if (!this.showAtRow(e, rows)) throw e;
    }
  }

  // An error whose path names a method (`methods[1].params.lamda`): at that
  // row, without the path ("lamda: unknown parameter of dls (known: …)").
  showAtRow(e, rows) {
    const m = /^methods\[(\d+)\](?:\.params)?\.?(.*)$/.exec((e && e.path) || '');
    const row = m && rows[Number(m[1])];
    if (!row) return false;
    const message = String(e.message).replace(/^methods\[\d+\](\.params)?\.?/, '');
    const what = m[2] && !message.startsWith(m[2]) ? `${m[2]}: ${message}` : message;
    mark(row.querySelector('input'), `method ${Number(m[1]) + 1} (${row.querySelector('select').value}): ${what}`, row.querySelector('.fields'));
    row.querySelector('input').focus();
    return true;
  }
}

// The success criterion the summary judges by (editable on the page; the
// benchmark's by default), and the last summaries shown, to judge again.
const criterion = { ...DEFAULT_CRITERION };
let shown = null;

// The summary of every lane's stored run, side by side: the best value of
// each row marked, rows where the methods differ highlighted, each run's pass
// or fail against the criterion, and one sentence that says what it means.
async function showCompareSummary(session) {
  const runs = await Promise.all(session.runIds.map((id) => api.run(id)));
  if (session.closed || runs.some((r) => !r.summary)) return;  // another session was opened meanwhile
  shown = { session, summaries: runs.map((r) => r.summary), frames: storedFrames.get(session) || [] };
  renderSummary();
}

// The lanes' stored frames (a replay's), by session: when each reason began.
const storedFrames = new WeakMap();

// The summary follows the session: a stored group's at once, a live group's at its end.
export function setupCompareSummary() {
  app.signals.sessionChanged.add(() => hideCompareSummary());
  app.signals.sessionOpened.add((session) => { if (session.kind === 'replay' && session.compare) showCompareSummary(session).catch((e) => app.error(e)); });
  app.signals.sessionEnded.add((session) => { if (session.compare) showCompareSummary(session).catch((e) => app.error(e)); });
  app.signals.storedFrames.add((lane, data) => {
    const session = app.session;
    if (!session || !session.compare || !session.lanes.includes(lane)) return;
    if (!storedFrames.has(session)) storedFrames.set(session, []);
    storedFrames.get(session)[lane.index] = data.frames;
    if (shown && shown.session === session) { shown.frames = storedFrames.get(session); renderSummary(); }
  });
}

function hideCompareSummary() {
  shown = null;
  $('compare-summary').hidden = true;
  delete $('compare-summary').dataset.group;
}

// The criterion's fields are made once per summary and never rebuilt under
// the cursor (a field removed while it has focus fires change again).
function renderSummary() {
  if (!shown) return;
  const { session, summaries } = shown;
  const box = $('compare-summary');
  if (box.dataset.group !== session.runIds.join(',')) buildSummary(box, session);
  const times = session.lanes.map((l) => (shown.frames[l.index] ? failureTimes(shown.frames[l.index], l.snapshot ? l.snapshot.dt : 0, criterion) : null));
  const verdict = compareVerdict(summaries, session.lanes.map((l) => l.label), criterion, times);
  box.querySelector('.verdict-headline').textContent = verdict.headline;
  const head = `<tr><th></th>${session.lanes.map((l, i) => `<th data-lane="${i}">${escapeHtml(l.label)}</th>`).join('')}</tr>`;
  const verdictRow = `<tr class="verdict-row"><td>verdict</td>${verdict.verdicts.map((v) =>
    `<td class="${v.pass ? 'pass' : 'fail'}" title="${escapeHtml(v.reasons.join('; ') || 'meets the criterion')}">${v.pass ? 'pass' : 'fail'}${v.reasons.length ? `<div class="why">${escapeHtml(v.reasons.join(', '))}</div>` : ''}</td>`).join('')}</tr>`;
  const rows = verdict.rows.map((row) => `<tr class="${row.differs ? 'differs' : ''}" data-row="${row.key}"><td>${row.label}</td>${row.values.map((v, i) => {
    const classes = [row.best.includes(i) ? 'best' : '', v === true && row.better === 'false' ? 'collided' : ''].filter(Boolean).join(' ');
    return `<td class="${classes}"${row.best.includes(i) ? ` title="best of the group${row.stated ? `, by more than ${row.stated}` : ''}"` : ''}>${fmt(v)}</td>`;
  }).join('')}</tr>`);
  const table = box.querySelector('#summary-table');
  table.innerHTML = head + verdictRow + rows.join('');
  table.querySelectorAll('th[data-lane]').forEach((th) => { th.style.color = session.lanes[Number(th.dataset.lane)].colour; });
  box.hidden = false;
}

function buildSummary(box, session) {
  box.dataset.group = session.runIds.join(',');
  box.innerHTML = `<details open><summary><h2>Summary of the compare group</h2></summary>
    <p class="verdict-headline"></p>
    <p class="criterion small">Success: tracking error ≤ <input type="text" inputmode="decimal" id="crit-error" aria-label="largest tracking error that passes, m"> m,
      clearance ≥ <input type="text" inputmode="decimal" id="crit-distance" placeholder="any" aria-label="smallest clearance that passes, m"> m,
      <label class="inline"><input type="checkbox" id="crit-collision"> no collision</label>,
      <label class="inline"><input type="checkbox" id="crit-limits"> joint limits kept</label>
      <button type="button" id="crit-default" title="the benchmark suite's criterion">default</button></p>
    <table id="summary-table"></table>
    <p class="muted small">Bold: the best value of a row, marked only when it beats the others by more than the row's tolerance (distances 1 mm, tracking errors 0.1 mm, condition number 1 %, step times 10 %). Shaded rows: the methods differ there (to 4 digits; step times always differ).</p></details>`;
  const fields = () => {
    $('crit-error').value = criterion.max_tracking_error ?? '';
    $('crit-distance').value = criterion.min_distance ?? '';
    $('crit-collision').checked = !criterion.collision;
    $('crit-limits').checked = criterion.joint_limits;
  };
  fields();
  // typed numbers (typed_number.js): "0,01" is 0.01; an empty field is no bound
  const number = (id, min) => {
    const text = $(id).value;
    if (text.trim() === '') { accept($(id)); return { value: null }; }
    const read = parseTypedNumber(text, { min, unit: 'm' });
    // the message under the criterion's line: nothing on the line moves when it goes
    if ('error' in read) refuse($(id), read.error, String(id === 'crit-error' ? criterion.max_tracking_error ?? '' : criterion.min_distance ?? ''), $(id).closest('p'));
    else accept($(id));
    return read;
  };
  const changed = () => {
    const error = number('crit-error', 0), distance = number('crit-distance', -Infinity);
    if ('error' in error || 'error' in distance) return;
    Object.assign(criterion, { max_tracking_error: error.value, min_distance: distance.value, collision: !$('crit-collision').checked, joint_limits: $('crit-limits').checked });
    renderSummary();
  };
  for (const id of ['crit-error', 'crit-distance', 'crit-collision', 'crit-limits']) $(id).onchange = changed;
  $('crit-default').onclick = () => { Object.assign(criterion, DEFAULT_CRITERION); fields(); accept($('crit-error')); accept($('crit-distance')); renderSummary(); };
}
