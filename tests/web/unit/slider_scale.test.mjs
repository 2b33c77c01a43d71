// Parameter sliders (web/js/params.js sliderScale): logarithmic where the
// range spans two decades or more, so one click moves by a fraction of a
// decade, not by half the range; linear otherwise; 0 stays reachable.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { sliderScale } from '../../../web/js/params.js';

test('0.001–10 m is logarithmic: the middle of the slider is 0.1 m, not 5 m', () => {
  const s = sliderScale({ min: 0.001, max: 10, step: 0.001 });
  assert.equal(s.log, true);
  assert.equal(s.fromPosition(500), 0.1);
  assert.equal(s.fromPosition(s.max), 10);
  assert.equal(s.fromPosition(0), 0.001);
  for (const v of [0.001, 0.05, 0.25, 3]) assert.ok(Math.abs(s.fromPosition(s.toPosition(v)) - v) / v < 0.01, `${v} round-trips`);
});

test('0–1000 keeps 0 at the left end and spreads the decades above it', () => {
  const s = sliderScale({ min: 0, max: 1000, step: 1 });
  assert.equal(s.log, true);
  assert.equal(s.fromPosition(0), 0);
  assert.equal(s.toPosition(0), 0);
  assert.equal(s.fromPosition(1), 1);
  assert.equal(s.fromPosition(s.max), 1000);
  assert.ok(s.fromPosition(500) < 50, `the middle is ${s.fromPosition(500)}`);
});

test('a range within two decades stays linear', () => {
  const s = sliderScale({ min: 0.5, max: 20, step: 0.5 });
  assert.equal(s.log, false);
  assert.equal(s.toPosition(3), 3);
  assert.equal(sliderScale({ min: -1, max: 1, step: 0.01 }).log, false);
});
