// The run list: stored and live runs (newest first) with filters, Watch for
// live runs, Replay for ended ones, a compare group's link, the frames
// exports and delete. Refreshed every 2 s while the page is visible.
import { api } from './api.js';
import { app } from './state.js';
import { isLive } from './session.js';
import { escapeHtml } from './dom.js';

const $ = (id) => document.getElementById(id);

export class RunList {
  constructor({ open, deleted }) {
    this.open = open;  // (ids) opens runs: live ones attach, ended ones replay
    this.deleted = deleted;  // (id) after a run was deleted
    for (const id of ['filter-scenario', 'filter-method', 'filter-status']) $(id).onchange = () => this.refresh();
    this.timer = setInterval(() => { if (!document.hidden) this.refresh(); }, 2000);
  }

  fillFilters() {
    const fill = (id, names) => {
      const select = $(id), first = select.options[0].outerHTML;
      select.innerHTML = first + names.map((n) => `<option>${escapeHtml(n)}</option>`).join('');
    };
    fill('filter-scenario', app.scenarios.map((s) => s.name));
    fill('filter-method', app.methods.map((m) => m.name));
  }

  async refresh() {
    const q = new URLSearchParams({ limit: '40' });
    for (const [key, id] of [['scenario', 'filter-scenario'], ['method', 'filter-method'], ['status', 'filter-status']])
      if ($(id).value) q.set(key, $(id).value);
    let runs;
    try { runs = await api('GET', `/api/runs?${q}`); } catch (e) { return; }
    const list = $('runs');
    list.replaceChildren(...runs.map((r) => this.item(r, runs)));
    if (!runs.length) list.innerHTML = '<li class="muted">no runs yet</li>';
  }

  item(r, runs) {
    const li = document.createElement('li');
    li.dataset.run = String(r.id);
    const live = isLive(r.status);
    if (live) li.className = 'live';
    li.innerHTML = `<div class="title">#${r.id} ${escapeHtml(r.scenario)}</div>
      <div class="muted small">${escapeHtml(r.method)} · ${escapeHtml(r.mode)} · ${escapeHtml(r.status)} · <span class="frames">${r.frames}</span> frames</div>
      <div class="actions"></div>`;
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
    if (r.compare_group) {
      const group = runs.filter((o) => o.compare_group === r.compare_group).map((o) => o.id).sort((a, b) => a - b);
      if (group.length > 1 && group[0] === r.id) button('Compare', `open the compare group ${group.join(', ')}`, () => this.open(group));
    }
    if (r.frames > 0) {
      for (const [text, format] of [['CSV', 'csv'], ['JSON', 'json']]) {
        const a = document.createElement('a');
        a.href = `/api/runs/${r.id}/frames?format=${format}`;
        a.textContent = text;
        a.title = `frames as ${text} (the first 20,000; page with from=)`;
        a.download = `run-${r.id}.${format}`;
        actions.appendChild(a);
      }
    }
    const del = button('Delete', 'delete the run, its frames and events', async () => {
      if (!confirm(`Delete run #${r.id} and its frames?`)) return;
      await api('DELETE', `/api/runs/${r.id}`).then(() => { this.deleted(r.id); this.refresh(); }, (e) => app.error(e));
    });
    del.disabled = live;
    if (live) del.title = 'a live run cannot be deleted: stop it first';
    return li;
  }
}
