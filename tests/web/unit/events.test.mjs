// Event markers of a replay (web/js/events.js): each recorded input named in
// plain words, joystick inputs left out, edits of one frame listed together.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { describeEvent, eventMarkers } from '../../../web/js/events.js';

const events = [
  { kind: 'params', payload: { gain: 3 }, seq: 3, step: 3 },
  { kind: 'obstacle', payload: { id: 'disc', position: [0.4, 1.2, 0] }, seq: 3, step: 3 },
  { kind: 'method', payload: { name: 'dls' }, seq: 3, step: 3 },
  { kind: 'joystick', payload: { linear: [0.1, 0, 0] }, seq: 4, step: 4 },
  { kind: 'obstacle', payload: { id: 'pin', position: [1.7, 1.25, 0] }, seq: 3, step: 3 },
  { kind: 'reset', payload: {}, seq: 9, step: 0 },
];

test('every kind has plain words', () => {
  assert.equal(describeEvent(events[0]), 'parameters: gain = 3');
  assert.equal(describeEvent(events[1]), 'obstacle disc moved to (0.4, 1.2, 0)');
  assert.equal(describeEvent(events[2]), 'method switched to dls');
  assert.equal(describeEvent({ kind: 'obstacle_add', payload: { id: 'x1', shape: 'sphere' } }), 'obstacle x1 added (sphere)');
  assert.equal(describeEvent({ kind: 'obstacle_remove', payload: { id: 'x1' } }), 'obstacle x1 removed');
  assert.match(describeEvent(events[5]), /^reset/);
});

test('markers: joystick left out, one per frame and kind, the same edit once across lanes', () => {
  const markers = eventMarkers([events, events.slice(0, 2)]);
  assert.deepEqual(markers.map((m) => [m.seq, m.kind]), [[3, 'method'], [3, 'obstacle'], [3, 'params'], [9, 'reset']]);
  assert.equal(markers[1].text, 'obstacle disc moved to (0.4, 1.2, 0); obstacle pin moved to (1.7, 1.25, 0)');
});
