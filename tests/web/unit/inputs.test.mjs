// web/js/api.js (INPUT_KINDS): every input kind the page sends to a live run becomes
// the REST request of its route (docs/api.md), and nothing else does.
import { test } from 'node:test';
import assert from 'node:assert/strict';

import { INPUT_KINDS, inputRequest } from '../../../web/js/api.js';

test('each input kind goes to its route with its body', () => {
  const cases = [
    ['control', { action: 'pause' }, 'POST', '/api/runs/7/control', { action: 'pause' }],
    ['joystick', { linear: [0.05, 0] }, 'POST', '/api/runs/7/joystick', { linear: [0.05, 0] }],
    ['params', { lambda: 0.02 }, 'PATCH', '/api/runs/7/params', { lambda: 0.02 }],
    ['method', { name: 'dls' }, 'POST', '/api/runs/7/method', { name: 'dls' }],
    ['obstacle_add', { id: 'o1', shape: 'sphere' }, 'POST', '/api/runs/7/obstacles', { id: 'o1', shape: 'sphere' }],
    ['obstacle_move', { id: 'disc', position: [1, 2, 0] }, 'PUT', '/api/runs/7/obstacles/disc', { position: [1, 2, 0] }],
    ['obstacle_delete', { id: 'disc' }, 'DELETE', '/api/runs/7/obstacles/disc', undefined],
  ];
  assert.deepEqual(cases.map((c) => c[0]).sort(), Object.keys(INPUT_KINDS).sort(), 'every kind is tested');
  for (const [kind, payload, verb, path, body] of cases) {
    assert.deepEqual(inputRequest(kind, 7, payload), { verb, path, body }, kind);
  }
});

test('an obstacle id is one path segment, whatever it holds', () => {
  assert.equal(inputRequest('obstacle_move', 3, { id: 'a/b c?', position: [0, 0, 0] }).path,
    '/api/runs/3/obstacles/a%2Fb%20c%3F');
  assert.equal(inputRequest('obstacle_delete', 3, { id: '../x' }).path, '/api/runs/3/obstacles/..%2Fx');
});

test('a move sends only the position', () => {
  assert.deepEqual(inputRequest('obstacle_move', 1, { id: 'o', position: [1, 1, 1], shape: 'box' }).body, { position: [1, 1, 1] });
});

test('unknown kinds and bad run ids are refused, not sent', () => {
  for (const kind of ['', 'replay', 'toString', '__proto__', 'constructor']) {
    assert.throws(() => inputRequest(kind, 1, {}), /unknown input kind/, kind);
  }
  for (const runId of [0, -1, 1.5, '3', null, undefined, NaN]) {
    assert.throws(() => inputRequest('control', runId, { action: 'play' }), /needs a run id/, String(runId));
  }
});
