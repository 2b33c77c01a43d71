// Shared harness of the browser tests: starts a real `rrlab serve --port 0`
// on a temporary database, drives Debian's chromium with playwright-core,
// fails a test on any console error, page error, failed request or 5xx
// answer, and saves screenshots under $RRLAB_SCREENSHOTS. Tests wait for
// conditions, never for a while: eventually(condition, {timeout, message}).
// Usage in a test file:
//   import { suite } from './harness.mjs';
//   await suite('dashboard', [['opens a live run', async (t) => { … }], …]);
import { spawn } from 'node:child_process';
import { mkdirSync, mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';

const here = dirname(fileURLToPath(import.meta.url));
export const sourceDir = resolve(here, '../..');
const binary = process.env.RRLAB_BINARY || join(sourceDir, 'build/cli/rrlab');
export const screenshotDir = process.env.RRLAB_SCREENSHOTS || '/tmp/rrlab-screens';

// `token`: serve with --token and send it on the helpers' requests; `args`: more serve options.
export async function startServer({ token = '', args = [] } = {}) {
  const dir = mkdtempSync(join(tmpdir(), 'rrlab-web-'));
  const serveArgs = ['serve', '--port', '0', '--db', join(dir, 'web.db'), '--web', join(sourceDir, 'web'), ...args];
  if (token) serveArgs.push('--token', token);
  const server = spawn(binary, serveArgs, { stdio: ['ignore', 'pipe', 'inherit'] });
  // on every way out: a failed start, the suite's end, an uncaught error, process.exit
  const stop = () => { process.off('exit', stop); server.kill('SIGTERM'); rmSync(dir, { recursive: true, force: true }); };
  process.on('exit', stop);
  let timer;
  const base = await new Promise((ok, fail) => {
    timer = setTimeout(() => fail(new Error('rrlab serve did not start in 20 s')), 20000);
    server.stdout.on('data', (chunk) => {
      const match = /serving (http:\/\/[^ ]+?)\/?\s/.exec(String(chunk));
      if (match) { clearTimeout(timer); ok(match[1]); }
    });
    server.on('error', fail);
    server.on('exit', (code) => fail(new Error(`rrlab serve exited with ${code}`)));
  }).catch((e) => { clearTimeout(timer); stop(); throw e; });
  const request = async (method, path, body) => {
    const headers = body ? { 'Content-Type': 'application/json' } : {};
    if (token) headers.Authorization = `Bearer ${token}`;
    const r = await fetch(base + path, { method, headers, body: body ? JSON.stringify(body) : undefined });
    const text = await r.text();
    let data;
    try { data = JSON.parse(text); } catch { data = text; }
    if (!r.ok) throw new Error(`${method} ${path}: ${r.status} ${text}`);
    return data;
  };
  return {
    base,
    get: (path) => request('GET', path),
    post: (path, body) => request('POST', path, body),
    // steps paused live run `id` n times, one step a request
    step: async (id, n) => { for (let i = 0; i < n; ++i) await request('POST', `/api/runs/${id}/control`, { action: 'step' }); },
    request,
    stop,
  };
}

// Stops live run `id` unless it has ended already (then the server answers 409).
// For the end of a test that leaves a long run going: it would load the cores
// under the tests that follow.
export async function stopIfLive(t, id) {
  try {
    await t.post(`/api/runs/${id}/control`, { action: 'stop' });
  } catch (e) {
    if (!/: 409 /.test(e.message)) throw e;
  }
}

// Catalogue scenario `name` made to last `seconds` (sent inline as `scenario`,
// under its own name): a live run of it is still live when a test acts on it,
// however slow the machine. A circle keeps its speed (more turns).
export async function longScenario(t, name = '01_planar7_obstacles', seconds = 600) {
  const scenario = await t.get(`/api/scenarios/${name}`);
  const trajectory = scenario.task && scenario.task.trajectory;
  if (trajectory && trajectory.type === 'circle') trajectory.turns = (trajectory.turns || 1) * seconds / scenario.duration;
  return { ...scenario, duration: seconds };
}

// longScenario stored (POST /api/scenarios) as `<its name>_<seconds>s`, for a
// test whose page starts the run from its picker; returns that name.
export async function storedLongScenario(t, name = '01_planar7_obstacles', seconds = 600) {
  const scenario = await longScenario(t, name, seconds);
  scenario.name = `${scenario.name}_${seconds}s`;
  await t.post('/api/scenarios', scenario).catch((e) => { if (!/: 409 /.test(e.message)) throw e; });  // 409: stored already
  return scenario.name;
}

export async function launchBrowser() {
  return chromium.launch({
    executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
    // WebGL through SwiftShader; Canvas 2D and compositing in software, which on
    // a machine without a GPU is 3–8× faster than emulating GL for them
    args: ['--headless', '--no-sandbox', '--disable-gpu-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader',
      '--disable-accelerated-2d-canvas', '--disable-gpu-compositing',
      '--no-first-run', '--disable-background-networking', '--disable-component-update', '--disable-sync',
      '--disable-quic', '--disable-background-timer-throttling', '--disable-renderer-backgrounding'],
  });
}

// The one way a browser test waits: polls condition() (sync or async) every
// 100 ms until it returns a truthy value, and returns that value; after
// `timeout` ms (15 s by default) it throws "timed out waiting for <message>",
// with the last error the condition threw. `options` is {timeout, message},
// or the message alone. A test waits for what it needs (a frame, an event on
// the server, a redraw), never for a fixed time.
export async function eventually(condition, options = {}) {
  const { timeout = 15000, message = 'a condition' } = typeof options === 'string' ? { message: options } : options;
  const end = Date.now() + timeout;
  let last;
  for (;;) {
    try { last = await condition(); if (last) return last; } catch (e) { last = e; }
    if (Date.now() >= end) break;
    await new Promise((r) => setTimeout(r, 100));
  }
  throw new Error(`timed out waiting for ${message}${last instanceof Error ? `: ${last.message}` : ''}`);
}

// Resolves once the page has drawn `count` more animation frames: whatever
// its render loop would do on its own (a camera coasting, a redraw) it has
// had the frames to do.
export const animationFrames = (page, count = 2) => page.evaluate((n) => new Promise((resolve) => {
  const next = () => (n-- <= 0 ? resolve(true) : requestAnimationFrame(next));
  requestAnimationFrame(next);
}), count);

// A mouse drag from `from` to `to` ({x, y}, page pixels) in `steps` moves;
// each move is dispatched and handled by the page before the next is sent.
export async function drag(page, from, to, steps = 8) {
  await page.mouse.move(from.x, from.y);
  await page.mouse.down();
  await page.mouse.move(to.x, to.y, { steps });
  await page.mouse.up();
}

export function check(condition, message) {
  if (!condition) throw new Error(message);
}

// Runs the named tests, each in its own page on one server and browser.
// Prints one line per test and the closing `N passed, M failed`; exits 1 on failure.
// `options`: startServer's ({ token, args }).
export async function suite(name, tests, options = {}) {
  mkdirSync(screenshotDir, { recursive: true });
  const server = await startServer(options);
  let browser = null;
  const only = process.env.RRLAB_WEB_ONLY;
  let passed = 0, failed = 0;
  try {
    browser = await launchBrowser();
    for (const [title, body] of tests) {
      if (only && !title.includes(only)) continue;
      const page = await browser.newPage({ viewport: { width: 1400, height: 900 } });
      const errors = [];
      const refusals = [];
      const inFlight = new Set();  // the page's requests without an answer yet (a body the page never reads is not waited for)
      page.on('request', (r) => inFlight.add(r));
      page.on('pageerror', (e) => errors.push(`page error: ${e.message}`));
      page.on('console', (m) => { if (m.type() === 'error') errors.push(`console error: ${m.text()}`); });
      page.on('requestfailed', (r) => {
        inFlight.delete(r);
        const failure = r.failure() ? r.failure().errorText : '';
        if (!page.isClosed() && failure !== 'net::ERR_ABORTED') errors.push(`request failed: ${r.url()} ${failure}`);
      });
      page.on('response', (r) => {
        inFlight.delete(r.request());
        if (r.status() >= 500) errors.push(`server error ${r.status()}: ${r.url()}`);
        else if (r.status() >= 400) refusals.push(`${r.status()} ${r.request().method()} ${r.url()}`);  // which answer a console error names
      });
      const slug = `${name}-${title}`.replace(/[^a-z0-9]+/gi, '-').toLowerCase();
      let shots = 0;
      const t = {
        page, ...server, errors,
        screenshot: async (label) => {
          const file = join(screenshotDir, `${slug}-${++shots}${label ? `-${label}` : ''}.png`);
          await page.screenshot({ path: file });
          return file;
        },
      };
      const started = Date.now();
      try {
        await body(t);
        // every request the page made is answered (a failure or a 5xx is in `errors`) and it has drawn since
        await eventually(async () => inFlight.size === 0 && animationFrames(page), {
          timeout: 10000, message: `the page's last requests to be answered (in flight at the end: ${[...inFlight].map((r) => r.url()).join(', ')})` });
        if (errors.length) throw new Error(`errors in the page:\n  ${errors.join('\n  ')}${refusals.length ? `\n  (the 4xx answers: ${refusals.join(', ')})` : ''}`);
        passed++;
        console.log(`ok   ${name}: ${title} (${((Date.now() - started) / 1000).toFixed(1)} s)`);
      } catch (e) {
        failed++;
        console.log(`FAIL ${name}: ${title}: ${e.message}`);
        await t.screenshot('failure').catch(() => {});
      } finally {
        await page.close().catch(() => {});
      }
    }
  } finally {
    try {
      if (browser) await browser.close();
    } finally {
      server.stop();
    }
  }
  console.log(`${passed} passed, ${failed} failed`);
  process.exit(failed ? 1 : 0);
}

// Helpers that read the page's state (window.__rrlab, see web/js/main.js).
export const pageState = {
  lane: (page, i = 0) => page.evaluate((index) => {
    const s = window.__rrlab.session;
    const lane = s && s.lanes[index];
    return lane && lane.frame ? { runId: lane.runId, step: lane.frame.step, seq: lane.frame.seq, q: lane.frame.q, target: lane.frame.target, obstacles: lane.frame.obstacles, method: lane.snapshot && lane.snapshot.method, status: lane.frame.status } : null;
  }, i),
  // Client coordinates of a world point in lane i's view.
  toClient: (page, point, i = 0) => page.evaluate(([p, index]) => window.__rrlab.session.lanes[index].view.worldToClient(p), [point, i]),
};
