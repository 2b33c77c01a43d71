// Obstacles in the 2D view: drawing each shape (as the server describes it in
// scenario syntax) at its current position, and picking one under the pointer.

// An obstacle's current position: the frame's, else its own from the snapshot.
export function obstacleAt(o, framePosition) {
  return framePosition || o.center || o.position || o.point || [0, 0, 0];
}

// Corners of a polygon or a box in world x-y at position `at`.
function outline(o, at) {
  if (o.shape === 'polygon') return o.points.map((p) => [p[0] + at[0], p[1] + at[1]]);
  if (o.shape !== 'box') return null;
  const yaw = o.rpy ? o.rpy[2] : 0, hx = o.size[0] / 2, hy = o.size[1] / 2;
  const cos = Math.cos(yaw), sin = Math.sin(yaw);
  return [[-hx, -hy], [hx, -hy], [hx, hy], [-hx, hy]].map(([x, y]) => [at[0] + x * cos - y * sin, at[1] + x * sin + y * cos]);
}

export function drawObstacle2D(view, o, at, selected) {
  const c = view.context;
  c.fillStyle = selected ? '#ffcc80' : '#b0bec5';
  c.strokeStyle = selected ? '#ef6c00' : '#607d8b';
  c.lineWidth = selected ? 2 : 1.5;
  c.beginPath();
  const corners = outline(o, at);
  if (corners) {
    corners.forEach((w, i) => { const s = view.toScreen(w); i ? c.lineTo(s.x, s.y) : c.moveTo(s.x, s.y); });
    c.closePath();
  } else if (o.shape === 'sphere') {
    const s = view.toScreen(at);
    c.arc(s.x, s.y, o.radius * view.scale, 0, 2 * Math.PI);
  } else if (o.shape === 'point') {
    const s = view.toScreen(at);
    c.arc(s.x, s.y, 5, 0, 2 * Math.PI);
  } else if (o.shape === 'wall') {
    // the blocked half-plane behind the line through `point`; normal into free space
    const n = o.normal, t = [-n[1], n[0]], far = 1e4;
    [[at[0] + t[0] * far, at[1] + t[1] * far], [at[0] - t[0] * far, at[1] - t[1] * far],
      [at[0] - t[0] * far - n[0] * far, at[1] - t[1] * far - n[1] * far],
      [at[0] + t[0] * far - n[0] * far, at[1] + t[1] * far - n[1] * far]]
      .forEach((w, i) => { const s = view.toScreen(w); i ? c.lineTo(s.x, s.y) : c.moveTo(s.x, s.y); });
    c.closePath();
  }
  c.fill();
  c.stroke();
  if (o.id && view.scale > 40) {
    const centre = corners ? corners.reduce((a, p) => [a[0] + p[0] / corners.length, a[1] + p[1] / corners.length], [0, 0]) : at;
    const s = view.toScreen(centre);
    view.addLabel(o.id, s.x, s.y, '#455a64');
  }
}

function inside(poly, x, y) {
  let inside = false;
  for (let i = 0, j = poly.length - 1; i < poly.length; j = i++) {
    const [xi, yi] = poly[i], [xj, yj] = poly[j];
    if ((yi > y) !== (yj > y) && x < ((xj - xi) * (y - yi)) / (yj - yi) + xi) inside = !inside;
  }
  return inside;
}

function segmentDistance(p, a, b) {
  const dx = b[0] - a[0], dy = b[1] - a[1], len = dx * dx + dy * dy;
  const t = len > 0 ? Math.max(0, Math.min(1, ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / len)) : 0;
  return Math.hypot(p[0] - a[0] - t * dx, p[1] - a[1] - t * dy);
}

// Index of the obstacle under screen point (x, y), within a few pixels; walls
// are not picked (they would cover half the view).
export function hitObstacle2D(view, x, y) {
  const w = view.toWorld(x, y), tolerance = 8 / view.scale;
  let best = null, bestDistance = tolerance;
  view.snapshot.obstacles.forEach((o, i) => {
    if (o.shape === 'wall') return;
    const at = view.positionOf(i);
    let d;
    const corners = outline(o, at);
    if (corners) {
      d = inside(corners, w[0], w[1]) ? 0 : Math.min(...corners.map((a, k) => segmentDistance(w, a, corners[(k + 1) % corners.length])));
    } else {
      d = Math.max(0, Math.hypot(w[0] - at[0], w[1] - at[1]) - (o.shape === 'sphere' ? o.radius : 0));
    }
    if (d <= bestDistance) { best = i; bestDistance = d; }
  });
  return best;
}
