// REST and WebSocket client: the one module that knows the server's paths.
// Every other module calls `api.<name>(…)` (a run, a sweep, an input to a
// live run) or opens a `Stream` on `paths.runStream(id)`, and never writes a
// URL. REST errors become ApiError with the server's {code, message, path}
// and the HTTP status; streams reconnect with back-off.
//
// Access: when the server requires a token (401), the page asks for it once
// (setTokenPrompt), keeps it in the tab's session storage and retries; every
// request then sends Authorization: Bearer TOKEN and a WebSocket the query
// parameter token=TOKEN (browsers cannot set its headers). Every request also
// names this tab as a client (Rrlab-Client header, `client` query parameter),
// so that the server knows which tab holds control of a live run.

export class ApiError extends Error {
  constructor(status, error) {
    super(error.message || `HTTP ${status}`);
    this.status = status;
    this.code = error.code || '';
    this.path = error.path || '';
  }
}

const TOKEN_KEY = 'rrlab.token';
const CLIENT_KEY = 'rrlab.client';

function stored(key) { try { return sessionStorage.getItem(key) || ''; } catch { return ''; } }
function store(key, value) {
  try { if (value) sessionStorage.setItem(key, value); else sessionStorage.removeItem(key); } catch { /* storage off */ }
}

// This tab's client name: random, kept for the tab's life (session storage).
export function clientId() {
  let id = stored(CLIENT_KEY);
  if (!id) {
    const bytes = crypto.getRandomValues(new Uint8Array(12));
    id = `tab-${[...bytes].map((b) => b.toString(16).padStart(2, '0')).join('')}`;
    store(CLIENT_KEY, id);
  }
  return id;
}

// `ask(refused)` resolves to the token the user typed, or '' if they gave none;
// `refused` is true when the stored token was turned down.
let askToken = null;
let asking = null;  // one prompt for every request that got a 401 meanwhile
export function setTokenPrompt(ask) { askToken = ask; }

async function newToken(refusedToken) {
  if (!asking) {
    asking = (async () => {
      const token = askToken ? (await askToken(Boolean(refusedToken))).trim() : '';
      if (token) store(TOKEN_KEY, token);
      return token;
    })().finally(() => { asking = null; });
  }
  return asking;
}

function headers(extra) {
  const h = { Accept: 'application/json', 'Rrlab-Client': clientId(), ...extra };
  const token = stored(TOKEN_KEY);
  if (token) h.Authorization = `Bearer ${token}`;
  return h;
}

// JSON in and out (`asText`: the answer's text, an error still JSON). A body
// is sent as application/json. A 401 asks for the token (one prompt for all
// requests waiting), and again while the server refuses what was typed;
// Cancel gives up with the 401.
async function request(method, path, body, asText = false) {
  let sent = '';
  const send = async () => {
    sent = stored(TOKEN_KEY);
    const options = { method, headers: headers() };
    if (body !== undefined) {
      options.headers['Content-Type'] = 'application/json';
      options.body = typeof body === 'string' ? body : JSON.stringify(body);
    }
    try {
      return await fetch(path, options);
    } catch (e) {
      throw new ApiError(0, { code: 'network', message: 'the server cannot be reached' });
    }
  };
  let response = await send();
  while (response.status === 401) {
    // another request may be asking, or may have got a new token meanwhile
    let token;
    if (asking) token = await asking;
    else if (stored(TOKEN_KEY) !== sent) token = stored(TOKEN_KEY);
    else token = await newToken(sent);
    if (!token) break;
    response = await send();
  }
  if (asText && response.ok) {
    try { return await response.text(); } catch (e) { throw new ApiError(0, { code: 'network', message: 'the answer was cut short' }); }
  }
  const data = await response.json().catch(() => ({}));
  if (!response.ok) throw new ApiError(response.status, data.error || { message: response.statusText });
  return data;
}

const enc = encodeURIComponent;
const query = (params) => {
  const q = new URLSearchParams();
  for (const [k, v] of Object.entries(params || {})) if (v !== null && v !== undefined && v !== '') q.set(k, String(v));
  const text = q.toString();
  return text ? `?${text}` : '';
};

