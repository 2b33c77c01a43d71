// Canvas 2D view of planar models in the x-y plane, drawn only from what the
// server sends (link segments, obstacles, target, path, overlays). Fits the
// scene on open; drag empty space to pan, wheel or pinch to zoom, double-click
// to fit again; drag an obstacle to move it. Same interface as View3D.
import { drawOverlays2D, drawArm2D, ellipseScale } from './view2d_overlays.js';
import { drawObstacle2D, obstacleAt, hitObstacle2D } from './view2d_obstacles.js';
import { LabelLayout } from './label_layout.js';

const TRACE_POINTS = 4000;

export class View2D {
  constructor(container) {
    this.container = container;
    this.canvas = document.createElement('canvas');
    this.canvas.className = 'view-canvas';
    this.canvas.tabIndex = 0;
    this.canvas.setAttribute('aria-label', 'arm view: drag empty space to pan, wheel to zoom, double-click to fit, drag an obstacle to move it');
    container.appendChild(this.canvas);
    this.context = this.canvas.getContext('2d');
    this.snapshot = null;
    this.frame = null;
    this.lanes = [];
    this.colour = '#37474f';
    this.label = '';
    this.overlays = {};
    this.placing = null;
    this.selected = null;
    this.onPlace = null;
    this.onObstacleDrag = null;
    this.onSelect = null;
    this.scale = 100;
    this.origin = { x: 0, y: 0 };
    this.userMoved = false;
    this.dirty = true;
    this.pointers = new Map();
    this.gesture = null;
    this.pending = null;  // a dragged obstacle's position until frames confirm it
    this.trace = new Float64Array(2 * TRACE_POINTS);
    this.traceCount = 0;
    this.traceStart = 0;
    this.lastStep = -1;
    this.ellipseScale = null;
    this.marks = [];
    this.resizeObserver = new ResizeObserver(() => this.resize());
    this.resizeObserver.observe(container);
    this.listen();
    this.resize();
  }

  setSnapshot(snapshot) {
    const first = !this.snapshot;
    const previous = this.snapshot;
    this.snapshot = snapshot;
    if (previous) this.followObstacles(previous, snapshot);
    if (snapshot.frame) this.setFrame(snapshot.frame);
    if (first) this.fit();
    this.dirty = true;
  }

  setFrame(frame) {
    if (frame.step < this.lastStep) this.resetTrace();
    if (frame.step !== this.lastStep) this.appendTrace(frame.ee);
    this.lastStep = frame.step;
    this.frame = frame;
    if (this.ellipseScale === null && frame.ellipsoid && this.snapshot) this.ellipseScale = ellipseScale(frame.ellipsoid, this.snapshot.model.reach);
    if (this.pending && (performance.now() > this.pending.until || near(frame.obstacles[this.pending.index], this.pending.position))) this.pending = null;
    this.dirty = true;
  }

  // Obstacles added or removed renumber the others: a drag, its held position
  // and the selection follow their obstacle by id, and end if it is gone.
  followObstacles(previous, snapshot) {
    const remap = (i) => {
      const id = previous.obstacles[i] ? previous.obstacles[i].id : null;
      const now = id === null ? -1 : snapshot.obstacles.findIndex((o) => o.id === id);
      return now >= 0 ? now : null;
    };
    if (this.gesture && this.gesture.kind === 'drag') {
      this.gesture.index = remap(this.gesture.index);
      if (this.gesture.index === null) this.gesture = null;
    }
    if (this.pending) {
      this.pending.index = remap(this.pending.index);
      if (this.pending.index === null) this.pending = null;
    }
    if (this.selected !== null) this.select(remap(this.selected));
  }

  setLanes(lanes) { this.lanes = lanes; this.dirty = true; }
  invalidate() { this.dirty = true; }

