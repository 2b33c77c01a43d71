// Overlays of the 3D view, each drawn only when the page's toggle is on:
// nearest link-obstacle segments with distances, the manipulability ellipsoid,
// the method's own overlays (ellipses, points, segments), ghost arms and the
// end-effector trace. Objects are pooled: a frame rewrites them, never adds.
import * as THREE from 'three';
import { NEAREST_LINK_COLOUR } from './state.js';
import { CSS2DObject } from 'three/addons/renderers/CSS2DRenderer.js';
import { SegmentBuffer } from './view3d_lines.js';

export const overlayColours = { nearest: NEAREST_LINK_COLOUR, distance: '#78909c', ellipsoid: '#1e88e5', method: '#8e24aa', trace: '#1e88e5' };
const traceCapacity = 2000;
const unitSphere = new THREE.SphereGeometry(1, 32, 16);
const pointMatrix = new THREE.Matrix4();

// Three unit circles (xy, yz, zx) as segments: the ellipsoid's principal sections.
function unitRings(colour, width) {
  const steps = 48, rings = new SegmentBuffer(3 * steps, { colour, width });
  const point = (plane, a) => {
    const c = Math.cos(a), s = Math.sin(a);
    return plane === 0 ? [c, s, 0] : plane === 1 ? [0, c, s] : [s, 0, c];
  };
  for (let plane = 0; plane < 3; ++plane)
    for (let k = 0; k < steps; ++k)
      rings.push(point(plane, (2 * Math.PI * k) / steps), point(plane, (2 * Math.PI * (k + 1)) / steps));
  rings.commit();
  return rings;
}

// An ellipsoid {centre, axes: three semi-axis vectors} as a translucent shell and its sections.
class EllipsoidMark {
  constructor(colour, opacity) {
    this.object = new THREE.Group();
    this.object.matrixAutoUpdate = false;
    this.material = new THREE.MeshBasicMaterial({ color: colour, transparent: true, opacity, depthWrite: false });
    this.rings = unitRings(colour, 1.5);
    this.object.add(new THREE.Mesh(unitSphere, this.material), this.rings.object);
    for (const child of this.object.children) child.frustumCulled = false;
  }

  set(centre, axes, scale = 1) {
    const [a, b, c] = axes;
    // keep the basis right-handed (the ellipsoid is the same with -c): three flips the
    // front face of mirrored objects, and the screen-space line quads would then be culled
    const determinant = a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
    const sc = determinant < 0 ? -scale : scale;
    this.object.matrix.set(
      a[0] * scale, b[0] * scale, c[0] * sc, centre[0],
      a[1] * scale, b[1] * scale, c[1] * sc, centre[1],
      a[2] * scale, b[2] * scale, c[2] * sc, centre[2],
      0, 0, 0, 1);
    this.object.matrixWorldNeedsUpdate = true;
    this.object.visible = true;
  }

  dispose() { this.material.dispose(); this.rings.dispose(); }
}

function label(className) {
  const element = document.createElement('div');
  element.className = className;
  const object = new CSS2DObject(element);
  object.visible = false;
  return object;
}

function semiAxisLength(axis) { return Math.hypot(axis[0], axis[1], axis[2]); }

export class Overlays {
  constructor(reach, legend) {
    this.reach = reach;
    this.legend = legend;  // a DOM element for the ellipsoid's scale
    this.object = new THREE.Group();
    this.nearestLines = new SegmentBuffer(32, { colour: overlayColours.distance, width: 1.5 });
    this.nearestMin = new SegmentBuffer(1, { colour: overlayColours.nearest, width: 3 });
    this.nearestLabels = [];
    this.ellipsoid = new EllipsoidMark(overlayColours.ellipsoid, 0.07);
    this.ellipsoidScale = null;  // fixed at the run's first ellipsoid
    this.methodEllipses = [];
    this.methodPoints = null;
    this.methodSegments = new SegmentBuffer(64, { colour: overlayColours.method, width: 2 });
    this.ghosts = new SegmentBuffer(64, { colour: overlayColours.method, width: 2, opacity: 0.45 });
    this.trace = new SegmentBuffer(traceCapacity, { colour: overlayColours.trace, width: 2.5 });
    this.traceNext = 0;
    this.traceCount = 0;
    this.traceLast = null;
    this.object.add(this.nearestLines.object, this.nearestMin.object, this.ellipsoid.object,
      this.methodSegments.object, this.ghosts.object, this.trace.object);
    this.pointRadius = 0.008 * reach;
    this.ensurePoints(16);
  }

