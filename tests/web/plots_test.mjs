// The dashboard's time series (web/js/plots.js) on the real page: a live
// run's charts gain points, ticking a diagnostic adds a chart with the data
// kept so far, a stored compare replays one series per lane and a click on a
// chart seeks inside the run, and 4 lanes × 20,000 stored frames stay
// responsive. Screenshots go to $RRLAB_SCREENSHOTS (default /tmp/rrlab-screens).
// Usage: node plots_test.mjs   (exit 0 on success; RRLAB_BINARY, CHROMIUM as in harness.mjs)
import { join } from 'node:path';
import { suite, eventually, check, screenshotDir, longScenario, storedLongScenario } from './harness.mjs';

const counts = (page) => page.evaluate(() => window.__rrlab.plots.pointCounts());
// Each chart's newest time: it advances while a live run plays, also once the
// chart's 10 s window is full and its point count no longer grows.
const newest = (page) => page.evaluate(() => Object.fromEntries([...window.__rrlab.plots.charts].map(([id, c]) => [id, c.u.data[0].at(-1)])));
const times = (page, id) => page.evaluate((chart) => {
  const xs = window.__rrlab.plots.charts.get(chart).u.data[0];
  return [xs[0], xs[xs.length - 1]];
}, id);
const shootPlots = (page, name) => page.locator('#plots').screenshot({ path: join(screenshotDir, `plots-${name}.png`) });

