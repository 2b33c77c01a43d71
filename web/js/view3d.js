// The 3D view (three.js, z up) for spatial models: the arm, obstacles, task
// path and target, overlays, compare lanes, obstacle picking and dragging.
// It owns its renderer, its scene and its camera (view3d_camera.js: orbit,
// gizmo, framing); the page feeds it snapshots and frames and calls render()
// from its animation loop (it draws only when something changed).
import * as THREE from 'three';
import { CSS2DRenderer, CSS2DObject } from 'three/addons/renderers/CSS2DRenderer.js';
import { CameraRig, DEFAULT_DIRECTION } from './view3d_camera.js';
import { Arm, GroundShadow, visualRadius, armColours } from './view3d_arm.js';
import { Obstacles, obstaclePosition } from './view3d_obstacles.js';
import { Overlays } from './view3d_overlays.js';
import { PointerTool } from './view3d_drag.js';
import { polylineSegments } from './view3d_lines.js';

const defaultColour = '#37474f';
const pathColour = '#43a047', targetColour = '#2e7d32';
const laneOpacity = 0.4;
const dragHoldMs = 1500;  // after a drag, keep the dragged position until the server's frames show it

// Probed once per page; the probe's context is released at once (browsers
// keep only a few contexts alive, and every view already needs its own).
let webgl2Probe = null;
function webgl2Available() {
  if (webgl2Probe === null) {
    try {
      const gl = document.createElement('canvas').getContext('webgl2');
      webgl2Probe = !!gl;
      if (gl) { const lose = gl.getExtension('WEBGL_lose_context'); if (lose) lose.loseContext(); }
    } catch { webgl2Probe = false; }
  }
  return webgl2Probe;
}

// A round grid step for about 12 lines over a span: 1, 2 or 5 times a power of ten.
function gridStep(span) {
  const raw = Math.max(span, 1e-3) / 12, power = 10 ** Math.floor(Math.log10(raw));
  return [1, 2, 5, 10].map((m) => m * power).find((s) => s >= raw);
}

// Red, green, blue axes of a frame (x, y, z) as thin cylinders of `length`.
function frameAxes(length) {
  const group = new THREE.Group(), radius = length * 0.035;
  const geometry = new THREE.CylinderGeometry(radius, radius, length, 8);
  geometry.translate(0, length / 2, 0);
  [['#e53935', [0, 0, -Math.PI / 2]], ['#43a047', [0, 0, 0]], ['#1e88e5', [Math.PI / 2, 0, 0]]].forEach(([colour, r]) => {
    const axis = new THREE.Mesh(geometry, new THREE.MeshBasicMaterial({ color: colour }));
    axis.rotation.set(...r);
    group.add(axis);
  });
  group.visible = false;
  return group;
}

function textLabel(text, className) {
  const element = document.createElement('div');
  element.className = className;
  element.textContent = text;
  return new CSS2DObject(element);
}

function modelKey(model) {
  return JSON.stringify([model.kind, model.dof, model.base, model.reach, model.links]);
}

function disposeTree(object) {
  object.traverse((o) => {
    if (o.isCSS2DObject) o.element.remove();
    if (o.geometry) o.geometry.dispose();
    if (o.material) [].concat(o.material).forEach((m) => m.dispose());
  });
  object.removeFromParent();
}

export class View3D {
  constructor(container) {
    this.container = container;
    this.onPlace = null;
    this.onObstacleDrag = null;
    this.onSelect = null;
    this.snapshot = null;
    this.frame = null;
    this.stats = { renders: 0, totalMs: 0, lastMs: 0, maxMs: 0 };  // time inside render() when it draws
    this._colour = defaultColour;
    this._overlays = { nearest: false, manipulability: false, method: true, ghosts: true, trace: false };
    this._placing = null;
    this._selected = null;
    this.overlayKey = '';
    this.lanes = [];
    this.laneArms = [];
    this.override = null;  // {index, position, releasedAt}: the dragged obstacle's position
    this.dirty = true;
    container.classList.add('view3d');
    if (!webgl2Available()) {
      this.failed = true;
      const message = document.createElement('p');
      message.className = 'view3d-message';
      message.textContent = 'The 3D view needs WebGL 2, which this browser does not provide (check that hardware acceleration is on).';
      container.appendChild(message);
      return;
    }
    this.createRenderer();
    this.createScene();
    this.pointer = new PointerTool(this, this.renderer.domElement);  // before OrbitControls: see view3d_drag.js
    this.rig.attach(this.container, { fit: () => this.fit(), fitFromHere: () => this.fitFromHere() });
    this.controls = this.rig.controls;
    this.resizeObserver = new ResizeObserver(() => this.resize());
    this.resizeObserver.observe(container);
    this.resize();
  }