  // Restarts per-run state (the trace and the ellipsoid's scale) for a new run.
  newRun() {
    this.ellipsoidScale = null;
    this.resetTrace();
  }

  resetTrace() {
    this.traceNext = 0;
    this.traceCount = 0;
    this.traceLast = null;
    this.trace.commit(0);
  }

  // Called for every frame received (drawn or not): a ring buffer of segments.
  record(ee) {
    if (!ee) return;
    const last = this.traceLast;
    if (last && last[0] === ee[0] && last[1] === ee[1] && last[2] === ee[2]) return;
    if (last) {
      this.trace.set(this.traceNext, last[0], last[1], last[2], ee[0], ee[1], ee[2]);
      this.traceNext = (this.traceNext + 1) % traceCapacity;
      this.traceCount = Math.min(this.traceCount + 1, traceCapacity);
      this.traceDirty = true;
    }
    this.traceLast = ee.slice(0, 3);
  }

  // Growing a pool happens only when a method shows more than ever before.
  growSegments(name, needed) {
    const old = this[name];
    if (needed <= old.capacity) return old;
    const grown = new SegmentBuffer(Math.max(needed, 2 * old.capacity),
      { colour: old.material.color.getStyle(), width: old.material.linewidth, opacity: old.material.opacity });
    this.object.remove(old.object);
    old.dispose();
    this.object.add(grown.object);
    this[name] = grown;
    return grown;
  }

  ensurePoints(needed) {
    if (this.methodPoints && needed <= this.methodPoints.instanceMatrix.count) return;
    const capacity = Math.max(needed, 2 * (this.methodPoints ? this.methodPoints.instanceMatrix.count : 8));
    if (this.methodPoints) { this.object.remove(this.methodPoints); this.methodPoints.material.dispose(); this.methodPoints.dispose(); }
    this.methodPoints = new THREE.InstancedMesh(unitSphere, new THREE.MeshBasicMaterial({ color: overlayColours.method }), capacity);
    this.methodPoints.frustumCulled = false;
    this.methodPoints.count = 0;
    this.object.add(this.methodPoints);
  }

  // toggles: the page's overlays object; frame: the latest frame.
  update(frame, toggles) {
    this.updateNearest(toggles.nearest ? frame.nearest : null, frame.metrics);
    this.updateEllipsoid(toggles.manipulability ? frame.ellipsoid : null);
    const method = frame.overlays || {};
    this.updateMethod(toggles.method ? method : {});
    this.updateGhosts(toggles.ghosts ? method.ghost_links : null);
    this.trace.object.visible = !!toggles.trace;
    if (this.traceDirty) { this.trace.commit(this.traceCount); this.traceDirty = false; }
  }

  updateNearest(nearest, metrics) {
    const rows = nearest || [];
    this.growSegments('nearestLines', rows.length);
    const minLink = metrics ? metrics.min_distance_link : 0;
    while (this.nearestLabels.length < rows.length) {
      const l = label('view3d-label');
      this.nearestLabels.push(l);
      this.object.add(l);
    }
    // distances written only for the few nearest links: more would overlap
    const labelled = this.labelledRows(rows);
    let lines = 0, minDrawn = 0;
    rows.forEach(([link, , distance, ax, ay, az, bx, by, bz], i) => {
      const isMin = link === minLink;
      if (isMin) { this.nearestMin.set(0, ax, ay, az, bx, by, bz); minDrawn = 1; }
      else this.nearestLines.set(lines++, ax, ay, az, bx, by, bz);
      const l = this.nearestLabels[i];
      l.position.set(ax + 0.3 * (bx - ax), ay + 0.3 * (by - ay), az + 0.3 * (bz - az));  // near the link: lines to one obstacle point would stack their labels
      const text = Number.isFinite(distance) ? `${distance.toFixed(3)} m` : '—';
      if (l.element.textContent !== text) l.element.textContent = text;
      l.element.classList.toggle('view3d-label-nearest', isMin);
      l.visible = labelled.has(i);
    });
    for (let i = rows.length; i < this.nearestLabels.length; ++i) this.nearestLabels[i].visible = false;
    this.nearestLines.commit(lines);
    this.nearestMin.commit(minDrawn);
  }

