// The viewer page: wires the run's data, the 3D scene, the controls and the
// plots together, plays the frames, and exposes window.gjkdemViewer for tests.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { ForceChains } from './chains.js';
import { BondLines } from './bonds.js';
import { CHANNEL_MODE, colorBodies, modeInfo } from './coloring.js';
import { CHAINS, VIRIDIS, paintBar } from './colors.js';
import { Grains } from './grains.js';
import { Spheres } from './spheres.js';
import { Plot, formatNumber } from './plots.js';
import { RunSource } from './run_source.js';
import { showSummary } from './summary.js';
import { parseCsv } from './view_format.js';

const POLL_MS = 2000; // index.csv is re-read this often, so a run still going shows its new frames
const PREFETCH = 8; // frames read ahead while playing

const $ = (id) => document.getElementById(id);
const source = new RunSource();

const state = { frame: null, k: -1, mode: 'speed', draw: 'auto', chains: false, bonds: true, threshold: 0.1, playing: false, speed: 1, loop: true, acc: 0 };
// lastFrameLoadMs: fetch + decode + update + draw of the last frame asked for;
// lastUpdateMs: the page's own work on a frame (colours, matrices, chains, labels).
const stats = { fps: 0, lastFrameLoadMs: 0, lastUpdateMs: 0, lastRenderMs: 0, framesShown: 0 };
let run = null; // run.json
let grains = null;
let loadToken = 0;
const fit = { box: new THREE.Box3(), center: new THREE.Vector3(), planeSize: 1, chainWidth: 0.01 };

// --- 3D scene -------------------------------------------------------------
const canvas = $('scene');
const renderer = new THREE.WebGLRenderer({ canvas, antialias: false, preserveDrawingBuffer: false });
renderer.setPixelRatio(window.devicePixelRatio || 1);
renderer.setClearColor(0x262b33);
const scene = new THREE.Scene();
const camera = new THREE.PerspectiveCamera(35, 1, 1e-3, 1e3);
scene.add(camera, new THREE.HemisphereLight(0xffffff, 0x404850, 1.2));
const headlight = new THREE.DirectionalLight(0xffffff, 1.8);
headlight.position.set(0.3, 0.6, 1); // over the viewer's shoulder, so every view is lit
headlight.target.position.set(0, 0, -1);
camera.add(headlight, headlight.target);
const chains = new ForceChains(scene);
const bonds = new BondLines(scene);
const spheres = new Spheres(scene);
// 'auto' draws the free grains as spheres while playing a frame of more than
// AUTO_SPHERES_BODIES bodies, and always beyond AUTO_SPHERES_ALWAYS (a
// software renderer takes seconds over a million triangles); as their shapes
// otherwise.
const AUTO_SPHERES_BODIES = 5000;
const AUTO_SPHERES_ALWAYS = 50000;
const CURSOR_MS = 100;
let cursorDrawn = -Infinity;
let controls = null;
const axes = { up: new THREE.Vector3(0, 0, 1), side: new THREE.Vector3(1, 0, 0), depth: new THREE.Vector3(0, 1, 0) };

// Drawing happens once per animation frame, however many changes asked for
// it: a slider dragged over many frames would otherwise queue a draw for each
// (seconds of work for a software renderer) and the page would lag behind.
// The promise resolves once drawn.
let drawQueued = null;
function render() {
  drawQueued ??= new Promise((resolve) =>
    requestAnimationFrame(() => {
      drawQueued = null;
      const t0 = performance.now();
      spheres.fit(camera, renderer);
      renderer.render(scene, camera);
      stats.lastRenderMs = performance.now() - t0; // the GL calls; a busy GPU makes them wait
      resolve();
    }));
  return drawQueued;
}

new ResizeObserver(() => {
  const { clientWidth: w, clientHeight: h } = $('view');
  renderer.setSize(w, h, false);
  camera.aspect = w / Math.max(h, 1);
  camera.updateProjectionMatrix();
  render();
}).observe($('view'));

