// The dashboard: wires the panels to the central state (state.js) and the
// session (session.js). Opens what the address asks for (?run=, ?compare=,
// ?scenario=&method=), draws at the display rate with requestAnimationFrame.
import { api, describeError, listScenarios, setTokenPrompt } from './api.js';
import { askForToken } from './token_prompt.js';
import { app, readUrl, writeUrl } from './state.js';
import { sessionFor } from './session.js';
import { buildParams, updateParams, setupMethodSwitch, fmt } from './params.js';
import { showMetrics } from './metrics.js';
import { RunList } from './runs.js';
import { CompareSetup, showCompareSummary, hideCompareSummary } from './compare.js';
import { ReplayBar } from './replay.js';
import { SceneTools, buildOverlayToggles } from './scene_tools.js';
import { Plots } from './plots.js';
import { Joystick } from './joystick.js';
import { ScenarioEditor } from './scenario_editor.js';
import { SweepList } from './sweeps.js';
import { SweepPage } from './sweep_view.js';
import { resimulate } from './resimulate.js';
import { Papers, PAPER_KEYS } from './paper_view.js';
import { setupLayout } from './layout.js';
import { ExportDialog } from './export_dialog.js';
import { eventMarkers } from './events.js';
import { escapeHtml } from './dom.js';

const $ = (id) => document.getElementById(id);
let session = null;
let metricsDirty = false;

// ---- messages -----------------------------------------------------------
setTokenPrompt(askForToken);
setupLayout();
app.signals.message.add((what, kind) => {
  // another tab or client steers this run: say so plainly and offer to take over
  if (what && what.code === 'not_controller') {
    showControl('other');
    what = 'Another client controls this run; you are watching. Press “Take control” to steer it.';
  }
  const box = $('message');
  box.className = kind === 'info' ? 'info' : '';
  box.querySelector('span').textContent = typeof what === 'string' ? what : describeError(what);
  box.hidden = false;
  clearTimeout(box.timer);
  if (kind === 'info') box.timer = setTimeout(() => { box.hidden = true; }, 4000);
});
$('message').querySelector('button').onclick = () => { $('message').hidden = true; };
const report = (e) => app.error(e);

// ---- panels ---------------------------------------------------------------
const runList = new RunList({
  open: (ids) => openRuns(ids).catch(report),
  // the run on screen was deleted: nothing left to show
  deleted: (id) => { if (session && session.runIds.includes(id)) closeSession(`run #${id} was deleted`); },
});
const sweepPage = new SweepPage({ open: (ids) => openRuns(ids).catch(report) });
const sweepList = new SweepList({ open: (id) => openSweep(id).catch(report) });
runList.sweeps = () => sweepList.sweeps;
runList.openSweep = (id) => openSweep(id).catch(report);
runList.resimulate = (id) => resimulateAndOpen(id).catch(report);
const papers = new Papers({ start: (what) => startPaperExample(what).catch(report) });
const compareSetup = new CompareSetup({ start: (body, layout) => startCompare(body, layout) });
// The replay's current frame, shown everywhere it is named (the bar's readout is its own).
const replayBar = new ReplayBar({
  onPresent: (seq, frame) => {
    const lane = session && session.lanes[0];
    if (lane && lane.snapshot) plots.setCursor(seq * lane.snapshot.dt);
    const t = frame ? frame.t : lane && lane.snapshot ? seq * lane.snapshot.dt : null;
    $('status').textContent = `${t === null ? '' : `t = ${t.toFixed(2)} s · `}${frame ? `step ${frame.step} · ` : ''}frame ${seq}`;
  },
});
const sceneTools = new SceneTools(() => session);
const plots = new Plots($('plots'));
const exportDialog = new ExportDialog({ getSession: () => session, plots, replayBar });
plots.onSeek = (t) => replayBar.seekTime(t);
const joystick = new Joystick($('joystick'), {
  send: (command) => {
    if (!session || session.kind !== 'live') return undefined;
    return session.input('joystick', command);
  },
});
const editor = new ScenarioEditor($('editor-host'), {
  api,
  onStart: async (name) => {
    app.scenarios = await listScenarios(api);
    fillScenarios(name);
    await startLive();
  },
});
setupMethodSwitch(() => session);
buildOverlayToggles(() => { if (session) for (const lane of session.lanes) if (lane.view) lane.view.invalidate(); });

