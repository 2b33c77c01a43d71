// A replayed run's method and parameters as they stood at a frame, from its
// recorded events ({seq, kind, payload}: an event took effect before frame
// seq, so frame seq shows it). A parameter change sets its values; a method
// switch starts from the new method's defaults with the values it names (as
// the engine's switch does); a reset keeps both (the method is made anew with
// the same values). Obstacles are not followed here: the replay's server
// player applies the scene's events and sends the scene as it is at the
// frame it shows. Pure: no DOM.

const MARKED = new Set(['params', 'obstacle', 'obstacle_add', 'obstacle_remove', 'method', 'reset']);

// A parameter's value as a number: an enumeration may be recorded by its label.
function valueOf(spec, v) {
  if (typeof v === 'number') return v;
  if (spec && Array.isArray(spec.choices)) {
    const i = spec.choices.indexOf(v);
    if (i >= 0) return i;
  }
  const n = Number(v);
  return Number.isFinite(n) ? n : v;
}

function specsOf(methods, name) {
  const m = methods.find((x) => x.name === name);
  return (m && (m.params || m.param_specs)) || [];
}

function withValues(params, payload, specs) {
  const next = { ...params };
  if (payload && typeof payload === 'object') {
    for (const [k, v] of Object.entries(payload)) next[k] = valueOf(specs.find((s) => s.name === k), v);
  }
  return next;
}

// {method, params, seq}: `start` {method, params} is the run's starting
// state, `methods` the catalogue (each {name, params: [{name, default,
// choices}]}) for a switch's defaults; seq: the frame of the last recorded
// input at or before `frame` (any that is marked on the scrubber), or null
// when none is: the starting values.
export function recordedAt(events, frame, start, methods = []) {
  let method = start.method;
  let params = { ...start.params };
  let seq = null;
  for (const e of events || []) {
    if (!e || !Number.isInteger(e.seq) || e.seq > frame) continue;
    if (MARKED.has(e.kind)) seq = seq === null ? e.seq : Math.max(seq, e.seq);
    const p = e.payload || {};
    if (e.kind === 'params') params = withValues(params, p, specsOf(methods, method));
    else if (e.kind === 'method' && typeof p.name === 'string') {
      method = p.name;
      const specs = specsOf(methods, method);
      params = withValues(Object.fromEntries(specs.map((s) => [s.name, s.default])), p.params, specs);
    }
  }
  return { method, params, seq };
}