// Up is against gravity (run.json's scene), along its main axis; z when unknown.
function setAxes(gravity) {
  if (!gravity || gravity.every((g) => g === 0)) return;
  const a = [0, 1, 2].reduce((b, i) => (Math.abs(gravity[i]) > Math.abs(gravity[b]) ? i : b), 0);
  const s = gravity[a] > 0 ? -1 : 1, unit = (i, k) => new THREE.Vector3().setComponent(i, k);
  axes.up = unit(a, s);
  axes.side = unit((a + 1) % 3, s);
  axes.depth = unit((a + 2) % 3, 1); // side x depth = up
}

// Camera looking at the scene's box from a preset direction, at the nearest
// distance where all eight corners are inside the field of view.
function setPreset(name) {
  const { up, side, depth } = axes, dir = new THREE.Vector3();
  if (name === 'front') dir.copy(depth).negate();
  else if (name === 'side') dir.copy(side);
  else if (name === 'top') dir.copy(up).addScaledVector(depth, -1e-3);
  else dir.copy(side).sub(depth).addScaledVector(up, 0.8);
  dir.normalize();
  const right = new THREE.Vector3().crossVectors(up, dir).normalize(), upward = new THREE.Vector3().crossVectors(dir, right);
  const tanV = Math.tan(THREE.MathUtils.degToRad(camera.fov) / 2), tanH = tanV * camera.aspect;
  const corner = new THREE.Vector3(), { min, max } = fit.box;
  let distance = 0;
  for (let c = 0; c < 8; c++) {
    corner.set(c & 1 ? max.x : min.x, c & 2 ? max.y : min.y, c & 4 ? max.z : min.z).sub(fit.center);
    const z = corner.dot(dir);
    distance = Math.max(distance, z + Math.abs(corner.dot(right)) / tanH, z + Math.abs(corner.dot(upward)) / tanV);
  }
  distance *= 1.08; // a margin around the scene
  camera.up.copy(up);
  camera.position.copy(fit.center).addScaledVector(dir, distance);
  camera.near = distance / 100;
  camera.far = distance * 100;
  camera.updateProjectionMatrix();
  controls.target.copy(fit.center);
  controls.update();
  return render();
}

// Scene extent from the first frame: camera fit, plane squares, chain width.
function measureScene(frame) {
  const box = grains.bounds(frame);
  for (let k = 0; k < frame.p; k++) box.expandByPoint(new THREE.Vector3().fromArray(frame.planePoint, 3 * k));
  if (box.isEmpty()) box.set(new THREE.Vector3(-1, -1, -1), new THREE.Vector3(1, 1, 1));
  showPeriodicCell(frame, box);
  if (cell?.visible) box.union(cell.geometry.boundingBox);
  fit.box = box;
  box.getCenter(fit.center);
  const diagonal = box.getSize(new THREE.Vector3()).length();
  fit.planeSize = 1.2 * diagonal;
  const radii = [];
  for (let i = 0; i < frame.n; i++) if (!(frame.flags[i] & 1)) radii.push(grains.radius[frame.template[i]]);
  radii.sort((a, b) => a - b);
  fit.chainWidth = 0.3 * (radii.length ? radii[radii.length >> 1] : diagonal / 100);
}

