// Failures where they happened: a failed run, opened from the run list or
// from a sweep's cell, opens paused at its first failure, marked on the
// scrubber and on every chart, with its reason written beside the marks; a
// run that passes plays from its start with no such mark.
// Usage: node failures_test.mjs   (RRLAB_BINARY, RRLAB_SCREENSHOTS, CHROMIUM)
import { suite, eventually, check } from './harness.mjs';

// What the page shows of the replay and its failure marks.
const shown = (page) => page.evaluate(() => {
  const s = window.__rrlab.session;
  const texts = (selector) => [...document.querySelectorAll(selector)].map((el) => el.textContent);
  return {
    kind: s && s.kind,
    seq: s && s.lanes[0].frame ? s.lanes[0].frame.seq : null,
    scrubber: Number(document.getElementById('scrubber').value),
    playing: window.__rrlab.replay.playing,
    address: new URLSearchParams(location.search).get('frame'),
    scrubberMarks: [...document.querySelectorAll('#replay-markers .event-failure')].map((m) => m.title),
    labels: texts('#failure-labels .failure-label'),
    charts: window.__rrlab.plots.charts.size,
    chartMarks: texts('#plots .plots-marker.event-failure .plots-failure-label'),
  };
});

// The page at frame `seq`, paused, with one failure mark on the scrubber and
// one on every chart, all saying `reason` (a RegExp).
async function pausedAtFailure(page, seq, reason) {
  return eventually(async () => {
    const s = await shown(page);
    const ok = s.kind === 'replay' && !s.playing && s.seq === seq && s.scrubber === seq && s.address === String(seq)
      && s.scrubberMarks.length === 1 && reason.test(s.scrubberMarks[0]) && s.labels.length === 1 && reason.test(s.labels[0])
      && s.charts >= 3 && s.chartMarks.length === s.charts && s.chartMarks.every((text) => reason.test(text));
    if (!ok) throw new Error(`last seen ${JSON.stringify(s)}`);
    return s;
  }, { timeout: 30000, message: `the replay paused at frame ${seq} with its failure marked ${reason}` });
}

// The label under the scrubber sits at the failure's mark.
async function labelAtMark(page) {
  const mark = await page.locator('#replay-markers .event-failure').boundingBox();
  const label = await page.locator('#failure-labels .failure-label span').boundingBox();
  const bar = await page.locator('#replay-bar').boundingBox();
  check(label.x <= mark.x + mark.width && label.x + label.width >= mark.x, `the reason is written at its mark (mark x ${mark.x}, label ${label.x}–${label.x + label.width})`);
  check(label.y > mark.y && label.y + label.height <= bar.y + bar.height, 'the reason is under the mark, inside the replay bar');
}

// The run list's Replay button of run `id`.
async function replayFromList(page, id) {
  const button = page.locator(`#runs li[data-run="${id}"] button`, { hasText: 'Replay' });
  await button.waitFor({ timeout: 15000 });
  await button.click();
}

await suite('failures', [
  ['a run that collided, opened from the run list, opens paused at its first collision, named, on the scrubber and every chart', async (t) => {
    const run = await t.post('/api/runs', { scenario: '00_demo_avoidance', method: 'pinv', mode: 'batch' });
    const frames = (await t.get(`/api/runs/${run.id}/frames?from=0&to=799`)).frames;
    const first = frames.find((f) => f.metrics.collided).seq;
    await t.page.goto(`${t.base}/`);
    await replayFromList(t.page, run.id);
    const s = await pausedAtFailure(t.page, first, new RegExp(`collision with obstacle post at ${(first * 0.01).toFixed(2)} s`));
    check(!(await t.page.evaluate(() => window.__rrlab.replay.playing)), 'it stays paused');
    await labelAtMark(t.page);
    await t.screenshot('collision');
    // the chart marks sit at the failure's time: a click on the scrubber's mark keeps the frame
    await t.page.locator('#replay-markers .event-failure').click();
    check((await shown(t.page)).scrubber === s.seq, 'the mark seeks to its frame');
    await t.page.locator('#plots .plots-chart[data-chart="distance"]').scrollIntoViewIfNeeded();
    await t.screenshot('charts');
  }],

  ['a run that lost track says by how much, against the bound', async (t) => {
    const run = await t.post('/api/runs', { scenario: '01_planar7_obstacles', method: 'dls', params: { lambda: 2 }, mode: 'batch' });
    const frames = (await t.get(`/api/runs/${run.id}/frames?from=0&to=799`)).frames;
    const first = frames.find((f) => f.metrics.task_error > 0.01);
    await t.page.goto(`${t.base}/`);
    await replayFromList(t.page, run.id);
    const s = await pausedAtFailure(t.page, first.seq, new RegExp(`tracking error [0-9.]+ cm > 1 cm at ${(first.seq * 0.01).toFixed(2)} s`));
    // the error just past the bound, with the digits that tell it from the bound
    const cm = Number(/tracking error ([0-9.]+) cm/.exec(s.labels[0])[1]);
    check(cm > 1 && Math.abs(cm - first.metrics.task_error * 100) < 0.01, `the error in centimetres (${cm}, stored ${first.metrics.task_error} m)`);
    await t.screenshot('tracking');
  }],

  ["a sweep's failed run, opened from its cell, re-simulates and opens paused at the sweep's first failure", async (t) => {
    const spec = { name: 'web-failures', scenarios: ['00_demo_avoidance'], methods: ['pinv', 'closest_point'],
      success: { max_tracking_error: 0.01, collision: false, joint_limits: true } };
    const started = await t.post('/api/sweeps?jobs=1', spec);
    await eventually(async () => (await t.get(`/api/sweeps/${started.id}`)).status === 'completed', { message: 'the sweep to finish', timeout: 60000 });
    const row = (await t.get(`/api/sweeps/${started.id}/runs?config=pinv`)).runs[0];
    check(!row.success && row.failure_mode === 'collision' && row.failure_t > 0, `pinv's run fails by a collision (${JSON.stringify(row)})`);
    await t.page.goto(`${t.base}/?sweep=${started.id}`);
    await t.page.locator('.sweep-success td.cell[data-config="pinv"]').click();
    await t.page.locator(`.sweep-runs tr[data-run="${row.run}"] .run-open`).click();
    await pausedAtFailure(t.page, Math.round(row.failure_t / 0.01), new RegExp(`collision with obstacle post at ${row.failure_t.toFixed(2)} s`));
    await labelAtMark(t.page);
    await t.screenshot('sweep-cell');
  }],

  ['a run that passes plays from its start, with no failure marked', async (t) => {
    const run = await t.post('/api/runs', { scenario: '00_demo_avoidance', method: 'closest_point', mode: 'batch' });
    await t.page.goto(`${t.base}/`);
    await replayFromList(t.page, run.id);
    await eventually(async () => { const s = await shown(t.page); return s.playing && s.seq > 10; }, 'the replay to play from its start');
    // its stored frames (the charts) and recorded inputs are loaded, and nothing is marked
    await eventually(() => t.page.evaluate(() => Object.values(window.__rrlab.plots.pointCounts()).some((n) => n === 800)), 'the charts to hold the stored run');
    const s = await shown(t.page);
    check(s.scrubberMarks.length === 0 && s.labels.length === 0 && s.chartMarks.length === 0, `no failure marked (${JSON.stringify(s)})`);
    await t.page.locator('#replay-play').click();
  }],
]);