  resetTrace() { this.traceCount = 0; this.traceStart = 0; this.lastStep = -1; this.dirty = true; }
  // A replay's seek: the trace as it stood at the frame shown, from the stored ends.
  rebuildTrace(points) {
    const step = this.lastStep;
    this.resetTrace();
    for (const p of points.slice(-TRACE_POINTS)) this.appendTrace(p);
    this.lastStep = step;
  }
  appendTrace(p) {
    if (!p) return;
    const i = (this.traceStart + this.traceCount) % TRACE_POINTS;
    this.trace[2 * i] = p[0];
    this.trace[2 * i + 1] = p[1];
    if (this.traceCount < TRACE_POINTS) this.traceCount++;
    else this.traceStart = (this.traceStart + 1) % TRACE_POINTS;
  }

  resize() {
    const rect = this.container.getBoundingClientRect();
    const ratio = window.devicePixelRatio || 1;
    this.width = Math.max(1, rect.width);
    this.height = Math.max(1, rect.height);
    this.canvas.width = Math.round(this.width * ratio);
    this.canvas.height = Math.round(this.height * ratio);
    this.canvas.style.width = `${this.width}px`;
    this.canvas.style.height = `${this.height}px`;
    this.context.setTransform(ratio, 0, 0, ratio, 0, 0);
    if (this.snapshot && !this.userMoved) this.fit();
    this.dirty = true;
  }

  // The view drawn afresh into a canvas of width × height pixels (an export):
  // the same picture as on screen, at that resolution; a different aspect
  // shows more or less of the scene around the same centre.
  renderAt(width, height) {
    const saved = { canvas: this.canvas, context: this.context, width: this.width, height: this.height, scale: this.scale, origin: this.origin };
    const out = document.createElement('canvas');
    out.width = width;
    out.height = height;
    const k = width / this.width;  // pixels per on-screen pixel: lines and text keep their look
    const logical = { w: this.width, h: height / k };
    const centre = this.toWorld(this.width / 2, this.height / 2);
    try {
      this.canvas = out;
      this.context = out.getContext('2d');
      this.context.setTransform(k, 0, 0, k, 0, 0);
      this.width = logical.w;
      this.height = logical.h;
      this.origin = { x: logical.w / 2 - this.scale * centre[0], y: logical.h / 2 + this.scale * centre[1] };
      this.dirty = true;
      this.render();
    } finally {
      Object.assign(this, saved);
      this.dirty = true;
    }
    return out;
  }

  // The scene as it is: the arm, every bounded obstacle, the path and the
  // target (the whole reach would leave the arm small in an empty grid).
  fit() {
    if (!this.snapshot) return;
    const s = this.snapshot, base = s.model.base;
    const box = { minX: base[0], maxX: base[0], minY: base[1], maxY: base[1] };
    const add = (x, y) => { box.minX = Math.min(box.minX, x); box.maxX = Math.max(box.maxX, x); box.minY = Math.min(box.minY, y); box.maxY = Math.max(box.maxY, y); };
    for (const p of s.task.path) add(p[0], p[1]);
    if (this.frame) {
      for (const l of this.frame.links) { add(l[0], l[1]); add(l[3], l[4]); }
      add(this.frame.target[0], this.frame.target[1]);
    } else add(base[0] + s.model.reach, base[1]);
    s.obstacles.forEach((o, i) => {
      if (o.shape === 'wall') return;
      const at = obstacleAt(o, this.frame ? this.frame.obstacles[i] : null);
      const r = o.shape === 'sphere' ? o.radius : o.shape === 'box' ? Math.hypot(o.size[0], o.size[1]) / 2 : 0;
      if (o.shape === 'polygon') for (const p of o.points) add(p[0] + at[0], p[1] + at[1]);
      else { add(at[0] - r, at[1] - r); add(at[0] + r, at[1] + r); }
    });
    const size = Math.max(box.maxX - box.minX, box.maxY - box.minY, 0.1 * s.model.reach);
    const margin = 0.12 * size;
    const minimum = 0.1 * s.model.reach;
    const w = Math.max(box.maxX - box.minX, minimum) + 2 * margin, h = Math.max(box.maxY - box.minY, minimum) + 2 * margin;
    this.scale = Math.min(this.width / w, this.height / h);
    this.origin = { x: this.width / 2 - this.scale * (box.minX + box.maxX) / 2, y: this.height / 2 + this.scale * (box.minY + box.maxY) / 2 };
    this.userMoved = false;
    this.dirty = true;
  }