await suite('plots', [
  ['a live run fills the charts; a ticked diagnostic gets its chart', async (t) => {
    const { page } = t;
    // 01 stored for 600 s, started from the picker: still live at the Stop click however slow the machine
    const scenario = await storedLongScenario(t);
    await page.goto(`${t.base}/?scenario=${scenario}&method=gpm`);
    await eventually(() => page.evaluate((s) => document.getElementById('scenario').value === s && document.getElementById('method').value === 'gpm', scenario),
      'the scenario and method from the address');
    await page.click('#start-live');
    const first = await eventually(async () => { const c = await counts(page); return c.error > 20 && c; }, 'points in the charts');
    const start = await newest(page);
    const ids = ['error', 'distance', 'conditioning', 'step'];
    for (const id of ids) check(first[id] > 0, `the ${id} chart has points while the run plays`);
    const later = await eventually(async () => { const n = await newest(page); return ids.every((id) => n[id] > start[id]) && n; },
      `every chart to gain points (newest times ${JSON.stringify(start)})`);
    const second = await counts(page);
    console.log(`     points ${ids.map((id) => `${id} ${first[id]} → ${second[id]}`).join(', ')}; newest t ${start.error} → ${later.error}`);
    // paused for the rest (a paused run stays live): the page stands still for the clicks and screenshots
    const runId = await page.evaluate(() => window.__rrlab.session.runIds[0]);
    await t.post(`/api/runs/${runId}/control`, { action: 'pause' });
    await eventually(async () => (await t.get(`/api/runs/${runId}`)).status === 'paused', 'the run to pause');
    check(await page.locator('#plots .plots-chart').count() === 4, 'four charts before any diagnostic is ticked');

    const name = await page.locator('#plots .plots-diagnostics input').first().getAttribute('value');
    await page.check(`#plots .plots-diagnostics input[value="${name}"]`);
    const diag = await page.evaluate((n) => {
      const u = window.__rrlab.plots.charts.get(`diag:${n}`).u;
      return { points: u.data[0].length, values: u.data[1].filter((v) => v !== null && v !== undefined).length };
    }, name);
    check(diag.points > 0 && diag.values > 0, `the ${name} chart comes filled with the data kept so far`);
    // a metric of the frame field table without a chart of its own is offered too, and charted when ticked
    await page.check('#plots .plots-diagnostics input[value="metric:joint_limit_margin"]');
    const margin = await page.evaluate(() => {
      const chart = window.__rrlab.plots.charts.get('metric:joint_limit_margin');
      return chart ? chart.u.data[0].length : 0;
    });
    check(margin > 0, 'the joint_limit_margin chart comes filled from the frame field table\'s metric');
    await eventually(() => page.evaluate(() => !window.__rrlab.plots.dirty), 'the charts drawn');
    await t.screenshot('live');
    await page.setViewportSize({ width: 1400, height: 1500 });  // the whole stack of charts
    await shootPlots(page, 'live');
    await page.click('[data-action=stop]');
  }],

  ['a live compare plots one series per lane', async (t) => {
    const { page } = t;
    // 01 for 600 s: still live at the stop however slow the machine
    const group = await t.post('/api/compare', { scenario: await longScenario(t), methods: ['dls', 'gpm'], mode: 'live', rate: 1 });
    await page.goto(`${t.base}/?compare=${group.runs.map((r) => r.id).join(',')}`);
    await eventually(async () => (await counts(page)).distance > 60, 'points in the charts');
    const lanes = await page.evaluate(() => {
      const u = window.__rrlab.plots.charts.get('distance').u;
      return u.data.slice(1).map((column) => column.filter((v) => typeof v === 'number').length);
    });
    check(lanes.length === 2 && lanes.every((n) => n > 20), `each lane has its own points (${lanes.join(', ')})`);
    await t.post(`/api/runs/${group.runs[0].id}/control`, { action: 'pause' });  // the whole group: the page stands still for the screenshot
    await page.setViewportSize({ width: 1400, height: 1500 });
    await shootPlots(page, 'live-compare');
    await t.post(`/api/runs/${group.runs[0].id}/control`, { action: 'stop' });  // stops the whole group
  }],

  ['a replayed compare shows each lane; a click on a chart seeks', async (t) => {
    const { page } = t;
    const group = await t.post('/api/compare', { scenario: '03_dh7_pose', methods: ['dls', 'pinv'], mode: 'batch' });
    await page.goto(`${t.base}/?compare=${group.runs.map((r) => r.id).join(',')}`);
    await eventually(async () => (await counts(page)).error > 500, 'the whole runs plotted');
    const plotted = await counts(page);
    check(!('step' in plotted), 'no step-time chart in a replay (step times are not stored)');
    const series = await page.evaluate(() => window.__rrlab.plots.charts.get('distance').u.series.slice(1).map((s) => s.label));
    check(series.length === 2, `one series per lane (${series.join(', ')})`);
    await page.evaluate(() => {
      const plots = window.__rrlab.plots;
      const seek = plots.onSeek;
      window.__seeks = [];
      plots.onSeek = (time) => { window.__seeks.push(time); seek(time); };
    });
    const [t0, t1] = await times(page, 'distance');
    const over = page.locator('#plots .plots-chart[data-chart="distance"] .u-over');
    await over.scrollIntoViewIfNeeded();
    const box = await over.boundingBox();
    await over.click({ position: { x: box.width * 0.4, y: box.height / 2 } });
    const seeks = await page.evaluate(() => window.__seeks);
    check(seeks.length === 1, 'a click on a chart seeks');
    check(seeks[0] > t0 && seeks[0] < t1, `the seek time ${seeks[0]} lies inside the run [${t0}, ${t1}]`);
    check(Math.abs(seeks[0] - (t0 + 0.4 * (t1 - t0))) < 0.05 * (t1 - t0), 'the seek time is where the click was');
    await eventually(() => page.locator('#plots .plots-cursor').first().isVisible(), 'the replay cursor line');
    await over.hover({ position: { x: box.width * 0.7, y: box.height / 2 } });
    await eventually(() => page.evaluate(() => window.__rrlab.plots.charts.get('distance').u.cursor.left > 0), 'the cursor where the pointer is');
    await t.screenshot('replay');
    await shootPlots(page, 'replay-compare');
  }],

  ['4 lanes of 20,000 stored frames stay responsive', async (t) => {
    const { page } = t;
    await page.goto(t.base + '/');
    // the page has loaded the frame field table (the charts' metrics) before the lanes are configured
    await eventually(() => page.evaluate(() => window.__rrlab && window.__rrlab.plots && window.__rrlab.app.frameFields.length > 0),
      'the page and its frame field table');
    const ms = await page.evaluate(async () => {
      const plots = window.__rrlab.plots;
      const colours = ['#1e88e5', '#ef6c00', '#2e7d32', '#8e24aa'];
      plots.configure({ lanes: colours.map((colour, i) => ({ label: `lane ${i + 1}`, colour })), diagnosticNames: ['x'], mode: 'replay' });
      const start = performance.now();
      colours.forEach((c, i) => {
        const frames = [];
        for (let k = 0; k < 20000; ++k) {
          const time = k * 0.005;
          frames.push({ t: time, metrics: { task_error: 1e-3 * (1 + Math.sin(time + i)), orientation_error: 0,
            min_distance: 0.1 * Math.cos(time / 7 + i), manipulability: 0.2 + 0.1 * Math.sin(time / 3),
            condition_number: 10 ** (1 + 2 * Math.abs(Math.sin(time / 11 + i))) }, diagnostics: [k % 100] });
        }
        plots.setRun(i, { frames });
      });
      // drawn by the page's own requestAnimationFrame loop (uPlot draws in a microtask)
      await new Promise((done) => {
        const drawn = () => (plots.pointCounts().error === 20000 ? setTimeout(done, 0) : requestAnimationFrame(drawn));
        drawn();
      });
      return performance.now() - start;
    });
    // what a playing replay costs per frame (cursor line and legends) and a
    // full redraw of every chart (as on a resize)
    const cost = await page.evaluate(async () => {
      const plots = window.__rrlab.plots;
      let start = performance.now();
      for (let i = 0; i < 100; ++i) plots.setCursor(i);
      const cursor = (performance.now() - start) / 100;
      start = performance.now();
      for (const chart of plots.charts.values()) chart.u.redraw(true);
      await new Promise((done) => setTimeout(done, 0));  // uPlot draws in a microtask
      return { cursor, redraw: performance.now() - start };
    });
    // printed, not asserted: they depend on how busy the machine is (idle, 2 cores: about 0.4 s, 2 ms and 0.1 s)
    console.log(`     4 × 20,000 frames set and drawn in ${ms.toFixed(0)} ms; a cursor move ${cost.cursor.toFixed(2)} ms; redrawing all ${cost.redraw.toFixed(0)} ms`);
    check((await counts(page)).error === 20000, 'every frame is plotted');
    // the stored frames' shape is read: every point has a value, not a gap
    const gaps = await page.evaluate(() => window.__rrlab.plots.series.map((s) =>
      ['task_error', 'condition_number', 'diag:x'].map((k) => s.column(k).filter((v) => v === null).length)));
    check(gaps.flat().every((n) => n === 0), `no gaps in the stored series: ${JSON.stringify(gaps)}`);
    await shootPlots(page, 'replay-long');
  }],
]);