// A periodic world's cell, as the frame has it (a deforming cell stretches
// and shears: docs/scenes.md), as a wire parallelepiped; along axes that are
// not periodic it spans `box`. Bodies leave it on one side and come back on
// the other.
let cell = null;
function showPeriodicCell(frame, box) {
  if (!frame.cellAxes) {
    if (cell) cell.visible = false;
    return;
  }
  const c = frame.cell, lo = [c[0], c[1], c[2]], size = [c[3] - c[0], c[4] - c[1], c[5] - c[2]];
  for (let a = 0; a < 3; a++) {
    if (frame.cellAxes >> a & 1) continue;
    lo[a] = box.min.getComponent(a);
    size[a] = box.max.getComponent(a) - lo[a];
  }
  const edges = [[size[0], 0, 0], [c[6], size[1], 0], [c[7], c[8], size[2]]];
  const corner = (n) => [0, 1, 2].map((d) => lo[d] + n[0] * edges[0][d] + n[1] * edges[1][d] + n[2] * edges[2][d]);
  const points = [];
  for (let d = 0; d < 3; d++)
    for (let u = 0; u < 2; u++)
      for (let v = 0; v < 2; v++) {
        const n = [0, 0, 0];
        n[(d + 1) % 3] = u;
        n[(d + 2) % 3] = v;
        points.push(...corner(n));
        n[d] = 1;
        points.push(...corner(n));
      }
  if (!cell) {
    cell = new THREE.LineSegments(new THREE.BufferGeometry(), new THREE.LineBasicMaterial({ color: 0xffd54f }));
    scene.add(cell);
  }
  cell.geometry.setAttribute('position', new THREE.Float32BufferAttribute(points, 3));
  cell.geometry.computeBoundingBox();
  cell.geometry.computeBoundingSphere();
  cell.visible = true;
}

// --- drawing a frame --------------------------------------------------------
function apply(frame, k) {
  const t0 = performance.now();
  state.frame = frame;
  state.k = k;
  offerChannels(frame);
  const coloring = colorBodies(frame, state.mode, grains.geometries.length);
  grains.update(frame, coloring.colors);
  const asSpheres = state.draw === 'spheres' ||
    (state.draw === 'auto' && (frame.n > AUTO_SPHERES_ALWAYS || (state.playing && frame.n > AUTO_SPHERES_BODIES)));
  if (asSpheres) spheres.update(frame, coloring.colors, grains.volumeRadius);
  spheres.visible = asSpheres;
  grains.setFreeVisible(!asSpheres);
  grains.updatePlanes(frame, fit.center, fit.planeSize);
  showPeriodicCell(frame, fit.box);
  if (state.chains) chains.update(frame, state.threshold, grains.radius, fit.chainWidth);
  chains.setVisible(state.chains);
  $('bonds-control').hidden = frame.bonds === 0;
  if (state.bonds) bonds.update(frame);
  bonds.setVisible(state.bonds && frame.bonds > 0);
  showLegend(coloring);
  $('slider').value = k;
  showTimeLabel();
  $('frame-info').textContent = `${frame.n} bodies, ${frame.m} contacts` + (state.chains ? `, ${chains.shown} chains drawn` : '') +
    (frame.bonds > 0 ? `, ${frame.bonds - bondsBroken(frame)} of ${frame.bonds} bonds holding` : '') + `, step ${frame.steps}`;
  // Plot cursors at most every CURSOR_MS while playing: redrawing five
  // canvases each frame cost a software renderer a fifth of its frame rate.
  const now = performance.now();
  if (!state.playing || now - cursorDrawn >= CURSOR_MS) {
    for (const plot of plots) plot.setCursor(frame.time);
    if (forceBins) showForceBins(k);
    cursorDrawn = now;
  }
  stats.lastUpdateMs = performance.now() - t0;
  countShown();
  return render();
}

function showTimeLabel() {
  $('time-label').textContent = `frame ${state.k + 1} / ${source.frameCount} \u00b7 t = ${state.frame.time.toPrecision(4)} s`;
}

function redraw() {
  return state.frame ? apply(state.frame, state.k) : Promise.resolve();
}

