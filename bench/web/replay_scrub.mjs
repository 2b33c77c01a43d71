// Scrubbing a replay in headless chromium, not a test: a 3-lane compare of
// the planar demo (800 frames a lane), first with every frame asked of the
// server's replay players (the page's old path), then drawn from the page's
// own memory (web/js/local_frames.js). Prints, for each:
//   seek: ms from a seek to every lane drawing that frame (median, max of 40
//         seeks to frames spread over the run);
//   play: distinct frames every lane drew per second while playing at 1×
//         (the run has 100 stored frames a second; the page draws at most one
//         per display frame).
//   webm: seconds to record frames 0-200 as a 1280×720 WebM at 30 frames/s
//         (the Export dialog's video: 6.7 s of video), and the ratio to real time;
// and how long the frames took to load and their size.
// Usage (from tests/web, where playwright-core is installed):
//   node ../../bench/web/replay_scrub.mjs
import { startServer, launchBrowser, eventually } from '../../tests/web/harness.mjs';

const server = await startServer();
const browser = await launchBrowser();

async function measure(label, ids, holdFrames) {
  const page = await browser.newPage({ viewport: { width: 1400, height: 900 } });
  await page.goto(server.base + '/');
  await eventually(() => page.evaluate(() => Boolean(window.__rrlab && window.__rrlab.replay)), { message: 'the page', timeout: 30000 });
  const started = Date.now();
  await page.evaluate(({ ids, holdFrames }) => {
    window.__rrlab.replay.holdFrames = holdFrames;
    window.__rrlab.app.execute({ type: 'open', ids, layout: 'side', frame: 0 });
  }, { ids, holdFrames });
  await eventually(() => page.evaluate(() => {
    const s = window.__rrlab.session;
    return s && s.kind === 'replay' && s.lanes.every((l) => l.view && l.frame && l.frame.seq === 0);
  }), { message: 'the replay at frame 0', timeout: 30000 });
  let loaded = '';
  if (holdFrames) {
    await eventually(() => page.evaluate(() => window.__rrlab.replay.local && window.__rrlab.replay.local.done), { message: 'frames in memory', timeout: 60000 });
    const bytes = await page.evaluate(() => window.__rrlab.replay.local.bytes);
    loaded = `, frames in memory after ${((Date.now() - started) / 1000).toFixed(1)} s (${(bytes / 1048576).toFixed(1)} MB)`;
  }
  const result = await page.evaluate(async () => {
    const replay = window.__rrlab.replay;
    const lanes = window.__rrlab.session.lanes;
    const waitAll = (k) => new Promise((resolve) => {
      const check = () => (lanes.every((l) => l.frame && l.frame.seq === k) ? resolve() : requestAnimationFrame(check));
      check();
    });
    const seeks = [];
    for (let i = 0; i < 40; ++i) {
      const k = (i * 373 + 17) % 800;  // spread over the run, never twice in a row
      const t0 = performance.now();
      replay.seek(k);
      await waitAll(k);
      seeks.push(performance.now() - t0);
    }
    seeks.sort((a, b) => a - b);
    replay.seek(0);
    await waitAll(0);
    replay.setPlaying(true);
    const drawn = lanes.map(() => new Set());
    const start = performance.now();
    await new Promise((resolve) => {
      const tick = () => {
        lanes.forEach((l, i) => drawn[i].add(l.frame.seq));
        if (performance.now() - start < 5000 && replay.playing) requestAnimationFrame(tick); else resolve();
      };
      requestAnimationFrame(tick);
    });
    const seconds = (performance.now() - start) / 1000;
    replay.setPlaying(false);
    const { recordVideo } = await import('./js/exports.js');
    const t0 = performance.now();
    const video = await recordVideo(window.__rrlab.session, (seq) => replay.showAndWait(seq), { from: 0, to: 200, fps: 30, width: 1280, height: 720 });
    const webm = (performance.now() - t0) / 1000;
    return { median: seeks[seeks.length >> 1], max: seeks[seeks.length - 1], fps: Math.min(...drawn.map((d) => d.size)) / seconds, webm, webmFrames: video.frames };
  });
  console.log(`${label}: seek ${result.median.toFixed(1)} ms median, ${result.max.toFixed(1)} ms max; play ${result.fps.toFixed(1)} frames/s on every lane; ` +
    `webm of ${result.webmFrames} frames ${result.webm.toFixed(1)} s (${(result.webmFrames / 30 / result.webm).toFixed(2)}× real time)${loaded}`);
  await page.close();
}

try {
  const group = await server.post('/api/compare', { scenario: '01_planar7_obstacles', methods: ['pinv', 'dls', 'gpm'], mode: 'batch' });
  const ids = group.runs.map((r) => r.id);
  await measure('3-lane replay, frames from the server', ids, false);
  await measure('3-lane replay, frames from the page', ids, true);
} finally {
  await browser.close();
  server.stop();
}
