// The compare summary's verdict (web/js/compare_verdict.js): best values per
// row with their direction, rows that differ, pass or fail against the
// criterion, and the headline sentence.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { bestOf, differs, judge, contacts, compareVerdict, DEFAULT_CRITERION } from '../../../web/js/compare_verdict.js';

const summary = (over = {}) => ({
  collided: false, min_distance: 0.2, max_tracking_error: 0.003, final_tracking_error: 0.001, joint_limit_violated: false,
  min_joint_limit_margin: 1.5, max_condition_number: 4, nonfinite_steps: 0, step_us: { p50: 2, p99: 9 }, ...over,
});

test('the best value follows the row\'s direction; ties share it; equal rows have none', () => {
  assert.deepEqual(bestOf([0.1, 0.3, 0.2], 'high'), [1]);
  assert.deepEqual(bestOf([0.1, 0.3, 0.1], 'low'), [0, 2]);
  assert.deepEqual(bestOf([true, false, false], 'false'), [1, 2]);
  assert.deepEqual(bestOf([0.2, 0.2], 'high'), []);
  assert.deepEqual(bestOf([0.2, null], 'high'), []);  // one known value ranks nothing
  assert.deepEqual(bestOf([0.1, 0.3], null), []);
});

test('"best" is marked only beyond the row\'s stated tolerance', () => {
  assert.deepEqual(bestOf([8.70e-6, 8.80e-6], 'low', { abs: 1e-4 }), []);  // 0.01 µm apart: noise
  assert.deepEqual(bestOf([0.002, 0.0035, 0.0021], 'low', { abs: 1e-4 }), [0, 2]);
  assert.deepEqual(bestOf([10, 10.05, 12], 'low', { rel: 0.01 }), [0, 1]);
  const rows = compareVerdict([summary({ max_tracking_error: 8.7e-6 }), summary({ max_tracking_error: 8.8e-6 })], ['a', 'b']).rows;
  assert.deepEqual(rows.find((r) => r.key === 'max_tracking_error').best, []);
  assert.equal(rows.find((r) => r.key === 'max_tracking_error').stated, '0.1 mm');
});

test('values equal to 4 significant digits do not differ', () => {
  assert.equal(differs([0.16411, 0.164112]), false);
  assert.equal(differs([0.1641, 0.1642]), true);
  assert.equal(differs([false, false]), false);
  assert.equal(differs([false, true]), true);
});

test('the default criterion is the benchmark suite\'s; each failure is named', () => {
  assert.deepEqual({ ...DEFAULT_CRITERION }, { max_tracking_error: 0.01, min_distance: null, collision: false, joint_limits: true });
  assert.deepEqual(judge(summary()), { pass: true, reasons: [] });
  assert.deepEqual(judge(summary({ collided: true, min_distance: -0.1 })).reasons, ['collision, 10 cm deep']);
  assert.deepEqual(judge(summary({ max_tracking_error: 0.0478 })).reasons, ['tracking error 4.8 cm > 1 cm']);
  assert.deepEqual(judge(summary({ min_distance: 0.031 }), { min_distance: 0.05 }).reasons, ['clearance 3.1 cm < 5 cm']);
  assert.deepEqual(judge(summary({ max_tracking_error: NaN })).pass, false);  // NaN never passes a bound
  assert.deepEqual(judge(summary({ joint_limit_violated: true, nonfinite_steps: 3 })).reasons, ['crossed a joint limit', 'non-finite output']);
  assert.equal(judge(summary({ collided: true }), { collision: true }).pass, true);
  assert.equal(judge(summary({ min_distance: 0.04 }), { min_distance: 0.05 }).pass, false);
});

test('a self-collision is named as such, beside or without an obstacle contact', () => {
  // format 2: collided is either contact
  assert.deepEqual(judge(summary({ collided: true, obstacle_collided: false, self_collided: true })).reasons, ['self-collision']);
  assert.deepEqual(judge(summary({ collided: true, obstacle_collided: true, self_collided: true, min_distance: -0.002 })).reasons, ['collision, 2 mm deep', 'self-collision']);
  assert.deepEqual(judge(summary({ collided: true, obstacle_collided: false, self_collided: true }), { collision: true }).reasons, []);
  assert.deepEqual(contacts(summary({ collided: true })), ['collided']);  // format 1: obstacles only
  const rows = compareVerdict([summary({ self_collided: true, min_self_distance: -0.02 }), summary({ self_collided: false, min_self_distance: 0.3 })], ['a', 'b']).rows;
  assert.deepEqual(rows.find((r) => r.key === 'self_collided').best, [1]);
  assert.deepEqual(rows.find((r) => r.key === 'min_self_distance').best, [1]);
  const both = compareVerdict([summary({ collided: true, obstacle_collided: false, self_collided: true })], ['a']).rows;
  assert.deepEqual(both.find((r) => r.key === 'collided').values, [false]);  // the collided row is the obstacle contact
});

test('the headline says no difference, who passes and who fails', () => {
  assert.match(compareVerdict([summary(), summary({ step_us: { p50: 5, p99: 20 } })], ['pinv', 'dls']).headline, /^No difference/);
  const split = compareVerdict([summary({ collided: true, min_distance: -0.1 }), summary({ min_distance: 0.19 })], ['pinv', 'closest_point']);
  assert.equal(split.headline, 'closest_point passes; pinv fails (collision, 10 cm deep).');
  const none = compareVerdict([summary({ max_tracking_error: 0.02 }), summary({ collided: true, min_distance: -0.001 })], ['pinv', 'dls']);
  assert.equal(none.headline, 'All fail: pinv (tracking error 2 cm > 1 cm); dls (collision, 1 mm deep).');
  assert.deepEqual(split.verdicts.map((v) => v.pass), [false, true]);
  const distance = split.rows.find((r) => r.key === 'min_distance');
  assert.deepEqual(distance.best, [1]);
  assert.equal(distance.differs, true);
  assert.equal(split.rows.find((r) => r.key === 'step_p50').differs, false);  // timing never makes methods differ
  assert.match(compareVerdict([summary(), summary({ min_distance: 0.3 })], ['a', 'b']).headline, /^All pass; they differ in min distance/);
});

test('a reason says when it first happened, where the stored frames tell', async () => {
  const { judge } = await import('../../../web/js/compare_verdict.js');
  const summary = { collided: true, min_distance: -0.012, max_tracking_error: 0.048, joint_limit_violated: true };
  const timed = judge(summary, undefined, { collision: 4.04, tracking_lost: 3.2, joint_limit: 1.5 });
  assert.deepEqual(timed.reasons, ['collision at 4.04 s, 1.2 cm deep', 'crossed a joint limit at 1.50 s', 'tracking error 4.8 cm > 1 cm at 3.20 s']);
  assert.deepEqual(judge(summary).reasons, ['collision, 1.2 cm deep', 'crossed a joint limit', 'tracking error 4.8 cm > 1 cm']);
});
