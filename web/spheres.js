// Grains as shaded spheres, one point sprite each, of the radius of the
// sphere with the grain's volume. A software renderer (headless Chromium's
// SwiftShader) is bound by triangles: a 10,000-grain frame of 16-triangle
// polyhedra plays at a few frames per second as meshes and many times faster
// as sprites. The viewer uses them while it plays big runs (docs/viewer.md).
import * as THREE from 'three';

const vertexShader = /* glsl */ `
attribute float radius;
attribute vec3 tint;
uniform float pixelsPerUnit; // drawing-buffer pixels per unit length at distance 1
varying vec3 vTint;
void main() {
  vec4 eye = modelViewMatrix * vec4(position, 1.0);
  gl_Position = projectionMatrix * eye;
  gl_PointSize = max(1.5, 2.0 * radius * pixelsPerUnit / -eye.z);
  vTint = tint;
}`;

const fragmentShader = /* glsl */ `
varying vec3 vTint;
void main() {
  vec2 p = 2.0 * gl_PointCoord - 1.0;
  float r2 = dot(p, p);
  if (r2 > 1.0) discard;
  vec3 normal = vec3(p.x, -p.y, sqrt(1.0 - r2));
  float light = 0.3 + 0.7 * max(dot(normal, normalize(vec3(0.3, 0.6, 1.0))), 0.0);
  gl_FragColor = vec4(vTint * light, 1.0);
  #include <colorspace_fragment>
}`;

export class Spheres {
  constructor(scene) {
    this.geometry = new THREE.BufferGeometry();
    this.material = new THREE.ShaderMaterial({ vertexShader, fragmentShader, uniforms: { pixelsPerUnit: { value: 1 } } });
    this.points = new THREE.Points(this.geometry, this.material);
    this.points.frustumCulled = false; // its bounding sphere would go stale as grains move
    this.points.visible = false;
    this.capacity = 0;
    scene.add(this.points);
  }

  set visible(on) {
    this.points.visible = on;
  }

  // The free bodies of `frame`, coloured by `colors` (linear RGB per body),
  // each of radius radii[template].
  update(frame, colors, radii) {
    const { n, position: x, template, flags } = frame;
    if (n > this.capacity) {
      this.capacity = Math.max(n, 2 * this.capacity);
      for (const [name, size] of [['position', 3], ['tint', 3], ['radius', 1]])
        this.geometry.setAttribute(name, new THREE.BufferAttribute(new Float32Array(size * this.capacity), size).setUsage(THREE.DynamicDrawUsage));
    }
    const p = this.geometry.attributes.position.array, c = this.geometry.attributes.tint.array, r = this.geometry.attributes.radius.array;
    let s = 0;
    for (let i = 0; i < n; i++) {
      if (flags[i] & 1) continue; // fixed bodies stay meshes
      p[3 * s] = x[3 * i], p[3 * s + 1] = x[3 * i + 1], p[3 * s + 2] = x[3 * i + 2];
      c[3 * s] = colors[3 * i], c[3 * s + 1] = colors[3 * i + 1], c[3 * s + 2] = colors[3 * i + 2];
      r[s++] = radii[template[i]];
    }
    this.geometry.setDrawRange(0, s);
    for (const name of ['position', 'tint', 'radius']) this.geometry.attributes[name].needsUpdate = true;
  }

  // Point sizes follow the camera's field of view and the drawing buffer's height.
  fit(camera, renderer) {
    const height = renderer.getDrawingBufferSize(new THREE.Vector2()).y;
    this.material.uniforms.pixelsPerUnit.value = height / (2 * Math.tan(THREE.MathUtils.degToRad(camera.fov) / 2));
  }
}
