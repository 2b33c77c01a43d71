// REST and WebSocket client. REST errors become ApiError with the server's
// {code, message, path} and the HTTP status; streams reconnect with back-off.

export class ApiError extends Error {
  constructor(status, error) {
    super(error.message || `HTTP ${status}`);
    this.status = status;
    this.code = error.code || '';
    this.path = error.path || '';
  }
}

// JSON in and out. A body is sent as application/json.
export async function api(method, path, body) {
  const options = { method, headers: { Accept: 'application/json' } };
  if (body !== undefined) {
    options.headers['Content-Type'] = 'application/json';
    options.body = typeof body === 'string' ? body : JSON.stringify(body);
  }
  let response;
  try {
    response = await fetch(path, options);
  } catch (e) {
    throw new ApiError(0, { code: 'network', message: 'the server cannot be reached' });
  }
  const data = await response.json().catch(() => ({}));
  if (!response.ok) throw new ApiError(response.status, data.error || { message: response.statusText });
  return data;
}

// Plain words for an error, naming the field the server blamed.
export function describeError(error) {
  if (error instanceof ApiError && error.path) return `${error.message} (at ${error.path})`;
  return error.message || String(error);
}

// A stream of snapshots and frames over /ws/runs/{id} or /ws/replays/{id}.
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
    this.socket = new WebSocket(`${scheme}://${location.host}${this.path}`);
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
