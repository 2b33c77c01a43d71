// The page's commands: every input to a live run and every change of what
// is shown goes through app.execute({type, ...}) (state.js) to a handler
// here, as every change in the three.js editor goes through
// editor.execute(command). A handler changes the state (app.setSession,
// app.setPage, app.choice, ...) and the signals tell the panels; it never
// touches the page's elements. Panels build the command from their inputs.
import { api } from './api.js';
import { app, PAPER_KEYS, readUrl, writeUrl } from './state.js';
import { sessionFor } from './session.js';
import { resimulate } from './resimulate.js';
import { eventMarkers } from './events.js';
import { fmt } from './dom.js';
import { contacts } from './compare_verdict.js';
import { runFails } from './first_failure.js';
import { failureSources } from './failures.js';

const report = (e) => app.error(e);

// A session on screen: the panels hear of it, its streams open, and a
// replay's stored frames and recorded inputs load for its charts and scrubber.
async function show(next, frame = null) {
  app.setSession(next);
  await next.open();
  if (app.session !== next) return;  // another session was opened meanwhile
  await opened(next, frame);
}

// The panels hear that a session's streams are open (at `frame`, or for a
// failed single run at its first failure when no frame is asked for); a
// replay's stored frames and recorded inputs load.
async function opened(s, frame) {
  const sources = s.kind === 'replay' ? await failureSources(s.runs) : [];
  if (app.session !== s) return;
  const atFailure = frame === null && !s.compare && sources.length > 0 && runFails(sources[0]);
  app.signals.sessionOpened.dispatch(s, { frame, sources, atFailure });
  if (s.kind === 'replay' && !s.empty) {
    loadStoredFrames(s).catch(report);
    loadMarkers(s).catch(report);
  }
}

// Replays plot the whole run (exact stored values; strided beyond 20,000
// frames) against run time, seq·dt: a run that was reset goes on to the right
// instead of folding back, and a click on a plot names one frame.
async function loadStoredFrames(s) {
  await Promise.all(s.lanes.map(async (lane) => {
    const frames = s.runs[lane.index].frames;
    if (frames === 0) return;
    const { dt } = await lane.ready;
    const stride = Math.max(1, Math.ceil(frames / 20000));
    const data = await api.frames(lane.runId, { from: 0, to: frames - 1, stride });
    for (const f of data.frames) f.t = f.seq * dt;
    if (app.session === s) app.signals.storedFrames.dispatch(lane, data);
  }));
}

// The recorded inputs of a replay, for the scrubber and the charts.
async function loadMarkers(s) {
  const events = await Promise.all(s.runIds.map((id) => api.events(id)));
  const lane = s.lanes.find((l) => s.runs[l.index].frames > 0) || s.lanes[0];
  const { dt } = await lane.ready;
  if (app.session !== s) return;
  // the parameter panel shows the values recorded at the playhead (session.js showRecordedAt)
  s.setEvents(events);
  if (app.playhead !== null) s.showRecordedAt(app.playhead);
  app.signals.markers.dispatch(eventMarkers(events).map((m) => ({ ...m, t: m.seq * dt })));
}

function open(ids, layout = 'side', frame = null) {
  return sessionFor(ids, layout).then((next) => show(next, frame));
}

// `replace`: the view closed can never come back (its run was deleted), so
// it leaves no history entry to go Back to.
function close(why, replace = false) {
  app.setSession(null);
  writeUrl({}, { replace });
  if (why) app.info(why);
}

// A page in the centre — a paper's or a sweep's — instead of any run.
function showPage(page, address) {
  app.setPage(page);
  writeUrl(address);
}

// A sweep's page, with one of its cells ({family, config}) open or none.
function showSweep(id, cell = null) {
  showPage({ name: 'sweep', id, cell }, { sweep: id, family: cell && cell.family, config: cell && cell.config });
}

// What an address asks for (readUrl): a compare, a run (at a frame), a
// sweep (and a cell), a paper; false when it names none of them (the start
// view: the pickers), an unknown paper said on the message line.
async function openAddress(url) {
  if (url.compare.length > 1) await open(url.compare, 'side', url.frame);
  else if (url.run) await open([url.run], 'side', url.frame);
  else if (url.sweep) showSweep(url.sweep, url.family ? { family: url.family, config: url.config } : null);
  else if (url.paper && PAPER_KEYS.includes(url.paper)) showPage({ name: 'paper', key: url.paper }, { paper: url.paper });
  else {
    if (url.paper) app.error(`no paper "${url.paper}" (paper= takes one of ${PAPER_KEYS.join(', ')})`);
    return false;
  }
  return true;
}

