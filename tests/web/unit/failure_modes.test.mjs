// A sweep run's failure mode in words (web/js/failure_modes.js).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { failureModeText, outcomeText } from '../../../web/js/failure_modes.js';

test('every mode of sweep/failure_watch.cpp reads as words; self-collision by its name', () => {
  assert.equal(failureModeText('self_collision'), 'self-collision');
  assert.equal(failureModeText('collision'), 'collision');
  assert.equal(failureModeText('tracking_lost'), 'tracking lost');
  assert.equal(failureModeText('some_new_mode'), 'some new mode');
});

test('a run\'s outcome: pass, fail, or fail with its first failure and when', () => {
  assert.equal(outcomeText({ success: true }), 'pass');
  assert.equal(outcomeText({ success: false, failure_mode: null }), 'fail');
  assert.equal(outcomeText({ success: false, failure_mode: 'self_collision', failure_t: 0 }), 'fail: self-collision at 0.00 s');
  assert.equal(outcomeText({ success: false, failure_mode: 'collision', failure_t: null }), 'fail: collision');
});
