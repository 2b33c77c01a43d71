// Names of the lanes of a compare group that tell them apart: a lane whose
// method no other lane has is named by its method; lanes sharing a method
// add the parameters in which they differ, as `key=value` sorted by key
// (`ccp_voronoi · ccp_link=3`). Lanes alike in everything are numbered.
// Pure: no DOM.

// A parameter's value, short: numbers to 4 significant digits, lists in brackets.
export function formatValue(value) {
  if (typeof value === 'number') return Number.isFinite(value) ? String(Number(value.toPrecision(4))) : String(value);
  if (Array.isArray(value)) return `[${value.map(formatValue).join(',')}]`;
  if (value === null || value === undefined) return 'default';
  if (typeof value === 'object') return JSON.stringify(value);
  return String(value);
}

// lanes: [{method, params?}]; returns one label per lane, in order.
export function laneLabels(lanes) {
  const shown = lanes.map((lane) => ({ method: lane.method, params: lane.params || {} }));
  const labels = shown.map((lane) => {
    const peers = shown.filter((other) => other.method === lane.method);
    if (peers.length < 2) return lane.method;
    const keys = [...new Set(peers.flatMap((p) => Object.keys(p.params)))].sort();
    // a key differs when any two peers format it differently (a missing key is its default)
    const differing = keys.filter((key) => new Set(peers.map((p) => formatValue(p.params[key]))).size > 1);
    const parts = differing.map((key) => `${key}=${formatValue(lane.params[key])}`);
    return parts.length ? `${lane.method} · ${parts.join(', ')}` : lane.method;
  });
  // lanes still alike (the same method and parameters) are numbered in order
  return labels.map((label, i) => {
    const alike = labels.filter((other) => other === label).length;
    if (alike < 2) return label;
    const nth = labels.slice(0, i + 1).filter((other) => other === label).length;
    return `${label} · #${nth}`;
  });
}