  toScreen(p) { return { x: this.origin.x + this.scale * p[0], y: this.origin.y - this.scale * p[1] }; }
  toWorld(x, y) { return [(x - this.origin.x) / this.scale, (this.origin.y - y) / this.scale]; }
  worldToClient(p) {
    const rect = this.canvas.getBoundingClientRect(), s = this.toScreen(p);
    return { x: rect.left + s.x, y: rect.top + s.y };
  }

  zoomAt(x, y, factor) {
    const [wx, wy] = this.toWorld(x, y);
    this.scale = Math.min(1e5, Math.max(1, this.scale * factor));
    this.origin = { x: x - wx * this.scale, y: y + wy * this.scale };
    this.userMoved = true;
    this.dirty = true;
  }

  local(event) {
    const rect = this.canvas.getBoundingClientRect();
    return [event.clientX - rect.left, event.clientY - rect.top];
  }

  listen() {
    const c = this.canvas;
    c.addEventListener('pointerdown', (event) => {
      const [x, y] = this.local(event);
      this.pointers.set(event.pointerId, { x, y });
      c.setPointerCapture(event.pointerId);
      if (this.pointers.size === 2) { this.gesture = { kind: 'pinch', distance: this.pinchDistance() }; return; }
      if (this.placing && this.onPlace) {
        const [wx, wy] = this.toWorld(x, y);
        this.onPlace([wx, wy, 0]);
        return;
      }
      const index = this.snapshot && this.frame ? hitObstacle2D(this, x, y) : null;
      if (index !== null) {
        this.select(index);
        if (this.onObstacleDrag) {
          const from = this.positionOf(index).slice();
          this.gesture = { kind: 'drag', index, start: this.toWorld(x, y), from };
        }
        return;
      }
      this.select(null);
      this.gesture = { kind: 'pan', x, y, origin: { ...this.origin } };
    });
    c.addEventListener('pointermove', (event) => {
      if (!this.pointers.has(event.pointerId)) return;
      const [x, y] = this.local(event);
      this.pointers.set(event.pointerId, { x, y });
      const g = this.gesture;
      if (!g) return;
      if (g.kind === 'pinch' && this.pointers.size === 2) {
        const d = this.pinchDistance(), m = this.pinchMiddle();
        if (g.distance > 0) this.zoomAt(m.x, m.y, d / g.distance);
        g.distance = d;
      } else if (g.kind === 'pan') {
        this.origin = { x: g.origin.x + x - g.x, y: g.origin.y + y - g.y };
        this.userMoved = true;
        this.dirty = true;
      } else if (g.kind === 'drag') {
        if (!this.onObstacleDrag) { this.endDrag(); return; }  // the run ended meanwhile
        const [wx, wy] = this.toWorld(x, y);
        const position = [g.from[0] + wx - g.start[0], g.from[1] + wy - g.start[1], g.from[2] || 0];
        this.pending = { index: g.index, position, until: Infinity };
        this.dirty = true;
        this.onObstacleDrag(g.index, position, 'move');
      }
    });
    const end = (event) => {
      this.pointers.delete(event.pointerId);
      const g = this.gesture;
      if (g && g.kind === 'drag' && this.pending && this.onObstacleDrag) {
        this.pending.until = performance.now() + 1500;
        this.onObstacleDrag(g.index, this.pending.position, 'end');
      }
      this.gesture = null;
    };
    c.addEventListener('pointerup', end);
    c.addEventListener('pointercancel', end);
    c.addEventListener('wheel', (event) => {
      event.preventDefault();
      const [x, y] = this.local(event);
      this.zoomAt(x, y, Math.exp(-event.deltaY * 0.0015));
    }, { passive: false });
    c.addEventListener('dblclick', () => this.fit());
  }

