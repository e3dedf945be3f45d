// Bonds of bonded assemblies (docs/breakage.md): one line per bond from its
// first piece's centre through the glued face's centre to its second's,
// light while it holds, red once broken.
import * as THREE from 'three';

const HOLDS = [0.85, 0.85, 0.8], BROKEN = [0.9, 0.15, 0.1];

export class BondLines {
  constructor(scene) {
    this.geometry = new THREE.BufferGeometry();
    this.material = new THREE.LineBasicMaterial({ vertexColors: true, depthTest: false, transparent: true });
    this.lines = new THREE.LineSegments(this.geometry, this.material);
    this.lines.frustumCulled = false;
    this.lines.renderOrder = 2; // over the grains
    this.lines.visible = false;
    this.capacity = 0;
    this.intact = 0;
    this.broken = 0;
    scene.add(this.lines);
  }

  setVisible(on) {
    this.lines.visible = on;
  }

  update(frame) {
    const k = frame.bonds, x = frame.position, p = frame.bondPoint;
    if (this.capacity < k) {
      this.capacity = Math.max(k, 2 * this.capacity, 64);
      this.geometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array(12 * this.capacity), 3));
      this.geometry.setAttribute('color', new THREE.BufferAttribute(new Float32Array(12 * this.capacity), 3));
    }
    if (k === 0) {
      this.geometry.setDrawRange(0, 0);
      this.intact = this.broken = 0;
      return;
    }
    const pos = this.geometry.attributes.position.array, col = this.geometry.attributes.color.array;
    let intact = 0;
    for (let b = 0; b < k; b++) {
      const ends = [frame.bondFirst[b], -1, -1, frame.bondSecond[b]]; // centre, face, face, centre
      const c = frame.bondIntact[b] ? HOLDS : BROKEN;
      intact += frame.bondIntact[b];
      for (let e = 0; e < 4; e++) {
        const src = ends[e] < 0 ? p : x, i = ends[e] < 0 ? b : ends[e];
        for (let d = 0; d < 3; d++) {
          pos[12 * b + 3 * e + d] = src[3 * i + d];
          col[12 * b + 3 * e + d] = c[d];
        }
      }
    }
    this.intact = intact;
    this.broken = k - intact;
    this.geometry.setDrawRange(0, 4 * k);
    this.geometry.attributes.position.needsUpdate = true;
    this.geometry.attributes.color.needsUpdate = true;
  }
}
