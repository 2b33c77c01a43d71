// The 3D view (web/js/view3d.js) in headless Chromium (WebGL through
// SwiftShader) against a real `rrlab serve`, on a small page of its own
// (written by the test, not stored under web/), through the shared harness
// (tests/web/harness.mjs): 17_chen_sim2_spatial16_window renders in WebGL (a
// context, pixels that are not all background), the picture changes while the
// run plays, dragging an obstacle moves the server's obstacle (an `obstacle`
// event), overlays, a compare lane and placing draw without error; a mesh
// obstacle (43_urdf_iiwa14_mesh_obstacle's torus hoop) draws from the
// snapshot's triangles and drags like the others. Prints the
// frame rate and where a draw's time goes. Screenshots of the view go to
// $RRLAB_SCREENSHOTS (default /tmp/rrlab-screens) as view3d-*.png;
// RRLAB_VIEW3D_GALLERY=1 adds the dh and spatial_xz scenarios.
// Usage: node view3d_test.mjs   (exit 0 on success)
import { join } from 'node:path';
import { suite, check, eventually, screenshotDir, stopIfLive, drag } from './harness.mjs';

// The page under test: the view alone, fed by a live run's WebSocket; a drag
// is sent as the page will (PUT, at most every 50 ms, and at release).
const HARNESS = `<!doctype html>
<html lang="en"><head><meta charset="utf-8"><title>view3d</title>
<link rel="icon" href="data:,">
<script type="importmap">{"imports": {"three": "/node_modules/three/build/three.module.js",
  "three/addons/": "/node_modules/three/examples/jsm/"}}</script>
<link rel="stylesheet" href="/css/view3d.css">
<style>body { margin: 0; background: #fff; } #view { width: 960px; height: 640px; }</style>
</head><body><div id="view"></div>
<script type="module">
import { View3D } from '/js/view3d.js';
const view = new View3D(document.getElementById('view'));
const harness = window.harness = { view, frames: 0, drawn: 0, puts: 0, run: null, errors: [] };
harness.start = async (scenario, rate) => {
  const response = await fetch('/api/runs', { method: 'POST', headers: { 'Content-Type': 'application/json' },
    body: JSON.stringify({ scenario, mode: 'live', rate }) });
  const run = await response.json();
  harness.run = run.id;
  const socket = new WebSocket('ws://' + location.host + run.ws);
  socket.onmessage = (event) => {
    const message = JSON.parse(event.data);
    // a paused run answers an input with a snapshot that carries its latest frame
    if (message.type === 'snapshot') { harness.snapshot = message; view.setSnapshot(message); if (message.frame) harness.frame = message.frame; }
    else if (message.type === 'frame') { harness.frames += 1; harness.frame = message; view.setFrame(message); }
  };
  harness.socket = socket;
  return run.id;
};
let lastPut = 0;
view.onObstacleDrag = (index, position, phase) => {
  const now = performance.now();
  if (phase === 'move' && now - lastPut < 50) return;
  lastPut = now;
  const id = harness.snapshot.obstacles[index].id;
  harness.puts += 1;
  fetch('/api/runs/' + harness.run + '/obstacles/' + encodeURIComponent(id), { method: 'PUT',
    headers: { 'Content-Type': 'application/json' }, body: JSON.stringify({ position }) });
};
// Colour samples of the drawing buffer, read right after a forced draw.
harness.sample = () => {
  view.dirty = true;
  view.render();
  const gl = view.renderer.getContext();
  const w = gl.drawingBufferWidth, h = gl.drawingBufferHeight, pixel = new Uint8Array(4);
  let coloured = 0, total = 0;
  const colours = new Set();
  for (let y = 8; y < h; y += 16) for (let x = 8; x < w; x += 16) {
    gl.readPixels(x, y, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, pixel);
    total += 1;
    if (pixel[0] < 245 || pixel[1] < 245 || pixel[2] < 245) coloured += 1;
    colours.add(pixel.join());
  }
  return { webgl2: gl instanceof WebGL2RenderingContext, coloured, total, colours: colours.size };
};
// Where a draw's time goes: the view's update, three's render calls, the
// labels and axes, and the GPU finishing (a one-pixel read waits for it).
harness.profile = (count) => {
  const gl = view.renderer.getContext(), pixel = new Uint8Array(4), sum = [0, 0, 0, 0];
  for (let i = 0; i < count; ++i) {
    const t0 = performance.now();
    view.applyFrame();
    const t1 = performance.now();
    view.renderer.clear();
    view.renderer.render(view.scene, view.camera);
    const t2 = performance.now();
    view.axesGizmo.render(view.renderer);
    view.labels.render(view.scene, view.camera);
    const t3 = performance.now();
    gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, pixel);
    const t4 = performance.now();
    sum[0] += t1 - t0; sum[1] += t2 - t1; sum[2] += t3 - t2; sum[3] += t4 - t3;
  }
  return sum.map((s) => s / count);
};
(function loop() { if (view.render()) harness.drawn += 1; requestAnimationFrame(loop); })();
</script></body></html>`;


