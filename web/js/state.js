// The page's state and its one owner, in the manner of the three.js editor's
// Editor.js: what is shown (the session and its lanes, or a centre page), the
// catalogue, the pickers' choice and the overlay toggles; the signals the
// panels subscribe to; and execute(command), the one path by which inputs
// and session changes are made. Commands are plain objects {type, ...}; their
// handlers (commands.js) are the only code that calls setSession / setPage.
// The address bar follows what is shown, so a copied link reopens it, and
// every new view is a history entry of its own (writeUrl), so Back and
// Forward move between views.

// A dispatch made by a listener of the same signal waits until every listener
// has heard the one before it: all hear them in the order they were made
// (a replay draws frames synchronously, and a frame may publish anew).
export class Signal {
  constructor() { this.listeners = []; this.queue = null; }
  add(listener) { this.listeners.push(listener); }
  dispatch(...args) {
    if (this.queue) { this.queue.push(args); return; }
    this.queue = [args];
    try {
      for (let i = 0; i < this.queue.length; ++i) for (const listener of this.listeners) listener(...this.queue[i]);
    } finally {
      this.queue = null;
    }
  }
}

export const LANE_COLOURS = ['#1e88e5', '#ef6c00', '#2e7d32', '#8e24aa'];
// The link nearest an obstacle, and a collided one: hues no lane wears.
export const NEAREST_LINK_COLOUR = '#fbc02d';
export const COLLIDED_COLOUR = '#c62828';

export const OVERLAYS = [
  { key: 'nearest', label: 'Nearest obstacle', help: 'segment from each link to its nearest obstacle, with the distance' },
  { key: 'manipulability', label: 'Manipulability', help: 'velocity manipulability ellipse (ellipsoid in 3D) at the end-effector, scaled to the arm at the first frame' },
  { key: 'method', label: 'Method overlays', help: "the method's own ellipses, points and segments" },
  { key: 'ghosts', label: 'Ghosts', help: 'imaginary arms a method plans with (multi_preview)' },
  { key: 'trace', label: 'End-effector trace', help: 'where the end-effector has been' },
];

// The papers a page `?paper=KEY` can show.
export const PAPER_KEYS = ['sezgin', 'chen', 'qiu', 'zhang', 'kapoor'];

const handlers = {};

export const app = {
  session: null,      // the run or compare group on screen (session.js), or null
  page: null,         // the page shown in the centre instead: {name: 'paper', key} | {name: 'sweep', id, cell: {family, config} | null} | null
  playhead: null,     // a replay's frame on screen (replay.js moves it: setPlayhead)
  overlays: Object.fromEntries(OVERLAYS.map((o) => [o.key, true])),
  methods: [],        // the server's methods
  frameFields: [],    // the frame field table (GET /api/frame-fields): what a frame carries, the charts' metrics
  scenarios: [],      // every scenario's summary
  version: '',        // rrlab's, from the health route
  choice: { scenario: null, method: '', rate: 1 },  // the pickers of a new run
  signals: {
    sessionChanged: new Signal(),  // (session | null) another session is on screen (its streams not yet open), or none
    sessionOpened: new Signal(),   // (session, {frame, sources, atFailure}) its streams are open; frame: the replay frame asked for; sources: each run's {summary, sweep}; atFailure: open paused at its first failure
    sessionEnded: new Signal(),    // (session) every run of the live session on screen ended
    pageChanged: new Signal(),     // (page | null) a paper's or a sweep's page in the centre, or none
    focusChanged: new Signal(),    // (session) another lane's parameters are shown
    snapshot: new Signal(),        // (lane) a lane got a new snapshot
    params: new Signal(),          // (lane) a lane's parameter values changed (lane.snapshot.params)
    frame: new Signal(),           // (lane) a lane got a new frame
    viewCreated: new Signal(),     // (lane) a lane's view exists (2D or 3D)
    connection: new Signal(),      // (session) a stream's state, or the live run's status, changed
    storedFrames: new Signal(),    // (lane, {frames}) a replayed lane's stored frames (strided), each with its t
    markers: new Signal(),         // (markers) a replay's recorded inputs, [{seq, t, kind, text}]
    failures: new Signal(),        // (failures) a replay's first failures, one per failing lane: [{lane, seq, t, kind: 'failure', mode, text}]
    playhead: new Signal(),        // (seq, frame | null) the replay's current frame (app.setPlayhead)
    seek: new Signal(),            // (seq) the address asks the replay on screen for another frame (Back / Forward)
    scenariosChanged: new Signal(),  // () app.scenarios (and app.choice.scenario) loaded anew
    methodsChanged: new Signal(),  // () app.methods loaded
    choiceChanged: new Signal(),   // () the pickers of a new run (app.choice) changed
    started: new Signal(),         // () the page opened what its address asked for
    status: new Signal(),          // (text) a line about work in progress (a batch run, a re-simulation)
    message: new Signal(),         // (text or error, kind 'error'|'info')
    controlTaken: new Signal(),    // (text) another client took control of the live run from this tab
    control: new Signal(),         // ('you' | 'other' | 'none') who holds control of the live run
  },

  get lanes() { return this.session ? this.session.lanes : []; },
  // The live session on screen that still takes inputs, or null.
  get liveSession() { return this.session && this.session.kind === 'live' && !this.session.ended ? this.session : null; },

  // Runs a command {type, ...}: resolves with its result, rejects with its
  // failure, which is also shown on the message line unless the command says
  // `report: false` (its caller shows it). The promise returned is handled,
  // so a caller may ignore it.
  execute(command) {
    const handler = command && Object.hasOwn(handlers, command.type) ? handlers[command.type] : null;
    let result;
    try {
      if (!handler) throw new Error(`unknown command "${command && command.type}"`);
      result = Promise.resolve(handler(command));
    } catch (e) {
      result = Promise.reject(e);
    }
    result.catch((e) => { if (command.report !== false) this.error(e); });
    return result;
  },
  // The handlers by command type (main.js registers commands.js's).
  define(table) { Object.assign(handlers, table); },

  // The one place the session on screen changes (commands only): a page in
  // the centre gives way, the old session closes, the panels hear of it.
  setSession(next) {
    if (this.page) { this.page = null; this.signals.pageChanged.dispatch(null); }
    if (this.session && this.session !== next) this.session.close();
    this.session = next;
    this.playhead = null;
    this.signals.sessionChanged.dispatch(next);
  },
  // A paper's or a sweep's page instead of any session (commands only); the
  // same page again (another cell of the sweep on screen) stays up.
  setPage(page) {
    const same = this.page && page && this.page.name === page.name && this.page.id === page.id && this.page.key === page.key;
    if (!same) this.setSession(null);
    this.page = page;
    this.signals.pageChanged.dispatch(page);
  },

  // The replay's current frame (as the three.js editor's select(): state
  // that changes at the display rate, not a command).
  setPlayhead(seq, frame) {
    this.playhead = seq;
    this.signals.playhead.dispatch(seq, frame);
  },

  error(e) { this.signals.message.dispatch(e, 'error'); },
  info(text) { this.signals.message.dispatch(text, 'info'); },
  status(text) { this.signals.status.dispatch(text); },
};