// The pickers' scenario and method from an address, where the catalogue has them.
function choiceFrom(url) {
  if (url.scenario && app.scenarios.some((s) => s.name === url.scenario)) app.choice.scenario = url.scenario;
  if (url.method && app.methods.some((m) => m.name === url.method)) app.choice.method = url.method;
}

const sameIds = (a, b) => a.length === b.length && a.every((id, i) => id === b[i]);

// An obstacle of a snapshot in the scenario format, where the run left it: an
// obstacle of the scenario keeps its own description (sizes, rpy in the
// scenario's angle unit, a mesh's file) and takes the snapshot's place; one
// added during the run is taken as the snapshot has it (rpy converted from
// radians when the scenario counts in degrees).
export function asScenarioObstacle(o, scenario) {
  const original = (scenario.obstacles || []).find((x) => x.id === o.id);
  const { mesh, ...live } = o;
  if (!original) {
    if (Array.isArray(live.rpy) && scenario.angle_unit === 'deg') live.rpy = live.rpy.map((r) => (r * 180) / Math.PI);
    if (live.shape === 'polygon' && Array.isArray(live.position)) {
      const [dx, dy] = live.position;
      live.points = live.points.map(([x, y]) => [x + dx, y + dy]);
      delete live.position;
    }
    return live;
  }
  const moved = structuredClone(original);
  if ('center' in original && live.center) moved.center = live.center;
  if ('position' in original && live.position && original.shape !== 'polygon') moved.position = live.position;
  if ('point' in original && live.point) moved.point = live.point;
  if (original.shape === 'polygon' && Array.isArray(live.position)) {
    const [dx, dy] = live.position;
    moved.points = live.points.map(([x, y]) => [x + dx, y + dy]);
  }
  return moved;
}

// A new live run's body from the pickers' choice, or from what the command names.
function liveBody(c) {
  const body = { scenario: c.scenario ?? app.choice.scenario, mode: 'live', rate: c.rate ?? app.choice.rate };
  const method = c.method ?? app.choice.method;
  if (method) body.method = method;
  return body;
}