// The harness page is written into a page already at the server's origin, so
// that its modules, fetches and WebSocket are same-origin (a page served by
// page.route has no address, and Chromium's local-network checks block its socket).
// `pause`: pause the run once frames arrive, so that a test acting on it finds
// it live however slow the machine is (scenario 43 ends after 4 s at 1x).
async function open(t, scenario, pause = false) {
  await t.page.setViewportSize({ width: 980, height: 660 });
  await t.page.route('**/favicon.ico', (route) => route.fulfill({ status: 204 }));  // the JSON page has no icon link
  await t.page.goto(t.base + '/api/health');
  await t.page.setContent(HARNESS);
  await t.page.waitForFunction(() => window.harness);
  const runId = await t.page.evaluate((s) => window.harness.start(s, 1), scenario);
  await t.page.waitForFunction(() => window.harness.frames >= 3);
  if (pause) {
    await t.post(`/api/runs/${runId}/control`, { action: 'pause' });
    await eventually(async () => (await t.get(`/api/runs/${runId}`)).status === 'paused', 'the run to pause');
  }
  return runId;
}
// The view has drawn what it was given (its render loop found nothing new),
// and, with `trace`, the end-effector trace has that many segments.
const drawn = (t, trace = 0) => eventually(() => t.page.evaluate((n) => {
  const view = window.harness.view;
  return !view.dirty && (n === 0 || (view.overlayLayer && view.overlayLayer.traceCount >= n));
}, trace), trace ? `a trace of ${trace} segments drawn` : 'the view drawn');
const shot = (t, name) => t.page.locator('#view').screenshot({ path: join(screenshotDir, `view3d-${name}.png`) });

