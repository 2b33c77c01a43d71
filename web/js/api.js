// REST helpers: JSON in and out; errors carry the server's {code, message, path}.
export async function api(method, path, body) {
  const options = { method, headers: {} };
  if (body !== undefined) {
    options.headers['Content-Type'] = 'application/json';
    options.body = JSON.stringify(body);
  }
  const response = await fetch(path, options);
  const data = await response.json().catch(() => ({}));
  if (!response.ok) {
    const e = data.error || { message: response.statusText, path: '' };
    throw new Error(`${e.message}${e.path ? ` (${e.path})` : ''}`);
  }
  return data;
}

// Live stream of a run or replay: snapshot, then frames (latest wins on the server).
export function openStream(path, { onSnapshot, onFrame, onMessage, onClose }) {
  const scheme = location.protocol === 'https:' ? 'wss' : 'ws';
  const socket = new WebSocket(`${scheme}://${location.host}${path}`);
  socket.onmessage = (event) => {
    const message = JSON.parse(event.data);
    if (message.type === 'snapshot') onSnapshot(message);
    else if (message.type === 'frame') onFrame(message);
    else if (onMessage) onMessage(message);
  };
  socket.onclose = () => onClose && onClose();
  return socket;
}
