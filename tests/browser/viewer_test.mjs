// Browser test of the viewer page (web/): serves a run folder with
// `gjkdem view RUN --port 0`, opens the page in headless Chromium and checks
// that it loads cleanly, that the slider, the colouring modes, drawing grains
// as spheres and the force chains change the picture, and that the plots draw and follow the slider.
// Screenshots go to the artifacts folder, named by check.
//
//   node tests/browser/viewer_test.mjs --gjkdem BIN --run DIR --artifacts DIR [--live-scene SCENE] [--periodic-scene SCENE] [--breakage-scene SCENE] [--bonded-scene SCENE] [--channel-scene SCENE] [--bench] [--chromium PATH]
//
// --live-scene also opens a run of SCENE that is still going (stopped, then
// resumed beside the open page) and checks that the page follows it;
// --periodic-scene SCENE, that a periodic world's cell is drawn;
// --breakage-scene SCENE, that fragments of grains that break are drawn as
// the run adds them; with --bonded-scene SCENE, that a bonded assembly's
// bonds are drawn, broken ones apart; --channel-scene SCENE, that the frames'
// channels (applied loads) are colouring modes.
//
// --bench measures instead (for a big run): page open to first frame drawn,
// one uncached frame's fetch + decode + draw, and frames per second while
// playing, from an empty cache and with every frame decoded; printed as one
// line of JSON.
// Exit status: 0 passed, 1 failed, 77 skipped (no playwright-core or Chromium).
import { spawn, spawnSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import { createRequire } from 'node:module';
import path from 'node:path';

const args = { chromium: '/usr/bin/chromium', bench: false };
for (let i = 2; i < process.argv.length; i++) {
  const name = process.argv[i].replace(/^--/, '');
  if (name === 'bench') args.bench = true;
  else args[name] = process.argv[++i];
}
if (!args.gjkdem || !args.run || (!args.artifacts && !args.bench)) {
  console.error('usage: viewer_test.mjs --gjkdem BIN --run DIR --artifacts DIR [--bench] [--chromium PATH]');
  process.exit(2);
}

let chromium;
try {
  ({ chromium } = createRequire(new URL('../../web/package.json', import.meta.url))('playwright-core'));
} catch {
  console.log('SKIP: playwright-core is not installed (run `npm install` in web/)');
  process.exit(77);
}
if (!fs.existsSync(args.chromium)) {
  console.log(`SKIP: no Chromium at ${args.chromium}`);
  process.exit(77);
}
if (args.artifacts) fs.mkdirSync(args.artifacts, { recursive: true });

let server, liveServer, browser;
const failures = [];
const check = (ok, what) => {
  console.log(`${ok ? 'ok  ' : 'FAIL'} ${what}`);
  if (!ok) failures.push(what);
};
async function finish(code) {
  await browser?.close().catch(() => {});
  server?.kill();
  liveServer?.kill();
  process.exit(code);
}
setTimeout(() => {
  console.error('FAIL: the test took more than 180 s');
  finish(1);
}, 180_000).unref();

// `gjkdem view` prints "gjkdem view: serving OUT at http://127.0.0.1:PORT/".
function serve(run) {
  const proc = spawn(args.gjkdem, ['view', run, '--port', '0'], { stdio: ['ignore', 'pipe', 'inherit'] });
  const url = new Promise((resolve, reject) => {
    let text = '';
    const timer = setTimeout(() => reject(new Error(`gjkdem view printed no address in 10 s (got: ${JSON.stringify(text)})`)), 10_000);
    proc.stdout.on('data', (chunk) => {
      text += chunk;
      const found = text.match(/http:\/\/127\.0\.0\.1:\d+\//);
      if (found) {
        clearTimeout(timer);
        resolve(found[0]);
      }
    });
    proc.on('exit', (code) => reject(new Error(`gjkdem view exited (${code}) before serving`)));
  });
  return { proc, url };
}

function startServer() {
  const s = serve(args.run);
  server = s.proc;
  return s.url;
}

// Pixels that differ (any channel by more than 8) between two PNGs, inside
// `rect` (CSS pixels; the whole image when absent). Decoded by the page.
function differingPixels(page, a, b, rect = null) {
  return page.evaluate(
    async ({ a, b, rect }) => {
      const decode = async (base64) => {
        const bitmap = await createImageBitmap(new Blob([Uint8Array.from(atob(base64), (c) => c.charCodeAt(0))], { type: 'image/png' }));
        const ctx = new OffscreenCanvas(bitmap.width, bitmap.height).getContext('2d');
        ctx.drawImage(bitmap, 0, 0);
        return ctx.getImageData(0, 0, bitmap.width, bitmap.height);
      };
      const [p, q] = await Promise.all([decode(a), decode(b)]);
      const r = rect ?? { x0: 0, y0: 0, x1: p.width, y1: p.height };
      let count = 0;
      for (let y = Math.max(0, Math.floor(r.y0)); y < Math.min(p.height, Math.ceil(r.y1)); y++) {
        for (let x = Math.max(0, Math.floor(r.x0)); x < Math.min(p.width, Math.ceil(r.x1)); x++) {
          const o = 4 * (y * p.width + x);
          if (Math.abs(p.data[o] - q.data[o]) > 8 || Math.abs(p.data[o + 1] - q.data[o + 1]) > 8 || Math.abs(p.data[o + 2] - q.data[o + 2]) > 8) count++;
        }
      }
      return count;
    },
    { a: a.toString('base64'), b: b.toString('base64'), rect },
  );
}

// Pixels of a 2D canvas that are not its background colour (its top-left pixel).
const inkedPixels = (page, id) =>
  page.evaluate((id) => {
    const c = document.getElementById(id), d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    let count = 0;
    for (let o = 0; o < d.length; o += 4) if (d[o] !== d[0] || d[o + 1] !== d[1] || d[o + 2] !== d[2]) count++;
    return count;
  }, id);

const canvasData = (page, id) => page.evaluate((id) => document.getElementById(id).toDataURL('image/png').split(',')[1], id).then((b) => Buffer.from(b, 'base64'));

async function shoot(page, name, selector = '#scene') {
  const png = await page.locator(selector).screenshot();
  if (args.artifacts) fs.writeFileSync(path.join(args.artifacts, `${name}.png`), png);
  return png;
}

// The rectangle around grain-centre boxes (from the page's grainBox()), widened to the grains' outlines.
function around(...boxes) {
  const pad = 12;
  return {
    x0: Math.min(...boxes.map((b) => b.x0)) - pad,
    y0: Math.min(...boxes.map((b) => b.y0)) - pad,
    x1: Math.max(...boxes.map((b) => b.x1)) + pad,
    y1: Math.max(...boxes.map((b) => b.y1)) + pad,
  };
}

// Moves the time slider as a user would and waits until that frame is drawn.
async function slideTo(page, k) {
  await page.locator('#slider').fill(String(k));
  await page.waitForFunction((k) => window.gjkdemViewer.currentFrame === k, k, { timeout: 20_000 });
}

async function runChecks(page, errors) {
  const frameCount = await page.evaluate(() => window.gjkdemViewer.frameCount);
  check(frameCount >= 2, `the run has frames to play (${frameCount})`);
  if (frameCount < 2) return;
  const last = frameCount - 1;
  const contacts = await page.evaluate(async () => {
    const rows = (await (await fetch('/run/view/index.csv')).text()).trim().split('\n').slice(1);
    return rows.map((r) => Number(r.split(',')[4]));
  });
  const busiest = contacts.reduce((b, c, k) => (c > contacts[b] ? k : b), last);

  // 1. A clean load.
  check(errors.length === 0, `the page loads with no console or page error${errors.length ? ':\n  ' + errors.join('\n  ') : ''}`);

  // 2. The slider moves the grains.
  await slideTo(page, 0);
  const first = await shoot(page, 'slider_first_frame');
  const box0 = await page.evaluate(() => window.gjkdemViewer.grainBox());
  await slideTo(page, last);
  const late = await shoot(page, 'slider_last_frame');
  const box1 = await page.evaluate(() => window.gjkdemViewer.grainBox());
  const moved = await differingPixels(page, first, late, around(box0, box1));
  check(moved > 100, `the slider moves the grains: ${moved} pixels differ between frames 1 and ${frameCount} where grains are`);

  // 3. Each colouring mode changes the picture (where the grains are: the legend changes too).
  await slideTo(page, busiest);
  const grains = around(await page.evaluate(() => window.gjkdemViewer.grainBox()));
  const modes = ['speed', 'force', 'template', 'id'], shots = {};
  for (const mode of modes) {
    await page.selectOption('#color-mode', mode);
    shots[mode] = await shoot(page, `color_${mode}`);
  }
  for (let i = 0; i < modes.length; i++) {
    for (let j = i + 1; j < modes.length; j++) {
      const d = await differingPixels(page, shots[modes[i]], shots[modes[j]], grains);
      check(d > 50, `colour by ${modes[i]} and by ${modes[j]} differ (${d} pixels)`);
    }
  }
  await page.selectOption('#color-mode', 'speed');

  // 3b. Grains drawn as spheres of equal volume (what big runs play with)
  // are a different picture from their shapes.
  await page.selectOption('#draw', 'spheres');
  const asSpheres = await shoot(page, 'draw_spheres');
  await page.selectOption('#draw', 'shapes');
  const asShapes = await shoot(page, 'draw_shapes');
  const drawn = await differingPixels(page, asSpheres, asShapes, grains);
  check(drawn > 50, `grains drawn as spheres and as shapes differ (${drawn} pixels)`);
  await page.selectOption('#draw', 'auto');

  // 4. Force chains, at the frame with the most contacts, against the same
  // faded grains without them.
  if (contacts[busiest] === 0) {
    console.log('note: no frame has contacts; force chains not checked');
  } else {
    await page.locator('#threshold').fill('0');
    await page.locator('#chains').check();
    const shown = await page.evaluate(() => window.gjkdemViewer.chainsShown);
    const on = await shoot(page, 'chains_on');
    const opacity = await page.locator('#opacity').inputValue();
    await page.locator('#chains').uncheck();
    await page.locator('#opacity').fill(opacity);
    const off = await shoot(page, 'chains_off');
    const d = await differingPixels(page, on, off, grains);
    check(shown > 0 && d > 20, `force chains appear at frame ${busiest + 1} (${contacts[busiest]} contacts, ${shown} chains, ${d} pixels differ)`);
    await page.locator('#chains').check();
    await page.locator('#threshold').fill('1');
    const strongest = await page.evaluate(() => window.gjkdemViewer.chainsShown);
    check(strongest >= 1 && strongest <= shown, `the threshold hides weaker chains (${strongest} of ${shown} at 100% of max)`);
    await page.locator('#chains').uncheck();
  }

  // 5. The plots draw, and their cursor follows the slider.
  for (const id of ['plot-energy', 'plot-contacts']) {
    const inked = await inkedPixels(page, id);
    check(inked > 200, `${id} draws (${inked} pixels off its background)`);
  }
  await slideTo(page, 0);
  const plotsFirst = await canvasData(page, 'plot-energy');
  const forcesFirst = await canvasData(page, 'plot-normal-forces');
  await shoot(page, 'plots_first_frame', '#plots');
  await slideTo(page, busiest);
  const plotsLast = await canvasData(page, 'plot-energy');
  const forcesLast = await canvasData(page, 'plot-normal-forces');
  await shoot(page, 'plots_busiest_frame', '#plots');
  const cursor = await differingPixels(page, plotsFirst, plotsLast);
  check(cursor > 20, `the plots' cursor follows the slider (${cursor} pixels differ)`);
  // The run was analysed (the fixture runs gjkdem analyze): the distribution
  // of normal forces is that of the frame shown, none at the first (no
  // contact), a curve at the busiest.
  const forces = await differingPixels(page, forcesFirst, forcesLast);
  check(forces > 50, `the normal force distribution follows the frame (${forces} pixels differ)`);

  await page.screenshot({ path: path.join(args.artifacts, 'page.png') });
  check(errors.length === 0, `no console or page error during the checks${errors.length ? ':\n  ' + errors.join('\n  ') : ''}`);
}

// Open time, one uncached frame, and playback rate (requestAnimationFrame-paced, 1 frame per tick, looping).
async function runBench(page, openMs) {
  const result = await page.evaluate(async () => {
    const v = window.gjkdemViewer, gl = document.getElementById('scene').getContext('webgl2');
    const drawn = () => gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, new Uint8Array(4)); // waits for the GPU
    const k = Math.min(1, v.frameCount - 1);
    v.clearCache();
    const t0 = performance.now();
    await v.setFrame(k);
    drawn();
    const frameOpenMs = performance.now() - t0;
    const updateMs = v.stats.lastUpdateMs;
    v.setLoop(true);
    v.setSpeed(1);
    await v.setFrame(0);
    v.play(true);
    await new Promise((r) => setTimeout(r, 1000)); // fill the cache, reach a steady rate
    const n0 = v.stats.framesShown, t1 = performance.now();
    await new Promise((r) => setTimeout(r, 3000));
    const fps = ((v.stats.framesShown - n0) * 1000) / (performance.now() - t1);
    v.play(false);
    // Again with every frame decoded once (the cache holds them): the drawing alone.
    for (let f = 0; f < v.frameCount; f++) await v.setFrame(f);
    v.play(true);
    await new Promise((r) => setTimeout(r, 500));
    const n1 = v.stats.framesShown, t2 = performance.now();
    await new Promise((r) => setTimeout(r, 3000));
    const fpsCached = ((v.stats.framesShown - n1) * 1000) / (performance.now() - t2);
    v.play(false);
    drawn();
    const renderer = gl.getExtension('WEBGL_debug_renderer_info');
    return { bodies: v.bodyCount, frameOpenMs, updateMs, fps, fpsCached, frames: v.frameCount, gpu: gl.getParameter(renderer ? renderer.UNMASKED_RENDERER_WEBGL : gl.RENDERER) };
  });
  const round = (x) => Math.round(x * 10) / 10;
  console.log(JSON.stringify({ bodies: result.bodies, frames: result.frames, open_ms: round(openMs), frame_open_ms: round(result.frameOpenMs), frame_update_ms: round(result.updateMs), fps: round(result.fps), fps_cached: round(result.fpsCached), gpu: result.gpu }));
}

// 6. A run still going: the page shows the frames so far, then the rest as
// they come. A run of the scene stopped after 250 steps (3 frames) is
// opened, then resumed beside the open page; the page must reach its 7
// frames and say it completed, with no error.
async function runLive(errors) {
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'gjkdem_live_'));
  try {
    const stopped = spawnSync(args.gjkdem, ['run', args['live-scene'], '--out', dir, '--quiet', '--stop-after', '250']);
    check(stopped.status === 130, `the live run stops after 250 steps (exit ${stopped.status})`);
    const live = serve(dir);
    liveServer = live.proc;
    const page = await browser.newPage({ viewport: { width: 1280, height: 800 } });
    page.on('pageerror', (e) => errors.push(`live page error: ${e.message}`));
    page.on('console', (m) => {
      const optional = /\/run\/analysis\/(measures|normal_forces)\.csv$/.test(m.location().url) && m.text().includes('404');
      if (m.type() === 'error' && !optional) errors.push(`live console: ${m.text()} (${m.location().url})`);
    });
    await page.goto(await live.url);
    await page.waitForFunction(() => window.gjkdemViewer !== undefined, null, { timeout: 20_000 });
    await page.evaluate(() => window.gjkdemViewer.ready);
    const before = await page.evaluate(() => window.gjkdemViewer.frameCount);
    const statusBefore = await page.locator('#summary').innerText();
    check(before === 3 && statusBefore.includes('interrupted'), `a stopped run shows its ${before} frames and says so`);
    const resumed = spawnSync(args.gjkdem, ['run', '--resume', dir, '--quiet']);
    check(resumed.status === 0, `the run resumes to its end (exit ${resumed.status})`);
    await page.waitForFunction(() => window.gjkdemViewer.frameCount === 7, null, { timeout: 15_000 }).catch(() => {});
    const after = await page.evaluate(() => window.gjkdemViewer.frameCount);
    await page.waitForFunction(() => document.getElementById('summary').innerText.includes('completed'), null, { timeout: 15_000 }).catch(() => {});
    const statusAfter = await page.locator('#summary').innerText();
    check(after === 7 && statusAfter.includes('completed'), `the open page follows the run to its ${after} frames and its completion`);
    await page.evaluate(() => window.gjkdemViewer.setFrame(6));
    check((await page.evaluate(() => window.gjkdemViewer.currentFrame)) === 6, 'the new frames can be shown');
    await shoot(page, 'live_completed');
    check(errors.length === 0, `no console or page error following the live run${errors.length ? ': ' + errors.join('; ') : ''}`);
    await page.close();
  } finally {
    liveServer?.kill();
    fs.rmSync(dir, { recursive: true, force: true });
  }
}