function showLegend({ min, max, categories }) {
  const { label, unit } = modeInfo(state.mode, state.frame) ?? { label: state.mode.slice(CHANNEL_MODE.length), unit: '' };
  $('legend-title').textContent = unit ? `${label} (${unit})` : label;
  $('legend-min').textContent = categories ? String(min) : formatNumber(min);
  $('legend-max').textContent = categories ? String(max) : formatNumber(max);
  $('chain-legend').hidden = !state.chains;
  if (state.chains) {
    $('chain-min').textContent = formatNumber(state.threshold * chains.maxForce);
    $('chain-max').textContent = formatNumber(chains.maxForce);
  }
}

function paintLegendBar() {
  paintBar($('legend-bar'), VIRIDIS, state.mode === 'template' ? grains.geometries.length : 0);
}

// Shows slider position k once its frame is loaded; a later request wins.
async function setFrame(k) {
  await ready; // the first frame sets up the scene's box and camera
  k = Math.max(0, Math.min(source.frameCount - 1, Math.round(k)));
  const token = ++loadToken, t0 = performance.now();
  try {
    const frame = await source.load(k);
    if (token !== loadToken) return;
    await apply(frame, k);
    stats.lastFrameLoadMs = performance.now() - t0;
  } catch (error) {
    fail(error);
  }
}

// --- playback ----------------------------------------------------------------
let fpsWindow = { t: 0, shown: 0 };

function countShown() {
  stats.framesShown++;
  const now = performance.now();
  if (!state.playing) {
    fpsWindow = { t: now, shown: stats.framesShown };
    return;
  }
  if (now - fpsWindow.t >= 500) {
    stats.fps = ((stats.framesShown - fpsWindow.shown) * 1000) / (now - fpsWindow.t);
    fpsWindow = { t: now, shown: stats.framesShown };
    $('perf').textContent = `${stats.fps.toFixed(0)} frames/s, frame update ${stats.lastUpdateMs.toFixed(1)} ms`;
  }
}

function setPlaying(on) {
  state.playing = on && source.frameCount > 1;
  state.acc = 0;
  $('play').innerHTML = state.playing ? '&#10074;&#10074;' : '&#9654;';
  if (state.playing && !state.loop && state.k >= source.frameCount - 1) setFrame(0);
  else if (!state.playing && state.draw === 'auto') redraw(); // shapes again when paused
}

// Each animation frame advances `speed` frames (fractions accumulate) when
// the next one is decoded; otherwise it waits for it rather than skip.
function tick() {
  requestAnimationFrame(tick);
  if (!state.playing || !state.frame) return;
  const count = source.frameCount;
  state.acc += state.speed;
  if (state.acc >= 1) {
    const step = Math.floor(state.acc);
    let next = state.k + step;
    if (next >= count) {
      if (state.loop) next %= count;
      else {
        next = count - 1;
        setPlaying(false);
      }
    }
    try {
      const frame = source.get(next);
      if (frame) {
        state.acc -= step;
        loadToken++; // supersedes a slider load still in flight
        apply(frame, next);
      } else {
        state.acc = Math.min(state.acc, Math.max(1, state.speed));
      }
    } catch (error) {
      setPlaying(false);
      fail(error);
    }
  }
  source.prefetch(state.k, PREFETCH, state.loop);
}

// --- plots -------------------------------------------------------------------
const plotEnergy = new Plot($('plot-energy'), 'energy (J)', [
  { name: 'kinetic', color: '#4fc3f7' },
  { name: 'potential', color: '#81c784' },
  { name: 'elastic', color: '#ffb74d' },
  { name: 'dissipated', color: '#e57373' },
]);
const plotContacts = new Plot($('plot-contacts'), 'contacts', [{ name: '', color: '#ce93d8' }]);
const analysisPlots = [
  ['solid_fraction', new Plot($('plot-solid-fraction'), 'solid fraction', [{ name: '', color: '#4db6ac' }])],
  ['coordination', new Plot($('plot-coordination'), 'coordination', [{ name: '', color: '#fff176' }])],
  ['pressure', new Plot($('plot-pressure'), 'pressure (Pa)', [{ name: '', color: '#f48fb1' }])],
];
const plots = [plotEnergy, plotContacts, ...analysisPlots.map(([, p]) => p)];
// The current frame's distribution of normal contact forces
// (analysis/normal_forces.csv): density against f / mean f, bins of the
// frame number in a Map; the open last bin (f / mean f beyond 5) is left out.
const plotForces = new Plot($('plot-normal-forces'), 'normal forces: density', [{ name: '', color: '#90caf9' }],
  { xName: 'f/<f>', xUnit: '' });
