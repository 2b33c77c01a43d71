// The 3D view's camera and how the user turns it: a perspective camera (z
// up), orbit controls with damping, the axes gizmo (bottom right; a click
// looks along that axis), the Fit and Reset buttons, and framing a box from a
// direction so that all of it is in the picture. The view (view3d.js) owns
// the scene and decides what to frame.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { ViewHelper } from 'three/addons/helpers/ViewHelper.js';

const GIZMO_PX = 128;  // the gizmo's corner, where pointer events are its own
export const DEFAULT_DIRECTION = new THREE.Vector3(0.45, -1, 0.6).normalize();  // from the front right, above

export class CameraRig {
  // element: the renderer's canvas; onChange(): the picture must be drawn again
  constructor(element, onChange) {
    this.element = element;
    this.onChange = onChange;
    this.camera = new THREE.PerspectiveCamera(40, 1, 0.01, 1000);
    this.camera.up.set(0, 0, 1);
    this.camera.position.set(3, -5, 3);
    this.gizmo = new ViewHelper(this.camera, element);  // the axes hint, bottom right
    this.gizmo.setLabels('x', 'y', 'z');
    this.controls = null;
  }

  // The orbit controls, after any listener that must see a press first (the
  // view's pointer tool), the gizmo's clicks and the Fit / Reset buttons in
  // `container`: fit(direction) frames the scene, fitFromHere() from the
  // direction the camera looks from now.
  attach(container, { fit, fitFromHere }) {
    this.controls = new OrbitControls(this.camera, this.element);
    this.controls.enableDamping = true;
    this.controls.dampingFactor = 0.15;
    this.controls.addEventListener('change', () => this.onChange());
    this.listenToGizmo();
    this.addViewButtons(container, fit, fitFromHere);
  }

  // The axes gizmo turns the camera to look along the clicked axis. Its
  // pointer events go to it alone: no drag, select or place.
  listenToGizmo() {
    const element = this.element;
    const inside = (e) => {
      const r = element.getBoundingClientRect();
      return e.clientX >= r.right - GIZMO_PX && e.clientY >= r.bottom - GIZMO_PX;
    };
    for (const type of ['pointerdown', 'pointermove', 'pointerup']) {
      element.addEventListener(type, (e) => {
        if (!inside(e) || (type === 'pointermove' && !e.buttons)) return;
        e.stopImmediatePropagation();
        if (type === 'pointerup') {
          this.gizmo.center.copy(this.controls.target);
          if (this.gizmo.handleClick(e)) { this.gizmoClock = performance.now(); this.onChange(); }
        }
      }, { capture: true });
    }
  }

  // Fit (frame the scene from where the camera looks now) and Reset (from the first view's direction).
  addViewButtons(container, fit, fitFromHere) {
    const bar = document.createElement('div');
    bar.className = 'view3d-buttons';
    for (const [text, title, action] of [
      ['Fit', 'frame the whole scene, looking from where you look now', fitFromHere],
      ['Reset', 'the first view: from the front right, above', () => fit()],
    ]) {
      const b = document.createElement('button');
      b.type = 'button';
      b.textContent = text;
      b.title = title;
      b.className = `view3d-${text.toLowerCase()}`;
      b.onclick = action;
      bar.appendChild(b);
    }
    container.appendChild(bar);
  }

  // Ends the orbit's coasting (damping) at once, so a fit is not turned afterwards.
  settle() {
    this.controls.enableDamping = false;
    this.controls.update();
    this.controls.enableDamping = true;
  }

  // The direction the camera looks from now (unit), or null when it sits on its target.
  lookingFrom() {
    this.settle();
    const direction = this.camera.position.clone().sub(this.controls.target);
    return direction.lengthSq() === 0 ? null : direction.normalize();
  }

  // Places the camera along `direction` from the box so that every corner of
  // it is in the picture, the picture's middle on the box's.
  frame(box, direction = DEFAULT_DIRECTION) {
    this.settle();
    const centre = box.getCenter(new THREE.Vector3());
    let distance = this.fitDistance(box, centre, direction);
    // perspective makes the near side look larger: centre the box's picture, then fit again
    for (let pass = 0; pass < 2; ++pass) {
      this.camera.position.copy(centre).addScaledVector(direction, distance);
      this.camera.lookAt(centre);
      this.camera.updateMatrixWorld();
      const picture = this.pictureBounds(box);
      const shift = new THREE.Vector3((picture.min.x + picture.max.x) / 2, (picture.min.y + picture.max.y) / 2, 0.5)
        .unproject(this.camera).sub(this.camera.position).normalize();
      // move the centre sideways so that it lies on the ray through the picture's middle
      const along = shift.multiplyScalar(distance / shift.dot(direction.clone().negate()));
      centre.copy(this.camera.position).add(along);
      distance = this.fitDistance(box, centre, direction);
    }
    this.camera.position.copy(centre).addScaledVector(direction, distance);
    this.controls.target.copy(centre);
    this.camera.near = distance / 100;
    this.camera.far = distance * 20;
    this.camera.updateProjectionMatrix();
    this.controls.update();
  }

  // The camera distance from `centre` along `direction` at which every corner of the box is in view.
  fitDistance(box, centre, direction) {
    const forward = direction.clone().negate();
    const right = new THREE.Vector3().crossVectors(forward, this.camera.up).normalize();
    const up = new THREE.Vector3().crossVectors(right, forward);
    const tanV = Math.tan(THREE.MathUtils.degToRad(this.camera.fov / 2)), tanH = tanV * this.camera.aspect;
    let distance = 0;
    const corner = new THREE.Vector3();
    for (let k = 0; k < 8; ++k) {
      corner.set(k & 1 ? box.max.x : box.min.x, k & 2 ? box.max.y : box.min.y, k & 4 ? box.max.z : box.min.z).sub(centre);
      const depth = corner.dot(forward);  // a corner beyond the centre needs less distance
      distance = Math.max(distance, Math.abs(corner.dot(right)) / tanH - depth, Math.abs(corner.dot(up)) / tanV - depth);
    }
    return distance * 1.05;
  }

  // The box's corners in normalised device coordinates: their 2D bounds.
  pictureBounds(box) {
    const bounds = new THREE.Box2(), corner = new THREE.Vector3();
    for (let k = 0; k < 8; ++k) {
      corner.set(k & 1 ? box.max.x : box.min.x, k & 2 ? box.max.y : box.min.y, k & 4 ? box.max.z : box.min.z).project(this.camera);
      bounds.expandByPoint(new THREE.Vector2(corner.x, corner.y));
    }
    return bounds;
  }

  // Called before each draw: true when the camera moved (coasting, or
  // turning to a clicked axis).
  update() {
    let moved = this.controls.update();
    if (this.gizmo.animating) {
      const now = performance.now();
      this.gizmo.update((now - (this.gizmoClock || now)) / 1000);
      this.gizmoClock = now;
      moved = true;
    }
    return moved;
  }

  setAspect(aspect) {
    this.camera.aspect = aspect;
    this.camera.updateProjectionMatrix();
  }

  // Page (client) coordinates of a world point.
  toClient(p) {
    const v = new THREE.Vector3(p[0], p[1], p[2] || 0).project(this.camera);
    const rect = this.element.getBoundingClientRect();
    return { x: rect.left + ((v.x + 1) / 2) * rect.width, y: rect.top + ((1 - v.y) / 2) * rect.height };
  }

  dispose() {
    if (this.controls) this.controls.dispose();
    this.gizmo.dispose();
  }
}
