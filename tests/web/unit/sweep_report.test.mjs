// What the sweep page reads of a report (web/js/sweep_report.js): the
// difficulty measures and their charts, quartiles and obstacle counts, and
// "which method when" in words for every verdict status.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { difficultyMeasures, difficultySvg, countBinLabel, verdictWords, formatFailureModes, successTable } from '../../../web/js/sweep_report.js';

const counts = (successes) => successes.map((s, k) => ({ low: k, high: k === 4 ? null : k, n: 4, successes: s }));
const group = (config, over = {}) => ({
  config, family: 'fam', n: 20, successes: 10, success_rate: 0.5, step_us_p50: 2.5, failure_modes: {},
  difficulty: { measure: 'clearance', bins: [{ low: 0.01, high: 0.05, n: 5, successes: 1 }, { low: 0.05, high: 0.2, n: 15, successes: 9 }] },
  difficulty_counts: { blocking_obstacles: counts([4, 3, 2, 1, 0]) },
  ...over,
});

test('a family\'s measures: the quartiles, then each obstacle count it carries', () => {
  assert.deepEqual(difficultyMeasures([group('a'), group('b', { difficulty_counts: { tight_obstacles: counts([1, 1, 1, 1, 1]) } })]),
    [null, 'blocking_obstacles', 'tight_obstacles']);
  assert.deepEqual(difficultyMeasures([group('a', { difficulty: { measure: null, bins: [] }, difficulty_counts: {} })]), []);
});

test('an obstacle count\'s chart puts its bins at even steps, labelled 0 … 4+', () => {
  assert.equal(countBinLabel({ low: 4, high: null }), '4+');
  assert.equal(countBinLabel({ low: 2, high: 2 }), '2');
  const svg = difficultySvg([group('a'), group('b')], ['#111111', '#222222'], { measure: 'blocking_obstacles' });
  assert.match(svg, /aria-label="success against blocking_obstacles"/);
  for (const label of ['0', '1', '2', '3', '4+']) assert.match(svg, new RegExp(`text-anchor="middle" font-size="10">${label.replace('+', '\\+')}</text>`));
  assert.match(svg, /<title>a: 0\/4 with 4\+<\/title>/);
  assert.match(svg, /stroke="#222222"/);  // each group its colour
  // the quartiles' chart as before
  assert.match(difficultySvg([group('a')], ['#111111']), /aria-label="success against clearance"/);
  assert.equal(difficultySvg([group('a')], ['#111111'], { measure: 'tight_obstacles' }), null);
});

test('which method when reads well in every status', () => {
  const { cell } = successTable({ groups: [group('a', { success_rate: 0.9 }), group('b')], ranking: [] });
  const contenders = verdictWords({ family: 'fam', best: 'a', status: 'contenders', not_worse: ['a', 'b'], detectable_difference: 0.094 }, cell);
  assert.deepEqual(contenders, { detects: '9.4 points', listed: 'a (2.5000 µs/step), b (2.5000 µs/step)' });
  const few = verdictWords({ family: 'fam', best: 'a', status: 'too_few_cases', not_worse: [], cases_needed: 199,
    separable_difference: 0.2, detectable_difference: 0.35 }, cell);
  assert.equal(few.listed, 'too few cases to separate the methods (a difference of 20 points needs about 199 cases); best observed, not separated from the others: a (90 %)');
  assert.equal(few.detects, '35.0 points');
  const none = verdictWords({ family: 'fam', best: 'a', status: 'no_success', not_worse: [], detectable_difference: null }, cell);
  assert.deepEqual(none, { detects: 'none: too few cases for p < 0.05', listed: 'no configuration succeeded on any case' });
  const cut = verdictWords({ family: 'fam', best: 'a', status: 'contenders', not_worse: ['a'], not_worse_total: 3, detectable_difference: 0.1 }, cell);
  assert.match(cut.listed, /, and 2 more$/);
});

test('failure modes in words, most frequent first', () => {
  assert.equal(formatFailureModes({ collision: 1, self_collision: 3 }), 'self-collision 3 · collision 1');
});
