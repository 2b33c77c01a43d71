// Typed numbers (web/js/typed_number.js): a decimal comma is a decimal point,
// never dropped; text read two ways or out of range is refused with a message.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { parseTypedNumber } from '../../../web/js/typed_number.js';

test('a decimal point or a decimal comma', () => {
  assert.deepEqual(parseTypedNumber('0.3'), { value: 0.3 });
  assert.deepEqual(parseTypedNumber('0,3'), { value: 0.3 });
  assert.deepEqual(parseTypedNumber('0,35'), { value: 0.35 });
  assert.deepEqual(parseTypedNumber(' -1,5 '), { value: -1.5 });
  assert.deepEqual(parseTypedNumber(',5'), { value: 0.5 });
  assert.deepEqual(parseTypedNumber('1e-3'), { value: 0.001 });
  assert.deepEqual(parseTypedNumber('12'), { value: 12 });
});

test('text read two ways is refused, never reinterpreted', () => {
  for (const text of ['1,234.5', '1.234,5', '1,2,3']) assert.match(parseTypedNumber(text).error, /two ways/, text);
});

test('what is not a number is refused', () => {
  for (const text of ['abc', '0.3m', '--1', '1..2', 'Infinity', '0x10']) assert.ok('error' in parseTypedNumber(text), text);
  assert.match(parseTypedNumber('').error, /type a number/);
  assert.match(parseTypedNumber('1e999').error, /too large/);
});

test('a range with its unit', () => {
  assert.deepEqual(parseTypedNumber('0,3', { min: 0, max: 1, unit: 'm' }), { value: 0.3 });
  assert.equal(parseTypedNumber('3', { min: 0, max: 1, unit: 'm' }).error, '3 is out of range: type a number in [0, 1] m');
  assert.match(parseTypedNumber('', { min: 0, max: 1 }).error, /type a number in \[0, 1\]/);
  assert.equal(parseTypedNumber('-0,1', { min: 0, unit: 'm' }).error, '-0.1 is out of range: type a number ≥ 0 m');
});