// 6b. The address opens a view: the last frame, a colouring, a camera and
// the chains from a shared link; a frame by its time; a bad value is said.
async function runAddress(url, errors) {
  const open = async (query) => {
    const page = await browser.newPage({ viewport: { width: 1280, height: 800 } });
    page.on('pageerror', (e) => errors.push(`page error (${query}): ${e.message}`));
    await page.goto(`${url}?${query}`);
    await page.waitForFunction(() => window.gjkdemViewer !== undefined, null, { timeout: 20_000 });
    await page.evaluate(() => window.gjkdemViewer.ready);
    return page;
  };
  const page = await open('frame=last&color=force&camera=top&chains=on');
  const last = (await page.evaluate(() => window.gjkdemViewer.frameCount)) - 1;
  const atLast = await page
    .waitForFunction((k) => window.gjkdemViewer.currentFrame === k, last, { timeout: 10_000 })
    .then(() => true, () => false);
  check(atLast, `?frame=last opens the last frame (${last + 1})`);
  const shown = await page.evaluate(() => ({ color: document.getElementById('color-mode').value, chains: document.getElementById('chains').checked }));
  check(shown.color === 'force', `?color=force colours by force (${shown.color})`);
  check(shown.chains === true, '?chains=on draws the force chains');
  if (args.artifacts) await page.screenshot({ path: path.join(args.artifacts, 'address-last-frame.png') });
  await page.close();
  const times = await (await fetch(`${url}run/view/index.csv`)).text().then((t) => t.trim().split('\n').slice(1).map((r) => Number(r.split(',')[1])));
  const middle = Math.floor(times.length / 2);
  const byTime = await open(`time=${times[middle]}&frame=zz`);
  const atMiddle = await byTime
    .waitForFunction((k) => window.gjkdemViewer.currentFrame === k, middle, { timeout: 10_000 })
    .then(() => true, () => false);
  check(atMiddle, `?time=${times[middle]} opens frame ${middle + 1}`);
  // The message is written once every value of the address is applied,
  // after the frame is shown: wait for it (a loaded machine was seen to
  // read the line between the two).
  await byTime
    .waitForFunction(() => document.getElementById('message').textContent.includes('address:'), null, { timeout: 10_000 })
    .catch(() => {});
  const message = await byTime.evaluate(() => document.getElementById('message').textContent);
  check(message.includes('address: frame=zz'), `a bad address value is said (${message})`);
  await byTime.close();
}