await suite('view3d', [
  ['renders the window scenario in WebGL and plays', async (t) => {
    const runId = await open(t, '17_chen_sim2_spatial16_window');
    const sample = await t.page.evaluate(() => window.harness.sample());
    const first = await shot(t, 'chen-start');
    check(sample.webgl2, 'a WebGL 2 context');
    check(sample.coloured > 0.02 * sample.total && sample.colours > 8,
      `the canvas is not blank (${sample.coloured} of ${sample.total} samples coloured, ${sample.colours} colours)`);
    const probe = () => t.page.evaluate(() => ({ frames: window.harness.frames, stats: { ...window.harness.view.stats }, t: performance.now() }));
    const before = await probe();
    await eventually(async () => !(await shot(t, 'chen-playing')).equals(first), { message: 'the picture to change while the run plays', timeout: 60000 });
    // the rates printed below (not asserted) are measured over 3 s at least: a wait about time itself
    const rest = 3000 - ((await probe()).t - before.t);
    if (rest > 0) await t.page.waitForTimeout(rest);
    const after = await probe();
    const seconds = (after.t - before.t) / 1000, draws = after.stats.renders - before.stats.renders;
    console.log(`  while playing: ${(draws / seconds).toFixed(1)} draws/s for ${((after.frames - before.frames) / seconds).toFixed(1)} frames/s received, `
      + `render() ${((after.stats.totalMs - before.stats.totalMs) / Math.max(1, draws)).toFixed(1)} ms mean (CPU side)`);
    check(draws > 0, 'the view draws while frames arrive');
    const [update, draw, extras, gpu] = await t.page.evaluate(() => window.harness.profile(20));
    console.log(`  one draw: update ${update.toFixed(2)} ms, three render calls ${draw.toFixed(2)} ms, `
      + `axes gizmo and labels ${extras.toFixed(2)} ms, GPU finish ${gpu.toFixed(2)} ms (SwiftShader)`);
    const bench = await t.page.evaluate(() => new Promise((done) => {
      const view = window.harness.view, start = performance.now(), stats0 = { ...view.stats };
      (function force() {
        view.dirty = true;
        if (performance.now() - start < 2000) return requestAnimationFrame(force);
        done((view.stats.renders - stats0.renders) / ((performance.now() - start) / 1000));
      })();
    }));
    console.log(`  redrawing at every animation frame: ${bench.toFixed(1)} fps`);
    await stopIfLive(t, runId);  // 75 s otherwise, loading the cores under the next tests
  }],

  ['dragging an obstacle moves it on the server', async (t) => {
    const runId = await open(t, '17_chen_sim2_spatial16_window', true);
    // a page point on the cube that no other obstacle hides, near its projected centre
    const block = await t.page.evaluate(() => {
      const h = window.harness, index = h.snapshot.obstacles.findIndex((o) => o.id === 'target_block');
      const centre = h.view.worldToClient(h.frame.obstacles[index]);
      for (let r = 0; r <= 30; r += 3) for (let a = 0; a < 8; ++a) {
        const at = { x: centre.x + r * Math.cos(a * Math.PI / 4), y: centre.y + r * Math.sin(a * Math.PI / 4) };
        if (h.view.obstacleAt(at.x, at.y) === index) return { index, at };
      }
      return { index, at: null };
    });
    check(block.at, 'the cube can be grabbed somewhere near its centre');
    await drag(t.page, block.at, { x: block.at.x + 40, y: block.at.y - 24 }, 8);
    check(await t.page.evaluate(() => window.harness.view.selected) === block.index, 'the grabbed obstacle is selected');
    const moves = await eventually(async () => (await t.get(`/api/runs/${runId}/events`)).filter((e) => e.kind === 'obstacle').length
      ? (await t.get(`/api/runs/${runId}/events`)).filter((e) => e.kind === 'obstacle') : null, 'an obstacle event');
    check(moves[0].payload.id === 'target_block', `the dragged obstacle is the one moved (${JSON.stringify(moves[0])})`);
    await shot(t, 'chen-dragged');
    await t.post(`/api/runs/${runId}/control`, { action: 'stop' });  // paused, so still live
  }],

  ['overlays, a compare lane and placing draw', async (t) => {
    const runId = await open(t, '17_chen_sim2_spatial16_window');
    await t.page.evaluate(() => { window.harness.view.overlays = { nearest: true, manipulability: true, method: true, ghosts: true, trace: true }; });
    await drawn(t, 20);
    await shot(t, 'chen-overlays');
    // the method's overlays, as multi_preview and the others send them (this method sends none)
    await t.page.evaluate(() => {
      const h = window.harness, f = h.frame, ee = f.ee;
      const shifted = (dy) => f.links.map((l) => l.map((v, k) => v + (k % 3 === 1 ? dy : 0)));
      h.socket.close();
      h.view.setFrame({ ...f, overlays: {
        ghosts: [], ghost_links: [shifted(-0.5), shifted(-1)],
        ellipses: [{ centre: ee, axes: [[0.5, 0, 0], [0, 0.3, 0], [0, 0, 0]] }],
        points: [[ee[0] - 1, ee[1], ee[2]], [ee[0] - 1.5, ee[1], ee[2]]],
        segments: [[[ee[0] - 1, ee[1], ee[2]], [ee[0] - 1.5, ee[1], ee[2]]]] } });
    });
    await drawn(t);
    await shot(t, 'chen-method-overlays');
    // a compare lane (this run's frame, shifted) and a click while placing
    await t.page.evaluate(() => {
      const h = window.harness, f = h.frame;
      const lane = { ...f, links: f.links.map((l) => l.map((v, k) => v + (k % 3 === 1 ? 0.6 : 0))) };
      h.view.setLanes([{ snapshot: h.snapshot, frame: lane, colour: '#8e24aa', label: 'lane 2' }]);
      h.view.placing = 'sphere';
      h.view.onPlace = (point) => { h.placed = point; };
    });
    const rect = await t.page.locator('#view').boundingBox();
    await t.page.mouse.click(rect.x + 120, rect.y + rect.height - 120);
    const placed = await t.page.evaluate(() => window.harness.placed);
    check(Array.isArray(placed) && placed.length === 3 && placed.every(Number.isFinite), `a click while placing gives a point (${placed})`);
    await shot(t, 'chen-lane');
    await t.page.evaluate(() => { const v = window.harness.view; v.placing = null; v.setLanes([]); v.resetTrace(); v.fit(); v.destroy(); });
    await stopIfLive(t, runId);  // its socket is closed; 75 s otherwise
  }],

  ['draws a mesh obstacle and drags it', async (t) => {
    const runId = await open(t, '43_urdf_iiwa14_mesh_obstacle', true);
    const hoop = await t.page.evaluate(() => {
      const h = window.harness, index = h.snapshot.obstacles.findIndex((o) => o.id === 'hoop');
      const o = h.snapshot.obstacles[index], item = h.view.obstacles.items[index];
      const position = item.mesh.geometry.getAttribute('position');
      return { index, shape: o.shape, file: o.file, vertices: o.mesh.vertices.length / 3, indices: o.mesh.triangles.length,
        drawnVertices: position.count, drawnIndices: item.mesh.geometry.index.count };
    });
    check(hoop.shape === 'mesh' && hoop.file === 'meshes/torus.obj', `the hoop is a mesh obstacle (${JSON.stringify(hoop)})`);
    check(hoop.indices === 3 * 576 && hoop.drawnIndices === hoop.indices && hoop.drawnVertices === hoop.vertices,
      `its 576 triangles are drawn (${JSON.stringify(hoop)})`);
    await t.page.evaluate(() => { window.harness.view.overlays = { nearest: true, manipulability: false, method: false, ghosts: false, trace: false }; });
    await drawn(t);
    const sample = await t.page.evaluate(() => window.harness.sample());
    check(sample.coloured > 0.02 * sample.total, `the canvas is not blank (${sample.coloured} of ${sample.total})`);
    await shot(t, 'mesh-obstacle');
    // grab the hoop's tube (its centre is a hole) and drag it
    const grip = await t.page.evaluate((index) => {
      const h = window.harness, centre = h.view.worldToClient(h.frame.obstacles[index]);
      for (let r = 0; r <= 120; r += 4) for (let a = 0; a < 16; ++a) {
        const at = { x: centre.x + r * Math.cos(a * Math.PI / 8), y: centre.y + r * Math.sin(a * Math.PI / 8) };
        if (h.view.obstacleAt(at.x, at.y) === index) return at;
      }
      return null;
    }, hoop.index);
    check(grip, 'the hoop can be grabbed');
    await drag(t.page, grip, { x: grip.x + 48, y: grip.y + 16 }, 8);
    const moves = await eventually(async () => {
      const events = (await t.get(`/api/runs/${runId}/events`)).filter((e) => e.kind === 'obstacle');
      return events.length ? events : null;
    }, 'an obstacle event');
    check(moves[0].payload.id === 'hoop', `the hoop is the one moved (${JSON.stringify(moves[0])})`);
    const moved = await eventually(async () => {
      const now = await t.page.evaluate((index) => window.harness.frame.obstacles[index], hoop.index);
      const start = await t.page.evaluate((index) => window.harness.snapshot.obstacles[index].center, hoop.index);
      return Math.hypot(now[0] - 0.8, now[1] + 0.1, now[2] - 0.4208) > 1e-3 ? { now, start } : null;
    }, 'the hoop at a new position in the frames');
    console.log(`  hoop moved to ${moved.now.map((v) => v.toFixed(3)).join(', ')}`);
    await drawn(t);
    await shot(t, 'mesh-obstacle-dragged');
    await t.post(`/api/runs/${runId}/control`, { action: 'stop' });  // paused, so still live
  }],

  ...(process.env.RRLAB_VIEW3D_GALLERY ? ['03_dh7_pose', '02_spatial_xz_reach', '23_kapoor_dm_rule'] : []).map((scenario) => [`gallery ${scenario}`, async (t) => {
    await open(t, scenario);
    await t.page.evaluate(() => { window.harness.view.overlays = { nearest: true, manipulability: true, method: true, ghosts: true, trace: true }; });
    await drawn(t, 40);
    await shot(t, scenario);
  }]),
]);