  createRenderer() {
    this.renderer = new THREE.WebGLRenderer({ antialias: true });
    this.renderer.setPixelRatio(Math.min(window.devicePixelRatio || 1, 2));
    this.renderer.setClearColor('#ffffff');
    this.renderer.autoClear = false;  // the axes gizmo draws over the scene
    this.container.appendChild(this.renderer.domElement);
    this.labels = new CSS2DRenderer();
    this.labels.domElement.className = 'view3d-labels';
    this.container.appendChild(this.labels.domElement);
    this.legend = document.createElement('div');
    this.legend.className = 'view3d-legend';
    this.legend.hidden = true;
    this.container.appendChild(this.legend);
  }

  createScene() {
    this.scene = new THREE.Scene();
    this.rig = new CameraRig(this.renderer.domElement, () => { this.dirty = true; });
    this.camera = this.rig.camera;
    this.axesGizmo = this.rig.gizmo;
    this.scene.add(new THREE.HemisphereLight('#ffffff', '#b0bec5', 2.2));
    this.sun = new THREE.DirectionalLight('#ffffff', 1.6);
    this.sun.position.set(0.4, -0.6, 1);
    this.scene.add(this.sun);
    this.sceneRoot = new THREE.Group();  // everything built from a snapshot
    this.scene.add(this.sceneRoot);
    // the target is drawn over everything (the ellipsoid, the frame axes and the trace sit around it)
    this.target = new THREE.Mesh(new THREE.SphereGeometry(1, 20, 14), new THREE.MeshBasicMaterial({ color: targetColour, depthTest: false }));
    this.target.renderOrder = 10;
    this.target.visible = false;
    this.scene.add(this.target);
    this.buildGround(new THREE.Box3(new THREE.Vector3(-2, -2, 0), new THREE.Vector3(2, 2, 1)), 3, [0, 0, 0]);
  }

  // Grid on z = 0 under the framed region (box), the world axes at the origin.
  buildGround(box, reach, base) {
    if (this.ground) disposeTree(this.ground);
    const size = Math.max(box.max.x - box.min.x, box.max.y - box.min.y, 1e-3);
    const step = gridStep(size);
    // a square of whole steps centred on a grid line, so that lines fall on round coordinates
    const x0 = Math.min(box.min.x, base[0], 0), x1 = Math.max(box.max.x, base[0], 0);
    const y0 = Math.min(box.min.y, base[1], 0), y1 = Math.max(box.max.y, base[1], 0);
    const half = (Math.ceil(Math.max(x1 - x0, y1 - y0) / 2 / step) + 1) * step;
    const grid = new THREE.GridHelper(2 * half, Math.round((2 * half) / step), '#e3e7ea', '#e3e7ea');
    grid.rotation.x = Math.PI / 2;  // GridHelper lies in x-z; ours in x-y
    grid.position.set(Math.round((x0 + x1) / 2 / step) * step, Math.round((y0 + y1) / 2 / step) * step, 0);
    this.ground = new THREE.Group();
    this.ground.add(grid);
    this.gridStep = step;
    this.scene.add(this.ground);
  }

  // A post from the ground to a raised base, and a plate under it.
  buildBase(model) {
    const [x, y, z] = model.base;
    const radius = 1.15 * Math.max(...model.links.map((l) => visualRadius(l.radius, model.reach)), 0.005 * model.reach);
    const material = new THREE.MeshLambertMaterial({ color: armColours.base });
    const group = new THREE.Group();
    const plate = new THREE.Mesh(new THREE.CylinderGeometry(1.7 * radius, 1.7 * radius, 0.4 * radius, 32), material);
    plate.rotation.x = Math.PI / 2;
    plate.position.set(x, y, Math.min(z, 0) + 0.2 * radius);
    group.add(plate);
    if (z > 0) {
      const post = new THREE.Mesh(new THREE.CylinderGeometry(radius, radius, z, 24), material);
      post.rotation.x = Math.PI / 2;
      post.position.set(x, y, z / 2);
      group.add(post);
    }
    return group;
  }

  // Fit: the scene framed from where the camera looks now.
  fitFromHere() {
    if (this.failed || !this.snapshot) return;
    this.fit(this.rig.lookingFrom() || DEFAULT_DIRECTION);
  }

