// Editing the scene of a live run from the views: drag an obstacle (PUT at
// most 20 times a second, and once more at release), add one by choosing a
// shape and clicking where it goes, delete the selected one. In a compare
// group the server applies scene edits to every lane. Edits are input
// commands; the tools follow the session's signals (bound to a live run's
// views, read-only once it ended).
import { app, OVERLAYS } from './state.js';
import { isTyping } from './dom.js';

const $ = (id) => document.getElementById(id);

export class SceneTools {
  constructor() {
    this.placing = null;
    this.selected = null;
    this.lastPut = 0;
    this.added = 0;
    $('add-obstacle').onclick = () => this.setPlacing(this.placing ? null : $('add-shape').value);
    $('delete-obstacle').onclick = () => this.deleteSelected();
    window.addEventListener('keydown', (e) => {
      if (isTyping(e.target, e.key)) return;
      if (e.key === 'Escape') this.setPlacing(null);
      if (e.key === 'Delete' && this.selected !== null) this.deleteSelected();
    });
    const current = (lane) => app.session && app.session.lanes.includes(lane);
    app.signals.sessionChanged.add(() => this.reset());
    app.signals.viewCreated.add((lane) => {
      if (app.session && app.session.kind === 'live') this.bind(lane);
      else lane.view.onSelect = null;
    });
    app.signals.snapshot.add((lane) => { if (current(lane) && lane.index === 0) this.configure(lane.snapshot); });
    // an ended run's scene is read-only on screen too: no drags, no placing, no delete
    app.signals.sessionEnded.add((session) => {
      for (const lane of session.lanes) this.unbind(lane);
      this.reset();
    });
  }

  // Shapes that make sense for the model: planar arms get prisms (squares) and discs.
  configure(snapshot) {
    const planar = snapshot.model.kind === 'planar';
    const shapes = planar ? [['sphere', 'disc (sphere)'], ['polygon', 'square (polygon)'], ['point', 'point']]
      : [['sphere', 'sphere'], ['box', 'box'], ['point', 'point']];
    const current = $('add-shape').value;
    $('add-shape').innerHTML = shapes.map(([v, l]) => `<option value="${v}" ${v === current ? 'selected' : ''}>${l}</option>`).join('');
  }

  // Hooks a lane's view to the run's scene.
  bind(lane) {
    const view = lane.view;
    view.onObstacleDrag = (index, position, phase) => this.drag(lane, index, position, phase);
    view.onPlace = (point) => this.place(lane, point).catch((e) => app.error(e));
    view.onSelect = (index) => this.select(lane, index);
    view.placing = this.placing;
  }

  // An ended run's scene is read-only: nothing drags, places or deletes,
  // and a drag in progress lets go (the obstacle is drawn where the run left it).
  unbind(lane) {
    const view = lane.view;
    if (!view) return;
    view.onObstacleDrag = null;
    view.onPlace = null;
    view.placing = null;
    view.selected = null;
    if (view.endDrag) view.endDrag();
    view.invalidate();
  }

  live() { return app.liveSession; }

  input(kind, payload, report = true) { return app.execute({ type: 'input', kind, payload, report }); }

  drag(lane, index, position, phase) {
    const session = this.live();
    if (!session) return;
    const now = performance.now();
    if (phase === 'move' && now - this.lastPut < 50) return;
    this.lastPut = now;
    const obstacle = lane.snapshot.obstacles[index];
    if (!obstacle) return;
    const id = obstacle.id;
    this.input('obstacle_move', { id, position });
  }

  setPlacing(shape) {
    this.placing = shape;
    $('add-obstacle').setAttribute('aria-pressed', String(Boolean(shape)));
    $('add-obstacle').textContent = shape ? 'Click in the view… (Esc)' : 'Place';
    for (const lane of app.lanes) {
      if (lane.view) lane.view.placing = shape;
      if (lane.cell) lane.cell.classList.toggle('placing', Boolean(shape));
    }
  }

  async place(lane, point) {
    const session = this.live();
    const shape = this.placing;
    this.setPlacing(null);
    if (!session || !shape) return;
    const size = Math.max(0.02, 0.06 * lane.snapshot.model.reach);
    const ids = new Set(lane.snapshot.obstacles.map((o) => o.id));
    let id;
    do id = `added${++this.added}`; while (ids.has(id));
    const body = { id, shape };
    if (shape === 'sphere') Object.assign(body, { center: point, radius: size });
    else if (shape === 'box') Object.assign(body, { center: point, size: [2 * size, 2 * size, 2 * size] });
    else if (shape === 'point') Object.assign(body, { position: point });
    else if (shape === 'polygon') Object.assign(body, { points: [[-size, -size], [size, -size], [size, size], [-size, size]].map(([x, y]) => [point[0] + x, point[1] + y]) });
    await this.input('obstacle_add', body, false);
  }

  // A new session starts with nothing selected and nothing being placed.
  reset() {
    this.setPlacing(null);
    this.selected = null;
    $('selected-obstacle').textContent = 'no obstacle selected';
    $('delete-obstacle').disabled = true;
  }

  select(lane, index) {
    this.selected = index === null ? null : { lane, index };
    const o = index === null ? null : lane.snapshot.obstacles[index];
    $('selected-obstacle').textContent = o ? `selected: ${o.id} (${o.shape})` : 'no obstacle selected';
    $('delete-obstacle').disabled = !o || !this.live();
  }

  async deleteSelected() {
    const session = this.live();
    if (!session || !this.selected) return;
    const { lane, index } = this.selected;
    const id = lane.snapshot.obstacles[index].id;
    this.select(lane, null);
    if (lane.view) lane.view.selected = null;
    await this.input('obstacle_delete', { id });
  }
}

// One check box per overlay; the views read app.overlays at each render.
export function buildOverlayToggles() {
  const box = $('overlay-toggles');
  box.replaceChildren();
  for (const o of OVERLAYS) {
    const label = document.createElement('label');
    label.className = 'overlay-toggle';
    label.title = o.help;
    label.innerHTML = `<input type="checkbox" data-overlay="${o.key}" ${app.overlays[o.key] ? 'checked' : ''}> ${o.label}`;
    label.querySelector('input').onchange = (e) => app.execute({ type: 'overlay', key: o.key, on: e.target.checked });
    box.appendChild(label);
  }
}