// ---- catalogue -----------------------------------------------------------
function fillScenarios(selected) {
  const options = (chosen) => app.scenarios.map((s) => `<option value="${escapeHtml(s.name)}" ${s.name === chosen ? 'selected' : ''}>${escapeHtml(s.name)}</option>`).join('');
  $('scenario').innerHTML = options(selected);
  $('compare-scenario').innerHTML = options(selected);
  describeScenario();
}
// The list gives the first 200 characters of a description; "read all" fetches the rest.
function describeScenario() {
  const s = app.scenarios.find((x) => x.name === $('scenario').value);
  $('scenario-description').textContent = s ? s.description : '';
  $('scenario-more').hidden = !s || s.description.length < 199;
}
$('scenario-more').onclick = async () => {
  const name = $('scenario').value;
  try {
    const full = await api('GET', `/api/scenarios/${encodeURIComponent(name)}`);
    if ($('scenario').value === name) { $('scenario-description').textContent = full.description || ''; $('scenario-more').hidden = true; }
  } catch (e) { report(e); }
};
$('scenario').onchange = () => { describeScenario(); if (!session) writeUrl({ scenario: $('scenario').value, method: $('method').value }); };
$('method').onchange = () => { if (!session) writeUrl({ scenario: $('scenario').value, method: $('method').value }); };

async function loadCatalogue() {
  [app.scenarios, app.methods] = await Promise.all([listScenarios(api), api('GET', '/api/methods')]);
  api('GET', '/api/health').then((h) => { app.version = h.version; }, () => {});
  fillScenarios();
  $('method').innerHTML = '<option value="">(the scenario\'s own)</option>' +
    app.methods.map((m) => `<option value="${escapeHtml(m.name)}" title="${escapeHtml(m.description)}">${escapeHtml(m.name)}</option>`).join('');
  compareSetup.init();
  runList.fillFilters();
}

// ---- sessions ------------------------------------------------------------
function closeSession(why) {
  if (session) session.close();
  session = null;
  exportDialog.update(null);
  replayBar.detach();
  sceneTools.reset();
  joystick.configure({ enabled: false, space: 'xy', reach: 1 });
  for (const id of ['controls', 'params-section', 'joystick-section']) $(id).hidden = true;
  hideCompareSummary();
  $('session-title').textContent = '';
  $('status').textContent = '';
  $('connection').textContent = 'not connected';
  $('connection').className = 'pill muted';
  writeUrl({});
  if (why) app.info(why);
}

// A page in the centre — a paper's or a sweep's — instead of any run.
async function openCentrePage(name, address, show) {
  closeSession();
  (name === 'paper' ? sweepPage : papers).hide();
  writeUrl(address);
  $('connection').textContent = name;
  await show();
}
function openPaper(key) { return openCentrePage('paper', { paper: key }, () => papers.show(key)); }
function openSweep(id) { return openCentrePage('sweep', { sweep: id }, () => sweepPage.show(id)); }

// An example of a paper: live with its configuration, or as a live compare
// with the paper's baselines.
async function startPaperExample({ kind, scenario, methods }) {
  const rate = Number($('rate').value);
  if (kind === 'live') {
    const body = { scenario, mode: 'live', rate };
    const own = methods[0];
    if (typeof own === 'string') body.method = own;
    else if (own) { body.method = own.name; body.params = own.params; }
    const run = await api('POST', '/api/runs', body);
    await openRuns([run.id]);
    return;
  }
  const group = await api('POST', '/api/compare', { scenario, methods, mode: 'live', rate });
  await openRuns(group.runs.map((r) => r.id), 'side');
}