  // Lets go of an obstacle being dragged: it is drawn where the frames put it.
  endDrag() {
    if (this.gesture && this.gesture.kind === 'drag') this.gesture = null;
    this.pending = null;
    this.dirty = true;
  }

  pinchDistance() { const [a, b] = [...this.pointers.values()]; return Math.hypot(a.x - b.x, a.y - b.y); }
  pinchMiddle() { const [a, b] = [...this.pointers.values()]; return { x: (a.x + b.x) / 2, y: (a.y + b.y) / 2 }; }

  select(index) {
    if (this.selected === index) return;
    this.selected = index;
    this.dirty = true;
    if (this.onSelect) this.onSelect(index);
  }

  // Where obstacle i is drawn: a drag in progress wins over the frames.
  positionOf(i) {
    if (this.pending && this.pending.index === i) return this.pending.position;
    return obstacleAt(this.snapshot.obstacles[i], this.frame ? this.frame.obstacles[i] : null);
  }

  render() {
    if (!this.dirty) return;
    this.dirty = false;
    const c = this.context;
    c.clearRect(0, 0, this.width, this.height);
    this.grid();
    if (!this.snapshot) return;
    this.labels = [];  // obstacle names and distances: placed last, clear of the arm (drawLabels)
    this.path(this.snapshot.task.path);
    this.snapshot.obstacles.forEach((o, i) => drawObstacle2D(this, o, this.positionOf(i), i === this.selected));
    if (this.overlays.trace) this.drawTrace();
    if (this.frame) {
      drawOverlays2D(this, this.snapshot, this.frame, this.colour);
      for (const lane of this.lanes) if (lane.frame && lane.snapshot) drawArm2D(this, lane.snapshot, lane.frame, lane.colour, 0.75);
      this.marks = drawArm2D(this, this.snapshot, this.frame, this.colour, 1);  // the links' marks as drawn (link_marks.js)
      this.cross(this.frame.target, '#2e7d32');
    }
    const taken = [this.scaleBar()];
    if (this.label) taken.push(this.caption(this.label, this.colour));
    if (this.lanes.length) taken.push(this.legend());
    this.drawLabels(taken);
  }

  // A text label near (x, y) on screen, drawn once the arm is (drawLabels).
  addLabel(text, x, y, colour) { this.labels.push({ text, x, y, colour }); }

  // The labels where they cover no link of any arm drawn, no other label and
  // none of the boxes `taken` (caption, legend, scale bar): label_layout.js.
  // this.labelBoxes: where each went (tests read them).
  drawLabels(taken) {
    const c = this.context;
    c.font = '11px system-ui, sans-serif';
    const layout = new LabelLayout(this.width, this.height, (text) => c.measureText(text).width, 12);
    for (const box of taken) if (box) layout.block(box);
    const arms = [[this.snapshot, this.frame], ...this.lanes.map((l) => [l.snapshot, l.frame])];
    for (const [snapshot, frame] of arms) {
      if (!snapshot || !frame) continue;
      frame.links.forEach((l, i) => {
        const radius = snapshot.model.links[i] ? snapshot.model.links[i].radius : 0;
        const a = this.toScreen([l[0], l[1]]), b = this.toScreen([l[3], l[4]]);
        layout.blockSegment(a.x, a.y, b.x, b.y, Math.max(1.5, radius * this.scale));
      });
    }
    this.labelBoxes = this.labels.map((label) => {
      const box = layout.place(label.text, label.x, label.y);
      c.fillStyle = label.colour;
      c.fillText(label.text, box.x, box.y + box.h - 2);
      return { text: label.text, ...box };
    });
  }

