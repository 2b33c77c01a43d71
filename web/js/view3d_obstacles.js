// Obstacles in the 3D view, drawn as the engine checks them (engine/collision):
// box (size, rpy = Rz·Ry·Rx), sphere, point, polygon as a prism over
// z in [z_min, z_max] of its frame (default [-1, 1]), wall as a patch of its
// plane with the blocked half-space behind it, mesh from the triangles the
// snapshot carries (o.mesh: flat vertices in its own frame, flat indices;
// scaled already) turned by rpy. Built once per snapshot; update() only
// moves them to the frame's positions.
import * as THREE from 'three';

export const obstacleColours = {
  fill: '#b0bec5', edge: '#607d8b', selectedFill: '#ffcc80', selectedEdge: '#ef6c00', wall: '#90a4ae',
};

// Reference point of an obstacle in scenario syntax (what frame.obstacles[i] moves).
export function obstaclePosition(o) {
  const p = o.center || o.position || o.point || [0, 0, 0];
  return [p[0], p[1], p[2] || 0];
}

// Geometry that changes the mesh (not where it is): to reuse meshes across snapshots.
export function obstacleShapeKey(o) {
  return JSON.stringify([o.id, o.shape, o.points, o.z, o.size, o.rpy, o.radius, o.normal, o.file, o.scale]);
}

function prismGeometry(o) {
  const shape = new THREE.Shape(o.points.map(([x, y]) => new THREE.Vector2(x, y)));
  const [zMin, zMax] = o.z || [-1, 1];
  const geometry = new THREE.ExtrudeGeometry(shape, { depth: zMax - zMin, bevelEnabled: false });
  geometry.translate(0, 0, zMin);
  return geometry;
}

// A mesh obstacle's triangles (snapshot.obstacles[i].mesh), with smooth-ish
// shading from per-vertex normals.
function meshGeometry(o) {
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.Float32BufferAttribute(o.mesh.vertices, 3));
  geometry.setIndex(o.mesh.triangles);
  geometry.computeVertexNormals();
  return geometry;
}

// Wall: a square patch of the plane (side ~2.4 reach) and a thin slab behind it.
function wallObject(o, reach, materials) {
  const n = new THREE.Vector3(...o.normal).normalize();
  const group = new THREE.Group();
  const side = 2.4 * reach, depth = 0.04 * reach;
  const patch = new THREE.Mesh(new THREE.PlaneGeometry(side, side), materials.wall);
  const slab = new THREE.Mesh(new THREE.BoxGeometry(side, side, depth), materials.wallSlab);
  slab.position.z = -depth / 2;
  const outline = new THREE.LineSegments(new THREE.EdgesGeometry(patch.geometry), materials.edge);
  group.add(patch, slab, outline);
  group.quaternion.setFromUnitVectors(new THREE.Vector3(0, 0, 1), n);  // plane's +z = free side
  group.userData.normal = n;
  return group;
}

export class Obstacles {
  // obstacles: snapshot.obstacles; reach and base: the model's, to size points and walls.
  constructor(obstacles, reach, base) {
    this.reach = reach;
    this.base = new THREE.Vector3(...base);
    this.keys = obstacles.map(obstacleShapeKey);
    this.kinds = obstacles.map((o) => o.shape);
    this.materials = {
      fill: new THREE.MeshLambertMaterial({ color: obstacleColours.fill, transparent: true, opacity: 0.85 }),
      selected: new THREE.MeshLambertMaterial({ color: obstacleColours.selectedFill, transparent: true, opacity: 0.9 }),
      point: new THREE.MeshLambertMaterial({ color: obstacleColours.edge }),
      edge: new THREE.LineBasicMaterial({ color: obstacleColours.edge }),
      selectedEdge: new THREE.LineBasicMaterial({ color: obstacleColours.selectedEdge }),
      wall: new THREE.MeshBasicMaterial({ color: obstacleColours.wall, transparent: true, opacity: 0.18, side: THREE.DoubleSide, depthWrite: false }),
      wallSlab: new THREE.MeshBasicMaterial({ color: obstacleColours.wall, transparent: true, opacity: 0.1, depthWrite: false }),
    };
    this.object = new THREE.Group();
    this.items = obstacles.map((o, index) => this.build(o, index));
    this.pickables = this.items.filter((item) => item.mesh).map((item) => item.mesh);
    this.selected = null;
    obstacles.forEach((o, i) => this.place(i, obstaclePosition(o)));
  }