// A run that stored no frames: re-simulated from its recorded inputs (progress
// in the status line), then replayed.
async function resimulateAndOpen(runId) {
  const id = await resimulate(runId, (done, total) => {
    $('status').textContent = `re-simulating run #${runId}: ${done}${total ? ` / ${total}` : ''} frames`;
  });
  await openRuns([id]);
}

async function show(next, startFrame) {
  sweepPage.hide();
  papers.hide();
  exportDialog.update(next);
  if (session) session.close();
  session = next;
  replayBar.detach();
  sceneTools.reset();
  hideCompareSummary();
  $('controls').hidden = next.kind !== 'live';
  $('ended-note').hidden = true;
  showControl('none');
  for (const el of document.querySelectorAll('#controls button:not(#delete-obstacle), #controls select')) el.disabled = false;
  // a session on screen: its controls come first, the pickers fold away
  $('new-run').open = false;
  $('compare-setup').open = false;
  $('run-id').textContent = next.runIds.map((id) => `#${id}`).join(' ');
  $('session-title').textContent = `${next.kind === 'live' ? 'live' : 'replay'} · ${next.runs[0].scenario} · ${next.runs.map((r) => r.method).join(' vs ')}`;
  configurePlots(next, next.runs.map((r) => r.diagnostic_names || []));
  await next.open();
  if (session !== next) return;  // another session was opened meanwhile
  if (next.kind === 'replay' && !next.empty) {
    replayBar.attach(next, startFrame);
    loadWholeRuns(next).catch(report);
    loadMarkers(next).catch(report);
  }
  // a stored compare group has its summary at once
  if (next.kind === 'replay' && next.compare) showCompareSummary(next).catch(report);
  runList.refresh();
}

// One series per lane; each lane's diagnostics in its method's order.
function configurePlots(s, namesPerLane) {
  s.plotNames = namesPerLane.map((names) => names.join('\n'));
  plots.configure({
    lanes: s.lanes.map((l, i) => ({ label: l.label, colour: l.colour, diagnosticNames: namesPerLane[i] })),
    diagnosticNames: [...new Set(namesPerLane.flat())],
    mode: s.kind,
    windowSeconds: 10,
  });
}

// Replays plot the whole run (exact stored values; strided beyond 20,000
// frames) against run time, seq·dt: a run that was reset goes on to the right
// instead of folding back, and a click on a plot names one frame.
async function loadWholeRuns(s) {
  await Promise.all(s.lanes.map(async (lane) => {
    const frames = s.runs[lane.index].frames;
    if (frames === 0) return;
    const { dt } = await lane.ready;
    const stride = Math.max(1, Math.ceil(frames / 20000));
    const data = await api('GET', `/api/runs/${lane.runId}/frames?from=0&to=${frames - 1}&stride=${stride}`);
    lane.stored = data.frames.map((f) => ({ seq: f.seq, ee: f.ee }));  // the trace up to any frame, after a seek
    for (const f of data.frames) f.t = f.seq * dt;
    if (session !== s) return;
    plots.setRun(lane.index, data);
    if (lane.shownSeq !== null && lane.shownSeq !== undefined && lane.view) replayBar.rebuildTrace(lane, lane.shownSeq);
  }));
}

// The recorded inputs of a replay, marked on the scrubber and the charts.
async function loadMarkers(s) {
  const events = await Promise.all(s.runIds.map((id) => api('GET', `/api/runs/${id}/events`)));
  const markers = eventMarkers(events);
  if (session !== s) return;
  replayBar.setMarkers(markers);
  const lane = s.lanes.find((l) => s.runs[l.index].frames > 0) || s.lanes[0];
  const { dt } = await lane.ready;
  if (session === s) plots.setMarkers(markers.map((m) => ({ ...m, t: m.seq * dt })));
}

async function openRuns(ids, layout = 'side', frame = null) {
  await show(await sessionFor(ids, layout), frame);
}

