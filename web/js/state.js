// The page's one central object: what is shown (the session and its lanes),
// the overlay toggles, and signals the panels listen to. The address bar
// follows the session, so a copied link reopens what is shown.

export class Signal {
  constructor() { this.listeners = []; }
  add(listener) { this.listeners.push(listener); }
  dispatch(...args) { for (const listener of this.listeners) listener(...args); }
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

export const app = {
  overlays: Object.fromEntries(OVERLAYS.map((o) => [o.key, true])),
  methods: [],        // GET /api/methods
  scenarios: [],      // GET /api/scenarios: every page's summaries
  signals: {
    sessionChanged: new Signal(),  // (session) lanes opened or closed
    snapshot: new Signal(),        // (lane) a lane got a new snapshot
    params: new Signal(),          // (lane) a lane's parameter values changed (lane.snapshot.params)
    frame: new Signal(),           // (lane) a lane got a new frame
    viewCreated: new Signal(),     // (lane) a lane's view exists (2D or 3D)
    connection: new Signal(),      // (session) a stream's state changed
    overlaysChanged: new Signal(),
    message: new Signal(),         // (text, kind 'error'|'info')
    controlTaken: new Signal(),    // (text) another client took control of the live run from this tab
    control: new Signal(),         // ('you' | 'other' | 'none') who holds control of the live run
  },
  error(e) { this.signals.message.dispatch(e, 'error'); },
  info(text) { this.signals.message.dispatch(text, 'info'); },
};

// ?run=ID[&frame=K] | ?compare=ID,ID[,..][&frame=K] | ?sweep=ID | ?paper=KEY | ?scenario=NAME[&method=M]
// The query string (with or without its "?") as {run, compare, sweep, paper, scenario, method, frame}.
export function parseUrlState(search) {
  const q = new URLSearchParams(search);
  // decimal digits only: '', ' 3', '0x10' and '1e2' are not ids or frames
  const integer = (s) => (/^\d+$/.test(s) ? Number(s) : NaN);
  const ids = (name) => (q.get(name) || '').split(',').map(integer).filter((n) => Number.isInteger(n) && n > 0);
  const frame = q.has('frame') ? integer(q.get('frame')) : null;
  return {
    run: ids('run')[0] || null,
    compare: ids('compare'),
    sweep: ids('sweep')[0] || null,
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

// Replaces the address (no history entry per frame).
export function writeUrl(params) {
  const url = `${location.pathname}${formatUrlState(params)}`;
  if (url !== location.pathname + location.search) history.replaceState(null, '', url);
}
