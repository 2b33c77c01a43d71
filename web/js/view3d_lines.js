// Thick line segments (pixel widths, legible on a projector) with a fixed
// capacity: positions are rewritten in place each frame, nothing is allocated.
import { LineSegments2 } from 'three/addons/lines/LineSegments2.js';
import { LineSegmentsGeometry } from 'three/addons/lines/LineSegmentsGeometry.js';
import { LineMaterial } from 'three/addons/lines/LineMaterial.js';

export class SegmentBuffer {
  constructor(capacity, { colour, width = 2, opacity = 1, dashed = false, dashSize = 0.1 }) {
    this.capacity = capacity;
    this.positions = new Float32Array(capacity * 6);
    this.geometry = new LineSegmentsGeometry();
    this.geometry.setPositions(this.positions);
    this.material = new LineMaterial({
      color: colour, linewidth: width, transparent: opacity < 1, opacity,
      dashed, dashSize, gapSize: dashSize * 0.6,
    });
    this.object = new LineSegments2(this.geometry, this.material);
    this.object.frustumCulled = false;  // bounds change every frame; the lines are few
    this.count = 0;
    this.geometry.instanceCount = 0;
  }

  clear() { this.count = 0; }

  // Writes segment `slot` (0 <= slot < capacity) from a to b.
  set(slot, ax, ay, az, bx, by, bz) {
    const p = this.positions, k = slot * 6;
    p[k] = ax; p[k + 1] = ay; p[k + 2] = az; p[k + 3] = bx; p[k + 4] = by; p[k + 5] = bz;
  }

  push(a, b) {
    if (this.count >= this.capacity) return;
    this.set(this.count++, a[0], a[1], a[2], b[0], b[1], b[2]);
  }

  // Uploads the first `count` segments.
  commit(count = this.count) {
    this.count = count;
    this.geometry.instanceCount = count;
    this.geometry.attributes.instanceStart.data.needsUpdate = true;
    if (this.material.dashed) this.object.computeLineDistances();
  }

  dispose() {
    this.geometry.dispose();
    this.material.dispose();
  }
}

// A polyline through fixed points (the task path), drawn once per snapshot.
export function polylineSegments(points, style) {
  const lines = new SegmentBuffer(Math.max(1, points.length - 1), style);
  for (let i = 1; i < points.length; ++i) lines.push(points[i - 1], points[i]);
  lines.commit();
  return lines;
}