// Serves run folder `dir` (liveServer) and opens the page on it, its first
// frame drawn; page errors go to `errors` under `label`.
async function openRun(dir, label, errors) {
  const s = serve(dir);
  liveServer = s.proc;
  const page = await browser.newPage({ viewport: { width: 1280, height: 800 } });
  page.on('pageerror', (e) => errors.push(`${label} page error: ${e.message}`));
  await page.goto(await s.url);
  await page.waitForFunction(() => window.gjkdemViewer !== undefined, null, { timeout: 20_000 });
  await page.evaluate(() => window.gjkdemViewer.ready);
  return page;
}

// 7. A periodic world: its cell is drawn, as run.json's scene gives it.
async function runPeriodic(errors) {
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'gjkdem_periodic_'));
  try {
    const started = spawnSync(args.gjkdem, ['run', args['periodic-scene'], '--out', dir, '--quiet', '--stop-after', '10']);
    check(started.status === 130, `the periodic run starts (exit ${started.status})`);
    const periodic = JSON.parse(fs.readFileSync(path.join(dir, 'run.json'), 'utf8')).scene.simulation.periodic;
    const page = await openRun(dir, 'periodic', errors);
    const drawn = await page.evaluate(() => window.gjkdemViewer.periodicCell);
    const matches = drawn && ['x', 'y', 'z'].every((axis, a) =>
      !periodic[axis] || (Math.abs(drawn.min[a] - periodic[axis][0]) < 1e-6 && Math.abs(drawn.max[a] - periodic[axis][1]) < 1e-6));
    check(Boolean(matches), `the periodic cell is drawn where the scene puts it (${JSON.stringify(drawn)} for ${JSON.stringify(periodic)})`);
    await shoot(page, 'periodic_cell');
    await page.close();
  } finally {
    liveServer?.kill();
    fs.rmSync(dir, { recursive: true, force: true });
  }
}

