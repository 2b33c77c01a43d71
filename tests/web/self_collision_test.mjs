// A self-colliding arm on the page: four 1 m links whose start folds link 3
// back across link 1 (q0 = [0, 150, 150, 0] deg), the hand holding still.
// The 2D view (live and replay) and the 3D view (a spatial_xz arm folded the
// same way) mark both links of the pair as they mark an obstacle contact
// (read from the view's marks and from the pixels drawn), the metrics show
// the self distance and the pair, and the compare verdict and the run list
// name "self-collision" as the failure.
// Usage: node self_collision_test.mjs   (RRLAB_BINARY, RRLAB_SCREENSHOTS, CHROMIUM)
import { mkdtempSync, readdirSync, rmSync, symlinkSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { suite, eventually, check, sourceDir } from './harness.mjs';

const Q0 = [0, 150, 150, 0];  // deg
const LINKS = Array.from({ length: 4 }, () => ({ length: 1, radius: 0.05 }));

// The hand's place at Q0, so that the task holds the arm where it starts.
function tip() {
  let a = 0, x = 0, y = 0;
  for (const q of Q0) { a += (q * Math.PI) / 180; x += Math.cos(a); y += Math.sin(a); }
  return [x, y];
}

// The folded arm, planar or spatial_xz (the same fold, in the plane z = 1).
function folded(name, duration, kind = 'planar') {
  const [x, y] = tip();
  const robot = kind === 'planar'
    ? { kind, base: [0, 0], links: LINKS, q0: Q0 }
    : { kind, base: [0, 0, 1], links: LINKS, q0: Q0.flatMap((q) => [0, q]) };
  const point = kind === 'planar' ? [x, y] : [x, y, 1];
  return { name, dt: 0.01, duration, angle_unit: 'deg', robot,
    task: { space: kind === 'planar' ? 'xy' : 'xyz', trajectory: { type: 'polyline', points: [point, point] } } };
}

// The server's catalogue: the repository's scenarios and the short folded arm,
// which a sweep names (sweeps take catalogue scenarios only, not stored ones).
function catalogueWithFolded() {
  const dir = mkdtempSync(join(tmpdir(), 'rrlab-folded-'));
  process.on('exit', () => rmSync(dir, { recursive: true, force: true }));
  for (const entry of readdirSync(join(sourceDir, 'scenarios'))) symlinkSync(join(sourceDir, 'scenarios', entry), join(dir, entry));
  writeFileSync(join(dir, 'folded_short.json'), JSON.stringify(folded('folded_short', 0.5)));
  return dir;
}

// Lane 0's marks and, at three points (link 1 at 80 %, link 3 at 25 %, link 2
// at 50 % of its length: away from the crossing and the joints), the colour
// drawn, read from the canvas right after a forced draw.
const drawnMarks = (page) => page.evaluate(() => {
  const lane = window.__rrlab.session.lanes[0], view = lane.view, f = lane.frame;
  const at = (i, s) => { const l = f.links[i]; return [0, 1, 2].map((k) => l[k] + s * (l[k + 3] - l[k])); };
  const points = [at(0, 0.8), at(2, 0.25), at(1, 0.5)];
  view.dirty = true;
  view.render();
  if (view.arm) {  // 3D: the drawing buffer, read before the browser clears it
    const gl = view.renderer.getContext(), rect = view.renderer.domElement.getBoundingClientRect();
    const sx = gl.drawingBufferWidth / rect.width, sy = gl.drawingBufferHeight / rect.height, pixel = new Uint8Array(4);
    const colours = points.map((p) => {
      const c = view.worldToClient(p);
      gl.readPixels(Math.round((c.x - rect.left) * sx), Math.round((rect.bottom - c.y) * sy), 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, pixel);
      return [...pixel.slice(0, 3)];
    });
    return { marks: view.arm.marks, colours, metrics: f.metrics };
  }
  const ratio = window.devicePixelRatio || 1;
  const colours = points.map((p) => {
    const s = view.toScreen(p);
    return [...view.context.getImageData(Math.round(s.x * ratio), Math.round(s.y * ratio), 1, 1).data.slice(0, 3)];
  });
  return { marks: view.marks, colours, metrics: f.metrics };
});

// COLLIDED_COLOUR (#c62828), shaded or not: red well above green and blue.
const red = ([r, g, b]) => r > 80 && r > 1.8 * g && r > 1.8 * b;

async function checkPairMarked(t) {
  await t.page.uncheck('input[data-overlay=manipulability]');  // the ellipsoid would tint the links behind it
  const drawn = await eventually(async () => {
    const d = await drawnMarks(t.page);
    return d.metrics.self_collided ? d : null;
  }, 'a self-colliding frame drawn');
  check(drawn.metrics.self_link_a === 1 && drawn.metrics.self_link_b === 3 && drawn.metrics.min_self_distance < 0,
    `the frame names links 1 and 3, interpenetrating (${JSON.stringify(drawn.metrics)})`);
  check(drawn.marks.join() === 'collided,,collided,', `links 1 and 3 marked as a contact, 2 and 4 not (${drawn.marks})`);
  const [one, three, two] = drawn.colours;
  check(red(one) && red(three), `links 1 and 3 drawn red (${one}; ${three})`);
  check(!red(two), `link 2 drawn in the lane's colour (${two})`);
}

// The metrics panel's rows by name (lane 0's column).
const metricRows = (page) => page.evaluate(() => Object.fromEntries([...document.querySelectorAll('#metrics tbody tr')]
  .map((tr) => [tr.cells[0].textContent, tr.cells[1].textContent])));

async function openRun(t, body) {
  const run = await t.post('/api/runs', body);
  await t.page.goto(`${t.base}/?run=${run.id}`);
  await eventually(() => t.page.evaluate(() => { const s = window.__rrlab.session; return s && s.lanes[0].frame && s.lanes[0].view; }), 'the first frame drawn');
  return run.id;
}

await suite('self-collision', [
  ['a live planar run marks both links of the self-colliding pair, and the metrics show the self distance', async (t) => {
    const id = await openRun(t, { scenario: folded('folded_live', 600), method: 'pinv', mode: 'live', rate: 1 });
    await checkPairMarked(t);
    const rows = await eventually(async () => { const r = await metricRows(t.page); return r['self-collided'] === 'yes' ? r : null; }, 'the metrics to show the contact');
    check(Number(rows['min self distance (m)']) < 0 && rows['nearest self pair'] === '1 · 3', `self distance and pair shown (${JSON.stringify(rows)})`);
    check(rows.collided === 'no', 'no obstacle contact');
    await t.screenshot('live-2d');
    await t.post(`/api/runs/${id}/control`, { action: 'stop' });
  }],

  ['a stored run replays with the pair marked', async (t) => {
    await openRun(t, { scenario: folded('folded_batch', 0.5), method: 'pinv', mode: 'batch' });
    check(await t.page.evaluate(() => window.__rrlab.session.kind) === 'replay', 'the ended run opens as a replay');
    await checkPairMarked(t);
    await t.screenshot('replay-2d');
  }],

  ['a 3D view marks the pair of a folded spatial arm', async (t) => {
    const id = await openRun(t, { scenario: folded('folded_xz', 600, 'spatial_xz'), method: 'pinv', mode: 'live', rate: 1 });
    check(await t.page.evaluate(() => Boolean(window.__rrlab.session.lanes[0].view.arm)), 'a three.js view');
    await checkPairMarked(t);
    await t.screenshot('live-3d');
    await t.post(`/api/runs/${id}/control`, { action: 'stop' });
  }],

  ['the compare verdict and the run list name self-collision as the failure', async (t) => {
    const group = await t.post('/api/compare', { scenario: 'folded_short', methods: ['pinv', 'dls'], mode: 'batch' });
    const ids = group.runs.map((r) => r.id);
    await t.page.goto(`${t.base}/?compare=${ids.join(',')}`);
    await eventually(async () => !(await t.page.isHidden('#compare-summary')), 'the compare summary');
    const reasons = await t.page.locator('#summary-table tr.verdict-row td.fail').evaluateAll((tds) => tds.map((td) => td.title));
    // the reason alone, or with its time once the stored frames are in
    check(reasons.length === 2 && reasons.every((r) => /^self-collision( at [\d.]+ s)?$/.test(r)), `both fail by self-collision (${reasons})`);
    check((await t.page.textContent('#summary-table tr[data-row="self_collided"]')).includes('yes'), 'the summary has a self-collided row');
    check(!(await t.page.textContent('#summary-table tr[data-row="collided"]')).includes('yes'), 'and no obstacle contact');
    await t.screenshot('verdict');
    // a sweep's run in the run list, with its first failure
    const sweep = await t.post('/api/sweeps?jobs=1', { name: 'folded-sweep', scenarios: ['folded_short'], methods: ['pinv'],
      success: { max_tracking_error: 0.01, collision: false, joint_limits: true } });
    await eventually(async () => (await t.get(`/api/sweeps/${sweep.id}`)).status === 'completed', 'the sweep to finish');
    await t.page.goto(t.base + '/');
    const runs = t.page.locator('#runs details.sweep-runs[data-sweep="folded-sweep"]');
    await runs.waitFor();
    await runs.locator('summary').click();
    const verdict = await eventually(async () => (await runs.locator('li[data-run] .fail').count()) && runs.locator('li[data-run] .fail').first().textContent(), 'the sweep run\'s verdict');
    check(verdict === 'fail: self-collision at 0.00 s', `the run list names the failure (${verdict})`);
    await t.screenshot('run-list');
    await t.page.goto(`${t.base}/?sweep=${sweep.id}`);
    await t.page.waitForSelector('.sweep-success td.cell');
    const modes = await t.page.textContent('.sweep-success td.cell .modes');
    check(modes === 'self-collision 1', `the sweep's cell names the mode (${modes})`);
  }],
], { args: ['--scenarios', catalogueWithFolded()] });
