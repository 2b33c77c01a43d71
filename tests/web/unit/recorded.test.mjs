// A replay's method and parameters at a frame, from its recorded events
// (web/js/recorded.js): what the parameter panel shows at the playhead.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { recordedAt } from '../../../web/js/recorded.js';

const METHODS = [
  { name: 'closest_point', params: [{ name: 'influence', default: 0.3 }, { name: 'gain', default: 5 }] },
  { name: 'ccp_voronoi', params: [{ name: 'mode', default: 0, choices: ['DI', 'DM', 'hybrid'] }, { name: 'ccp_link', default: 3 }] },
];
const START = { method: 'closest_point', params: { influence: 0.25, gain: 5 } };
const EVENTS = [
  { seq: 100, kind: 'params', payload: { gain: 417 } },
  { seq: 150, kind: 'joystick', payload: { linear: [0.1, 0] } },
  { seq: 200, kind: 'obstacle', payload: { id: 'post', position: [1, 0, 0] } },
  { seq: 2747, kind: 'params', payload: { influence: 0.4 } },
  { seq: 3000, kind: 'method', payload: { name: 'ccp_voronoi', params: { mode: 'hybrid' } } },
  { seq: 3100, kind: 'reset', payload: {} },
];

test('before any input: the starting values', () => {
  assert.deepEqual(recordedAt(EVENTS, 99, START, METHODS), { ...START, seq: null });
});

test('an event shows from its own frame on (it took effect before frame seq)', () => {
  assert.deepEqual(recordedAt(EVENTS, 100, START, METHODS).params, { influence: 0.25, gain: 417 });
  assert.deepEqual(recordedAt(EVENTS, 2746, START, METHODS), { method: 'closest_point', params: { influence: 0.25, gain: 417 }, seq: 200 });
  assert.deepEqual(recordedAt(EVENTS, 2747, START, METHODS), { method: 'closest_point', params: { influence: 0.4, gain: 417 }, seq: 2747 });
});

test('seeking back restores the earlier values', () => {
  recordedAt(EVENTS, 2800, START, METHODS);
  assert.equal(recordedAt(EVENTS, 150, START, METHODS).params.influence, 0.25);
  assert.equal(recordedAt(EVENTS, 150, START, METHODS).seq, 100, 'a joystick input is not a recorded change');
});

test("a method switch starts from the new method's defaults with the values it names (labels as indices); a reset keeps them", () => {
  const at = recordedAt(EVENTS, 3000, START, METHODS);
  assert.deepEqual(at, { method: 'ccp_voronoi', params: { mode: 2, ccp_link: 3 }, seq: 3000 });
  assert.deepEqual(recordedAt(EVENTS, 5000, START, METHODS), { ...at, seq: 3100 });
});

test('no events, malformed events and an unknown method do not throw', () => {
  assert.deepEqual(recordedAt(null, 10, START), { ...START, seq: null });
  assert.deepEqual(recordedAt([null, { kind: 'params' }, { seq: 1, kind: 'params', payload: null }], 10, START), { ...START, seq: 1 });
  assert.deepEqual(recordedAt([{ seq: 1, kind: 'method', payload: { name: 'nope' } }], 10, START, METHODS), { method: 'nope', params: {}, seq: 1 });
});