// 8. Grains that break: a run stopped after its first split is opened, then
// resumed beside the page; frames naming the later fragments' shapes make
// the page read shapes.bin again, and the last frame draws every fragment.
async function runBreakage(errors) {
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'gjkdem_breakage_'));
  try {
    const stopped = spawnSync(args.gjkdem, ['run', args['breakage-scene'], '--out', dir, '--quiet', '--stop-after', '120']);
    check(stopped.status === 130, `the press stops after 120 steps (exit ${stopped.status})`);
    const page = await openRun(dir, 'breakage', errors);
    const templatesBefore = await page.evaluate(() => window.gjkdemViewer.templateCount);
    const resumed = spawnSync(args.gjkdem, ['run', '--resume', dir, '--quiet']);
    check(resumed.status === 0, `the press resumes to its end (exit ${resumed.status})`);
    const frames = JSON.parse(fs.readFileSync(path.join(dir, 'run.json'), 'utf8')).frames;
    await page.waitForFunction((n) => window.gjkdemViewer.frameCount === n, frames, { timeout: 15_000 }).catch(() => {});
    await page.evaluate((n) => window.gjkdemViewer.setFrame(n - 1), frames);
    const shown = await page.evaluate(() => ({ bodies: window.gjkdemViewer.bodyCount, templates: window.gjkdemViewer.templateCount }));
    check(shown.bodies === 16 && shown.templates > templatesBefore,
      `the last frame draws the 16 fragments (${shown.bodies} bodies; ${templatesBefore} then ${shown.templates} shapes)`);
    await shoot(page, 'breakage_fragments');
    check(errors.length === 0, `no page error following the fragments${errors.length ? ': ' + errors.join('; ') : ''}`);
    await page.close();
  } finally {
    liveServer?.kill();
    fs.rmSync(dir, { recursive: true, force: true });
  }
}