let forceBins = null;

function readForceBins(text) {
  const { columns: c, rows } = parseCsv(text);
  const bins = new Map();
  for (let r = 0; r < rows; r++) {
    if (!Number.isFinite(c.high[r])) continue;
    let b = bins.get(c.frame[r]);
    if (!b) bins.set(c.frame[r], (b = { x: [], density: [] }));
    b.x.push((c.low[r] + c.high[r]) / 2);
    b.density.push(c.density[r]);
  }
  return bins;
}

function showForceBins(k) {
  const b = forceBins?.get(source.index.columns.frame[k]);
  plotForces.setData(b ? b.x : [], [b ? b.density : []]);
}

async function loadTables() {
  const energy = await source.text('energy.csv');
  if (energy !== null) {
    const { columns: c } = parseCsv(energy);
    plotEnergy.setData(c.time, [c.kinetic, c.potential, c.elastic, c.dissipated]);
    plotContacts.setData(c.time, [c.contacts]);
  }
  // analysis/measures.csv exists once `gjkdem analyze` ran: a 404 is normal.
  const forces = await source.text('analysis/normal_forces.csv');
  plotForces.canvas.hidden = forces === null;
  forceBins = forces === null ? null : readForceBins(forces);
  const measures = await source.text('analysis/measures.csv');
  for (const [name, plot] of analysisPlots) {
    plot.canvas.hidden = measures === null;
    if (measures !== null) {
      const { columns: c } = parseCsv(measures);
      plot.setData(c.time, [c[name]]);
    }
  }
}

async function loadRunJson() {
  const text = await source.text('run.json');
  if (text === null) return;
  run = JSON.parse(text);
  showSummary(run, source.frameCount);
}

// Re-reads what a running run appends (the index, then the tables), every
// POLL_MS after the last reading ended.
async function poll() {
  try {
    const changed = await source.refreshIndex();
    if (changed || !run || run.status === 'running') await loadRunJson();
    if (changed) {
      $('slider').max = Math.max(0, source.frameCount - 1);
      await loadTables();
      if (state.frame && state.k >= source.frameCount && source.frameCount > 0) {
        await setFrame(source.frameCount - 1); // a resumed run cut its index back
      } else if (state.frame) {
        showTimeLabel();
      }
    }
    if (!state.frame && source.frameCount > 0) await showFirstFrame();
  } catch (error) {
    fail(error);
  }
  setTimeout(poll, POLL_MS);
}

// --- start -------------------------------------------------------------------
function fail(error) {
  console.error(error);
  $('message').textContent = String(error.message ?? error);
}

let firstFrameDrawn;
const ready = new Promise((resolve) => (firstFrameDrawn = resolve));

async function showFirstFrame() {
  const frame = await source.load(0);
  measureScene(frame);
  $('message').textContent = '';
  apply(frame, 0);
  await setPreset('iso');
  firstFrameDrawn();
  await showAddressedView();
}

