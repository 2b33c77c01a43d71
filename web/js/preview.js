// The start page: with nothing in the centre (no run, compare, replay, paper
// or sweep page), the scenario chosen under New run is drawn as a run of it
// would start — the snapshot and frame 0 of GET /api/scenarios/{name}/preview,
// in the view a run would use (Canvas 2D for planar arms, three.js for the
// others) — labelled a preview, with the first thing to do (Start live) and
// where to look next. It gives way to any session or page (their signals)
// and comes back when the centre is empty again; a scenario that cannot be
// drawn says why in the view. It draws only: nothing is sent to the server.
import { api } from './api.js';
import { app } from './state.js';
import { View2D } from './view2d.js';

const $ = (id) => document.getElementById(id);

export class StartPreview {
  constructor() {
    this.view = null;
    this.cell = null;
    this.shown = null;       // the scenario drawn (or asked for)
    this.generation = 0;     // a newer refresh or a clear makes an older answer stale
    this.ready = false;      // the page opened what its address asked for
    const s = app.signals;
    s.started.add(() => { this.ready = true; this.refresh(); });
    s.sessionChanged.add((session) => (session ? this.clear() : this.refresh()));
    s.pageChanged.add((page) => (page ? this.clear() : this.refresh()));
    s.choiceChanged.add(() => this.refresh());
    s.scenariosChanged.add(() => this.refresh());
  }

  // Whether the centre is the start page's.
  get wanted() { return this.ready && !app.session && !app.page; }

  // After the current task: a command that clears the session and then opens
  // a page (setPage) has done both before the preview looks.
  refresh() {
    queueMicrotask(() => this.update().catch((e) => this.failed(this.shown, e)));
  }

  async update() {
    if (!this.wanted) { this.clear(); return; }
    const name = app.choice.scenario;
    if (!name) { this.clear(); this.hint('No scenario to preview: add one with the Scenario editor.'); return; }
    if (name === this.shown && this.cell && this.cell.isConnected) return;
    const generation = ++this.generation;
    this.shown = name;
    let snapshot;
    try {
      snapshot = await api.scenarioPreview(name);
    } catch (e) {
      if (generation === this.generation && this.wanted) this.failed(name, e);
      return;
    }
    if (generation !== this.generation || !this.wanted) return;
    this.removeView();
    const cell = this.makeCell(name);
    let view;
    if (snapshot.model.kind === 'planar') view = new View2D(cell);
    else {
      const { View3D } = await import('./view3d.js');
      if (generation !== this.generation || !this.wanted) return;
      view = new View3D(cell);
    }
    if (generation !== this.generation || !this.wanted) { view.destroy(); return; }
    view.overlays = app.overlays;
    view.setSnapshot(snapshot);
    this.view = view;
    this.snapshot = snapshot;
  }

  // A fresh cell in the centre with the preview's line (what it is, the first
  // action, where next) above the element the view fills.
  makeCell(name) {
    const views = $('views');
    views.replaceChildren();
    views.className = 'layout-1';
    const cell = document.createElement('div');
    cell.className = 'view-cell preview-cell';
    cell.dataset.preview = name;
    const note = document.createElement('div');
    note.className = 'preview-note';
    note.innerHTML = `<b>Preview</b> · <span class="preview-name"></span> at its start: not a run.
      Press <b>Start live</b> to run it, or look at
      <button type="button" class="link" data-goto="papers-section">Papers</button>,
      <button type="button" class="link" data-goto="sweeps-section">Sweeps</button> or
      <button type="button" class="link" data-goto="compare-setup">Compare methods</button>.`;
    note.querySelector('.preview-name').textContent = name;
    note.addEventListener('click', (e) => {
      const button = e.target.closest('button[data-goto]');
      if (button) goTo(button.dataset.goto);
    });
    // the view below the line, so that the line hides nothing of the scene
    const host = document.createElement('div');
    host.className = 'preview-host';
    cell.append(note, host);
    views.appendChild(cell);
    this.cell = cell;
    return host;
  }

  // The scenario could not be drawn: why, in the view (not on the message line).
  failed(name, e) {
    this.removeView();
    const reason = e && e.status === 404 ? `there is no scenario "${name}"` : (e && e.message) || String(e);
    this.hint(`No preview of ${name}: ${reason}.`);
    this.cell.classList.add('preview-failed');
  }

  hint(text) {
    this.removeView();
    const views = $('views');
    views.replaceChildren();
    views.className = 'layout-1';
    const cell = document.createElement('div');
    cell.className = 'view-cell preview-cell';
    const p = document.createElement('p');
    p.className = 'preview-message muted';
    p.textContent = text;
    cell.appendChild(p);
    views.appendChild(cell);
    this.cell = cell;
  }

  removeView() {
    if (this.view) this.view.destroy();
    this.view = null;
    this.snapshot = null;
    if (this.cell) this.cell.remove();
    this.cell = null;
  }

  // A session or a page takes the centre: the preview goes, its answer if still coming is dropped.
  clear() {
    this.generation += 1;
    this.shown = null;
    this.removeView();
  }

  render() {
    if (this.view) this.view.render();
  }
}

// "Papers", "Sweeps", "Compare methods": the section unfolded, in sight and focused.
function goTo(id) {
  const section = $(id);
  if (!section) return;
  if (section.tagName === 'DETAILS') section.open = true;
  section.scrollIntoView({ block: 'nearest' });
  const target = section.querySelector('summary, h2, select, button');
  if (target) target.focus({ preventScroll: true });
}