  // ---- the page's interface ----

  get colour() { return this._colour; }
  set colour(value) {
    this._colour = value || defaultColour;
    if (this.arm) this.arm.setColour(this._colour);
    this.dirty = true;
  }

  get overlays() { return this._overlays; }
  set overlays(value) { this._overlays = value || {}; this.dirty = true; }

  get placing() { return this._placing; }
  set placing(shape) {
    this._placing = shape || null;
    if (this.renderer) this.renderer.domElement.style.cursor = this._placing ? 'crosshair' : '';
  }

  get selected() { return this._selected; }
  set selected(index) {
    this._selected = index === undefined ? null : index;
    if (this.obstacles) this.obstacles.setSelected(this._selected);
    this.dirty = true;
  }

  // A user's selection: the page hears of it.
  select(index) {
    if (index === this._selected) return;
    this.selected = index;
    if (this.onSelect) this.onSelect(index);
  }

  setSnapshot(snapshot) {
    if (this.failed || !snapshot) return;
    const previous = this.snapshot;
    this.snapshot = snapshot;
    const model = snapshot.model;
    const newModel = !previous || modelKey(previous.model) !== modelKey(model);
    if (newModel) {
      if (this.arm) this.arm.dispose();
      if (this.shadow) this.shadow.dispose();
      if (this.base) disposeTree(this.base);
      if (this.overlayLayer) this.overlayLayer.dispose();
      this.arm = new Arm(model, { colour: this._colour });
      this.shadow = new GroundShadow(model.links.length, 0.002 * model.reach);
      this.sceneRoot.add(this.shadow.object);
      this.base = this.buildBase(model);
      this.overlayLayer = new Overlays(model.reach, this.legend);
      this.sceneRoot.add(this.arm.object, this.base, this.overlayLayer.object);
      this.target.scale.setScalar(0.015 * model.reach);
      if (this.eeAxes) disposeTree(this.eeAxes);
      if (this.targetAxes) disposeTree(this.targetAxes);
      this.eeAxes = frameAxes(0.14 * model.reach);
      this.targetAxes = frameAxes(0.1 * model.reach);
      this.sceneRoot.add(this.eeAxes, this.targetAxes);
    }
    if (!this.obstacles || !this.obstacles.sameShapes(snapshot.obstacles) || newModel) {
      const keepId = previous && this._selected !== null && previous.obstacles[this._selected] ? previous.obstacles[this._selected].id : null;
      if (this.obstacles) this.obstacles.dispose();
      this.obstacles = new Obstacles(snapshot.obstacles, model.reach, model.base);
      this.sceneRoot.add(this.obstacles.object);
      const index = keepId === null ? -1 : snapshot.obstacles.findIndex((o) => o.id === keepId);
      this._selected = null;
      this.selected = index >= 0 ? index : null;
      // a drag in progress follows its obstacle by id; it ends if that one is gone
      const remap = (i) => {
        const id = previous && previous.obstacles[i] ? previous.obstacles[i].id : null;
        const now = id === null ? -1 : snapshot.obstacles.findIndex((o) => o.id === id);
        return now >= 0 ? now : null;
      };
      if (this.override) { const i = remap(this.override.index); if (i === null) this.override = null; else this.override.index = i; }
      if (this.pointer && this.pointer.down && this.pointer.down.index !== null) this.pointer.down.index = remap(this.pointer.down.index);
    }
    const pathKey = JSON.stringify(snapshot.task.path);
    if (pathKey !== this.pathKey) {
      if (this.path) { this.path.dispose(); this.sceneRoot.remove(this.path.object); }
      this.path = snapshot.task.path.length > 1
        ? polylineSegments(snapshot.task.path, { colour: pathColour, width: 2.5, dashed: true, dashSize: 0.02 * model.reach })
        : null;
      if (this.path) this.sceneRoot.add(this.path.object);
      this.pathKey = pathKey;
    }
    if (!previous || previous.run !== snapshot.run) this.overlayLayer.newRun();
    if (snapshot.frame) this.frame = snapshot.frame;
    if (!previous || newModel || previous.scenario !== snapshot.scenario) this.fit();
    this.dirty = true;
  }

  setFrame(frame) {
    if (this.failed || !frame) return;
    if (this.frame && frame.t < this.frame.t) this.resetTrace();  // a reset or a seek back
    this.frame = frame;
    if (this.overlayLayer) this.overlayLayer.record(frame.ee);
    this.dirty = true;
  }