// The view the page's address asks for, so that a shared link or a headless
// screenshot shows a result, not t = 0: ?frame=N (from 1, as the label
// counts) or frame=last, or ?time=T (the last frame at or before T s);
// ?color=MODE, ?draw=shapes|spheres|auto, ?camera=front|side|top|iso,
// ?chains=on. A bad value is said in the message line; the rest still apply.
async function showAddressedView() {
  const q = new URLSearchParams(window.location.search);
  const wrong = [];
  const attempt = async (key, action) => {
    if (!q.has(key)) return;
    try {
      await action(q.get(key));
    } catch (error) {
      wrong.push(`${key}=${q.get(key)}: ${error.message ?? error}`);
    }
  };
  await attempt('color', setColorMode);
  await attempt('draw', setDraw);
  await attempt('chains', (v) => {
    if (v !== 'on' && v !== 'off') throw new Error('on or off');
    return setChains(v === 'on');
  });
  await attempt('camera', (v) => {
    if (!['front', 'side', 'top', 'iso'].includes(v)) throw new Error('front, side, top or iso');
    return setPreset(v);
  });
  await attempt('frame', (v) => {
    const n = v === 'last' ? source.frameCount : Number(v);
    if (!Number.isInteger(n) || n < 1 || n > source.frameCount)
      throw new Error(`a frame number from 1 to ${source.frameCount}, or last`);
    return setFrame(n - 1);
  });
  await attempt('time', (v) => {
    const t = Number(v), times = source.index.columns.time ?? [];
    if (!Number.isFinite(t)) throw new Error('a time in seconds');
    let k = 0;
    while (k + 1 < times.length && times[k + 1] <= t) k++;
    return setFrame(k);
  });
  if (wrong.length) $('message').textContent = `address: ${wrong.join('; ')}`;
}

async function start() {
  let shapes;
  while (!(shapes = await source.loadShapes())) {
    $('message').textContent = 'waiting for view/shapes.bin (is the run writing its view/ folder?)';
    await new Promise((r) => setTimeout(r, POLL_MS));
  }
  await loadRunJson();
  grains = new Grains(scene, shapes);
  source.onShapes = (more) => grains.addTemplates(more); // fragments of grains that broke
  setAxes(run?.scene?.simulation?.gravity);
  camera.up.copy(axes.up); // OrbitControls takes its up axis when made
  controls = new OrbitControls(camera, canvas);
  controls.addEventListener('change', render);
  paintBar($('chain-bar'), CHAINS);
  paintLegendBar();
  $('message').textContent = 'waiting for frames...';
  await poll();
  requestAnimationFrame(tick);
}

// --- controls ------------------------------------------------------------------
// How free grains are drawn: 'shapes', 'spheres', or 'auto' (spheres while
// playing big frames).
function setDraw(mode) {
  if (!['shapes', 'spheres', 'auto'].includes(mode)) throw new Error(`unknown drawing ${mode}`);
  state.draw = $('draw').value = mode;
  return redraw();
}

// A channel's colouring mode in the menu, once.
function offerChannel(name) {
  const select = $('color-mode'), value = CHANNEL_MODE + name;
  if ([...select.options].some((o) => o.value === value)) return;
  const option = document.createElement('option');
  option.value = value;
  option.textContent = name.replaceAll('_', ' ');
  select.append(option);
}

// Each channel of a frame's channel block becomes a colouring mode.
function offerChannels(frame) {
  for (const name of Object.keys(frame.channels)) offerChannel(name);
}

// A channel may be asked for before a frame that has it is shown (an
// address, a run that gains it later): its mode shows zeros until then.
function setColorMode(mode) {
  const channel = mode.startsWith(CHANNEL_MODE) && /^[a-z0-9_]+$/.test(mode.slice(CHANNEL_MODE.length));
  if (!modeInfo(mode, state.frame) && !channel) throw new Error(`unknown colour mode ${mode}`);
  if (channel) offerChannel(mode.slice(CHANNEL_MODE.length));
  state.mode = $('color-mode').value = mode;
  paintLegendBar();
  return redraw();
}

// Chains on fade the grains so that the chains inside the pack show; off
// makes them opaque again (the opacity slider can change either).
function setChains(on, threshold = state.threshold) {
  if (on !== state.chains) setOpacity(on ? 0.2 : 1);
  state.chains = $('chains').checked = on;
  state.threshold = threshold;
  $('threshold').value = threshold;
  $('threshold-value').textContent = `${Math.round(threshold * 100)}% of max`;
  return redraw();
}

