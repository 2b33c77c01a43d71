// A failed run's first failure (web/js/first_failure.js): from a sweep's row
// or the stored frames, with its reason in words; bad input never throws.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { firstFailure, failureText, runFails, touchedObstacles } from '../../../web/js/first_failure.js';

const ok = { collided: false, self_collided: false, joint_limit_margin: 1, task_error: 0.001, min_distance: 0.2 };
const frame = (seq, metrics = {}) => ({ seq, metrics: { ...ok, ...metrics } });
const summary = { collided: true, obstacle_collided: true, self_collided: false, joint_limit_violated: false, max_tracking_error: 0.001, min_distance: -0.1, nonfinite_steps: 0 };
const passing = { ...summary, collided: false, obstacle_collided: false, min_distance: 0.2 };

test('a passing run has no failure', () => {
  assert.equal(runFails({ summary: passing }), false);
  assert.equal(firstFailure({ summary: passing }, [frame(0)], 0.01), null);
  assert.equal(firstFailure({ summary, sweep: { success: true } }, [frame(0, { collided: true })], 0.01), null);
});

test('the first failing frame of a run without a sweep row, and its reason', () => {
  const frames = [frame(0), frame(1), frame(2, { collided: true, min_distance: -0.01 }), frame(3, { collided: true })];
  const f = firstFailure({ summary }, frames, 0.02);
  assert.deepEqual([f.mode, f.seq, f.t], ['collision', 2, 0.04]);
  assert.equal(failureText(f), 'collision at 0.04 s');
  assert.equal(failureText(f, ['post']), 'collision with obstacle post at 0.04 s');
  assert.equal(failureText(f, ['a', 'b']), 'collision with obstacles a and b at 0.04 s');
});

test('tracking error past the criterion, in centimetres against the bound', () => {
  const tracking = { ...passing, max_tracking_error: 0.048 };
  const f = firstFailure({ summary: tracking }, [frame(0), frame(320, { task_error: 0.048 })], 0.01);
  assert.equal(f.mode, 'tracking_lost');
  assert.equal(failureText(f), 'tracking error 4.8 cm > 1 cm at 3.20 s');
  const near = firstFailure({ summary: tracking }, [frame(13, { task_error: 0.01032 })], 0.01);
  assert.equal(failureText(near), 'tracking error 1.03 cm > 1 cm at 0.13 s');
});

test("a sweep's row gives the mode and the time; the frame nearest it the details", () => {
  const sweep = { success: false, failure_mode: 'self_collision', failure_t: 4.04 };
  const f = firstFailure({ summary: passing, sweep }, [frame(0), frame(404, { self_link_a: 2, self_link_b: 5 })], 0.01);
  assert.deepEqual([f.mode, f.seq], ['self_collision', 404]);
  assert.equal(failureText(f), 'self-collision of links 2 and 5 at 4.04 s');
  const lost = firstFailure({ summary: passing, sweep: { success: false, failure_mode: 'tracking_lost', failure_t: 1 } }, [frame(100, { task_error: 0.05 })], 0.01);
  assert.equal(failureText(lost), 'tracking lost at 1.00 s (error 5 cm)');
  assert.equal(failureText(firstFailure({ sweep: { success: false, failure_mode: 'stalled', failure_t: 2 } }, [], 0.01)), 'stalled at 2.00 s');
});

test('touched obstacles by id from a view frame', () => {
  const viewFrame = { nearest: [[1, 0, 0.3], [2, 1, -0.01], [3, 1, 0], [4, 0, null]], obstacles: [{ id: 'wall' }, { id: 'post' }] };
  assert.deepEqual(touchedObstacles(viewFrame), ['post']);
  assert.deepEqual(touchedObstacles({ nearest: [[1, 1, -0.1]], obstacles: [[0, 0], [1, 1]] }, [{ id: 'wall' }, { id: 'post' }]), ['post']);
  assert.deepEqual(touchedObstacles({ nearest: [[1, 0, -1]] }, [{ id: 7 }]), ['7']);
});

test('bad input never throws', () => {
  assert.equal(runFails({}), false);
  assert.equal(firstFailure({ summary: null }, null, 0), null);
  const f = firstFailure({ summary: { ...passing, nonfinite_steps: 3 } }, 'nonsense', NaN);
  assert.equal(f.mode, 'nonfinite');
  assert.equal(failureText(f), 'non-finite output');
  assert.equal(failureText(firstFailure({ summary }, [{ seq: 1 }, null, frame(2)], 0.01)), 'fails the criterion (no frame shows where)');
  assert.deepEqual(touchedObstacles(null), []);
  assert.deepEqual(touchedObstacles({ nearest: [null, [1, 9, -1]] }, []), ['9']);
  assert.equal(failureText(null), '');
});

test('failureTimes: when each way of failing first shows', async () => {
  const { failureTimes } = await import('../../../web/js/first_failure.js');
  const frame = (seq, m) => ({ seq, metrics: { task_error: 0, min_distance: 0.2, joint_limit_margin: 0.5, collided: false, ...m } });
  const frames = [frame(0), frame(10, { task_error: 0.02 }), frame(20, { collided: true, min_distance: -0.01 }), frame(30, { self_collided: true, collided: true }), frame(40, { joint_limit_margin: -0.1 })];
  assert.deepEqual(failureTimes(frames, 0.01), { tracking_lost: 0.1, collision: 0.2, self_collision: 0.3, joint_limit: 0.4 });
  assert.deepEqual(failureTimes(frames, 0.01, { max_tracking_error: 0.05, min_distance: 0 }), { collision: 0.2, clearance: 0.2, self_collision: 0.3, joint_limit: 0.4 });
  assert.deepEqual(failureTimes([], 0.01), {});
});