// The server's paths, by what they name (docs/api.md has the routes).
export const paths = {
  health: () => '/api/health',
  methods: () => '/api/methods',
  frameFields: () => '/api/frame-fields',
  scenarios: (params) => `/api/scenarios${query(params)}`,
  scenario: (name) => `/api/scenarios/${enc(name)}`,
  scenarioPreview: (name) => `/api/scenarios/${enc(name)}/preview`,  // the snapshot and frame 0 a run of it starts with
  validateScenario: () => '/api/scenarios/validate',
  runs: (params) => `/api/runs${query(params)}`,
  run: (id) => `/api/runs/${id}`,
  runPart: (id, part, params) => `/api/runs/${id}/${part}${query(params)}`,  // frames, events, record, replay, inputs
  replay: (id) => `/api/replays/${id}`,
  replayControl: (id) => `/api/replays/${id}/control`,
  compare: () => '/api/compare',
  groupExport: (group) => `/api/compare/${group}/export.html`,  // a compare group (its first run's id) as one HTML file
  sweeps: (params) => `/api/sweeps${query(params)}`,
  sweep: (id) => `/api/sweeps/${id}`,
  sweepPart: (id, part, params) => `/api/sweeps/${id}/${part}${query(params)}`,  // runs, control
  validateSweep: () => '/api/sweeps/validate',
  papers: () => '/data/papers.json',
  runStream: (id) => `/ws/runs/${id}`,  // a replay's stream path comes in the server's answer (player.ws)
};

// Every input the page sends to a live run, by kind, and the REST request it
// becomes. The page sends them as commands (state.js: execute({type: 'input',
// kind, payload})), in the manner of the three.js editor's execute(command):
// the modules say what the user did, not which URL takes it.
export const INPUT_KINDS = {
  control: (p) => ['POST', 'control', p],             // {action: play|pause|step|reset|stop|take|release}
  joystick: (p) => ['POST', 'joystick', p],           // {linear, angular}
  params: (p) => ['PATCH', 'params', p],              // {name: value, ...}
  method: (p) => ['POST', 'method', p],               // {name, params?}
  obstacle_add: (p) => ['POST', 'obstacles', p],      // an obstacle as in the scenario format
  obstacle_move: (p) => ['PUT', `obstacles/${enc(p.id)}`, { position: p.position }],
  obstacle_delete: (p) => ['DELETE', `obstacles/${enc(p.id)}`, undefined],
};

// {verb, path, body} of an input to run `runId`; throws on an unknown kind
// or a run id that is not a positive integer.
export function inputRequest(kind, runId, payload) {
  const route = Object.hasOwn(INPUT_KINDS, kind) ? INPUT_KINDS[kind] : null;
  if (!route) throw new Error(`unknown input kind "${kind}"`);
  if (!Number.isInteger(runId) || runId <= 0) throw new Error(`input "${kind}" needs a run id, not ${runId}`);
  const [verb, tail, body] = route(payload || {});
  return { verb, path: paths.runPart(runId, tail), body };
}

// Every scenario summary of GET /api/scenarios, fetched a page at a time
// ({scenarios, total, offset, limit}).
async function listScenarios() {
  const all = [];
  for (;;) {
    const page = await request('GET', paths.scenarios({ limit: 1000, offset: all.length }));
    all.push(...page.scenarios);
    if (page.scenarios.length === 0 || all.length >= page.total) return all;
  }
}

