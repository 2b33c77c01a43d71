// The run list: stored and live runs (newest first) with filters, Watch for
// live runs, Replay for ended ones, a compare group's link, the frames
// exports and delete. Refreshed every 2 s while the page is visible, and
// when a session opens or ends.
import { api } from './api.js';
import { app } from './state.js';
import { isLive } from './session.js';
import { outcomeText } from './failure_modes.js';
import { escapeHtml } from './dom.js';
import { laneLabels } from './lane_labels.js';

const $ = (id) => document.getElementById(id);

// A run's method as its compare group names it (lane_labels.js): the method
// plus the parameters in which it differs from the group's other runs in the list.
function runLabel(r, runs) {
  if (!r.compare_group) return r.method;
  const group = runs.filter((o) => o.compare_group === r.compare_group).sort((a, b) => a.id - b.id);
  return laneLabels(group.map((o) => ({ method: o.method, params: o.params })))[group.indexOf(r)] ?? r.method;
}

export class RunList {
  // sweeps() → the server's sweeps [{id, name, total, status}], grouped below the runs
  constructor({ sweeps = () => [] } = {}) {
    this.sweeps = sweeps;
    for (const id of ['filter-scenario', 'filter-method', 'filter-status']) $(id).onchange = () => this.refresh();
    this.timer = setInterval(() => { if (!document.hidden) this.refresh(); }, 2000);
    app.signals.scenariosChanged.add(() => this.fillFilter('filter-scenario', app.scenarios.map((s) => s.name)));
    app.signals.methodsChanged.add(() => this.fillFilter('filter-method', app.methods.map((m) => m.name)));
    for (const signal of ['sessionOpened', 'sessionEnded', 'started']) app.signals[signal].add(() => this.refresh());
  }

  // A filter's choices; the one chosen stays chosen.
  fillFilter(id, names) {
    const select = $(id), first = select.options[0].outerHTML, chosen = select.value;
    select.innerHTML = first + names.map((n) => `<option>${escapeHtml(n)}</option>`).join('');
    if (names.includes(chosen)) select.value = chosen;
  }

  open(ids) { app.execute({ type: 'open', ids }); }

  // Runs of no sweep, newest first; then one folded group per sweep of this
  // server, whose runs (named by their case) load when it is unfolded.
  async refresh() {
    const q = { limit: 40, sweep: 'none' };
    for (const [key, id] of [['scenario', 'filter-scenario'], ['method', 'filter-method'], ['status', 'filter-status']])
      if ($(id).value) q[key] = $(id).value;
    let runs;
    try { runs = await api.runs(q); } catch (e) { return; }
    const list = $('runs');
    const open = new Set([...list.querySelectorAll('details.sweep-runs[open]')].map((d) => d.dataset.sweep));
    const items = runs.map((r) => this.item(r, runs));
    if (!runs.length) items.push(Object.assign(document.createElement('li'), { className: 'muted', textContent: 'no runs yet' }));
    for (const sweep of this.sweeps()) items.push(this.sweepGroup(sweep, open.has(sweep.name), q));
    list.replaceChildren(...items);
  }

  // A sweep's runs under one folded entry: its name, Open (its page), and its
  // runs by case once unfolded.
  sweepGroup(sweep, open, filters) {
    const li = document.createElement('li');
    li.className = 'sweep-group';
    li.innerHTML = `<details class="sweep-runs" data-sweep="${escapeHtml(sweep.name)}"><summary><span class="title">sweep ${escapeHtml(sweep.name)}</span>
      <span class="muted small">${sweep.total} runs · ${escapeHtml(sweep.status)}</span></summary><ul class="sweep-run-list"><li class="muted small">loading…</li></ul></details>
      <div class="actions"><button type="button">Open sweep</button></div>`;
    li.querySelector('button').onclick = () => app.execute({ type: 'openSweep', id: sweep.id });
    const details = li.querySelector('details');
    const ul = li.querySelector('.sweep-run-list');
    const show = (runs) => {
      ul.replaceChildren(...runs.map((r) => this.item(r, runs)));
      if (!runs.length) ul.innerHTML = '<li class="muted small">no runs match the filters</li>';
    };
    // the last list shown stands until the new one comes (the list refreshes every 2 s)
    this.sweepRuns = this.sweepRuns || new Map();
    if (this.sweepRuns.has(sweep.name)) show(this.sweepRuns.get(sweep.name));
    const load = async () => {
      const runs = await api.runs({ ...filters, sweep: sweep.name }).catch(() => null);
      if (!runs) return;
      this.sweepRuns.set(sweep.name, runs);
      show(runs);
    };
    details.addEventListener('toggle', () => { if (details.open) load(); });  // fired by opening it, by hand or below
    if (open) details.open = true;
    return li;
  }

