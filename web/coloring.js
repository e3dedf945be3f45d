// Per-body colours of a frame for each colouring mode, and the range the
// legend shows. Ranges are taken over the free bodies only (fixed bodies are
// drawn grey). Scratch arrays grow with the body count and are reused.
import { VIRIDIS, category, sample } from './colors.js';
import { PLANE_BIT } from './view_format.js';

export const MODES = {
  speed: { label: 'speed', unit: 'm/s' },
  force: { label: 'resultant contact force', unit: 'N' },
  template: { label: 'template', unit: '' },
  id: { label: 'body id', unit: '' },
};

// Besides these, a frame's channel block (docs/view-format.md) gives one
// mode per channel, 'channel:NAME': its magnitude (its value with one
// component).
export const CHANNEL_MODE = 'channel:';

// {label, unit} of `mode` for the legend; null for a mode the frame cannot show.
export function modeInfo(mode, frame) {
  if (mode in MODES) return MODES[mode];
  const channel = mode.startsWith(CHANNEL_MODE) && frame ? frame.channels[mode.slice(CHANNEL_MODE.length)] : undefined;
  return channel ? { label: mode.slice(CHANNEL_MODE.length).replaceAll('_', ' '), unit: channel.unit } : null;
}

let values = new Float32Array(0);
let forces = new Float32Array(0);
let colors = new Float32Array(0);
let templateColors = new Float32Array(0); // 3 per template, made once

// Resultant contact force on each body: + the force on the second side,
// - that force on the first when it is a body (not a plane wall).
function resultantForces(frame) {
  const { n, m, contactFirst: first, contactSecond: second, contactForce: f } = frame;
  forces.fill(0, 0, 3 * n);
  for (let c = 0; c < m; c++) {
    const b = second[c], a = first[c];
    forces[3 * b] += f[3 * c];
    forces[3 * b + 1] += f[3 * c + 1];
    forces[3 * b + 2] += f[3 * c + 2];
    if (a < PLANE_BIT) {
      forces[3 * a] -= f[3 * c];
      forces[3 * a + 1] -= f[3 * c + 1];
      forces[3 * a + 2] -= f[3 * c + 2];
    }
  }
}

// Returns {colors (linear RGB, 3 per body), min, max, categories}.
export function colorBodies(frame, mode, templateCount) {
  const { n, flags } = frame;
  if (colors.length < 3 * n) {
    values = new Float32Array(n);
    forces = new Float32Array(3 * n);
    colors = new Float32Array(3 * n);
  }
  if (mode === 'template') {
    if (templateColors.length !== 3 * templateCount) {
      templateColors = new Float32Array(3 * templateCount);
      for (let t = 0; t < templateCount; t++) category(t, templateColors, 3 * t);
    }
    const tpl = frame.template;
    for (let i = 0; i < n; i++) {
      const t = 3 * tpl[i];
      colors[3 * i] = templateColors[t];
      colors[3 * i + 1] = templateColors[t + 1];
      colors[3 * i + 2] = templateColors[t + 2];
    }
    return { colors, min: 0, max: templateCount - 1, categories: templateCount };
  }
  if (mode === 'speed') {
    const v = frame.velocity;
    for (let i = 0; i < n; i++) values[i] = Math.sqrt(v[3 * i] ** 2 + v[3 * i + 1] ** 2 + v[3 * i + 2] ** 2);
  } else if (mode === 'force') {
    resultantForces(frame);
    for (let i = 0; i < n; i++) values[i] = Math.sqrt(forces[3 * i] ** 2 + forces[3 * i + 1] ** 2 + forces[3 * i + 2] ** 2);
  } else if (mode.startsWith(CHANNEL_MODE)) {
    // A channel this frame lacks (a feature turned off since) shows zeros.
    const channel = frame.channels[mode.slice(CHANNEL_MODE.length)];
    const c = channel ? channel.components : 0, v = channel ? channel.values : null;
    for (let i = 0; i < n; i++) {
      let sum = 0;
      for (let k = 0; k < c; k++) sum += v[c * i + k] ** 2;
      values[i] = c === 1 ? v[i] : Math.sqrt(sum);
    }
  } else {
    for (let i = 0; i < n; i++) values[i] = frame.id[i];
  }
  let min = Infinity, max = -Infinity;
  for (let i = 0; i < n; i++) {
    if (flags[i] & 1) continue;
    if (values[i] < min) min = values[i];
    if (values[i] > max) max = values[i];
  }
  if (min > max) min = max = 0; // no free body
  const scale = max > min ? 1 / (max - min) : 0;
  for (let i = 0; i < n; i++) sample(VIRIDIS, (values[i] - min) * scale, colors, 3 * i);
  return { colors, min, max, categories: 0 };
}
