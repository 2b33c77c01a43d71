// What the 2D view draws on top of the scene: arms (the lane's and the
// ghosts), the nearest-obstacle segments with their distances, the
// manipulability ellipse and the method's own overlays. Each overlay has its
// own toggle in view.overlays.
import { NEAREST_LINK_COLOUR, COLLIDED_COLOUR } from './state.js';
import { linkMarks } from './link_marks.js';

const MARK_COLOURS = { nearest: NEAREST_LINK_COLOUR, collided: COLLIDED_COLOUR };

// The ellipse is drawn at a fixed scale for the whole run, chosen at the first
// frame so that its largest semi-axis is 15% of the reach: changes stay visible.
export function ellipseScale(ellipsoid, reach) {
  const largest = Math.max(...ellipsoid.axes.map((a) => Math.hypot(a[0], a[1], a[2] || 0)));
  return largest > 0 ? (0.15 * reach) / largest : 1;
}

// Returns the links' marks as drawn (link_marks.js).
export function drawArm2D(view, snapshot, frame, colour, alpha) {
  const c = view.context;
  const marks = linkMarks(frame.metrics, frame.links.length);
  c.globalAlpha = alpha;
  c.lineCap = 'round';
  frame.links.forEach((l, i) => {
    const radius = snapshot.model.links[i] ? snapshot.model.links[i].radius : 0;
    c.strokeStyle = MARK_COLOURS[marks[i]] || colour;
    c.lineWidth = Math.max(3, 2 * radius * view.scale);
    view.line([l[0], l[1]], [l[3], l[4]]);
  });
  c.fillStyle = '#fff';
  c.strokeStyle = '#263238';
  c.lineWidth = 1.5;
  for (const l of frame.links) {
    const s = view.toScreen([l[0], l[1]]);
    c.beginPath();
    c.arc(s.x, s.y, 3.5, 0, 2 * Math.PI);
    c.fill();
    c.stroke();
  }
  const ee = view.toScreen(frame.ee);
  c.fillStyle = colour;
  c.beginPath();
  c.arc(ee.x, ee.y, 4, 0, 2 * Math.PI);
  c.fill();
  c.globalAlpha = 1;
  return marks;
}

function ellipse(view, centre, axes, scale) {
  const c = view.context;
  c.beginPath();
  for (let k = 0; k <= 64; ++k) {
    const a = (2 * Math.PI * k) / 64, u = Math.cos(a), v = Math.sin(a);
    const w = [centre[0] + scale * (u * axes[0][0] + v * axes[1][0]), centre[1] + scale * (u * axes[0][1] + v * axes[1][1])];
    const s = view.toScreen(w);
    k ? c.lineTo(s.x, s.y) : c.moveTo(s.x, s.y);
  }
  c.stroke();
}

export function drawOverlays2D(view, snapshot, frame, colour) {
  const c = view.context, on = view.overlays;
  const o = frame.overlays;
  if (on.ghosts && o && o.ghost_links) {
    o.ghost_links.forEach((links) => {
      c.globalAlpha = 0.35;
      c.strokeStyle = '#8e24aa';
      c.lineWidth = 2;
      c.setLineDash([4, 3]);
      for (const l of links) view.line([l[0], l[1]], [l[3], l[4]]);
      c.setLineDash([]);
      c.globalAlpha = 1;
    });
  }
  if (on.method && o) {
    c.strokeStyle = '#8e24aa';
    c.fillStyle = '#8e24aa';
    c.lineWidth = 1.2;
    for (const [a, b] of o.segments || []) view.line(a, b);
    for (const p of o.points || []) {
      const s = view.toScreen(p);
      c.beginPath();
      c.arc(s.x, s.y, 3, 0, 2 * Math.PI);
      c.fill();
    }
    for (const e of o.ellipses || []) ellipse(view, e.centre, e.axes, 1);
  }
  if (on.nearest && frame.nearest) {
    // every link's segment; the distance written once per obstacle, at its nearest link
    const labelled = new Map();
    for (const n of frame.nearest) if (n[2] !== null && (!labelled.has(n[1]) || n[2] < labelled.get(n[1])[2])) labelled.set(n[1], n);
    const labels = new Set(labelled.values());
    for (const n of frame.nearest) {
      const [, , distance, ax, ay, , bx, by] = n;
      if (distance === null) continue;
      c.strokeStyle = distance <= 0 ? '#c62828' : '#00897b';
      c.lineWidth = 1;
      c.setLineDash([3, 3]);
      view.line([ax, ay], [bx, by]);
      c.setLineDash([]);
      if (!labels.has(n)) continue;
      const m = view.toScreen([(ax + bx) / 2, (ay + by) / 2]);
      view.addLabel(`${distance.toFixed(3)} m`, m.x, m.y, c.strokeStyle);
    }
  }
  if (on.manipulability && frame.ellipsoid) {
    c.strokeStyle = colour;
    c.lineWidth = 1.5;
    c.setLineDash([2, 2]);
    ellipse(view, frame.ellipsoid.centre, frame.ellipsoid.axes, view.ellipseScale || 1);
    c.setLineDash([]);
  }
}