function bondsBroken(frame) {
  let broken = 0;
  for (let b = 0; b < frame.bonds; b++) broken += frame.bondIntact[b] ? 0 : 1;
  return broken;
}

function setBonds(on) {
  state.bonds = $('bonds').checked = on;
  return redraw();
}

function setOpacity(opacity) {
  $('opacity').value = opacity;
  grains?.setOpacity(opacity);
}

$('color-mode').addEventListener('change', (e) => setColorMode(e.target.value));
$('draw').addEventListener('change', (e) => setDraw(e.target.value));
$('chains').addEventListener('change', (e) => setChains(e.target.checked));
$('bonds').addEventListener('change', (e) => setBonds(e.target.checked));
$('threshold').addEventListener('input', (e) => setChains(state.chains, Number(e.target.value)));
$('opacity').addEventListener('input', (e) => {
  setOpacity(Number(e.target.value));
  render();
});
$('slider').addEventListener('input', (e) => setFrame(Number(e.target.value)));
$('play').addEventListener('click', () => setPlaying(!state.playing));
$('speed').addEventListener('change', (e) => (state.speed = Number(e.target.value)));
$('loop').addEventListener('change', (e) => (state.loop = e.target.checked));
$('presets').addEventListener('click', (e) => e.target.dataset.preset && controls && setPreset(e.target.dataset.preset));
window.addEventListener('keydown', (e) => {
  if (e.target !== document.body || !state.frame) return;
  if (e.key === ' ') setPlaying(!state.playing);
  else if (e.key === 'ArrowRight') setFrame(state.k + 1);
  else if (e.key === 'ArrowLeft') setFrame(state.k - 1);
  else return;
  e.preventDefault();
});
$('threshold-value').textContent = `${Math.round(state.threshold * 100)}% of max`;

// Screen rectangle (CSS pixels of the 3D view) around the free bodies' centres.
function grainBox() {
  const f = state.frame, v = new THREE.Vector3(), box = { x0: Infinity, y0: Infinity, x1: -Infinity, y1: -Infinity };
  const { clientWidth: w, clientHeight: h } = canvas;
  for (let i = 0; i < f.n; i++) {
    if (f.flags[i] & 1) continue;
    v.fromArray(f.position, 3 * i).project(camera);
    const x = ((v.x + 1) / 2) * w, y = ((1 - v.y) / 2) * h;
    box.x0 = Math.min(box.x0, x);
    box.x1 = Math.max(box.x1, x);
    box.y0 = Math.min(box.y0, y);
    box.y1 = Math.max(box.y1, y);
  }
  return box;
}

// The test hook: deterministic control of the page from tests and benchmarks.
window.gjkdemViewer = {
  ready,
  get frameCount() {
    return source.frameCount;
  },
  get currentFrame() {
    return state.k;
  },
  get bodyCount() {
    return state.frame ? state.frame.n : 0;
  },
  get templateCount() {
    return grains ? grains.geometries.length : 0;
  },
  get chainsShown() {
    return state.chains ? chains.shown : 0;
  },
  get bondsShown() {
    return state.bonds && bonds.lines.visible ? { holding: bonds.intact, broken: bonds.broken } : null;
  },
  get periodicCell() {
    return cell?.visible ? { min: cell.geometry.boundingBox.min.toArray(), max: cell.geometry.boundingBox.max.toArray() } : null;
  },
  grainBox,
  stats,
  setFrame,
  setColorMode,
  setDraw,
  setChains,
  setBonds,
  setPreset,
  play: setPlaying,
  setSpeed: (s) => (state.speed = $('speed').value = s),
  setLoop: (on) => (state.loop = $('loop').checked = on),
  clearCache: () => source.clear(),
};

start().catch(fail);