  // After the labels are placed on screen: a distance label that would cover
  // one of a nearer link is hidden (nearest first), so none overlap.
  declutter(canvas) {
    const shown = [];
    const labels = this.nearestLabels.filter((l) => l.visible && l.element.style.display !== 'none');
    const distance = (l) => parseFloat(l.element.textContent);
    labels.sort((a, b) => distance(a) - distance(b));
    for (const l of labels) {
      l.element.classList.remove('view3d-label-hidden');
      const r = l.element.getBoundingClientRect();
      if (!r.width) continue;
      if (shown.some((o) => r.left < o.right + 2 && r.right > o.left - 2 && r.top < o.bottom + 1 && r.bottom > o.top - 1)) {
        l.element.classList.add('view3d-label-hidden');
      } else shown.push(r);
    }
  }

  // Indices of the three rows with the smallest distances.
  labelledRows(rows) {
    const order = this.labelOrder || (this.labelOrder = []);
    order.length = 0;
    for (let i = 0; i < rows.length; ++i) order.push(i);
    order.sort((a, b) => rows[a][2] - rows[b][2]);
    const chosen = this.labelChosen || (this.labelChosen = new Set());
    chosen.clear();
    for (let k = 0; k < Math.min(3, order.length); ++k) chosen.add(order[k]);
    return chosen;
  }

  // Scaled so that its largest semi-axis at the run's first frame is 15% of the reach.
  updateEllipsoid(ellipsoid) {
    if (!ellipsoid || !ellipsoid.axes) {
      this.ellipsoid.object.visible = false;
      if (this.legend) this.legend.hidden = true;
      return;
    }
    if (this.ellipsoidScale === null) {
      const largest = Math.max(...ellipsoid.axes.map(semiAxisLength));
      if (!(largest > 0)) { this.ellipsoid.object.visible = false; return; }
      this.ellipsoidScale = (0.15 * this.reach) / largest;
      if (this.legend) {
        this.legend.textContent = `Manipulability ellipsoid: 1 m/s drawn as ${this.ellipsoidScale.toPrecision(2)} m`;
        this.legend.title = 'Velocity manipulability at the end-effector, one scale for the whole run: '
          + 'its largest semi-axis at the start is drawn as 15% of the reach, so growth and shrinkage show.';
      }
    }
    this.ellipsoid.set(ellipsoid.centre, ellipsoid.axes, this.ellipsoidScale);
    if (this.legend) this.legend.hidden = false;
  }

  updateMethod({ ellipses = [], points = [], segments = [] }) {
    while (this.methodEllipses.length < ellipses.length) {
      const mark = new EllipsoidMark(overlayColours.method, 0.08);
      this.methodEllipses.push(mark);
      this.object.add(mark.object);
    }
    ellipses.forEach((e, i) => this.methodEllipses[i].set(e.centre, e.axes));
    for (let i = ellipses.length; i < this.methodEllipses.length; ++i) this.methodEllipses[i].object.visible = false;

    this.ensurePoints(points.length);
    points.forEach((p, i) => {
      pointMatrix.makeScale(this.pointRadius, this.pointRadius, this.pointRadius).setPosition(p[0], p[1], p[2]);
      this.methodPoints.setMatrixAt(i, pointMatrix);
    });
    this.methodPoints.count = points.length;
    this.methodPoints.instanceMatrix.needsUpdate = true;

    const lines = this.growSegments('methodSegments', segments.length);
    lines.clear();
    for (const [a, b] of segments) lines.push(a, b);
    lines.commit();
  }

  // ghost_links: [[[sx,sy,sz,ex,ey,ez], ..], ..] one arm per ghost, as thin translucent lines.
  updateGhosts(ghostLinks) {
    const arms = ghostLinks || [];
    const lines = this.growSegments('ghosts', arms.reduce((n, links) => n + links.length, 0));
    lines.clear();
    for (const links of arms) for (const s of links) lines.set(lines.count++, s[0], s[1], s[2], s[3], s[4], s[5]);
    lines.commit();
  }

  dispose() {
    for (const b of [this.nearestLines, this.nearestMin, this.methodSegments, this.ghosts, this.trace]) b.dispose();
    this.ellipsoid.dispose();
    for (const e of this.methodEllipses) e.dispose();
    this.methodPoints.dispose();
    for (const l of this.nearestLabels) l.element.remove();
    this.object.removeFromParent();
  }
}
