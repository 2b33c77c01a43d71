// Canvas 2D drawing of the arm in the x-y plane (3D models: their top view),
// from what the server sends: link segments, obstacles, target, path, overlays.
export class View2D {
  constructor(canvas) {
    this.canvas = canvas;
    this.context = canvas.getContext('2d');
    this.scale = 100;
    this.origin = { x: canvas.width / 2, y: canvas.height / 2 };
  }

  // Fits the view to the model's reach around its base and the obstacles.
  fit(snapshot) {
    const base = snapshot.model.base;
    let minX = base[0] - snapshot.model.reach, maxX = base[0] + snapshot.model.reach;
    let minY = base[1] - snapshot.model.reach, maxY = base[1] + snapshot.model.reach;
    for (const p of snapshot.task.path) {
      minX = Math.min(minX, p[0]); maxX = Math.max(maxX, p[0]);
      minY = Math.min(minY, p[1]); maxY = Math.max(maxY, p[1]);
    }
    const margin = 0.1 * Math.max(maxX - minX, maxY - minY);
    minX -= margin; maxX += margin; minY -= margin; maxY += margin;
    this.scale = Math.min(this.canvas.width / (maxX - minX), this.canvas.height / (maxY - minY));
    this.origin = {
      x: this.canvas.width / 2 - this.scale * (minX + maxX) / 2,
      y: this.canvas.height / 2 + this.scale * (minY + maxY) / 2,
    };
  }

  toScreen(p) { return { x: this.origin.x + this.scale * p[0], y: this.origin.y - this.scale * p[1] }; }
  // Page coordinates of a world point (canvas pixels scaled to its CSS box): for browser tests.
  toScreenClient(x, y, rect) {
    const s = this.toScreen([x, y]);
    return { x: rect.left + s.x * (rect.width / this.canvas.width), y: rect.top + s.y * (rect.height / this.canvas.height) };
  }
  toWorld(x, y) { return [(x - this.origin.x) / this.scale, (this.origin.y - y) / this.scale]; }

  draw(snapshot, frame, highlight) {
    const c = this.context;
    c.clearRect(0, 0, this.canvas.width, this.canvas.height);
    this.grid();
    if (!snapshot) return;
    this.path(snapshot.task.path);
    snapshot.obstacles.forEach((o, i) => this.obstacle(o, frame ? frame.obstacles[i] : null, i === highlight));
    if (!frame) return;
    if (frame.overlays) this.overlays(frame.overlays);
    this.arm(snapshot, frame);
    this.cross(frame.target, '#2e7d32');
  }

  grid() {
    const c = this.context;
    c.strokeStyle = '#eeeeee';
    c.lineWidth = 1;
    const [x0, y1] = this.toWorld(0, 0), [x1, y0] = this.toWorld(this.canvas.width, this.canvas.height);
    for (let x = Math.ceil(x0 * 2) / 2; x <= x1; x += 0.5) this.line([x, y0], [x, y1]);
    for (let y = Math.ceil(y0 * 2) / 2; y <= y1; y += 0.5) this.line([x0, y], [x1, y]);
    c.strokeStyle = '#cfd8dc';
    this.line([x0, 0], [x1, 0]);
    this.line([0, y0], [0, y1]);
  }

  line(a, b) {
    const p = this.toScreen(a), q = this.toScreen(b);
    this.context.beginPath();
    this.context.moveTo(p.x, p.y);
    this.context.lineTo(q.x, q.y);
    this.context.stroke();
  }

  path(points) {
    if (!points.length) return;
    const c = this.context;
    c.strokeStyle = '#a5d6a7';
    c.lineWidth = 2;
    c.setLineDash([6, 4]);
    c.beginPath();
    points.forEach((p, i) => { const s = this.toScreen(p); i ? c.lineTo(s.x, s.y) : c.moveTo(s.x, s.y); });
    c.stroke();
    c.setLineDash([]);
  }

