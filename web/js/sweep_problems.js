// Every problem of a sweep spec the server refuses, not only the first: the
// server names one (POST /api/sweeps/validate stops at it), so each scenario
// entry and each method is checked again on its own, beside a partner known
// to pass (the method `pinv`; the first scenario entry that passes, else the
// planar demo), and each problem is named at its own entry. At most
// MAX_PROBES more requests a check.
export const MAX_PROBES = 16;
const FALLBACK_SCENARIO = '01_planar7_obstacles';

// `validate(spec)` resolves when the server accepts it and rejects with its
// error ({message, path}) when not. Resolves to {problems: [{path, message}],
// unchecked} (unchecked: entries not probed, over MAX_PROBES).
export async function sweepProblems(spec, validate) {
  const first = await refusal(validate, spec);
  if (!first) return { problems: [], unchecked: 0 };
  const problems = new Map([[first.path, first]]);
  const scenarios = Array.isArray(spec.scenarios) ? spec.scenarios : [];
  const methods = Array.isArray(spec.methods) ? spec.methods : [];
  if (!/^(scenarios|methods)\[\d+\]/.test(first.path)) return { problems: [...problems.values()], unchecked: 0 };
  let probes = 0, unchecked = 0, partner = null;
  const probe = async (variant, array, index) => {
    if (probes >= MAX_PROBES) { ++unchecked; return null; }
    ++probes;
    const e = await refusal(validate, variant);
    if (!e) return null;
    const at = new RegExp(`^${array}\\[0\\]`);
    // a problem of the entry itself; one elsewhere is the spec's own, named already or by the first answer
    if (at.test(e.path)) {
      const path = e.path.replace(at, `${array}[${index}]`);
      const message = e.message.replace(at, `${array}[${index}]`);
      if (!problems.has(path)) problems.set(path, { path, message });
    }
    return e;
  };
  for (let i = 0; i < scenarios.length; ++i) {
    const e = await probe({ ...spec, scenarios: [scenarios[i]], methods: ['pinv'] }, 'scenarios', i);
    if (!e && partner === null && probes <= MAX_PROBES) partner = scenarios[i];
  }
  for (let j = 0; j < methods.length; ++j) await probe({ ...spec, scenarios: [partner ?? FALLBACK_SCENARIO], methods: [methods[j]] }, 'methods', j);
  const order = (p) => { const m = /^(scenarios|methods)\[(\d+)\]/.exec(p.path); return m ? (m[1] === 'scenarios' ? 0 : 1e6) + Number(m[2]) : -1; };
  return { problems: [...problems.values()].sort((a, b) => order(a) - order(b)), unchecked };
}

async function refusal(validate, spec) {
  try {
    await validate(spec);
    return null;
  } catch (e) {
    if (!e || e.status === 0 || e.status >= 500 || e.status === 401 || e.status === 429) throw e;  // not the spec's fault
    return { path: e.path || '', message: e.message || String(e) };
  }
}

// A JSON.parse error with its line and column: the browser's message names
// neither, so the text is scanned for the first place it stops being JSON.
export function jsonErrorAt(text, error) {
  const message = error.message || String(error);
  const at = jsonErrorOffset(text);
  if (at === null) return message;
  const before = text.slice(0, at);
  const line = before.split('\n').length, column = before.length - before.lastIndexOf('\n');
  return `line ${line}, column ${column}: ${message}`;
}

// The offset of the first character that breaks JSON (the text's end when it
// stops early), or null when it is JSON. A small recursive-descent scanner.
export function jsonErrorOffset(text) {
  let i = 0;
  const fail = () => { throw i; };
  const space = () => { while (i < text.length && ' \t\n\r'.includes(text[i])) ++i; };
  const literal = (word) => { if (text.startsWith(word, i)) i += word.length; else fail(); };
  const string = () => {
    ++i;
    while (i < text.length && text[i] !== '"') {
      if (text[i] === '\\') { ++i; if (!'"\\/bfnrtu'.includes(text[i] || 'x')) fail(); if (text[i] === 'u') { if (!/^[0-9a-fA-F]{4}$/.test(text.slice(i + 1, i + 5))) fail(); i += 4; } } else if (text.charCodeAt(i) < 32) fail();
      ++i;
    }
    if (i >= text.length) fail();
    ++i;
  };
  const number = () => {
    const m = /^-?(0|[1-9]\d*)(\.\d+)?([eE][+-]?\d+)?/.exec(text.slice(i, i + 400));
    if (!m) fail();
    i += m[0].length;
  };
  const value = (depth) => {
    if (depth > 512) fail();
    space();
    const c = text[i];
    if (c === '{') {
      ++i; space();
      if (text[i] === '}') { ++i; return; }
      for (;;) {
        space(); if (text[i] !== '"') fail(); string(); space();
        if (text[i] !== ':') fail(); ++i; value(depth + 1); space();
        if (text[i] === ',') { ++i; continue; }
        if (text[i] === '}') { ++i; return; }
        fail();
      }
    } else if (c === '[') {
      ++i; space();
      if (text[i] === ']') { ++i; return; }
      for (;;) {
        value(depth + 1); space();
        if (text[i] === ',') { ++i; continue; }
        if (text[i] === ']') { ++i; return; }
        fail();
      }
    } else if (c === '"') string();
    else if (c === 't') literal('true');
    else if (c === 'f') literal('false');
    else if (c === 'n') literal('null');
    else number();
  };
  try {
    value(0);
    space();
    return i < text.length ? i : null;
  } catch (at) {
    if (typeof at !== 'number') throw at;
    return Math.min(at, text.length);
  }
}