// ?run=ID[&frame=K] | ?compare=ID,ID[,..][&frame=K] | ?sweep=ID[&family=F&config=C] | ?paper=KEY | ?scenario=NAME[&method=M]
// The query string (with or without its "?") as {run, compare, sweep, family,
// config, paper, scenario, method, frame}; family and config (a sweep's cell)
// only with a sweep and each other.
export function parseUrlState(search) {
  const q = new URLSearchParams(search);
  // decimal digits only: '', ' 3', '0x10' and '1e2' are not ids or frames
  const integer = (s) => (/^\d+$/.test(s) ? Number(s) : NaN);
  const ids = (name) => (q.get(name) || '').split(',').map(integer).filter((n) => Number.isInteger(n) && n > 0);
  const frame = q.has('frame') ? integer(q.get('frame')) : null;
  const sweep = ids('sweep')[0] || null;
  const cell = sweep !== null && q.get('family') && q.get('config');
  return {
    run: ids('run')[0] || null,
    compare: ids('compare'),
    sweep,
    family: cell ? q.get('family') : null,
    config: cell ? q.get('config') : null,
    paper: q.get('paper'),
    scenario: q.get('scenario'),
    method: q.get('method'),
    frame: Number.isInteger(frame) && frame >= 0 ? frame : null,
  };
}

// The query string for `params`, "?" included ('' when empty): null,
// undefined and '' values are dropped.
export function formatUrlState(params) {
  const q = new URLSearchParams();
  for (const [k, v] of Object.entries(params)) if (v !== null && v !== undefined && v !== '') q.set(k, String(v));
  const search = q.toString();
  return search ? `?${search}` : '';
}

export function readUrl() {
  return parseUrlState(location.search);
}

// The view an address names: everything but a replay's frame and the
// pickers' scenario and method.
export function viewOf(state) {
  const { run, compare, sweep, family, config, paper } = state;
  return JSON.stringify({ run, compare, sweep, family, config, paper });
}

// The one place the address is written. A new view (another run, compare,
// sweep, cell or paper, or none) pushes a history entry; the same view at
// another frame, or another pick of scenario or method, replaces the
// address: scrubbing adds no entry per frame. `push`: an entry even for the
// same view (a deliberate seek: a marker clicked); `replace`: none even for
// a new one (the view left can never come back: a deleted run).
export function writeUrl(params, { push = false, replace = false } = {}) {
  const url = `${location.pathname}${formatUrlState(params)}`;
  if (url === location.pathname + location.search) return;
  const newView = viewOf(parseUrlState(formatUrlState(params))) !== viewOf(parseUrlState(location.search));
  if ((push || newView) && !replace) history.pushState(null, '', url);
  else history.replaceState(null, '', url);
}