  item(r, runs) {
    const li = document.createElement('li');
    li.dataset.run = String(r.id);
    const live = isLive(r.status);
    if (live) li.className = 'live';
    if (r.sweep) {
      // a sweep's run: named by its case and method configuration, with its verdict
      const w = r.sweep;
      const verdict = outcomeText(w);
      li.innerHTML = `<div class="title">#${r.id} <span class="mono">${escapeHtml(w.case)}</span></div>
        <div class="muted small">${escapeHtml(w.config)} · <span class="${w.success ? 'pass' : 'fail'}">${escapeHtml(verdict)}</span> · ${r.frames ? `<span class="frames">${r.frames}</span> frames` : 'no frames stored'}</div>
        <div class="actions"></div>`;
    } else {
      li.innerHTML = `<div class="title">#${r.id} ${escapeHtml(r.scenario)}</div>
      <div class="muted small">${escapeHtml(runLabel(r, runs))} · ${escapeHtml(r.mode)}${r.source_run ? ` of #${r.source_run}` : ''} · ${escapeHtml(r.status)} · <span class="frames">${r.frames}</span> frames</div>
      <div class="actions"></div>`;
    }
    const actions = li.querySelector('.actions');
    const button = (text, title, onclick) => {
      const b = document.createElement('button');
      b.textContent = text;
      b.title = title;
      b.onclick = onclick;
      actions.appendChild(b);
      return b;
    };
    if (live) button('Watch', 'attach to the live run', () => this.open([r.id]));
    else if (r.frames > 0) button('Replay', 'play the stored frames', () => this.open([r.id]));
    else if (r.status === 'completed' && r.summary && r.summary.steps > 0) {
      button('Re-simulate', 'no frames were stored: simulate it again from its recorded inputs, then replay it', () => app.execute({ type: 'resimulate', id: r.id }));
    }
    if (r.compare_group) {
      const group = runs.filter((o) => o.compare_group === r.compare_group).map((o) => o.id).sort((a, b) => a - b);
      if (group.length > 1 && group[0] === r.id) button('Compare', `open the compare group ${group.join(', ')}`, () => this.open(group));
    }
    if (r.frames > 0) {
      for (const [text, format] of [['CSV', 'csv'], ['JSON', 'json']]) {
        const a = document.createElement('a');
        a.href = api.framesLink(r.id, format);
        a.textContent = text;
        a.title = `frames as ${text} (the first 20,000; page with from=)`;
        a.download = `run-${r.id}.${format}`;
        actions.appendChild(a);
      }
      const html = document.createElement('a');
      html.href = api.exportLink(r.id);
      html.textContent = 'HTML';
      html.title = 'the run as one HTML file that replays offline (views, scrubber, charts)';
      html.download = `rrlab-run-${r.id}.html`;
      actions.appendChild(html);
    }
    const del = button('Delete', 'delete the run, its frames and events', async () => {
      if (!confirm(`Delete run #${r.id} and its frames?`)) return;
      await app.execute({ type: 'deleteRun', id: r.id }).then(() => this.refresh(), () => {});
    });
    del.disabled = live;
    if (live) del.title = 'a live run cannot be deleted: stop it first';
    return li;
  }
}