export const commands = {
  // What the address asks for (?run=, ?compare=, ?sweep=, ?paper=,
  // ?scenario=&method=), once the catalogue is loaded.
  async start() {
    [app.scenarios, app.methods, app.frameFields] = await Promise.all([api.scenarios(), api.methods(), api.frameFields()]);
    api.health().then((h) => { app.version = h.version; }, () => {});
    const url = readUrl();
    choiceFrom(url);
    // the picker's first scenario is the choice until one is picked (the start page draws it)
    if (!app.choice.scenario && app.scenarios.length) app.choice.scenario = app.scenarios[0].name;
    app.signals.scenariosChanged.dispatch();
    app.signals.methodsChanged.dispatch();
    try {
      await openAddress(url);
    } finally {
      app.signals.started.dispatch();
    }
  },

  // Back or Forward (popstate): what the address names now. The replay on
  // screen at another frame seeks; any other view opens as a link does; an
  // address that names nothing is the start view.
  async navigate() {
    const url = readUrl();
    const s = app.session;
    const ids = url.compare.length > 1 ? url.compare : url.run ? [url.run] : [];
    if (s && ids.length && sameIds(s.runIds, ids)) {
      if (s.kind === 'replay' && url.frame !== null) app.signals.seek.dispatch(url.frame);
      return;
    }
    if (await openAddress(url)) return;
    app.setSession(null);
    const before = { ...app.choice };
    choiceFrom(url);
    // the pickers follow only what changed (a new catalogue signal rebuilds the compare rows)
    if (app.choice.scenario !== before.scenario) app.signals.scenariosChanged.dispatch();
    if (app.choice.method !== before.method) app.signals.methodsChanged.dispatch();
  },

  // The catalogue's scenarios again (one was saved), `select` chosen.
  async loadScenarios({ select }) {
    app.scenarios = await api.scenarios();
    if (select) app.choice.scenario = select;
    app.signals.scenariosChanged.dispatch();
  },

  // The pickers of a new run: {scenario?, method?, rate?}. With no session
  // on screen the address keeps the scenario and method.
  choose(c) {
    for (const key of ['scenario', 'method', 'rate']) if (c[key] !== undefined) app.choice[key] = c[key];
    if ((c.scenario !== undefined || c.method !== undefined) && !app.session) writeUrl({ scenario: app.choice.scenario, method: app.choice.method });
    app.signals.choiceChanged.dispatch();
  },

  // Runs by id ({ids, layout, frame}): live ones attach, ended ones replay (at `frame`).
  open: ({ ids, layout, frame }) => open(ids, layout, frame),
  close: ({ why }) => close(why),
  // {id, cell?: {family, config}}: a sweep's page, and one of its cells
  openSweep: ({ id, cell }) => showSweep(id, cell && cell.family && cell.config ? { family: cell.family, config: cell.config } : null),
  openPaper: ({ key }) => showPage({ name: 'paper', key }, { paper: key }),

  async startLive(c) {
    const run = await api.startRun(liveBody(c));
    await open([run.id]);
  },

  async startBatch(c) {
    const body = { ...liveBody(c), mode: 'batch' };
    delete body.rate;
    app.status('running to the end…');
    const result = await api.startRun(body);
    const s = result.summary;
    app.info(`batch run #${result.id}: ${s.steps} steps, max tracking error ${fmt(s.max_tracking_error)} m, min distance ${fmt(s.min_distance)} m, ${contacts(s).join(', ') || 'no collision'}`);
    app.status('');
    await open([result.id]);
  },

  // {body: {scenario, methods, mode, rate?}, layout}
  async startCompare({ body, layout = 'side' }) {
    const group = await api.startCompare(body);
    await open(group.runs.map((r) => r.id), layout);
  },

  // An example of a paper: live with its configuration, or as a live compare
  // with the paper's baselines. {kind: 'live'|'compare', scenario, methods}
  async startExample({ kind, scenario, methods }) {
    const rate = app.choice.rate;
    if (kind === 'live') {
      const body = { scenario, mode: 'live', rate };
      const own = methods[0];
      if (typeof own === 'string') body.method = own;
      else if (own) { body.method = own.name; body.params = own.params; }
      const run = await api.startRun(body);
      await open([run.id]);
      return;
    }
    const group = await api.startCompare({ scenario, methods, mode: 'live', rate });
    await open(group.runs.map((r) => r.id), 'side');
  },

  // A new live run of the ended run's scenario and method (parameters as they
  // stood at the end), with the obstacles where the run left them.
  async restart() {
    const s = app.session;
    if (!s || !s.restartable) return;
    const lane = s.lanes[0];
    const record = await api.record(lane.runId);
    const scenario = structuredClone(record.scenario);
    if (lane.snapshot && Array.isArray(lane.snapshot.obstacles)) {
      scenario.obstacles = lane.snapshot.obstacles.map((o) => asScenarioObstacle(o, record.scenario));
    }
    const body = { scenario, mode: 'live', rate: app.choice.rate };
    if (lane.snapshot) { body.method = lane.snapshot.method; body.params = lane.snapshot.params; }
    if (s.compare) {
      const methods = s.lanes.map((l) => (l.snapshot ? { name: l.snapshot.method, params: l.snapshot.params } : l.label));
      const group = await api.startCompare({ scenario, methods, mode: 'live', rate: body.rate });
      await open(group.runs.map((r) => r.id), s.layout);
      return;
    }
    const run = await api.startRun(body);
    await open([run.id]);
  },

  // The live session on screen ended: it becomes the replay of its runs,
  // its views kept, the scrubber at the end.
  async replayEnded() {
    const s = app.session;
    if (!s || !s.ended || !(await s.becomeReplay()) || app.session !== s) return;
    await opened(s, s.frameCount - 1);
  },

  // A run that stored no frames: re-simulated from its recorded inputs
  // (progress on the status line, or to onProgress(done, total)), then replayed.
  async resimulate({ id, onProgress }) {
    const progress = onProgress || ((done, total) => app.status(`re-simulating run #${id}: ${done}${total ? ` / ${total}` : ''} frames`));
    const copy = await resimulate(id, progress);
    await open([copy]);
  },

  // The compare layout applies to the group on screen too (at its current frame).
  async setLayout({ layout }) {
    const s = app.session;
    if (!s || !s.compare || s.layout === layout) return;
    await open(s.runIds, layout, s.kind === 'replay' ? app.playhead : null);
  },

  // Deletes a stored run; the run on screen, if it was, is closed.
  async deleteRun({ id }) {
    await api.deleteRun(id);
    if (app.session && app.session.runIds.includes(id)) close(`run #${id} was deleted`, true);
  },

  // An input to the live run on screen ({kind, payload, runId}: see
  // api.js INPUT_KINDS), to `runId` or the group's control run; nothing
  // without a live session. Resolves with the server's answer.
  input({ kind, payload, runId }) {
    const s = app.session;
    if (!s || s.kind !== 'live') return undefined;
    return api.input(runId ?? s.controlRun, kind, payload);
  },

  // The lane whose parameters the panel shows ({lane: index}).
  focus({ lane }) {
    const s = app.session;
    if (!s || !s.lanes[lane]) return;
    s.focus = lane;
    app.signals.focusChanged.dispatch(s);
  },

  // An overlay toggle ({key, on}); the views read app.overlays as they draw.
  overlay({ key, on }) {
    app.overlays[key] = Boolean(on);
    if (app.session) app.session.invalidateViews();
  },
};
