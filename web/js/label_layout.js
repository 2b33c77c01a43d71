// Where a view's text labels go (obstacle names, distances): near their
// anchors, on none of the arm's links and on no other label, caption, legend
// or scale bar. Each label tries positions round its anchor, nearest first,
// and takes the first that touches nothing; when none is free, the one that
// covers least. Pure geometry in screen pixels (`measure(text)` gives a
// label's width), so that it is tested without a browser.

const GAP = 3;  // px kept between a label and what it must not cover
// Offsets of a label's box from its anchor, as multiples of (its width, its height) plus pixels.
const DIRECTIONS = [
  [0, -1, 1, -1],   // right, above (the old place)
  [0, 0, 1, 1],     // right, below
  [-1, -1, -1, -1], // left, above
  [-1, 0, -1, 1],   // left, below
  [-0.5, -1, 0, -1], // above
  [-0.5, 0, 0, 1],   // below
  [0, -0.5, 1, 0],   // right
  [-1, -0.5, -1, 0], // left
];
const REACH = [4, 14, 28, 44];  // px from the anchor, tried in turn

export class LabelLayout {
  // `width`, `height`: the canvas in px; `lineHeight`: a label's height.
  constructor(width, height, measure, lineHeight = 12) {
    this.width = width;
    this.height = height;
    this.measure = measure;
    this.lineHeight = lineHeight;
    this.boxes = [];     // taken: {x, y, w, h}
    this.segments = [];  // the arm's links: [x1, y1, x2, y2, half width]
  }

  block(box) { this.boxes.push(box); }
  blockSegment(x1, y1, x2, y2, halfWidth = 2) { this.segments.push([x1, y1, x2, y2, halfWidth]); }

  // The box for `text` near (x, y), taken; {x, y, w, h} (x, y: its top left).
  place(text, x, y) {
    const w = this.measure(text), h = this.lineHeight;
    let best = null, bestCost = Infinity;
    for (const reach of REACH) {
      for (const [fw, fh, sx, sy] of DIRECTIONS) {
        const box = { x: x + fw * w + sx * reach, y: y + fh * h + sy * reach, w, h };
        const cost = this.cost(box);
        if (cost === 0) { this.boxes.push(box); return box; }
        if (cost < bestCost) { bestCost = cost; best = box; }
      }
    }
    this.boxes.push(best);
    return best;
  }

  // What a box would cover: area outside the canvas, over other boxes, and
  // a large cost for each link it crosses.
  cost(box) {
    let cost = 0;
    const outside = box.w * box.h - overlap(box, { x: 0, y: 0, w: this.width, h: this.height });
    cost += outside * 4;
    for (const b of this.boxes) cost += overlap(grow(box, GAP), b);
    for (const s of this.segments) if (segmentHitsBox(s, grow(box, GAP + s[4]))) cost += 1000;
    return cost;
  }
}

function grow(b, by) { return { x: b.x - by, y: b.y - by, w: b.w + 2 * by, h: b.h + 2 * by }; }

export function overlap(a, b) {
  const w = Math.min(a.x + a.w, b.x + b.w) - Math.max(a.x, b.x);
  const h = Math.min(a.y + a.h, b.y + b.h) - Math.max(a.y, b.y);
  return w > 0 && h > 0 ? w * h : 0;
}

// Whether the segment [x1, y1, x2, y2] meets the box (Liang–Barsky clipping).
export function segmentHitsBox([x1, y1, x2, y2], box) {
  const dx = x2 - x1, dy = y2 - y1;
  let t0 = 0, t1 = 1;
  for (const [p, q] of [[-dx, x1 - box.x], [dx, box.x + box.w - x1], [-dy, y1 - box.y], [dy, box.y + box.h - y1]]) {
    if (p === 0) { if (q < 0) return false; continue; }
    const t = q / p;
    if (p < 0) { if (t > t1) return false; if (t > t0) t0 = t; } else { if (t < t0) return false; if (t < t1) t1 = t; }
  }
  return true;
}