// 9. Bonded assemblies: a glued box dropped on a floor; the last frame
// draws its bonds, as many broken as run.json counts.
async function runBonded(errors) {
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'gjkdem_bonded_'));
  try {
    const done = spawnSync(args.gjkdem, ['run', args['bonded-scene'], '--out', dir, '--quiet']);
    check(done.status === 0, `the bonded drop runs (exit ${done.status})`);
    const info = JSON.parse(fs.readFileSync(path.join(dir, 'run.json'), 'utf8'));
    const page = await openRun(dir, 'bonded', errors);
    await page.evaluate((n) => window.gjkdemViewer.setFrame(n - 1), info.frames);
    const shown = await page.evaluate(() => window.gjkdemViewer.bondsShown);
    check(shown !== null && shown.broken === info.bonds_broken && shown.holding + shown.broken === info.bonds &&
            shown.broken > 0 && shown.holding > 0,
      `the last frame draws the bonds, ${info.bonds_broken} of ${info.bonds} broken (${JSON.stringify(shown)})`);
    await shoot(page, 'bonded_drop');
    await page.evaluate(() => window.gjkdemViewer.setBonds(false));
    check((await page.evaluate(() => window.gjkdemViewer.bondsShown)) === null, 'the bonds can be hidden');
    check(errors.length === 0, `no page error drawing bonds${errors.length ? ': ' + errors.join('; ') : ''}`);
    await page.close();
  } finally {
    liveServer?.kill();
    fs.rmSync(dir, { recursive: true, force: true });
  }
}