  // o: the obstacle as in the snapshot (scenario syntax); position: its current [x, y, z].
  obstacle(o, position, highlighted) {
    const c = this.context;
    const at = position || o.center || o.position || o.point || [0, 0, 0];
    c.fillStyle = highlighted ? '#ffcc80' : '#b0bec5';
    c.strokeStyle = '#607d8b';
    c.lineWidth = 1.5;
    c.beginPath();
    if (o.shape === 'polygon') {
      o.points.forEach((p, i) => {
        const s = this.toScreen([p[0] + at[0], p[1] + at[1]]);
        i ? c.lineTo(s.x, s.y) : c.moveTo(s.x, s.y);
      });
      c.closePath();
    } else if (o.shape === 'box') {
      const yaw = o.rpy ? o.rpy[2] : 0, hx = o.size[0] / 2, hy = o.size[1] / 2;
      [[-hx, -hy], [hx, -hy], [hx, hy], [-hx, hy]].forEach(([x, y], i) => {
        const w = [at[0] + x * Math.cos(yaw) - y * Math.sin(yaw), at[1] + x * Math.sin(yaw) + y * Math.cos(yaw)];
        const s = this.toScreen(w);
        i ? c.lineTo(s.x, s.y) : c.moveTo(s.x, s.y);
      });
      c.closePath();
    } else if (o.shape === 'sphere') {
      const s = this.toScreen(at);
      c.arc(s.x, s.y, o.radius * this.scale, 0, 2 * Math.PI);
    } else if (o.shape === 'point') {
      const s = this.toScreen(at);
      c.arc(s.x, s.y, 5, 0, 2 * Math.PI);
    } else if (o.shape === 'wall') {
      // the blocked half-plane behind the line through `point`, normal into free space
      const n = o.normal, t = [-n[1], n[0]], far = 100;
      const corners = [[at[0] + t[0] * far, at[1] + t[1] * far], [at[0] - t[0] * far, at[1] - t[1] * far],
        [at[0] - t[0] * far - n[0] * far, at[1] - t[1] * far - n[1] * far],
        [at[0] + t[0] * far - n[0] * far, at[1] + t[1] * far - n[1] * far]];
      corners.forEach((w, i) => { const s = this.toScreen(w); i ? c.lineTo(s.x, s.y) : c.moveTo(s.x, s.y); });
      c.closePath();
    }
    c.fill();
    c.stroke();
  }

  arm(snapshot, frame) {
    const c = this.context;
    const closest = frame.metrics.min_distance_link - 1;
    frame.links.forEach((l, i) => {
      const radius = snapshot.model.links[i].radius;
      c.strokeStyle = frame.metrics.collided && i === closest ? '#c62828' : i === closest ? '#ef6c00' : '#37474f';
      c.lineWidth = Math.max(3, 2 * radius * this.scale);
      c.lineCap = 'round';
      this.line([l[0], l[1]], [l[3], l[4]]);
    });
    c.fillStyle = '#fff';
    c.strokeStyle = '#263238';
    c.lineWidth = 1.5;
    for (const l of frame.links) {
      const s = this.toScreen([l[0], l[1]]);
      c.beginPath();
      c.arc(s.x, s.y, 4, 0, 2 * Math.PI);
      c.fill();
      c.stroke();
    }
  }

  cross(p, colour) {
    const c = this.context, s = this.toScreen(p);
    c.strokeStyle = colour;
    c.lineWidth = 2;
    c.beginPath();
    c.moveTo(s.x - 7, s.y); c.lineTo(s.x + 7, s.y);
    c.moveTo(s.x, s.y - 7); c.lineTo(s.x, s.y + 7);
    c.stroke();
  }

  overlays(o) {
    const c = this.context;
    c.strokeStyle = '#8e24aa';
    c.fillStyle = '#8e24aa';
    c.lineWidth = 1;
    for (const [a, b] of o.segments || []) this.line(a, b);
    for (const p of o.points || []) {
      const s = this.toScreen(p);
      c.beginPath();
      c.arc(s.x, s.y, 3, 0, 2 * Math.PI);
      c.fill();
    }
    for (const e of o.ellipses || []) {
      // semi-axes as columns: draw the x-y projection as a polyline
      c.beginPath();
      for (let k = 0; k <= 48; ++k) {
        const a = (2 * Math.PI * k) / 48, u = Math.cos(a), v = Math.sin(a);
        const w = [e.centre[0] + u * e.axes[0][0] + v * e.axes[1][0], e.centre[1] + u * e.axes[0][1] + v * e.axes[1][1]];
        const s = this.toScreen(w);
        k ? c.lineTo(s.x, s.y) : c.moveTo(s.x, s.y);
      }
      c.stroke();
    }
  }

  // Index of the obstacle under a screen point (null if none).
  hit(snapshot, frame, x, y) {
    if (!snapshot || !frame) return null;
    const [wx, wy] = this.toWorld(x, y);
    let best = null, bestDistance = 12 / this.scale;
    snapshot.obstacles.forEach((o, i) => {
      const at = frame.obstacles[i];
      let d = Math.hypot(wx - at[0], wy - at[1]);
      if (o.shape === 'sphere') d = Math.max(0, d - o.radius);
      if (o.shape === 'box') d = Math.max(0, Math.abs(wx - at[0]) - o.size[0] / 2, Math.abs(wy - at[1]) - o.size[1] / 2);
      if (o.shape === 'polygon') {
        const xs = o.points.map((p) => p[0] + at[0]), ys = o.points.map((p) => p[1] + at[1]);
        d = Math.max(0, Math.min(...xs) - wx, wx - Math.max(...xs), Math.min(...ys) - wy, wy - Math.max(...ys));
      }
      if (o.shape !== 'wall' && d < bestDistance) { best = i; bestDistance = d; }
    });
    return best;
  }
}