  // Same shapes in the same order: the meshes can stay, only positions change.
  sameShapes(obstacles) {
    return obstacles.length === this.keys.length && obstacles.every((o, i) => obstacleShapeKey(o) === this.keys[i]);
  }

  build(o, index) {
    const group = new THREE.Group();
    let geometry = null;
    if (o.shape === 'box') {
      geometry = new THREE.BoxGeometry(...o.size);
      if (o.rpy) group.rotation.set(o.rpy[0], o.rpy[1], o.rpy[2], 'ZYX');  // R = Rz(yaw)·Ry(pitch)·Rx(roll)
    } else if (o.shape === 'sphere') {
      geometry = new THREE.SphereGeometry(o.radius, 32, 20);
    } else if (o.shape === 'polygon') {
      geometry = prismGeometry(o);
    } else if (o.shape === 'point' || (o.shape === 'mesh' && !o.mesh)) {  // a mesh without its triangles: a marker
      geometry = new THREE.SphereGeometry(0.012 * this.reach, 16, 10);
    } else if (o.shape === 'mesh') {
      geometry = meshGeometry(o);
      if (o.rpy) group.rotation.set(o.rpy[0], o.rpy[1], o.rpy[2], 'ZYX');
    } else if (o.shape === 'wall') {
      const wall = wallObject(o, this.reach, this.materials);
      group.add(wall);
      this.object.add(group);
      return { group, wall, mesh: null, edges: null };
    }
    const mesh = new THREE.Mesh(geometry, o.shape === 'point' ? this.materials.point : this.materials.fill);
    mesh.userData.obstacleIndex = index;
    group.add(mesh);
    let edges = null;
    if (o.shape === 'box' || o.shape === 'polygon' || (o.shape === 'mesh' && o.mesh)) {
      // a mesh's creases only (40°): a tessellated curve draws no lines
      edges = new THREE.LineSegments(new THREE.EdgesGeometry(geometry, o.shape === 'mesh' ? 40 : 20), this.materials.edge);
      group.add(edges);
    }
    this.object.add(group);
    return { group, wall: null, mesh, edges };
  }

  // Moves obstacle i's reference point to p (walls: the patch follows the base's foot on the plane).
  place(i, p) {
    const item = this.items[i];
    if (!item || !p) return;
    if (item.wall) {
      const n = item.wall.userData.normal;
      const along = n.x * (this.base.x - p[0]) + n.y * (this.base.y - p[1]) + n.z * (this.base.z - (p[2] || 0));
      item.group.position.copy(this.base).addScaledVector(n, -along);
    } else {
      item.group.position.set(p[0], p[1], p[2] || 0);
    }
  }

  // positions: frame.obstacles; override: {index, position} held while the user drags.
  update(positions, override) {
    const count = Math.min(positions.length, this.items.length);
    for (let i = 0; i < count; ++i) this.place(i, override && override.index === i ? override.position : positions[i]);
  }

  setSelected(index) {
    if (index === this.selected) return;
    for (const i of [this.selected, index]) {
      const item = i === null ? null : this.items[i];
      if (!item || !item.mesh) continue;
      const on = i === index;
      if (this.kinds[i] !== 'point') item.mesh.material = on ? this.materials.selected : this.materials.fill;
      else item.mesh.material = on ? this.materials.selected : this.materials.point;
      if (item.edges) item.edges.material = on ? this.materials.selectedEdge : this.materials.edge;
    }
    this.selected = index;
  }

  // Bounding box of every obstacle (walls: their reference point only), for framing.
  expandBox(box) {
    this.object.updateMatrixWorld(true);
    const part = new THREE.Box3();
    for (const item of this.items) {
      if (item.mesh) box.union(part.setFromObject(item.mesh));
      else box.expandByPoint(item.group.position);
    }
    return box;
  }

  dispose() {
    this.object.traverse((o) => { if (o.geometry) o.geometry.dispose(); });
    for (const m of Object.values(this.materials)) m.dispose();
    this.object.removeFromParent();
  }
}
