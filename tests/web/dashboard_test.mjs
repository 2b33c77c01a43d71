// Drives the dashboard in headless Chromium against a real `rrlab serve`:
// start a live run, steer the joystick with the keyboard, drag an obstacle,
// move a parameter slider; every input must arrive as a stored event.
// Usage: node dashboard_test.mjs [path/to/rrlab]   (exit 0 on success)
import { spawn } from 'node:child_process';
import { mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import assert from 'node:assert/strict';
import { chromium } from 'playwright-core';

const binary = process.argv[2] || 'build/server/rrlab';
const dir = mkdtempSync(join(tmpdir(), 'rrlab-web-'));
const server = spawn(binary, ['serve', '--port', '0', '--db', join(dir, 'web.db')], { stdio: ['ignore', 'pipe', 'inherit'] });
const base = await new Promise((resolve, reject) => {
  server.stdout.on('data', (chunk) => {
    const match = /serving (http:\/\/[^ ]+)\//.exec(String(chunk));
    if (match) resolve(match[1]);
  });
  server.on('exit', (code) => reject(new Error(`rrlab serve exited with ${code}`)));
});
const get = async (path) => (await fetch(base + path)).json();

const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
  args: ['--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
    '--disable-background-networking', '--disable-component-update', '--disable-sync'],
});
let failed = false;
try {
  const page = await browser.newPage({ viewport: { width: 1500, height: 900 } });
  const errors = [];
  page.on('pageerror', (e) => errors.push(String(e)));
  page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
  await page.goto(base + '/');
  await page.waitForSelector('#scenario option', { state: 'attached' });
  assert.ok((await page.locator('#method option').count()) > 6, 'methods listed');

  await page.selectOption('#scenario', '04_planar7_joystick');
  await page.click('#start-live');
  await page.waitForFunction(() => /step \d+ · running/.test(document.getElementById('status').textContent));
  const runId = Number((await page.textContent('#run-id')).replace('#', ''));

  // joystick from the keyboard
  await page.keyboard.down('ArrowUp');
  await page.waitForTimeout(300);
  await page.keyboard.up('ArrowUp');

  // a slider: the method's first numeric parameter
  const slider = page.locator('.param input[type=range]').first();
  await slider.fill('0.4');
  await slider.dispatchEvent('change');

  // drag the obstacle "box" from its screen position
  const frame = await get(`/api/runs/${runId}/frames?from=0&to=0`);
  assert.ok(frame.frames.length === 1);
  const snapshot = await get('/api/scenarios/04_planar7_joystick');
  const box = snapshot.obstacles.find((o) => o.id === 'box');
  const centre = box.points.reduce((a, p) => [a[0] + p[0] / box.points.length, a[1] + p[1] / box.points.length], [0, 0]);
  const screen = await page.evaluate(([x, y]) => {
    const canvas = document.getElementById('view');
    const rect = canvas.getBoundingClientRect();
    // the view fits the model's reach: read its transform from a probe point
    return window.__rrlabView ? window.__rrlabView.toScreenClient(x, y, rect) : null;
  }, centre);
  assert.ok(screen, 'the view exposes its transform for tests');
  await page.mouse.move(screen.x, screen.y);
  await page.mouse.down();
  for (let i = 1; i <= 8; ++i) { await page.mouse.move(screen.x + 6 * i, screen.y - 6 * i); await page.waitForTimeout(70); }
  await page.mouse.up();
  await page.waitForTimeout(300);

  const kinds = new Set((await get(`/api/runs/${runId}/events`)).map((e) => e.kind));
  assert.ok(kinds.has('joystick'), 'joystick events stored');
  assert.ok(kinds.has('params'), 'parameter event stored');
  assert.ok(kinds.has('obstacle'), 'obstacle drag stored');
  assert.deepEqual(errors, [], 'no errors in the page');
  await page.click('[data-action=stop]');
  console.log('dashboard test: ok');
} catch (e) {
  failed = true;
  console.error('dashboard test: FAILED:', e.message);
} finally {
  await browser.close();
  server.kill('SIGTERM');
  rmSync(dir, { recursive: true, force: true });
}
process.exit(failed ? 1 : 0);
