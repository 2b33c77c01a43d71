// A run's recorded inputs as markers on the replay's timeline and charts:
// what happened (parameter changes, obstacle drags, additions and removals,
// method switches, resets) and at which frame. Joystick inputs, which come
// many a second, are not marked. Pure: no DOM.

const MARKED = new Set(['params', 'obstacle', 'obstacle_add', 'obstacle_remove', 'method', 'reset']);

const num = (v) => (typeof v === 'number' ? String(Number(v.toPrecision(4))) : String(v));
const point = (p) => `(${p.slice(0, 3).map(num).join(', ')})`;

// Plain words for one stored event ({seq, step, kind, payload}).
export function describeEvent(e) {
  const p = e.payload || {};
  switch (e.kind) {
    case 'params': return `parameters: ${Object.entries(p).map(([k, v]) => `${k} = ${num(v)}`).join(', ')}`;
    case 'obstacle': return `obstacle ${p.id} moved to ${Array.isArray(p.position) ? point(p.position) : '?'}`;
    case 'obstacle_add': return `obstacle ${p.id} added (${p.shape || 'shape?'})`;
    case 'obstacle_remove': return `obstacle ${p.id} removed`;
    case 'method': return `method switched to ${p.name}`;
    case 'reset': return 'reset: back to the start, the method made anew';
    default: return e.kind;
  }
}

// Markers {seq, kind, text} from the events of a session's lanes: one per
// frame and kind (several edits in one frame are listed together), in order.
export function eventMarkers(eventsPerLane) {
  const byKey = new Map();
  for (const events of eventsPerLane) {
    for (const e of events) {
      if (!MARKED.has(e.kind)) continue;
      const key = `${e.seq}\n${e.kind}`;
      const text = describeEvent(e);
      const marker = byKey.get(key) || { seq: e.seq, kind: e.kind, texts: [] };
      if (!marker.texts.includes(text)) marker.texts.push(text);
      byKey.set(key, marker);
    }
  }
  return [...byKey.values()].sort((a, b) => a.seq - b.seq || a.kind.localeCompare(b.kind))
    .map((m) => ({ seq: m.seq, kind: m.kind, text: m.texts.join('; ') }));
}
