// What the page shows: one run or a compare group, live or replayed. A
// session has one lane per run (its stream, snapshot, latest frame and view);
// views are made when the first snapshot says what the model is (Canvas 2D
// for planar arms, three.js for every other kind). The session and its lanes
// change here only: a stream's messages update them and the signals of
// state.js tell the panels. Inputs to a live run are commands (state.js:
// execute({type: 'input', …})), sent by commands.js.
import { api, paths, ApiError, Stream } from './api.js';
import { app, LANE_COLOURS, writeUrl } from './state.js';
import { View2D } from './view2d.js';
import { laneLabels } from './lane_labels.js';
import { recordedAt } from './recorded.js';

const TERMINAL = new Set(['completed', 'stopped', 'failed', 'interrupted']);
export const isLive = (status) => status === 'running' || status === 'paused';

class Lane {
  constructor(index, run, colour) {
    this.index = index;
    this.runId = run.id;
    this.method = run.method;
    this.label = run.method;  // set by Session.relabel: the method plus what tells it from the other lanes
    this.colour = colour;
    this.replayId = null;
    this.snapshot = null;
    this.frame = null;
    this.view = null;
    this.cell = null;
    this.stream = null;
    this.status = run.status;
    this.framesReceived = 0;
    this.startParams = {};  // by method: the parameters of its first snapshot (the run's starting values)
    this.events = null;     // a replay's recorded inputs (api.events), once loaded
    this.localScene = null; // a replay: the scene (local_frames.js) drawn from the page's memory
    this.recorded = null;   // a replay's method and parameters at the playhead (recorded.js): {method, params, seq}
    this.ready = new Promise((resolve) => { this.resolveReady = resolve; });  // the first snapshot
  }
}

export class Session {
  // kind: 'live' | 'replay'; runs: stored run records (api.run)
  constructor(kind, runs, layout) {
    this.kind = kind;
    this.runs = runs;
    this.layout = runs.length > 1 ? layout : 'side';
    this.lanes = runs.map((run, i) => new Lane(i, run, runs.length > 1 ? LANE_COLOURS[i] : '#37474f'));
    this.relabel();
    this.focus = 0;
    this.frameCount = Math.max(0, ...runs.map((r) => r.frames));
    this.closed = false;
    this.endSeen = false;   // sessionEnded dispatched
    this.fromLive = false;  // a live session that ended and became its replay (becomeReplay)
    this.shownStatus = null;  // lane 0's run status as the header shows it
    this.frameGate = null;    // a replay's: (lane, frame) → whether a frame its player sent is drawn
  }

  // Every lane's label from its method and starting parameters (lane_labels.js):
  // lanes of one method are told apart by the parameters in which they differ.
  relabel() {
    // the run's own method: its stored parameters; a method switched to: its first snapshot's
    const params = (lane) => (lane.method === this.runs[lane.index].method ? this.runs[lane.index].params : lane.startParams[lane.method]) || {};
    const labels = laneLabels(this.lanes.map((lane) => ({ method: lane.method, params: params(lane) })));
    this.lanes.forEach((lane, i) => { lane.label = labels[i]; });
  }

  get runIds() { return this.runs.map((r) => r.id); }
  get compare() { return this.runs.length > 1; }
  // Scene, joystick and reset inputs go to the group through its first run.
  get controlRun() { return this.runs[0].id; }
  get focusLane() { return this.lanes[this.focus]; }

  // Opens every lane's stream. A session closed meanwhile (the user opened
  // another) stops here and pauses any player it had asked for.
  async open() {
    this.buildCells();
    for (const lane of this.lanes) {
      let path = paths.runStream(lane.runId);
      const run = this.runs[lane.index];
      if (this.kind === 'replay' && run.frames === 0) {
        // a completed run without frames (a sweep's: summaries only) can be re-simulated; a stopped one had no step
        lane.cell.innerHTML = run.status === 'completed' && run.summary && run.summary.steps > 0
          ? `<p class="empty-lane muted">Run #${run.id} completed ${run.summary.steps} steps but stored no frames${run.sweep ? ' (a sweep stores summaries only)' : ''}.
             <button type="button" data-resimulate="${run.id}" title="simulate it again from its recorded inputs, store the frames and replay them">Re-simulate</button></p>`
          : `<p class="empty-lane muted">Run #${run.id} stored no frames: it ${run.status === 'failed' ? 'failed' : 'was stopped'} before its first step.</p>`;
        continue;
      }
      if (this.kind === 'replay') {
        const player = await api.replayRun(lane.runId, { mode: 'frames', speed: 1 });
        lane.replayId = player.replay;
        if (this.closed) { api.replayControl(player.replay, { action: 'pause' }).catch(() => {}); return; }
        path = player.ws;
      }
      this.connect(lane, path);
    }
    this.updateUrl();
  }

