// Mouse on the 3D view: a click selects an obstacle (or, while placing, puts a
// new one on the horizontal plane through the target); dragging an obstacle
// moves it on the plane through the grabbed point facing the camera. Orbit
// controls are off during a drag. Listeners are added before OrbitControls'
// so that a press on an obstacle never starts an orbit.
import * as THREE from 'three';

const clickSlop = 5;  // px: a press that moves less than this is a click

export class PointerTool {
  // view: the View3D (camera, controls, obstacles, callbacks, placing, selected).
  constructor(view, element) {
    this.view = view;
    this.element = element;
    this.raycaster = new THREE.Raycaster();
    this.ndc = new THREE.Vector2();
    this.plane = new THREE.Plane();
    this.hit = new THREE.Vector3();
    this.down = null;   // {x, y, index, offset, moved}
    this.handlers = {
      pointerdown: (e) => this.onDown(e),
      pointermove: (e) => this.onMove(e),
      pointerup: (e) => this.onUp(e),
      pointercancel: (e) => this.onUp(e),
    };
    for (const [name, handler] of Object.entries(this.handlers)) element.addEventListener(name, handler);
  }

  ray(event) {
    const rect = this.element.getBoundingClientRect();
    this.ndc.set(((event.clientX - rect.left) / rect.width) * 2 - 1, -((event.clientY - rect.top) / rect.height) * 2 + 1);
    this.raycaster.setFromCamera(this.ndc, this.view.camera);
    return this.raycaster.ray;
  }

  // Index of the obstacle under the pointer and the point hit, or null.
  pick(event) {
    const obstacles = this.view.obstacles;
    if (!obstacles) return null;
    this.ray(event);
    const hits = this.raycaster.intersectObjects(obstacles.pickables, false);
    return hits.length ? { index: hits[0].object.userData.obstacleIndex, point: hits[0].point } : null;
  }

  onDown(event) {
    if (event.button !== 0) return;
    const view = this.view;
    this.down = { x: event.clientX, y: event.clientY, index: null, moved: false };
    if (view.placing) return;  // a click will place; the orbit may still turn the view
    const picked = this.pick(event);
    if (!picked) return;
    view.select(picked.index);
    if (!view.onObstacleDrag) return;  // replays and ended runs: select only
    // grab: the plane facing the camera through the grabbed point
    const normal = view.camera.getWorldDirection(new THREE.Vector3());
    this.plane.setFromNormalAndCoplanarPoint(normal, picked.point);
    const position = view.obstaclePositionNow(picked.index);
    this.down.index = picked.index;
    this.down.offset = new THREE.Vector3(...position).sub(picked.point);
    view.controls.enabled = false;
    this.element.setPointerCapture(event.pointerId);
    event.preventDefault();
  }

  // Drops a grab in progress (the run ended): the orbit works again.
  cancel() {
    if (this.down && this.down.index !== null) this.view.controls.enabled = true;
    this.down = null;
  }

  onMove(event) {
    const down = this.down;
    if (!down) return this.hover(event);
    if (down.index === null) return;
    if (!down.moved && Math.hypot(event.clientX - down.x, event.clientY - down.y) < clickSlop) return;
    down.moved = true;
    if (!this.ray(event).intersectPlane(this.plane, this.hit)) return;
    const p = this.hit.add(down.offset);
    this.view.dragTo(down.index, [p.x, p.y, p.z], 'move');
  }

  // A hand over an obstacle says it can be grabbed.
  hover(event) {
    if (event.buttons || this.view.placing) return;
    const over = this.pick(event) !== null;
    if (over !== this.over) {
      this.over = over;
      this.element.style.cursor = over ? 'grab' : '';
    }
  }

  onUp(event) {
    const down = this.down;
    this.down = null;
    if (!down) return;
    const view = this.view;
    if (down.index !== null) {
      view.controls.enabled = true;
      if (this.element.hasPointerCapture(event.pointerId)) this.element.releasePointerCapture(event.pointerId);
      if (down.moved) view.dragTo(down.index, view.obstaclePositionNow(down.index), 'end');
      return;
    }
    if (event.type === 'pointercancel' || Math.hypot(event.clientX - down.x, event.clientY - down.y) >= clickSlop) return;
    if (view.placing) {
      const point = this.placePoint(event);
      if (point && view.onPlace) view.onPlace(point);
    } else if (view.selected !== null) {
      view.select(null);
    }
  }

  // Where a click places a new obstacle: the horizontal plane through the
  // target (z = 0 before any frame); seen edge-on, the plane facing the camera.
  placePoint(event) {
    const ray = this.ray(event);
    const target = this.view.frame ? this.view.frame.target : [0, 0, 0];
    const anchor = new THREE.Vector3(target[0], target[1], target[2] || 0);
    this.plane.setFromNormalAndCoplanarPoint(new THREE.Vector3(0, 0, 1), anchor);
    if (Math.abs(ray.direction.z) < 0.05 || !ray.intersectPlane(this.plane, this.hit)) {
      this.plane.setFromNormalAndCoplanarPoint(this.view.camera.getWorldDirection(new THREE.Vector3()), anchor);
      if (!ray.intersectPlane(this.plane, this.hit)) return null;
    }
    return [this.hit.x, this.hit.y, this.hit.z];
  }

  dispose() {
    for (const [name, handler] of Object.entries(this.handlers)) this.element.removeEventListener(name, handler);
  }
}
