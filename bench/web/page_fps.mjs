// The dashboard's frame rate in headless chromium (software GL), not a test:
// a live 16-DOF spatial run (three.js) and a 4-lane planar compare (Canvas 2D,
// side by side), each watched for 8 s. Prints frames per second of the page's
// requestAnimationFrame loop, the mean time spent drawing per frame (views and
// plots) and the stream's frames per second.
// Usage (from tests/web, where playwright-core is installed):
//   node ../../bench/web/page_fps.mjs
import { startServer, launchBrowser, eventually } from '../../tests/web/harness.mjs';

const server = await startServer();
const browser = await launchBrowser();

async function measure(label, path) {
  const page = await browser.newPage({ viewport: { width: 1400, height: 900 } });
  await page.goto(server.base + path);
  await eventually(() => page.evaluate(() => window.__rrlab.session && window.__rrlab.session.lanes.every((l) => l.frame && l.view)), { message: 'frames', timeout: 30000 });
  await page.waitForTimeout(1500);
  const result = await page.evaluate(async () => {
    const lanes = window.__rrlab.session.lanes;
    const seq0 = lanes.map((l) => l.frame.seq);
    const stream = { count: 0 };
    window.__rrlab.app.signals.frame.add(() => { stream.count++; });
    let frames = 0, drawing = 0, busiest = 0;
    const start = performance.now();
    await new Promise((resolve) => {
      const tick = () => {
        frames++;
        drawing += window.__rrlab.fps.renderMs;
        busiest = Math.max(busiest, window.__rrlab.fps.renderMs);
        if (performance.now() - start < 8000) requestAnimationFrame(tick); else resolve();
      };
      requestAnimationFrame(tick);
    });
    const seconds = (performance.now() - start) / 1000;
    return { fps: frames / seconds, drawMs: drawing / frames, busiestMs: busiest, streamFps: stream.count / seconds / lanes.length, steps: lanes.map((l, i) => l.frame.seq - seq0[i]) };
  });
  console.log(`${label}: ${result.fps.toFixed(1)} fps, drawing ${result.drawMs.toFixed(2)} ms/frame (max ${result.busiestMs.toFixed(1)}), stream ${result.streamFps.toFixed(1)} frames/s per lane`);
  await page.close();
}

try {
  const spatial = await server.post('/api/runs', { scenario: '17_chen_sim2_spatial16_window', mode: 'live', rate: 1 });
  await measure('16-DOF spatial (three.js)', `/?run=${spatial.id}`);
  const group = await server.post('/api/compare', { scenario: '01_planar7_obstacles', methods: ['pinv', 'dls', 'gpm', 'closest_point'], mode: 'live', rate: 1 });
  await measure('4-lane compare (Canvas 2D)', `/?compare=${group.runs.map((r) => r.id).join(',')}`);
  const group3d = await server.post('/api/compare', { scenario: '17_chen_sim2_spatial16_window', methods: ['pinv', 'dls', 'gpm', 'posture_generation'], mode: 'live', rate: 1 });
  await measure('4-lane compare, 16-DOF spatial (four three.js views)', `/?compare=${group3d.runs.map((r) => r.id).join(',')}`);
} finally {
  await browser.close();
  server.stop();
}
