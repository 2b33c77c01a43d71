// Every problem of a refused sweep spec (web/js/sweep_problems.js), each at
// its own entry, with a validator that names only the first as the server does.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { sweepProblems, jsonErrorAt, MAX_PROBES } from '../../../web/js/sweep_problems.js';

const KNOWN_METHODS = new Set(['pinv', 'dls', 'gpm']);
const KNOWN_SCENARIOS = new Set(['01_planar7_obstacles', 'a', 'b']);
// The server's way: the first problem only, scenarios before methods, the name first of all.
function validator() {
  const asked = [];
  const validate = async (spec) => {
    asked.push(spec);
    const fail = (path, message) => { const e = new Error(`${path}: ${message}`); e.status = 400; e.path = path; throw e; };
    if (typeof spec.name !== 'string') fail('name', 'must be a string');
    spec.scenarios.forEach((s, i) => { if (!KNOWN_SCENARIOS.has(s)) fail(`scenarios[${i}]`, `no scenario "${s}"`); });
    spec.methods.forEach((m, i) => { if (!KNOWN_METHODS.has(m)) fail(`methods[${i}]`, `unknown method "${m}"`); });
    return { total: spec.scenarios.length * spec.methods.length };
  };
  return { asked, validate };
}

test('a spec the server accepts has no problem, asked once', async () => {
  const v = validator();
  assert.deepEqual(await sweepProblems({ name: 's', scenarios: ['a'], methods: ['pinv'] }, v.validate), { problems: [], unchecked: 0 });
  assert.equal(v.asked.length, 1);
});

test('every bad scenario and method is named at its own entry, in order', async () => {
  const v = validator();
  const { problems } = await sweepProblems({ name: 's', scenarios: ['a', 'nope', 'b', 'gone'], methods: ['pinv', 'lamda', 'dls', 'xyz'] }, v.validate);
  assert.deepEqual(problems.map((p) => p.path), ['scenarios[1]', 'scenarios[3]', 'methods[1]', 'methods[3]']);
  assert.equal(problems[1].message, 'scenarios[3]: no scenario "gone"');
  assert.equal(problems[3].message, 'methods[3]: unknown method "xyz"');
});

test('a problem of the spec itself is named once; the entries are not probed for it', async () => {
  const v = validator();
  const { problems } = await sweepProblems({ name: 3, scenarios: ['nope'], methods: ['xyz'] }, v.validate);
  assert.deepEqual(problems.map((p) => p.path), ['name']);
  assert.equal(v.asked.length, 1);
});

test('the probes are bounded, and the rest said to be unchecked', async () => {
  const v = validator();
  const scenarios = Array.from({ length: 30 }, (_, i) => (i % 2 ? 'a' : `bad${i}`));
  const { problems, unchecked } = await sweepProblems({ name: 's', scenarios, methods: ['pinv'] }, v.validate);
  assert.equal(v.asked.length, 1 + MAX_PROBES);
  assert.equal(unchecked, 30 - MAX_PROBES + 1);
  assert.equal(problems.length, MAX_PROBES / 2);
});

test('a server that cannot answer is not a problem of the spec', async () => {
  await assert.rejects(sweepProblems({ name: 's', scenarios: ['a'], methods: ['pinv'] }, async () => { const e = new Error('busy'); e.status = 503; throw e; }), /busy/);
});

test('a JSON error says its line and column', () => {
  const text = '{\n  "a": 1,\n  "b": }';
  let error;
  try { JSON.parse(text); } catch (e) { error = e; }
  assert.match(jsonErrorAt(text, error), /line 3/);
});

test('the scanner finds where JSON breaks, and nothing in JSON', async () => {
  const { jsonErrorOffset } = await import('../../../web/js/sweep_problems.js');
  for (const good of ['{}', '[1, 2.5e3, -0.1, "a\\"b", true, false, null, {"x": [ ]}]', ' "s" ']) assert.equal(jsonErrorOffset(good), null, good);
  assert.equal(jsonErrorOffset('{"a": 1,}'), 8);
  assert.equal(jsonErrorOffset('{"a": 01}'), 7);
  assert.equal(jsonErrorOffset('[1, 2'), 5);
  assert.equal(jsonErrorOffset('{"a" 1}'), 5);
  assert.equal(jsonErrorOffset('[1] x'), 4);
});