  // Compare lanes: other runs' arms in their colour, translucent, with their label at the tip.
  setLanes(lanes) {
    if (this.failed) return;
    this.lanes = lanes || [];
    this.lanes.forEach((lane, i) => {
      let entry = this.laneArms[i];
      const key = lane.snapshot ? modelKey(lane.snapshot.model) : '';
      if (!entry || entry.key !== key) {
        if (entry) { entry.arm.dispose(); entry.label.removeFromParent(); }
        if (!lane.snapshot) { this.laneArms[i] = null; return; }
        entry = { key, arm: new Arm(lane.snapshot.model, { colour: lane.colour, opacity: laneOpacity, highlight: false }),
          label: textLabel('', 'view3d-lane-label') };
        this.scene.add(entry.arm.object, entry.label);
        this.laneArms[i] = entry;
      }
      entry.arm.setColour(lane.colour);
      entry.label.element.textContent = lane.label || '';
      entry.label.element.style.color = lane.colour;
    });
    for (let i = this.lanes.length; i < this.laneArms.length; ++i) {
      if (this.laneArms[i]) { this.laneArms[i].arm.dispose(); this.laneArms[i].label.removeFromParent(); }
    }
    this.laneArms.length = this.lanes.length;
    this.dirty = true;
  }

  resetTrace() {
    if (this.overlayLayer) this.overlayLayer.resetTrace();
    this.dirty = true;
  }

  // A replay's seek: the trace as it stood at the frame shown, from the stored ends.
  rebuildTrace(points) {
    this.resetTrace();
    if (this.overlayLayer) for (const p of points) this.overlayLayer.record(p);
  }

  // Frames the camera on the scene: the base, the arm as it stands, every
  // obstacle and the path (before any frame: the reach around the base); the
  // ground grid follows the same region.
  fit(direction = DEFAULT_DIRECTION) {
    if (this.failed || !this.snapshot) return;
    const box = this.sceneBox();
    const { base, reach } = this.snapshot.model;
    this.buildGround(box, reach, base);
    this.rig.frame(box, direction);
    this.dirty = true;
  }

  sceneBox() {
    const { base, reach } = this.snapshot.model;
    const box = new THREE.Box3().expandByPoint(new THREE.Vector3(...base)).expandByPoint(new THREE.Vector3(base[0], base[1], 0));
    const links = this.frame && this.frame.links;
    if (links && links.length) {
      for (const l of links) box.expandByPoint(new THREE.Vector3(l[0], l[1], l[2])).expandByPoint(new THREE.Vector3(l[3], l[4], l[5]));
    } else {
      box.expandByScalar(reach);
    }
    if (this.obstacles) this.obstacles.expandBox(box);
    for (const p of this.snapshot.task.path) box.expandByPoint(new THREE.Vector3(p[0], p[1], p[2] || 0));
    box.expandByScalar(0.03 * Math.max(box.getSize(new THREE.Vector3()).length(), 1e-3));
    return box;
  }

  // Draws when something changed (a frame, the page's settings, the camera).
  render() {
    if (this.failed) return false;
    const moved = this.rig.update();
    const key = Object.entries(this._overlays).map(([k, v]) => (v ? k : '')).join();
    if (key !== this.overlayKey) { this.overlayKey = key; this.dirty = true; }
    if (!this.dirty && !moved) return false;
    const started = performance.now();
    this.dirty = false;
    this.applyFrame();
    this.renderer.clear();
    this.renderer.render(this.scene, this.camera);
    this.axesGizmo.render(this.renderer);
    this.labels.render(this.scene, this.camera);
    if (this.overlayLayer) this.overlayLayer.declutter(this.renderer.domElement);
    const ms = performance.now() - started;
    this.stats.renders += 1;
    this.stats.totalMs += ms;
    this.stats.lastMs = ms;
    this.stats.maxMs = Math.max(this.stats.maxMs, ms);
    return true;
  }

  // The view drawn afresh at width × height pixels into a 2D canvas (an
  // export), from the same camera; labels drawn as HTML (distances, lane
  // names) are not in the picture.
  renderAt(width, height) {
    const out = document.createElement('canvas');
    out.width = width;
    out.height = height;
    if (this.failed) return out;
    const size = this.renderer.getSize(new THREE.Vector2());
    const ratio = this.renderer.getPixelRatio();
    const aspect = this.camera.aspect;
    try {
      this.renderer.setPixelRatio(1);
      this.renderer.setSize(width, height, false);
      this.rig.setAspect(width / height);
      this.applyFrame();
      this.renderer.clear();
      this.renderer.render(this.scene, this.camera);
      out.getContext('2d').drawImage(this.renderer.domElement, 0, 0);  // before the buffer is cleared
    } finally {
      this.renderer.setPixelRatio(ratio);
      this.renderer.setSize(size.x, size.y, false);
      this.rig.setAspect(aspect);
      this.dirty = true;
    }
    return out;
  }