  // A live session whose runs all ended becomes their replay, its lanes and
  // views kept (camera, zoom, trace): each lane's stream is now a player of
  // its stored run, started at its last frame. Resolves false when the
  // session was closed meanwhile or was not an ended live one.
  async becomeReplay() {
    if (this.closed || !this.ended) return false;
    const runs = await Promise.all(this.runIds.map((id) => api.run(id)));
    // an answer cut short (the page is leaving) is no run: nothing changes
    if (this.closed || runs.some((r, i) => !r || r.id !== this.runIds[i] || !Number.isInteger(r.frames))) return false;
    // every player first: when one cannot start (too many replays), the session stays as it ended
    const settled = await Promise.allSettled(runs.map((run) => (run.frames > 0 ? api.replayRun(run.id, { mode: 'frames', speed: 1, from: run.frames - 1 }) : null)));
    const players = settled.map((p) => (p.status === 'fulfilled' && p.value && typeof p.value.ws === 'string' ? p.value : null));
    const refused = settled.find((p, i) => p.status === 'rejected' || (runs[i].frames > 0 && !players[i]));
    if (this.closed || refused) {
      for (const player of players) if (player) api.replayControl(player.replay, { action: 'pause' }).catch(() => {});
      if (refused && !this.closed) throw refused.status === 'rejected' ? refused.reason : new Error('the server did not start a replay of the run');
      return false;
    }
    this.kind = 'replay';
    this.fromLive = true;
    this.runs = runs;
    this.frameCount = Math.max(0, ...runs.map((r) => r.frames));
    for (const lane of this.lanes) {
      if (lane.stream) lane.stream.close();
      lane.stream = null;
      lane.status = runs[lane.index].status;
      const player = players[lane.index];
      if (!player) continue;
      lane.replayId = player.replay;
      this.connect(lane, player.ws);
    }
    return true;
  }

  // The lane's stream at `path` (a live run's, or a replay player's).
  connect(lane, path) {
    lane.stream = new Stream(path, {
      onSnapshot: (snapshot) => this.snapshot(lane, snapshot),
      onFrame: (frame) => this.frame(lane, frame),
      onMessage: (message) => {
        if (message.type === 'params') this.paramsChanged(lane, message);
        else if (message.type === 'scene') this.sceneChanged(lane, message);
        else if (message.type === 'error') app.error(new ApiError(message.error.status || 400, message.error));
        // who holds control of this run: on connecting, and at every change
        else if (message.type === 'control' && message.event === 'state') app.signals.control.dispatch(message.controller);
        // another client took control of this run from this tab
        else if (message.type === 'control' && message.event === 'taken') app.signals.controlTaken.dispatch(message.message);
      },
      onState: (state) => this.streamState(lane, state),
      probe: () => this.probe(lane),
    });
  }

  // Reconnect only to something that still exists and still runs.
  async probe(lane) {
    if (this.closed) return false;
    if (this.kind === 'replay') return api.replay(lane.replayId).then(() => true, (e) => e.status !== 404);
    return api.run(lane.runId).then((run) => { lane.status = run.status; return isLive(run.status); }, (e) => e.status !== 404);
  }

  buildCells() {
    const views = document.getElementById('views');
    views.replaceChildren();
    const cells = this.layout === 'overlay' ? 1 : this.lanes.length;
    views.className = `layout-${cells}`;
    for (let i = 0; i < cells; ++i) {
      const cell = document.createElement('div');
      cell.className = 'view-cell';
      cell.dataset.lane = String(i);
      views.appendChild(cell);
      this.lanes[i].cell = cell;
    }
  }