// The server's REST calls by name; each resolves with the answer's JSON.
export const api = {
  health: () => request('GET', paths.health()),
  methods: () => request('GET', paths.methods()),
  frameFields: () => request('GET', paths.frameFields()).then((table) => table.fields),
  scenarios: listScenarios,
  scenario: (name) => request('GET', paths.scenario(name)),
  scenarioPreview: (name) => request('GET', paths.scenarioPreview(name)),
  validateScenario: (scenario) => request('POST', paths.validateScenario(), scenario),
  saveScenario: (scenario) => request('POST', paths.scenarios(), scenario),

  runs: (params) => request('GET', paths.runs(params)),  // {limit, sweep, scenario, method, status}
  run: (id) => request('GET', paths.run(id)),
  startRun: (body) => request('POST', paths.runs(), body),  // {scenario, mode, rate?, method?, params?}
  deleteRun: (id) => request('DELETE', paths.run(id)),
  frames: (id, range) => request('GET', paths.runPart(id, 'frames', range)),  // {from, to, stride}
  drawnFrames: (id, range) => request('GET', paths.runPart(id, 'drawn', range), undefined, true),  // NDJSON text (local_frames.js)
  framesLink: (id, format) => paths.runPart(id, 'frames', { format }),  // a download link, csv or json
  exportLink: (id) => paths.runPart(id, 'export.html'),  // a download link: the run as one HTML file that replays offline
  groupExportLink: (group) => paths.groupExport(group),
  events: (id) => request('GET', paths.runPart(id, 'events')),
  record: (id) => request('GET', paths.runPart(id, 'record')),
  replayRun: (id, body) => request('POST', paths.runPart(id, 'replay'), body),  // {mode: frames|resimulate, speed?}
  input: (runId, kind, payload) => { const { verb, path, body } = inputRequest(kind, runId, payload); return request(verb, path, body); },

  replay: (replayId) => request('GET', paths.replay(replayId)),
  replayControl: (replayId, body) => request('POST', paths.replayControl(replayId), body),  // {action, seq?}
  startCompare: (body) => request('POST', paths.compare(), body),  // {scenario, methods, mode, rate?}

  sweeps: () => request('GET', paths.sweeps()),
  sweep: (id) => request('GET', paths.sweep(id)),
  sweepRuns: (id, params) => request('GET', paths.sweepPart(id, 'runs', params)),  // {family, config, limit, offset}
  sweepControl: (id, body) => request('POST', paths.sweepPart(id, 'control'), body),
  validateSweep: (spec) => request('POST', paths.validateSweep(), spec),
  startSweep: (spec, jobs) => request('POST', paths.sweeps({ jobs }), spec),

  papers: () => request('GET', paths.papers()),
};

// Plain words for an error, naming the field the server blamed.
export function describeError(error) {
  if (error instanceof ApiError && error.path) return `${error.message} (at ${error.path})`;
  return error.message || String(error);
}

// A stream of snapshots and frames over paths.runStream(id) or a replay's
// stream path (from the server's answer).
// On a drop it reconnects with exponential back-off (0.5 s doubling to 8 s)
// and the server's first message, a snapshot, resyncs the page. Before each
// attempt `probe()` (async) may say there is nothing left to reconnect to
// (the run ended or was deleted); closed by the page, it stays closed.
export class Stream {
  constructor(path, { onSnapshot, onFrame, onMessage, onState, probe }) {
    this.path = path;
    this.handlers = { onSnapshot, onFrame, onMessage, onState };
    this.probe = probe;
    this.delay = 500;
    this.closed = false;
    this.open();
  }

  open() {
    const scheme = location.protocol === 'https:' ? 'wss' : 'ws';
    const query = new URLSearchParams({ client: clientId() });
    const token = stored(TOKEN_KEY);
    if (token) query.set('token', token);
    const separator = this.path.includes('?') ? '&' : '?';
    this.socket = new WebSocket(`${scheme}://${location.host}${this.path}${separator}${query}`);
    this.state('connecting');
    this.socket.onopen = () => { this.delay = 500; this.state('open'); };
    this.socket.onmessage = (event) => {
      let message;
      try { message = JSON.parse(event.data); } catch { return; }
      if (message.type === 'snapshot') this.handlers.onSnapshot(message);
      else if (message.type === 'frame') this.handlers.onFrame(message);
      else if (this.handlers.onMessage) this.handlers.onMessage(message);
    };
    this.socket.onclose = () => this.dropped();
  }

  async dropped() {
    if (this.closed) return;
    if (this.probe) {
      const alive = await this.probe().catch(() => true);
      if (!alive || this.closed) { this.state('ended'); return; }
    }
    this.state('reconnecting');
    this.timer = setTimeout(() => { if (!this.closed) this.open(); }, this.delay);
    this.delay = Math.min(8000, this.delay * 2);
  }

  state(name) { if (this.handlers.onState) this.handlers.onState(name); }

  // A message over the socket (inputs, replay control); false when not open.
  send(message) {
    if (this.socket.readyState !== WebSocket.OPEN) return false;
    this.socket.send(JSON.stringify(message));
    return true;
  }

  close() {
    this.closed = true;
    clearTimeout(this.timer);
    this.socket.onclose = null;
    this.socket.close();
  }
}
