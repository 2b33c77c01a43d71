// Parameter sliders (web/js/params.js sliderScale): logarithmic where the
// range spans two decades or more, in twentieths of a decade with two
// significant digits, so one step moves by ×1.12, not by half the range;
// linear otherwise; 0 stays reachable; steps out and back return to the
// anchors (the run's starting value) exactly.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { sliderScale } from '../../../web/js/params.js';

test('0.001–10 m is logarithmic: the middle of the slider is 0.1 m, not 5 m', () => {
  const s = sliderScale({ min: 0.001, max: 10, step: 0.001 });
  assert.equal(s.log, true);
  assert.equal(s.max, 80);  // four decades of 20 steps
  assert.equal(s.fromPosition(40), 0.1);
  assert.equal(s.fromPosition(s.max), 10);
  assert.equal(s.fromPosition(0), 0.001);
  for (const v of [0.001, 0.05, 0.25, 3]) assert.ok(Math.abs(s.fromPosition(s.toPosition(v)) - v) / v < 0.07, `${v} round-trips within a step`);
});

test('a step is a twentieth of a decade and lands on two significant digits', () => {
  const s = sliderScale({ min: 0.1, max: 1000, step: 0.1 });
  const decade = [];
  for (let p = s.toPosition(1); p <= s.toPosition(10); p++) decade.push(s.fromPosition(p));
  assert.deepEqual(decade, [1, 1.1, 1.3, 1.4, 1.6, 1.8, 2, 2.2, 2.5, 2.8, 3.2, 3.5, 4, 4.5, 5, 5.6, 6.3, 7.1, 7.9, 8.9, 10]);
});

test('six steps right and six left return to the starting value exactly', () => {
  const start = 4.99;
  const s = sliderScale({ min: 0.1, max: 1000, step: 0.1 }, [start]);
  let p = s.toPosition(start);
  for (let i = 0; i < 6; i++) p++;
  assert.ok(s.fromPosition(p) > 9);
  for (let i = 0; i < 6; i++) p--;
  assert.equal(s.fromPosition(p), start);
});

test('0–1000 keeps 0 at the left end and spreads the decades above it', () => {
  const s = sliderScale({ min: 0, max: 1000, step: 1 });
  assert.equal(s.log, true);
  assert.equal(s.fromPosition(0), 0);
  assert.equal(s.toPosition(0), 0);
  assert.equal(s.fromPosition(1), 1);
  assert.equal(s.fromPosition(s.max), 1000);
  assert.ok(s.fromPosition(Math.round(s.max / 2)) < 50, `the middle is ${s.fromPosition(Math.round(s.max / 2))}`);
});

test('a range within two decades stays linear', () => {
  const s = sliderScale({ min: 0.5, max: 20, step: 0.5 });
  assert.equal(s.log, false);
  assert.equal(s.toPosition(3), 3);
  assert.equal(sliderScale({ min: -1, max: 1, step: 0.01 }).log, false);
});