  async snapshot(lane, snapshot) {
    if (this.closed) return;
    if (!lane.startParams[snapshot.method]) lane.startParams[snapshot.method] = { ...snapshot.params };
    // a replay's player applies no parameter changes: the values recorded at the playhead
    if (this.kind === 'replay' && lane.recorded && lane.recorded.method === snapshot.method) snapshot = { ...snapshot, params: { ...snapshot.params, ...lane.recorded.params } };
    lane.snapshot = snapshot;
    lane.status = snapshot.status;
    lane.resolveReady(snapshot);
    // after a method switch the lane's name is its new method: tabs, captions, legends
    if (lane.method !== snapshot.method) {
      lane.method = snapshot.method;
      this.relabel();
      if (this.compare && this.layout === 'side') {
        for (const l of this.lanes) if (l.view && l.view.label !== l.label) { l.view.label = l.label; l.view.invalidate(); }
      }
    }
    const framesBefore = lane.framesReceived;
    if (!lane.view && lane.cell) await this.makeView(lane, snapshot);
    if (this.closed) return;
    if (lane.view) lane.view.setSnapshot(snapshot);
    // a frame that came while the view was being made (the 3D module loads) is newer than the snapshot's
    if (lane.framesReceived !== framesBefore && lane.frame) { if (lane.view) lane.view.setFrame(lane.frame); }
    else if (snapshot.frame) lane.frame = snapshot.frame;
    this.refreshOverlayLanes();
    app.signals.snapshot.dispatch(lane);
    this.checkEnded();
  }

  // A replay's recorded inputs, per lane (in the order of runIds).
  setEvents(eventsPerLane) {
    // joystick inputs (many a second) change neither the method nor its parameters
    for (const lane of this.lanes) lane.events = (eventsPerLane[lane.index] || []).filter((e) => e.kind !== 'joystick');
  }

  // The replay at frame `seq`: each lane's method and parameters as recorded
  // then (its events), the panel told of a change in place. The method's own
  // name, param specs and the obstacles come with the player's snapshot at
  // that frame (it applies the scene's events and method switches).
  showRecordedAt(seq) {
    if (this.closed || this.kind !== 'replay') return;
    for (const lane of this.lanes) {
      if (!lane.events || !lane.snapshot) continue;
      const run = this.runs[lane.index];
      const start = { method: run.method, params: lane.startParams[run.method] || run.params || {} };
      const recorded = recordedAt(lane.events, Math.min(seq, Math.max(0, run.frames - 1)), start, app.methods);
      const before = lane.recorded;
      lane.recorded = recorded;
      const changed = !before || before.seq !== recorded.seq || before.method !== recorded.method;
      if (recorded.method === lane.snapshot.method) {
        const params = { ...lane.snapshot.params, ...recorded.params };
        if (changed || Object.keys(params).some((k) => params[k] !== lane.snapshot.params[k])) {
          lane.snapshot = { ...lane.snapshot, params };
          app.signals.params.dispatch(lane);
        }
      } else if (changed) app.signals.params.dispatch(lane);
    }
  }

  // A parameter change: new values, the same method; the panel updates in place.
  paramsChanged(lane, message) {
    if (this.closed || !lane.snapshot) return;
    lane.snapshot = { ...lane.snapshot, params: message.params, scene_version: message.scene_version };
    app.signals.params.dispatch(lane);
  }

  // An obstacle edited: the new obstacles; a mesh obstacle keeps the
  // triangles its snapshot brought (an edit moves a mesh, never changes it).
  sceneChanged(lane, message) {
    if (this.closed || !lane.snapshot) return;
    const meshes = new Map(lane.snapshot.obstacles.filter((o) => o.mesh).map((o) => [o.id, o.mesh]));
    const obstacles = message.obstacles.map((o) => (!o.mesh && meshes.has(o.id) ? { ...o, mesh: meshes.get(o.id) } : o));
    lane.snapshot = { ...lane.snapshot, obstacles, scene_version: message.scene_version };
    if (lane.view) lane.view.setSnapshot(lane.snapshot);
    this.refreshOverlayLanes();
  }

