// Force chains: one instanced thin cylinder per touching contact, its width
// and colour by the normal force |f . n| relative to the frame's largest.
// A segment joins the two bodies' centres; a side that is a plane wall, a
// fixed body (a wall piece, whose centre may be far away) or across a
// periodic boundary (its centre further than 1.5 times its radius from the
// contact point) is replaced by the contact point.
import * as THREE from 'three';
import { CHAINS, sample } from './colors.js';
import { PLANE_BIT } from './view_format.js';

export class ForceChains {
  constructor(scene) {
    this.scene = scene;
    // Radius 1, height 1 along y, centred: scaled and turned per contact.
    this.geometry = new THREE.CylinderGeometry(1, 1, 1, 6, 1, true);
    this.material = new THREE.MeshLambertMaterial();
    this.mesh = null;
    this.capacity = 0;
    this.maxForce = 0;
    this.shown = 0;
    this.ab = new Float64Array(6); // the current segment's two ends
  }

  ensure(needed) {
    if (this.capacity >= needed) return;
    if (this.mesh) {
      this.scene.remove(this.mesh);
      this.mesh.dispose();
    }
    this.capacity = Math.max(needed, 2 * this.capacity, 64);
    this.mesh = new THREE.InstancedMesh(this.geometry, this.material, this.capacity);
    this.mesh.instanceMatrix.setUsage(THREE.DynamicDrawUsage);
    this.mesh.instanceColor = new THREE.InstancedBufferAttribute(new Float32Array(3 * this.capacity), 3).setUsage(THREE.DynamicDrawUsage);
    this.mesh.frustumCulled = false;
    this.scene.add(this.mesh);
  }

  setVisible(on) {
    if (this.mesh) this.mesh.visible = on;
  }

  // Draws the contacts of `frame` whose normal force is at least
  // `threshold` times the largest; `radius[t]` is template t's radius and
  // `width` the radius of the strongest chain.
  update(frame, threshold, radius, width) {
    const { m, position: x, template, flags, contactFirst: first, contactSecond: second } = frame;
    const p = frame.contactPoint, nrm = frame.contactNormal, f = frame.contactForce;
    this.ensure(m);
    let fmax = 0;
    for (let c = 0; c < m; c++) fmax = Math.max(fmax, Math.abs(f[3 * c] * nrm[3 * c] + f[3 * c + 1] * nrm[3 * c + 1] + f[3 * c + 2] * nrm[3 * c + 2]));
    this.maxForce = fmax;
    const cut = Math.max(threshold * fmax, Number.MIN_VALUE); // zero forces are never drawn
    const mat = this.mesh.instanceMatrix.array, col = this.mesh.instanceColor.array;
    // End of side `body` of contact c: its centre, or the contact point.
    const end = (body, c, out, o) => {
      let use = body < PLANE_BIT && !(flags[body] & 1);
      if (use) {
        const r = 1.5 * radius[template[body]];
        use = (x[3 * body] - p[3 * c]) ** 2 + (x[3 * body + 1] - p[3 * c + 1]) ** 2 + (x[3 * body + 2] - p[3 * c + 2]) ** 2 <= r * r;
      }
      const src = use ? x : p, s = use ? 3 * body : 3 * c;
      out[o] = src[s];
      out[o + 1] = src[s + 1];
      out[o + 2] = src[s + 2];
    };
    const ab = this.ab;
    let k = 0;
    for (let c = 0; c < m; c++) {
      const fn = Math.abs(f[3 * c] * nrm[3 * c] + f[3 * c + 1] * nrm[3 * c + 1] + f[3 * c + 2] * nrm[3 * c + 2]);
      if (fn < cut) continue;
      end(first[c], c, ab, 0);
      end(second[c], c, ab, 3);
      const dx = ab[3] - ab[0], dy = ab[4] - ab[1], dz = ab[5] - ab[2];
      const len = Math.sqrt(dx * dx + dy * dy + dz * dz);
      if (len === 0) continue;
      const t = fn / fmax, r = width * (0.3 + 0.7 * t); // the weakest still a few pixels wide
      // e1, e2: unit vectors across the segment, (e1, u, e2) right-handed.
      const ux = dx / len, uy = dy / len, uz = dz / len;
      let e1x, e1y, e1z;
      if (Math.abs(ux) < 0.9) { e1x = 0; e1y = uz; e1z = -uy; } else { e1x = -uz; e1y = 0; e1z = ux; }
      const l1 = Math.sqrt(e1x * e1x + e1y * e1y + e1z * e1z);
      e1x /= l1; e1y /= l1; e1z /= l1;
      const e2x = e1y * uz - e1z * uy, e2y = e1z * ux - e1x * uz, e2z = e1x * uy - e1y * ux;
      const o = 16 * k;
      mat[o] = e1x * r; mat[o + 1] = e1y * r; mat[o + 2] = e1z * r; mat[o + 3] = 0;
      mat[o + 4] = dx; mat[o + 5] = dy; mat[o + 6] = dz; mat[o + 7] = 0;
      mat[o + 8] = e2x * r; mat[o + 9] = e2y * r; mat[o + 10] = e2z * r; mat[o + 11] = 0;
      mat[o + 12] = ab[0] + dx / 2; mat[o + 13] = ab[1] + dy / 2; mat[o + 14] = ab[2] + dz / 2; mat[o + 15] = 1;
      sample(CHAINS, t, col, 3 * k);
      k++;
    }
    this.mesh.count = k;
    this.shown = k;
    this.mesh.instanceMatrix.needsUpdate = true;
    this.mesh.instanceColor.needsUpdate = true;
  }
}