  // A grid whose spacing is a 1-2-5 step about 60 px wide; the axes darker.
  grid() {
    const c = this.context, step = niceStep(60 / this.scale);
    const [x0, y1] = this.toWorld(0, 0), [x1, y0] = this.toWorld(this.width, this.height);
    c.lineWidth = 1;
    c.strokeStyle = '#eef1f3';
    c.beginPath();
    for (let x = Math.ceil(x0 / step) * step; x <= x1; x += step) { const s = this.toScreen([x, 0]); c.moveTo(s.x, 0); c.lineTo(s.x, this.height); }
    for (let y = Math.ceil(y0 / step) * step; y <= y1; y += step) { const s = this.toScreen([0, y]); c.moveTo(0, s.y); c.lineTo(this.width, s.y); }
    c.stroke();
    c.strokeStyle = '#cfd8dc';
    const o = this.toScreen([0, 0]);
    c.beginPath();
    c.moveTo(o.x, 0); c.lineTo(o.x, this.height);
    c.moveTo(0, o.y); c.lineTo(this.width, o.y);
    c.stroke();
  }

  scaleBar() {
    const c = this.context, metres = niceStep(120 / this.scale), px = metres * this.scale;
    const x = 16, y = this.height - 16;
    c.strokeStyle = '#37474f';
    c.lineWidth = 2;
    c.beginPath();
    c.moveTo(x, y - 5); c.lineTo(x, y); c.lineTo(x + px, y); c.lineTo(x + px, y - 5);
    c.stroke();
    c.fillStyle = '#37474f';
    c.font = '12px system-ui, sans-serif';
    const text = metres >= 1 ? `${metres} m` : `${Math.round(metres * 1000)} mm`;
    c.fillText(text, x + px + 6, y);
    return { x: x - 2, y: y - 14, w: px + 10 + c.measureText(text).width, h: 18 };  // what it covers
  }

  caption(text, colour) {
    const c = this.context;
    c.font = '600 13px system-ui, sans-serif';
    c.fillStyle = colour;
    const room = Math.max(40, this.width - 24);  // a long label in a small lane is narrowed, never cut
    c.fillText(text, 12, 20, room);
    return { x: 10, y: 6, w: Math.min(room, c.measureText(text).width) + 4, h: 18 };
  }

  // Overlaid compare: which colour is which method.
  legend() {
    const c = this.context;
    c.font = '600 12px system-ui, sans-serif';
    const entries = [[this.label || (this.snapshot && this.snapshot.method), this.colour], ...this.lanes.map((l) => [l.label, l.colour])];
    let widest = 0;
    entries.forEach(([text, colour], i) => {
      c.fillStyle = colour;
      c.fillRect(12, 12 + 18 * i, 10, 10);
      c.fillText(text || '', 28, 21 + 18 * i);
      widest = Math.max(widest, c.measureText(text || '').width);
    });
    return { x: 10, y: 8, w: widest + 22, h: 18 * entries.length + 2 };
  }

  line(a, b) {
    const p = this.toScreen(a), q = this.toScreen(b), c = this.context;
    c.beginPath();
    c.moveTo(p.x, p.y);
    c.lineTo(q.x, q.y);
    c.stroke();
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

  drawTrace() {
    if (this.traceCount < 2) return;
    const c = this.context;
    c.strokeStyle = 'rgba(30, 136, 229, 0.55)';
    c.lineWidth = 1.5;
    c.beginPath();
    for (let k = 0; k < this.traceCount; ++k) {
      const i = (this.traceStart + k) % TRACE_POINTS;
      const s = this.toScreen([this.trace[2 * i], this.trace[2 * i + 1]]);
      k ? c.lineTo(s.x, s.y) : c.moveTo(s.x, s.y);
    }
    c.stroke();
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

  destroy() {
    this.resizeObserver.disconnect();
    this.canvas.remove();
  }
}

// 1, 2 or 5 times a power of ten, at least `value`.
export function niceStep(value) {
  const power = 10 ** Math.floor(Math.log10(value));
  for (const m of [1, 2, 5, 10]) if (m * power >= value) return m * power;
  return 10 * power;
}

function near(a, b) { return a && b && Math.abs(a[0] - b[0]) < 1e-6 && Math.abs(a[1] - b[1]) < 1e-6; }