  applyFrame() {
    const frame = this.frame, snapshot = this.snapshot;
    if (!frame || !snapshot) return;
    this.arm.update(frame);
    this.shadow.update(frame);
    this.releaseOverride(frame);
    this.obstacles.update(frame.obstacles || [], this.override);
    if (frame.target) {
      this.target.position.set(frame.target[0], frame.target[1], frame.target[2] || 0);
      this.target.visible = true;
    }
    const pose = snapshot.task.space === 'pose';
    this.placeAxes(this.eeAxes, pose ? frame.ee : null, frame.ee_quat);
    this.placeAxes(this.targetAxes, pose ? frame.target : null, frame.target_quat);
    this.overlayLayer.update(frame, this._overlays);
    this.lanes.forEach((lane, i) => {
      const entry = this.laneArms[i];
      const visible = !!(entry && lane.frame);
      if (entry) entry.arm.object.visible = entry.label.visible = visible;
      if (!visible) return;
      entry.arm.update(lane.frame);
      entry.label.position.fromArray(Arm.tip(lane.frame));
    });
  }

  placeAxes(axes, position, quat) {
    axes.visible = !!(position && quat);
    if (!axes.visible) return;
    axes.position.set(position[0], position[1], position[2]);
    axes.quaternion.set(quat[1], quat[2], quat[3], quat[0]);  // [w, x, y, z] → three's (x, y, z, w)
  }

  // ---- dragging (called by the pointer tool) ----

  obstaclePositionNow(index) {
    if (this.override && this.override.index === index) return this.override.position.slice();
    if (this.frame && this.frame.obstacles && this.frame.obstacles[index]) return this.frame.obstacles[index].slice();
    return obstaclePosition(this.snapshot.obstacles[index]);
  }

  // Lets go of an obstacle being dragged (the run ended): drawn where the frames put it.
  endDrag() {
    this.override = null;
    if (this.pointer) this.pointer.cancel();
    this.dirty = true;
  }

  dragTo(index, position, phase) {
    if (!this.onObstacleDrag) return;  // an ended run: nothing moves
    this.override = { index, position, releasedAt: phase === 'end' ? performance.now() : null };
    this.dirty = true;
    if (this.onObstacleDrag) this.onObstacleDrag(index, position, phase);
  }

  // The dragged position stands until the server's frames show it (or a while has passed).
  releaseOverride(frame) {
    const o = this.override;
    if (!o || o.releasedAt === null) return;
    const now = frame.obstacles && frame.obstacles[o.index];
    const tolerance = 1e-4 * Math.max(1, this.snapshot.model.reach);
    const arrived = now && Math.hypot(now[0] - o.position[0], now[1] - o.position[1], (now[2] || 0) - o.position[2]) < tolerance;
    if (arrived || performance.now() - o.releasedAt > dragHoldMs) this.override = null;
  }

  // Index of the obstacle under a page point, or null.
  obstacleAt(clientX, clientY) {
    const picked = this.failed ? null : this.pointer.pick({ clientX, clientY });
    return picked ? picked.index : null;
  }

  // Page (client) coordinates of a world point: browser tests drag with them.
  worldToClient(p) { return this.rig.toClient(p); }

  resize() {
    const width = this.container.clientWidth, height = this.container.clientHeight;
    if (!width || !height) return;
    this.renderer.setSize(width, height, false);
    this.labels.setSize(width, height);
    this.rig.setAspect(width / height);
    this.dirty = true;
  }

  invalidate() { this.dirty = true; }

  destroy() {
    if (this.failed) { this.container.replaceChildren(); return; }
    this.resizeObserver.disconnect();
    this.pointer.dispose();
    this.rig.dispose();
    this.setLanes([]);
    for (const part of [this.arm, this.shadow, this.obstacles, this.overlayLayer, this.path]) if (part) part.dispose();
    disposeTree(this.scene);
    this.renderer.dispose();
    this.renderer.forceContextLoss();
    this.renderer.domElement.remove();
    this.labels.domElement.remove();
    this.legend.remove();
    this.container.classList.remove('view3d');
  }
}
