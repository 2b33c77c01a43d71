// The links a frame marks (web/js/link_marks.js): the nearest link to an
// obstacle, red when it touches, and both links of a self-colliding pair.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { linkMarks } from '../../../web/js/link_marks.js';

const metrics = (over = {}) => ({ min_distance_link: 0, collided: false, self_link_a: 0, self_link_b: 0, self_collided: false, ...over });

test('the link nearest an obstacle is marked, collided when it touches', () => {
  assert.deepEqual(linkMarks(metrics({ min_distance_link: 2 }), 4), ['', 'nearest', '', '']);
  assert.deepEqual(linkMarks(metrics({ min_distance_link: 2, collided: true }), 4), ['', 'collided', '', '']);
});

test('both links of a self-colliding pair are marked as a contact', () => {
  assert.deepEqual(linkMarks(metrics({ self_link_a: 1, self_link_b: 3, self_collided: true }), 4), ['collided', '', 'collided', '']);
  // the nearest pair is not marked while it does not touch
  assert.deepEqual(linkMarks(metrics({ self_link_a: 1, self_link_b: 3 }), 4), ['', '', '', '']);
  // with an obstacle contact beside it
  assert.deepEqual(linkMarks(metrics({ min_distance_link: 4, collided: true, self_link_a: 1, self_link_b: 3, self_collided: true }), 4),
    ['collided', '', 'collided', 'collided']);
});

test('frames without the fields (stored before self-collision), or links out of range, mark nothing more', () => {
  assert.deepEqual(linkMarks({ min_distance_link: 1, collided: false }, 2), ['nearest', '']);
  assert.deepEqual(linkMarks(metrics({ self_link_a: 1, self_link_b: 9, self_collided: true }), 3), ['collided', '', '']);
  assert.deepEqual(linkMarks(null, 2), ['', '']);
});
