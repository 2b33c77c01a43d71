// A sweep's page (/?sweep=ID): progress while it runs; once it has ended,
// which method to use per family, the method × family success table with
// 95 % intervals (each column's best marked), failure modes, success against
// difficulty, step cost and the ranking. A cell opens its runs; a run opens
// as a replay (re-simulated first when the sweep stored no frames) and a case
// as a compare of the sweep's methods on it.
import { api } from './api.js';
import { app, LANE_COLOURS } from './state.js';
import { escapeHtml } from './dom.js';
import { fmt } from './dom.js';
import { successTable, formatRate, formatFailureModes, difficultySvg, difficultyMeasures, verdictWords, parseConfig } from './sweep_report.js';
import { fallbackHtml } from './sweep_fallback.js';
import { outcomeText } from './failure_modes.js';

const $ = (id) => document.getElementById(id);
const POLL_MS = 1000;
const CHART_COLOURS = LANE_COLOURS.concat(['#00838f', '#6d4c41', '#c2185b', '#546e7a']);
const RUNS_PER_PAGE = 50;

export class SweepPage {
  // Shown while the page in the centre is a sweep's (state.js: app.page).
  constructor() {
    this.id = null;
    this.timer = null;
    this.status = null;
    this.cell = null;
    // the sweep on screen with another cell (Back, Forward, a click) keeps its page
    app.signals.pageChanged.add((page) => {
      if (page && page.name === 'sweep' && page.id === this.id && this.status) this.selectCell(page.cell);
      else if (page && page.name === 'sweep') this.show(page.id, page.cell).catch((e) => app.error(e));
      else this.hide();
    });
  }

  openRuns(ids) { return app.execute({ type: 'open', ids, report: false }); }

  get shown() { return this.id !== null; }

  // `cell`: {family, config} to open once the report is there, or null
  async show(id, cell = null) {
    this.hide();
    this.id = id;
    this.token = (this.token || 0) + 1;  // one polling chain per page shown
    this.cell = cell ? { family: cell.family, config: cell.config, offset: 0 } : null;
    document.getElementById('center').classList.add('showing-page');
    $('sweep-page').hidden = false;
    $('sweep-page').innerHTML = '<p class="muted">loading the sweep…</p>';
    await this.load();
  }

  hide() {
    clearTimeout(this.timer);
    this.id = null;
    this.status = null;
    if ($('paper-page').hidden) document.getElementById('center').classList.remove('showing-page');
    $('sweep-page').hidden = true;
    $('sweep-page').replaceChildren();
  }

  async load() {
    const id = this.id, token = this.token;
    const again = () => { this.timer = setTimeout(() => this.load().catch((e) => app.error(e)), POLL_MS); };
    let status;
    try {
      status = await api.sweep(id);
    } catch (e) {
      if (this.token !== token) return;
      if (e.status === 404 || !this.status) {
        $('sweep-page').innerHTML = `<p class="bad">${escapeHtml(e.status === 404 ? `There is no sweep #${id} on this server (sweeps are kept while the server runs; their runs stay stored).` : e.message)}</p>`;
      }
      if (e.status !== 404) again();  // a failed poll of a sweep on screen tries again
      return;
    }
    if (this.token !== token) return;
    this.status = status;
    this.render();
    if (status.status === 'running') again();
  }

  render() {
    const s = this.status;
    const page = $('sweep-page');
    const head = `<h2 class="sweep-title">Sweep ${escapeHtml(s.name)} <span class="muted">#${s.id}</span></h2>
      <p class="sweep-progress">${escapeHtml(s.status)} · ${s.done} / ${s.total} runs stored${s.failed ? ` · ${s.failed} could not run` : ''}
      ${s.status === 'running' ? `<progress max="${s.total}" value="${s.done}"></progress> <button type="button" id="sweep-stop">Stop</button>` : ''}</p>`;
    if (!s.report) {
      page.innerHTML = `${head}<p class="muted">The report appears when the sweep has ended.</p>`;
    } else {
      page.innerHTML = head + this.reportHtml(s.report) + '<div id="sweep-cell"></div>';
      page.querySelectorAll('.legend-item').forEach((el) => { el.style.color = CHART_COLOURS[Number(el.dataset.colour) % CHART_COLOURS.length]; });
      // a cell has an address of its own (?sweep=ID&family=F&config=C)
      page.querySelectorAll('td[data-family]').forEach((td) => {
        td.onclick = () => app.execute({ type: 'openSweep', id: s.id, cell: { family: td.dataset.family, config: td.dataset.config } });
      });
      if (this.cell) this.showCell(this.cell.family, this.cell.config, this.cell.offset).catch((e) => app.error(e));
    }
    const stop = $('sweep-stop');
    if (stop) stop.onclick = () => api.sweepControl(s.id, { action: 'stop' }).catch((e) => app.error(e));
  }

