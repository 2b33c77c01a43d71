// The step-time chart's range (web/js/plots_charts.js robustMax): a slow first
// step does not flatten the axis; an honest spread keeps its maximum.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { robustMax } from '../../../web/js/plots_charts.js';

test('one 2800 µs first step among 2 µs steps is drawn off the top', () => {
  const values = [2800, ...Array.from({ length: 500 }, (_, i) => 2 + (i % 10) * 0.1)];
  const top = robustMax(values);
  assert.ok(top < 5, `the axis tops at ${top} µs`);
});

test('a spread without outliers keeps its maximum; few values keep theirs', () => {
  const values = Array.from({ length: 100 }, (_, i) => 1 + i / 100);
  assert.equal(robustMax(values), Math.max(...values));
  assert.equal(robustMax([3, 1000, null, NaN]), 1000);
  assert.equal(robustMax([]), null);
});