  async makeView(lane, snapshot) {
    if (lane.viewPromise) return lane.viewPromise;
    lane.viewPromise = (async () => {
      let view;
      if (snapshot.model.kind === 'planar') view = new View2D(lane.cell);
      else {
        const { View3D } = await import('./view3d.js');
        if (this.closed) return;
        view = new View3D(lane.cell);
      }
      view.colour = lane.colour;
      if (this.compare && this.layout === 'side') view.label = lane.label;
      view.overlays = app.overlays;
      lane.view = view;
      app.signals.viewCreated.dispatch(lane);
    })();
    return lane.viewPromise;
  }

  // Overlaid compare: lane 0's view draws the other lanes' arms too.
  refreshOverlayLanes() {
    if (this.layout !== 'overlay' || !this.lanes[0].view) return;
    this.lanes[0].view.setLanes(this.lanes.slice(1));
  }

  // A frame to draw: from the lane's stream, which a replay's bar may hold
  // back (frameGate: not the frame to show), or from the page's memory (`held`).
  frame(lane, frame, held = false) {
    if (this.closed) return;
    if (!held && this.frameGate && !this.frameGate(lane, frame)) return;
    lane.frame = frame;
    lane.framesReceived += 1;
    lane.status = frame.status;
    if (lane.view) lane.view.setFrame(frame);
    if (this.layout === 'overlay' && lane.index > 0 && this.lanes[0].view) this.lanes[0].view.invalidate();
    app.signals.frame.dispatch(lane);
    // the header says paused or live as the run does
    if (this.kind === 'live' && lane.index === 0 && frame.status !== this.shownStatus) {
      this.shownStatus = frame.status;
      app.signals.connection.dispatch(this);
    }
    this.checkEnded();
  }

  // A live session whose runs all ended (seen in a frame, or in the first
  // snapshot when the runs ended before the page attached) says so once and
  // becomes their replay (commands.js replayEnded); one that ended before any
  // frame reached the page opens its stored runs as a replay instead.
  checkEnded() {
    if (this.closed || this.endSeen || !this.ended) return;
    this.endSeen = true;
    if (!this.lanes.some((l) => l.framesReceived > 0)) {
      app.execute({ type: 'open', ids: this.runIds, layout: this.layout });
      return;
    }
    app.signals.sessionEnded.dispatch(this);
    app.execute({ type: 'replayEnded' });
  }

  // The overlay toggles changed: every view draws again.
  invalidateViews() {
    for (const lane of this.lanes) if (lane.view) lane.view.invalidate();
  }

  streamState(lane, state) {
    lane.streamState = state;
    app.signals.connection.dispatch(this);
  }

  get ended() { return this.kind === 'live' && this.lanes.every((l) => TERMINAL.has(l.status)); }
  // Restart with this scene: an ended live session, or the replay it became.
  get restartable() { return (this.kind === 'live' && this.ended) || this.fromLive; }
  get empty() { return this.kind === 'replay' && this.frameCount === 0; }

  // The address of this session (at a replay's frame); options: writeUrl's.
  updateUrl(frame, options) {
    const ids = this.runIds.join(',');
    writeUrl({ run: this.compare ? null : ids, compare: this.compare ? ids : null, frame: this.kind === 'replay' ? frame : null }, options);
  }

  render() {
    for (const lane of this.lanes) if (lane.view) lane.view.render();
  }

  close() {
    this.closed = true;
    for (const lane of this.lanes) {
      if (lane.stream) lane.stream.close();
      if (lane.view) lane.view.destroy();
      if (lane.replayId) api.replayControl(lane.replayId, { action: 'pause' }).catch(() => {});
    }
    document.getElementById('views').replaceChildren();
  }
}

// Opens runs by id: live ones attach to their streams, ended ones replay.
export async function sessionFor(ids, layout) {
  const runs = await Promise.all(ids.map((id) => api.run(id)));
  const live = runs.some((r) => isLive(r.status));
  return new Session(live ? 'live' : 'replay', runs, layout);
}
