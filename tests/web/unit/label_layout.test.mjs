// Where a view's labels go (web/js/label_layout.js): near their anchor, off
// the arm's links, off each other and the caption, inside the canvas.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { LabelLayout, overlap, segmentHitsBox } from '../../../web/js/label_layout.js';

const measure = (text) => 6 * text.length;

test('a label with nothing near it takes its usual place, right of and above its anchor', () => {
  const layout = new LabelLayout(400, 300, measure);
  const box = layout.place('disc', 100, 100);
  assert.ok(box.x > 100 && box.y + box.h < 100, JSON.stringify(box));
});

test('a label whose usual place is on a link moves off it, and stays near its anchor', () => {
  const layout = new LabelLayout(400, 300, measure);
  layout.blockSegment(90, 60, 200, 100, 3);  // a link passing just above-right of the anchor
  const box = layout.place('0.543 m', 100, 100);
  assert.ok(!segmentHitsBox([90, 60, 200, 100], box), JSON.stringify(box));
  const cx = box.x + box.w / 2, cy = box.y + box.h / 2;
  assert.ok(Math.hypot(cx - 100, cy - 100) < 80, `near its anchor: ${JSON.stringify(box)}`);
});

test('labels at one anchor do not cover each other, the caption, or leave the canvas', () => {
  const layout = new LabelLayout(200, 150, measure);
  const caption = { x: 10, y: 6, w: 120, h: 18 };
  layout.block(caption);
  const boxes = ['box', '0.41 m', '0.543 m', 'pin'].map((t) => layout.place(t, 20, 20));
  for (let i = 0; i < boxes.length; ++i) {
    assert.equal(overlap(boxes[i], caption), 0, `label ${i} off the caption`);
    assert.ok(boxes[i].x >= 0 && boxes[i].y >= 0 && boxes[i].x + boxes[i].w <= 200, `label ${i} inside: ${JSON.stringify(boxes[i])}`);
    for (let j = 0; j < i; ++j) assert.equal(overlap(boxes[i], boxes[j]), 0, `labels ${i} and ${j}`);
  }
});

test('segments and boxes meet as they should', () => {
  const box = { x: 10, y: 10, w: 10, h: 10 };
  assert.ok(segmentHitsBox([0, 15, 30, 15], box));
  assert.ok(segmentHitsBox([12, 12, 13, 13], box), 'inside');
  assert.ok(!segmentHitsBox([0, 0, 30, 5], box));
  assert.ok(!segmentHitsBox([0, 30, 30, 25], box));
  assert.equal(overlap(box, { x: 15, y: 15, w: 10, h: 10 }), 25);
});
