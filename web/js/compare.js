// Compare: pick 2–4 methods (each with optional parameters, `name=value, …`)
// and start them as one live group on the chosen scenario; at the end, a
// summary table of every lane's run.
import { api, ApiError } from './api.js';
import { app, LANE_COLOURS } from './state.js';
import { fmt } from './params.js';
import { escapeHtml } from './dom.js';

const $ = (id) => document.getElementById(id);
const MAX_LANES = 4;

export class CompareSetup {
  constructor({ start }) {
    this.start = start;  // (body) POSTs /api/compare and opens the group
    $('compare-add').onclick = () => this.addRow();
    $('start-compare').onclick = () => this.submit().catch((e) => app.error(e));
  }

  // Two rows to begin with: the plain pseudoinverse against the next method.
  init() {
    $('compare-rows').replaceChildren();
    this.addRow('pinv');
    this.addRow(app.methods.find((m) => m.name === 'dls') ? 'dls' : app.methods[1].name);
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
        if (!key || value === undefined || value === '') throw new ApiError(400, { message: `write parameters as name=value (method ${i + 1}: "${part}")`, path: `methods[${i}].params` });
        params[key] = Number.isFinite(Number(value)) ? Number(value) : value;
      }
      return Object.keys(params).length ? { name, params } : name;
    });
  }

  async submit() {
    await this.start({ scenario: $('scenario').value, methods: this.methods(), mode: 'live', rate: Number($('rate').value) }, $('compare-layout').value);
  }
}

const SUMMARY = [
  ['collided', (s) => s.collided],
  ['min distance (m)', (s) => s.min_distance],
  ['max tracking error (m)', (s) => s.max_tracking_error],
  ['final tracking error (m)', (s) => s.final_tracking_error],
  ['joint limit violated', (s) => s.joint_limit_violated],
  ['min joint-limit margin', (s) => s.min_joint_limit_margin],
  ['max condition number', (s) => s.max_condition_number],
  ['non-finite steps', (s) => s.nonfinite_steps],
  ['step p50 (µs)', (s) => s.step_us && s.step_us.p50],
  ['step p99 (µs)', (s) => s.step_us && s.step_us.p99],
];

// The summary of every lane's stored run, side by side.
export async function showCompareSummary(session) {
  const box = $('compare-summary');
  const runs = await Promise.all(session.runIds.map((id) => api('GET', `/api/runs/${id}`)));
  if (runs.some((r) => !r.summary)) return;
  const head = `<tr><th></th>${session.lanes.map((l) => `<th>${escapeHtml(l.label)}</th>`).join('')}</tr>`;
  const rows = SUMMARY.map(([name, get]) => `<tr><td>${name}</td>${runs.map((r) => `<td class="${get(r.summary) === true ? 'collided' : ''}">${fmt(get(r.summary))}</td>`).join('')}</tr>`);
  box.innerHTML = `<h2>Summary of the compare group</h2><table id="summary-table">${head}${rows.join('')}</table>`;
  box.querySelectorAll('#summary-table tr:first-child th').forEach((th, i) => { if (i > 0) th.style.color = session.lanes[i - 1].colour; });
  box.hidden = false;
}