async function startLive() {
  const body = { scenario: $('scenario').value, mode: 'live', rate: Number($('rate').value) };
  if ($('method').value) body.method = $('method').value;
  const run = await api('POST', '/api/runs', body);
  await openRuns([run.id]);
}

async function startBatch() {
  const body = { scenario: $('scenario').value, mode: 'batch' };
  if ($('method').value) body.method = $('method').value;
  $('status').textContent = 'running to the end…';
  const result = await api('POST', '/api/runs', body);
  const s = result.summary;
  app.info(`batch run #${result.id}: ${s.steps} steps, max tracking error ${fmt(s.max_tracking_error)} m, min distance ${fmt(s.min_distance)} m, ${s.collided ? 'collided' : 'no collision'}`);
  $('status').textContent = '';
  await openRuns([result.id]);
}

async function startCompare(body, layout) {
  const group = await api('POST', '/api/compare', body);
  await openRuns(group.runs.map((r) => r.id), layout);
}

// An obstacle of a snapshot in the scenario format, where the run left it: an
// obstacle of the scenario keeps its own description (sizes, rpy in the
// scenario's angle unit, a mesh's file) and takes the snapshot's place; one
// added during the run is taken as the snapshot has it (rpy converted from
// radians when the scenario counts in degrees).
function asScenarioObstacle(o, scenario) {
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

// A new live run of the ended run's scenario and method (parameters as they
// stood at the end), with the obstacles where the run left them.
async function restartWithScene() {
  const s = session;
  if (!s || s.kind !== 'live' || !s.ended) return;
  const lane = s.lanes[0];
  const record = await api('GET', `/api/runs/${lane.runId}/record`);
  const scenario = structuredClone(record.scenario);
  if (lane.snapshot && Array.isArray(lane.snapshot.obstacles)) {
    scenario.obstacles = lane.snapshot.obstacles.map((o) => asScenarioObstacle(o, record.scenario));
  }
  const body = { scenario, mode: 'live', rate: Number($('rate').value) };
  if (lane.snapshot) { body.method = lane.snapshot.method; body.params = lane.snapshot.params; }
  if (s.compare) {
    const group = await api('POST', '/api/compare', { scenario, methods: s.lanes.map((l) => (l.snapshot ? { name: l.snapshot.method, params: l.snapshot.params } : l.label)), mode: 'live', rate: body.rate });
    await openRuns(group.runs.map((r) => r.id), s.layout);
    return;
  }
  const run = await api('POST', '/api/runs', body);
  await openRuns([run.id]);
}
// The compare layout applies to the group on screen too (at its current frame).
$('compare-layout').addEventListener('change', () => {
  if (!session || !session.compare || session.layout === $('compare-layout').value) return;
  openRuns(session.runIds, $('compare-layout').value, session.kind === 'replay' ? replayBar.seq : null).catch(report);
});
$('restart-scene').onclick = () => restartWithScene().catch(report);
$('start-live').onclick = () => startLive().catch(report);
$('start-batch').onclick = () => startBatch().catch(report);
for (const button of document.querySelectorAll('[data-action]')) {
  button.onclick = () => {
    if (!session || session.kind !== 'live') return;
    session.input('control', { action: button.dataset.action }).catch(report);
  };
}

// One client controls a live run: the line under the controls says who
// ('you': Release; 'other': Take control, the holder is told; 'none': hidden,
// the next input takes it). The server tells every socket at each change.
const controlText = {
  you: 'You control this run.',
  other: 'Another client controls this run; you are watching.',
};
function showControl(controller) {
  const note = $('control-note');
  note.dataset.controller = controller;
  note.hidden = !(controller in controlText);
  if (note.hidden) return;
  note.querySelector('span').textContent = controlText[controller];
  $('take-control').hidden = controller !== 'other';
  $('release-control').hidden = controller !== 'you';
}
function controlAction(action, done) {
  if (!session || session.kind !== 'live') return;
  session.input('control', { action })
    .then((state) => { showControl(state.controller || 'none'); done(); }, report);
}
$('take-control').onclick = () => controlAction('take', () => app.info('You control this run now.'));
$('release-control').onclick = () => controlAction('release', () => app.info('You let go of this run; another client may steer it.'));
app.signals.control.add((controller) => { if (session && session.kind === 'live' && !session.ended) showControl(controller); });
app.signals.controlTaken.add((text) => { showControl('other'); app.error(text); });

// "Re-simulate" in a lane that stored no frames
$('views').addEventListener('click', (e) => {
  const button = e.target.closest('button[data-resimulate]');
  if (button) { button.disabled = true; resimulateAndOpen(Number(button.dataset.resimulate)).catch(report); }
});

// ---- stream events -------------------------------------------------------
app.signals.viewCreated.add((lane) => {
  if (session && session.kind === 'live') sceneTools.bind(lane);
  else lane.view.onSelect = null;
  $('empty-hint')?.remove();
});

app.signals.snapshot.add((lane) => {
  if (!session || !session.lanes.includes(lane)) return;
  // after a method switch the lane's name is its new method: tabs, captions, legends
  if (lane.label !== lane.snapshot.method) {
    lane.label = lane.snapshot.method;
    $('session-title').textContent = `${session.kind === 'live' ? 'live' : 'replay'} · ${session.runs[0].scenario} · ${session.lanes.map((l) => l.label).join(' vs ')}`;
    if (lane.view && session.compare && session.layout === 'side') { lane.view.label = lane.label; lane.view.invalidate(); }
    if (session.layout === 'overlay') session.refreshOverlayLanes();
  }
  if (lane.index === session.focus) buildParams(session);
  // a replay's snapshot carries the frame its player shows
  if (session.kind === 'replay' && lane.frame) replayBar.onFrame(lane, lane.frame);
  // a method switch changes the diagnostics: the plots start again with the new names
  if (session.kind === 'live' && session.plotNames && session.plotNames[lane.index] !== lane.snapshot.diagnostic_names.join('\n')) {
    lane.label = lane.snapshot.method;
    configurePlots(session, session.lanes.map((l, i) => (l.snapshot ? l.snapshot.diagnostic_names : session.runs[i].diagnostic_names || [])));
  }
  if (lane.index === 0) {
    const s = lane.snapshot;
    sceneTools.configure(s);
    const joystickTask = s.task.trajectory === 'joystick' && session.kind === 'live' && !session.ended;
    $('joystick-section').hidden = !joystickTask;
    joystick.configure({ enabled: joystickTask, space: s.task.space, reach: s.model.reach });
  }
  metricsDirty = true;
  endIfEnded(session);
});

app.signals.params.add((lane) => {
  if (session && session.lanes.includes(lane) && lane.index === session.focus) updateParams(session);
});

app.signals.frame.add((lane) => {
  if (!session || !session.lanes.includes(lane)) return;
  metricsDirty = true;
  const f = lane.frame;
  lane.framesSeen = true;
  if (session.kind === 'live') plots.push(lane.index, f);
  if (session.kind === 'replay') replayBar.onFrame(lane, f);
  else if (lane.index === 0) $('status').textContent = `t = ${f.t.toFixed(2)} s · step ${f.step} · ${f.status}`;
  // the header says paused or live as the run does
  if (session.kind === 'live' && lane.index === 0 && f.status !== session.shownStatus) {
    session.shownStatus = f.status;
    app.signals.connection.dispatch(session);
  }
  endIfEnded(session);
});

// A live session whose runs all ended (seen in a frame, or in the first
// snapshot when the runs ended before the page attached): the controls go
// quiet, the scene turns read-only and a group gets its summary.
function endIfEnded(s) {
  if (s.kind === 'live' && s.ended && !s.summaryShown) {
    const session = s, lane = s.lanes[0];
    session.summaryShown = true;
    // ended before any frame reached the page: the stored runs replay instead
    if (!session.lanes.some((l) => l.framesSeen)) { openRuns(session.runIds, session.layout).catch(report); return; }
    // its scene is read-only on screen too: no drags, no placing, no delete, no control notice
    for (const l of session.lanes) sceneTools.unbind(l);
    showControl('none');
    $('ended-note').hidden = false;
    // an ended run takes no more inputs: its controls and joystick go quiet
    joystick.configure({ enabled: false, space: lane.snapshot ? lane.snapshot.task.space : 'xy', reach: 1 });
    $('joystick-section').hidden = true;
    for (const el of document.querySelectorAll('#controls button, #controls select')) el.disabled = true;
    $('restart-scene').disabled = false;
    buildParams(session);  // its parameters read-only too
    sceneTools.reset();
    app.signals.connection.dispatch(session);
    if (session.compare) showCompareSummary(session).catch(report);
    runList.refresh();
  }
}

app.signals.connection.add((s) => {
  if (s !== session) return;
  const states = s.lanes.map((l) => l.streamState);
  const el = $('connection');
  const open = states.every((x) => x === 'open');
  if (s.ended) { el.textContent = `ended (${s.lanes[0].status})`; el.className = 'pill muted'; return; }
  const paused = s.kind === 'live' && s.lanes[0].status === 'paused';
  el.textContent = open ? (s.kind === 'live' ? (paused ? 'paused' : 'live') : 'replay') : states.find((x) => x !== 'open') || '';
  el.className = `pill ${open ? 'ok' : 'warn'}`;
});

// ---- drawing loop --------------------------------------------------------
const fps = { frames: 0, since: performance.now(), value: 0, renderMs: 0 };
let lastMetrics = 0;
function tick(now) {
  const t0 = performance.now();
  replayBar.tick(now);
  if (session) session.render();
  plots.render();
  // tables are text for people: 10 updates a second are plenty and spare the layout work
  if (metricsDirty && now - lastMetrics >= 100) { metricsDirty = false; lastMetrics = now; showMetrics(session); }
  fps.renderMs = 0.9 * fps.renderMs + 0.1 * (performance.now() - t0);
  fps.frames++;
  if (now - fps.since >= 1000) { fps.value = (fps.frames * 1000) / (now - fps.since); fps.frames = 0; fps.since = now; }
  requestAnimationFrame(tick);
}
requestAnimationFrame(tick);

// ---- header --------------------------------------------------------------
$('copy-link').onclick = async () => {
  try { await navigator.clipboard.writeText(location.href); app.info('link copied'); } catch { app.info(location.href); }
};
$('open-editor').onclick = async () => {
  try {
    let scenario;
    if (session) scenario = (await api('GET', `/api/runs/${session.runIds[0]}/record`)).scenario;
    else scenario = await api('GET', `/api/scenarios/${encodeURIComponent($('scenario').value)}`);
    editor.open(scenario);
  } catch (e) { report(e); }
};

// For browser tests and for measuring: the state, the session and the frame rate.
window.__rrlab = { app, fps, get session() { return session; }, plots, replay: replayBar };

// ---- start: what the address asks for --------------------------------------
async function start() {
  await loadCatalogue();
  const url = readUrl();
  if (url.scenario && app.scenarios.some((s) => s.name === url.scenario)) fillScenarios(url.scenario);
  if (url.method && app.methods.some((m) => m.name === url.method)) $('method').value = url.method;
  if (url.compare.length > 1) await openRuns(url.compare, 'side', url.frame);
  else if (url.run) await openRuns([url.run], 'side', url.frame);
  else if (url.sweep) await openSweep(url.sweep);
  else if (url.paper) {
    if (PAPER_KEYS.includes(url.paper)) { $('papers-section').open = true; await openPaper(url.paper); }
    else app.error(`no paper "${url.paper}" (paper= takes one of ${PAPER_KEYS.join(', ')})`);
  }
  else runList.refresh();
  sweepList.refresh();
  papers.fillList((key) => openPaper(key).catch(report)).catch(report);
}
start().catch(report);