  reportHtml(report) {
    const table = successTable(report);
    const { families, configs, cell, best } = table;
    const verdicts = (report.verdicts || []).map((v) => {
      const { detects, listed } = verdictWords(v, cell);
      return `<tr data-family="${escapeHtml(v.family)}" data-status="${escapeHtml(v.status)}"><td>${escapeHtml(v.family)}</td><td>${escapeHtml(detects)}</td><td>${escapeHtml(listed)}</td></tr>`;
    }).join('');
    const headRow = `<tr><th>method</th>${families.map((f) => `<th>${escapeHtml(f)}</th>`).join('')}</tr>`;
    const rows = configs.map((c) => `<tr><th scope="row">${escapeHtml(c)}</th>${families.map((f) => {
      const g = cell(f, c);
      if (!g) return '<td class="muted">—</td>';
      const modes = formatFailureModes(g.failure_modes);
      const isBest = best.get(f).has(c);
      return `<td class="cell${isBest ? ' best' : ''}" data-family="${escapeHtml(f)}" data-config="${escapeHtml(c)}" tabindex="0"
        title="${g.successes} of ${g.n} passed${isBest ? '; the best of this family' : ''}. Click for its runs.">
        <div class="rate">${formatRate(g)}</div><div class="n small muted">n = ${g.n}</div>${modes ? `<div class="modes small">${escapeHtml(modes)}</div>` : ''}</td>`;
    }).join('')}</tr>`).join('');
    const cost = configs.map((c) => `<tr><th scope="row">${escapeHtml(c)}</th>${families.map((f) => {
      const g = cell(f, c);
      return g ? `<td>${fmt(g.step_us_p50)} / ${fmt(g.step_us_p99)}${Number.isFinite(g.step_ratio_to_pinv) ? ` <span class="muted">(${g.step_ratio_to_pinv.toFixed(2)}× pinv)</span>` : ''}</td>` : '<td class="muted">—</td>';
    }).join('')}</tr>`).join('');
    // per family: its quartile chart, then one per obstacle count (sweep_report.js: difficultyMeasures)
    const charts = families.map((f) => {
      const groups = configs.map((c) => cell(f, c));
      const present = groups.filter(Boolean), colours = configs.map((c, i) => CHART_COLOURS[i % CHART_COLOURS.length]).filter((_, i) => groups[i]);
      return difficultyMeasures(present).map((measure) => {
        const svg = difficultySvg(present, colours, { measure });
        return svg ? `<figure class="difficulty" data-family="${escapeHtml(f)}" data-measure="${escapeHtml(measure || 'quartiles')}"><figcaption>${escapeHtml(f)}${measure ? ` · ${escapeHtml(measure)}` : ''}</figcaption>${svg}</figure>` : '';
      }).join('');
    }).join('');
    const legend = charts ? `<p class="small">${configs.map((c, i) => `<span class="legend-item" data-colour="${i}">${escapeHtml(c)}</span>`).join(' ')}</p>` : '';
    const ranking = (report.ranking || []).map((r, i) => `<tr><td>${i + 1}</td><td>${escapeHtml(r.config)}</td><td>${Math.round(100 * r.success_rate)} %</td><td>${r.n}</td></tr>`).join('');
    return `<h3>Which method when</h3>
      <p class="small muted">Detects: the smallest difference in success these cases detect (80 % power, p &lt; 0.05); past 20 points none is listed.</p>
      ${report.rules && report.rules.verdicts ? `<details class="rule small"><summary>the rule</summary><p>${escapeHtml(report.rules.verdicts)}</p></details>` : ''}
      <table class="sweep-verdicts"><tr><th>family</th><th>detects</th><th>not significantly worse than the best (cost per step)</th></tr>${verdicts}</table>
      ${fallbackHtml(report)}
      <h3>Success by method and family</h3>
      <p class="small muted">Success rate with its 95 % Wilson interval; bold: a family's best. Click a cell for its runs.</p>
      <table class="sweep-success">${headRow}${rows}</table>
      ${charts ? `<h3>Success against difficulty</h3>
        <p class="small muted">Success per bin of each family's cases: the quartiles of the witness's clearance (or joint-limit margin), and the obstacle counts
          blocking_obstacles (those the minimum-norm arm meets) and tight_obstacles (those within twice the family's clearance of the witness) in bins 0, 1, 2, 3, 4+.</p>
        ${legend}<div class="difficulty-charts">${charts}</div>` : ''}
      <h3>Step cost</h3><p class="small muted">p50 / p99 µs per step, and the ratio to pinv (shifted geometric mean).</p>
      <table class="sweep-cost">${headRow}${cost}</table>
      <h3>Ranking</h3><table class="sweep-ranking"><tr><th>#</th><th>method</th><th>success</th><th>runs</th></tr>${ranking}</table>`;
  }

  // The cell the address names ({family, config}), or none.
  selectCell(cell) {
    if (cell && this.cell && this.cell.family === cell.family && this.cell.config === cell.config) return;
    if (!cell) { this.cell = null; $('sweep-cell')?.replaceChildren(); return; }
    if (!this.status.report) { this.cell = { ...cell, offset: 0 }; return; }  // shown when the report comes
    this.showCell(cell.family, cell.config).catch((e) => app.error(e));
  }

  // One cell's runs, a page at a time.
  async showCell(family, config, offset = 0) {
    const id = this.id;
    this.cell = { family, config, offset };
    const page = await api.sweepRuns(id, { family, config, limit: RUNS_PER_PAGE, offset });
    if (this.id !== id) return;
    const box = $('sweep-cell');
    const rows = page.runs.map((r) => `<tr data-run="${r.run}">
      <td class="mono">${escapeHtml(r.case)}</td>
      <td class="${r.success ? 'pass' : 'fail'}">${escapeHtml(outcomeText(r))}</td>
      <td>${fmt(r.min_distance)}</td><td>${fmt(r.max_tracking_error)}</td>
      <td class="actions"><button type="button" class="run-open" title="${r.frames ? 'replay its stored frames' : 'the sweep stored no frames: re-simulate the run from its recorded inputs, then replay it'}">${r.frames ? 'Replay' : 'Re-simulate'}</button>
        <button type="button" class="run-compare" title="run every method of this sweep on this case, side by side">Compare methods</button></td></tr>`).join('');
    const more = page.total > offset + page.runs.length;
    box.innerHTML = `<h3>Runs of ${escapeHtml(config)} on ${escapeHtml(family)} <span class="muted">(${offset + 1}–${offset + page.runs.length} of ${page.total})</span></h3>
      <p class="small muted" id="sweep-cell-progress" role="status"></p>
      <table class="sweep-runs"><tr><th>case</th><th>outcome</th><th>min distance (m)</th><th>max tracking error (m)</th><th></th></tr>${rows}</table>
      <div class="buttons">${offset > 0 ? '<button type="button" id="cell-prev">Previous</button>' : ''}${more ? '<button type="button" id="cell-next">Next</button>' : ''}</div>`;
    box.querySelectorAll('tr[data-run]').forEach((tr) => {
      const run = page.runs.find((r) => r.run === Number(tr.dataset.run));
      tr.querySelector('.run-open').onclick = () => this.openRun(run).catch((e) => app.error(e));
      tr.querySelector('.run-compare').onclick = () => this.compareCase(run).catch((e) => app.error(e));
    });
    if ($('cell-prev')) $('cell-prev').onclick = () => this.showCell(family, config, Math.max(0, offset - RUNS_PER_PAGE)).catch((e) => app.error(e));
    if ($('cell-next')) $('cell-next').onclick = () => this.showCell(family, config, offset + RUNS_PER_PAGE).catch((e) => app.error(e));
    box.scrollIntoView({ block: 'nearest' });
  }

  // A run with frames replays; one without is re-simulated first (with progress).
  async openRun(run) {
    if (run.frames > 0) return this.openRuns([run.run]);
    const note = $('sweep-cell-progress');
    const onProgress = (done, total) => {
      if (note) note.textContent = `re-simulating run #${run.run}: ${done}${total ? ` / ${total}` : ''} frames`;
    };
    return app.execute({ type: 'resimulate', id: run.run, onProgress, report: false });
  }

  // Every method configuration of the sweep on this run's case, as one group.
  async compareCase(run) {
    const report = this.status && this.status.report;
    const configs = successTable(report).configs.filter((c) => successTable(report).cell(run.family, c));
    const record = await api.record(run.run);
    const methods = configs.slice(0, 4).map(parseConfig);  // a compare group holds at most 4 lanes
    if (configs.length > 4) app.info(`a compare holds 4 methods: the sweep's first 4 of ${configs.length} (by rank)`);
    const note = $('sweep-cell-progress');
    if (note) note.textContent = `running ${methods.length} methods on ${run.case}…`;
    return app.execute({ type: 'startCompare', body: { scenario: record.scenario, methods, mode: 'batch' }, report: false });
  }
}