// 10. Channels: a frame's channel block (applied loads of a pulled ball)
// becomes colouring modes, its name and unit in the legend, its magnitude
// the colour.
async function runChannels(errors) {
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'gjkdem_channels_'));
  try {
    const done = spawnSync(args.gjkdem, ['run', args['channel-scene'], '--out', dir, '--quiet']);
    check(done.status === 0, `the pulled ball runs (exit ${done.status})`);
    const page = await openRun(dir, 'channels', errors);
    const offered = await page.evaluate(() => [...document.getElementById('color-mode').options].map((o) => o.value));
    check(offered.includes('channel:applied_force') && offered.includes('channel:applied_torque'),
      `the frame's channels are colouring modes (${offered.join(', ')})`);
    await page.selectOption('#color-mode', 'channel:applied_force');
    const legend = await page.evaluate(() => ({
      title: document.getElementById('legend-title').textContent,
      min: Number(document.getElementById('legend-min').textContent),
      max: Number(document.getElementById('legend-max').textContent),
    }));
    check(legend.title === 'applied force (N)' && legend.min === 0 && Math.abs(legend.max - 0.02) < 1e-4,
      `the legend shows the channel's name, unit and range (${JSON.stringify(legend)})`);
    await shoot(page, 'channel_applied_force');
    check(errors.length === 0, `no page error colouring by a channel${errors.length ? ': ' + errors.join('; ') : ''}`);
    await page.close();
  } finally {
    liveServer?.kill();
    fs.rmSync(dir, { recursive: true, force: true });
  }
}

