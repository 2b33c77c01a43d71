// One arm in the 3D view: links as capsules of their radius, joints as small
// spheres. Meshes are built once per model; update() only moves them.
import * as THREE from 'three';
import { NEAREST_LINK_COLOUR, COLLIDED_COLOUR } from './state.js';
import { SegmentBuffer } from './view3d_lines.js';
import { linkMarks } from './link_marks.js';

const unitCylinder = new THREE.CylinderGeometry(1, 1, 1, 20, 1, true);  // along y, centred
const unitSphere = new THREE.SphereGeometry(1, 20, 14);
const yAxis = new THREE.Vector3(0, 1, 0);
const start = new THREE.Vector3(), end = new THREE.Vector3(), direction = new THREE.Vector3();

export const armColours = { nearest: NEAREST_LINK_COLOUR, collided: COLLIDED_COLOUR, joint: '#eceff1', base: '#90a4ae' };

// Visible radius of a link: its own (what collisions use), but never thinner
// than a line you can see; a bare segment (radius 0) gets 1% of the reach.
export function visualRadius(radius, reach) {
  return radius > 0 ? Math.max(radius, 0.004 * reach) : 0.01 * reach;
}

function material(colour, opacity) {
  return new THREE.MeshLambertMaterial({
    color: colour, transparent: opacity < 1, opacity, depthWrite: opacity >= 1,
  });
}

export class Arm {
  // model: snapshot.model; opacity < 1 for compare lanes (drawn over the main arm).
  constructor(model, { colour = '#37474f', opacity = 1, highlight = true } = {}) {
    this.highlight = highlight;
    this.radii = model.links.map((l) => visualRadius(l.radius, model.reach));
    this.materials = {
      link: material(colour, opacity),
      nearest: material(armColours.nearest, opacity),
      collided: material(armColours.collided, opacity),
      joint: material(opacity < 1 ? colour : armColours.joint, opacity),
      tip: material(colour, opacity),
    };
    this.object = new THREE.Group();
    this.links = [];   // cylinder per link
    this.caps = [];    // sphere at each link's end (rounds the capsule)
    this.joints = [];  // sphere at each link's start
    for (let i = 0; i < this.radii.length; ++i) {
      const link = new THREE.Mesh(unitCylinder, this.materials.link);
      const cap = new THREE.Mesh(unitSphere, this.materials.link);
      const joint = new THREE.Mesh(unitSphere, this.materials.joint);
      cap.scale.setScalar(this.radii[i]);
      joint.scale.setScalar(Math.min(1.35 * this.radii[i], this.radii[i] + 0.008 * model.reach));  // thick links: a slim collar
      for (const m of [link, cap, joint]) { m.matrixAutoUpdate = false; m.visible = false; this.object.add(m); }
      this.links.push(link); this.caps.push(cap); this.joints.push(joint);
    }
    this.marks = [];  // the links' marks as drawn (link_marks.js)
    this.lastHighlight = '';
  }

  setColour(colour) {
    this.materials.link.color.set(colour);
    this.materials.tip.color.set(colour);
  }

  // frame.links: [[sx,sy,sz,ex,ey,ez], ..]; the nearest link in yellow, red on
  // collision, both links of a self-colliding pair red.
  update(frame) {
    const segments = frame.links;
    const count = Math.min(segments.length, this.links.length);
    for (let i = 0; i < count; ++i) {
      const s = segments[i];
      start.set(s[0], s[1], s[2]);
      end.set(s[3], s[4], s[5]);
      direction.subVectors(end, start);
      const length = direction.length();
      const link = this.links[i], cap = this.caps[i], joint = this.joints[i];
      link.visible = length > 1e-9;
      if (link.visible) {
        link.position.addVectors(start, end).multiplyScalar(0.5);
        link.quaternion.setFromUnitVectors(yAxis, direction.divideScalar(length));
        link.scale.set(this.radii[i], length, this.radii[i]);
        link.updateMatrix();
      }
      cap.position.copy(end);
      cap.updateMatrix();
      joint.position.copy(start);
      joint.updateMatrix();
      cap.visible = joint.visible = true;
    }
    for (let i = count; i < this.links.length; ++i) this.links[i].visible = this.caps[i].visible = this.joints[i].visible = false;
    if (this.highlight) this.highlightLink(frame.metrics);
  }

  highlightLink(metrics) {
    const marks = linkMarks(metrics, this.links.length);
    const key = marks.join();
    if (key === this.lastHighlight) return;  // materials change only when a mark does
    this.lastHighlight = key;
    this.marks = marks;
    this.links.forEach((link, i) => {
      const m = this.materials[marks[i] || 'link'];
      link.material = m;
      this.caps[i].material = m;
    });
  }

  // World position of the arm's tip (last link's end) from a frame.
  static tip(frame) {
    const last = frame.links[frame.links.length - 1];
    return last ? [last[3], last[4], last[5]] : frame.ee;
  }

  dispose() {
    for (const m of Object.values(this.materials)) m.dispose();
    this.object.removeFromParent();
  }
}

// The arm's shadow on the ground (z = 0) and a drop line under the target:
// depth cues that a perspective view lacks.
export class GroundShadow {
  // lift: a hair above the grid, so that the two never flicker
  constructor(linkCount, lift) {
    this.lift = lift;
    this.links = new SegmentBuffer(linkCount, { colour: '#b0bec5', width: 4, opacity: 0.55 });
    this.drop = new SegmentBuffer(1, { colour: '#a5d6a7', width: 1.5 });
    this.object = new THREE.Group();
    this.object.add(this.links.object, this.drop.object);
  }

  update(frame) {
    this.links.clear();
    const z = this.lift;
    for (const s of frame.links) this.links.set(this.links.count++, s[0], s[1], z, s[3], s[4], z);
    this.links.commit();
    const t = frame.target;
    if (t && t[2] > 0) this.drop.set(0, t[0], t[1], t[2], t[0], t[1], 0);
    this.drop.commit(t && t[2] > 0 ? 1 : 0);
  }

  dispose() {
    this.links.dispose();
    this.drop.dispose();
    this.object.removeFromParent();
  }
}
