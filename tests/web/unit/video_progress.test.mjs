// The video export's progress line (web/js/export_dialog.js videoProgress):
// the frame counts, and the time left at the pace so far once it is known.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { videoProgress } from '../../../web/js/export_dialog.js';

test('the first frames give no estimate; then the time left at the pace so far', () => {
  assert.equal(videoProgress(2, 201, 0.1), 'recording frame 2 of 201…');
  assert.equal(videoProgress(40, 201, 2), 'recording frame 40 of 201 · about 8 s left');
  assert.equal(videoProgress(10, 1000, 10), 'recording frame 10 of 1000 · about 16 min 30 s left');
  assert.equal(videoProgress(201, 201, 5), 'recording frame 201 of 201 · about 0 s left');
});