try {
  const url = await startServer();
  browser = await chromium.launch({ executablePath: args.chromium, args: ['--use-gl=angle', '--use-angle=swiftshader', '--enable-unsafe-swiftshader'] });
  const page = await browser.newPage({ viewport: { width: 1280, height: 800 } });
  const errors = [];
  page.on('pageerror', (e) => errors.push(`page error: ${e.message}`));
  page.on('console', (m) => {
    // The analysis table is optional: its 404 is the one expected error.
    const optional = /\/run\/analysis\/(measures|normal_forces)\.csv$/.test(m.location().url) && m.text().includes('404');
    if (m.type() === 'error' && !optional) errors.push(`console: ${m.text()} (${m.location().url})`);
  });
  const t0 = Date.now();
  await page.goto(url);
  await page.waitForFunction(() => window.gjkdemViewer !== undefined, null, { timeout: 20_000 });
  await Promise.race([
    page.evaluate(() => window.gjkdemViewer.ready),
    new Promise((_, reject) => setTimeout(() => reject(new Error(`the first frame was not drawn in 30 s; ${errors.join('; ')}`)), 30_000)),
  ]);
  if (args.bench) await runBench(page, Date.now() - t0);
  else await runChecks(page, errors);
  if (!args.bench) await runAddress(url, errors);
  if (args['live-scene'] && !args.bench) await runLive(errors);
  if (args['periodic-scene'] && !args.bench) await runPeriodic(errors);
  if (args['breakage-scene'] && !args.bench) await runBreakage(errors);
  if (args['bonded-scene'] && !args.bench) await runBonded(errors);
  if (args['channel-scene'] && !args.bench) await runChannels(errors);
} catch (error) {
  check(false, error.stack ?? String(error));
}
if (failures.length) console.log(`${failures.length} check(s) failed`);
await finish(failures.length ? 1 : 0);
