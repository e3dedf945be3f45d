// The bodies, drawn by instancing: one THREE.InstancedMesh per template and
// kind (free grains opaque and coloured, fixed bodies translucent grey), and
// the plane walls as translucent squares. A frame update writes every
// instance matrix in one loop over the frame's arrays, allocating nothing
// once the meshes are big enough.
import * as THREE from 'three';

const FIXED_GREY = 0.45; // linear grey of fixed bodies (walls, obstacles)
const Z = new THREE.Vector3(0, 0, 1);
const normal = new THREE.Vector3();

// Radius of the sphere of the closed mesh's volume (divergence theorem); the
// circumradius's third for a flat one.
function equalVolumeRadius(vertices, triangles) {
  let volume = 0, r2 = 0;
  for (let k = 0; k < triangles.length; k += 3) {
    const a = 3 * triangles[k], b = 3 * triangles[k + 1], c = 3 * triangles[k + 2];
    const v = vertices;
    volume += v[a] * (v[b + 1] * v[c + 2] - v[b + 2] * v[c + 1]) - v[a + 1] * (v[b] * v[c + 2] - v[b + 2] * v[c]) + v[a + 2] * (v[b] * v[c + 1] - v[b + 1] * v[c]);
  }
  volume /= 6;
  if (volume > 0) return Math.cbrt((3 * volume) / (4 * Math.PI));
  for (let i = 0; i < vertices.length; i += 3) r2 = Math.max(r2, vertices[i] ** 2 + vertices[i + 1] ** 2 + vertices[i + 2] ** 2);
  return Math.sqrt(r2) / 3;
}

export class Grains {
  constructor(scene, shapes) {
    this.scene = scene;
    this.geometries = [];
    // Each template's circumradius (its reach from the body's centre), the
    // radius of the sphere of its volume, and its box.
    this.radius = [];
    this.volumeRadius = [];
    this.boxes = [];
    this.addTemplates(shapes);
    // Flat shading shows the facets of polyhedra without per-vertex normals.
    this.freeMaterial = new THREE.MeshLambertMaterial({ flatShading: true });
    this.fixedMaterial = new THREE.MeshLambertMaterial({ flatShading: true, transparent: true, opacity: 0.25, depthWrite: false });
    this.batches = []; // index 2 * template + fixed: {mesh, capacity} or undefined
    this.planes = [];
    this.planeMaterial = new THREE.MeshBasicMaterial({ color: 0x6f8fb0, transparent: true, opacity: 0.22, side: THREE.DoubleSide, depthWrite: false });
    this.planeEdge = new THREE.LineBasicMaterial({ color: 0x9fb8d0, transparent: true, opacity: 0.6 });
  }

  // The templates of `shapes` past those already taken: all at first, then
  // the fragments of grains that broke as the run adds them.
  addTemplates(shapes) {
    const from = this.geometries.length;
    const added = shapes.templates.slice(from);
    for (const { vertices, triangles } of added) {
      const g = new THREE.BufferGeometry();
      g.setAttribute('position', new THREE.BufferAttribute(vertices, 3));
      g.setIndex(new THREE.BufferAttribute(triangles, 1));
      this.geometries.push(g);
    }
    added.forEach(({ vertices, triangles }, k) => {
      const t = from + k;
      let r2 = 0;
      const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
      for (let i = 0; i < vertices.length; i += 3) {
        r2 = Math.max(r2, vertices[i] ** 2 + vertices[i + 1] ** 2 + vertices[i + 2] ** 2);
        for (let a = 0; a < 3; a++) {
          lo[a] = Math.min(lo[a], vertices[i + a]);
          hi[a] = Math.max(hi[a], vertices[i + a]);
        }
      }
      this.radius[t] = Math.sqrt(r2);
      this.volumeRadius[t] = equalVolumeRadius(vertices, triangles);
      this.boxes[t] = vertices.length === 0
        ? { center: [0, 0, 0], half: [0, 0, 0] }
        : { center: lo.map((l, a) => (l + hi[a]) / 2), half: lo.map((l, a) => (hi[a] - l) / 2) };
    });
    this.counts = new Int32Array(2 * this.geometries.length);
  }

  // Free grains shown as meshes (or not: drawn as spheres meanwhile).
  setFreeVisible(on) {
    this.batches.forEach((batch, b) => {
      if (batch && !(b & 1)) batch.mesh.visible = on;
    });
    this.freeVisible = on;
  }

  // Opacity of the free grains (faded to see force chains inside the pack).
  setOpacity(opacity) {
    const transparent = opacity < 1;
    if (this.freeMaterial.transparent !== transparent) this.freeMaterial.needsUpdate = true;
    this.freeMaterial.transparent = transparent;
    this.freeMaterial.depthWrite = !transparent;
    this.freeMaterial.opacity = opacity;
  }

  batch(b, needed) {
    let batch = this.batches[b];
    if (batch && batch.capacity >= needed) return batch;
    const capacity = Math.max(needed, batch ? 2 * batch.capacity : 16);
    if (batch) {
      this.scene.remove(batch.mesh);
      batch.mesh.dispose();
    }
    const mesh = new THREE.InstancedMesh(this.geometries[b >> 1], b & 1 ? this.fixedMaterial : this.freeMaterial, capacity);
    mesh.instanceMatrix.setUsage(THREE.DynamicDrawUsage);
    mesh.instanceColor = new THREE.InstancedBufferAttribute(new Float32Array(3 * capacity), 3).setUsage(THREE.DynamicDrawUsage);
    mesh.frustumCulled = false; // its bounding sphere would go stale as grains move
    mesh.visible = b & 1 || this.freeVisible !== false;
    this.scene.add(mesh);
    batch = this.batches[b] = { mesh, capacity };
    return batch;
  }

  // Poses every body of `frame`; `colors` holds each free body's linear RGB.
  update(frame, colors) {
    const { n, position: x, quaternion: q, template, flags } = frame;
    const counts = this.counts;
    counts.fill(0);
    const templates = this.geometries.length;
    for (let i = 0; i < n; i++) {
      if (template[i] >= templates) throw new Error(`frame: body ${i} has template ${template[i]}, shapes.bin has ${templates}`);
      counts[2 * template[i] + (flags[i] & 1)]++;
    }
    const matrices = [], tints = [];
    for (let b = 0; b < counts.length; b++) {
      if (counts[b] === 0) {
        if (this.batches[b]) this.batches[b].mesh.count = 0;
        continue;
      }
      const { mesh } = this.batch(b, counts[b]);
      mesh.count = counts[b];
      mesh.instanceMatrix.needsUpdate = true;
      mesh.instanceColor.needsUpdate = true;
      matrices[b] = mesh.instanceMatrix.array;
      tints[b] = mesh.instanceColor.array;
    }
    counts.fill(0); // now the next free slot of each batch
    for (let i = 0; i < n; i++) {
      const fixed = flags[i] & 1, b = 2 * template[i] + fixed, s = counts[b]++;
      const m = matrices[b], o = 16 * s;
      const w = q[4 * i], qx = q[4 * i + 1], qy = q[4 * i + 2], qz = q[4 * i + 3];
      // Rotation of the unit quaternion, column-major, then the translation.
      m[o] = 1 - 2 * (qy * qy + qz * qz);
      m[o + 1] = 2 * (qx * qy + w * qz);
      m[o + 2] = 2 * (qx * qz - w * qy);
      m[o + 3] = 0;
      m[o + 4] = 2 * (qx * qy - w * qz);
      m[o + 5] = 1 - 2 * (qx * qx + qz * qz);
      m[o + 6] = 2 * (qy * qz + w * qx);
      m[o + 7] = 0;
      m[o + 8] = 2 * (qx * qz + w * qy);
      m[o + 9] = 2 * (qy * qz - w * qx);
      m[o + 10] = 1 - 2 * (qx * qx + qy * qy);
      m[o + 11] = 0;
      m[o + 12] = x[3 * i];
      m[o + 13] = x[3 * i + 1];
      m[o + 14] = x[3 * i + 2];
      m[o + 15] = 1;
      const c = tints[b];
      if (fixed) {
        c[3 * s] = c[3 * s + 1] = c[3 * s + 2] = FIXED_GREY;
      } else {
        c[3 * s] = colors[3 * i];
        c[3 * s + 1] = colors[3 * i + 1];
        c[3 * s + 2] = colors[3 * i + 2];
      }
    }
  }

  // Plane walls: squares of side `size` through each plane's point, centred
  // where the scene's centre projects onto the plane, facing its normal.
  updatePlanes(frame, center, size) {
    const { p, planePoint: pp, planeNormal: pn } = frame;
    while (this.planes.length < p) {
      const square = new THREE.Mesh(new THREE.PlaneGeometry(1, 1), this.planeMaterial);
      square.add(new THREE.LineSegments(new THREE.EdgesGeometry(square.geometry), this.planeEdge));
      this.scene.add(square);
      this.planes.push(square);
    }
    this.planes.forEach((square, k) => {
      square.visible = k < p;
      if (k >= p) return;
      normal.set(pn[3 * k], pn[3 * k + 1], pn[3 * k + 2]);
      const h = (center.x - pp[3 * k]) * normal.x + (center.y - pp[3 * k + 1]) * normal.y + (center.z - pp[3 * k + 2]) * normal.z;
      square.position.copy(center).addScaledVector(normal, -h);
      square.quaternion.setFromUnitVectors(Z, normal);
      square.scale.set(size, size, 1);
    });
  }

  // Box around every body: each template's own box, turned with the body.
  bounds(frame, box = new THREE.Box3()) {
    box.makeEmpty();
    const { n, position: x, quaternion: q, template } = frame;
    const r = new Float64Array(9), lo = new THREE.Vector3(), hi = new THREE.Vector3();
    for (let i = 0; i < n; i++) {
      const { center: c, half: h } = this.boxes[template[i]];
      const w = q[4 * i], qx = q[4 * i + 1], qy = q[4 * i + 2], qz = q[4 * i + 3];
      r.set([1 - 2 * (qy * qy + qz * qz), 2 * (qx * qy - w * qz), 2 * (qx * qz + w * qy),
        2 * (qx * qy + w * qz), 1 - 2 * (qx * qx + qz * qz), 2 * (qy * qz - w * qx),
        2 * (qx * qz - w * qy), 2 * (qy * qz + w * qx), 1 - 2 * (qx * qx + qy * qy)]);
      for (let a = 0; a < 3; a++) {
        const mid = x[3 * i + a] + r[3 * a] * c[0] + r[3 * a + 1] * c[1] + r[3 * a + 2] * c[2];
        const reach = Math.abs(r[3 * a]) * h[0] + Math.abs(r[3 * a + 1]) * h[1] + Math.abs(r[3 * a + 2]) * h[2];
        lo.setComponent(a, mid - reach);
        hi.setComponent(a, mid + reach);
      }
      box.expandByPoint(lo).expandByPoint(hi);
    }
    return box;
  }
}
