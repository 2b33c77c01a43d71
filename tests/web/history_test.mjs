// History and links (issue 42 item 7) and a replay that shows what was
// recorded at its playhead (item 2), as a person uses them: every view with
// an address (paper, sweep, sweep cell, run, compare, a marker's frame) is a
// history entry, Back and Forward move between them and a reload shows the
// same view, while scrubbing adds no entry; a malformed address opens the
// start view. In a replay the parameter panel shows the values recorded at
// the frame on screen, says so, and follows a seek both ways; the obstacles
// and the method's name follow too.
// Usage: node history_test.mjs   (RRLAB_BINARY, RRLAB_SCREENSHOTS, CHROMIUM)
import { suite, eventually, check } from './harness.mjs';

const SPEC = {
  name: 'web-history',
  scenarios: [{ generator: 'planar_clutter', count: 2, seed: 5 }],
  methods: ['pinv', 'closest_point'],
  success: { max_tracking_error: 0.01, collision: false, joint_limits: true },
  steps: 200,
};

// What the page shows: {address, view} where view names the session or page.
const shown = (page) => page.evaluate(() => {
  const { app } = window.__rrlab;
  const s = app.session;
  let view = 'start';
  if (s) view = `${s.compare ? 'compare' : 'run'}:${s.runIds.join(',')}`;
  else if (app.page && app.page.name === 'paper') view = `paper:${app.page.key}`;
  else if (app.page && app.page.name === 'sweep') view = `sweep:${app.page.id}${app.page.cell ? `:${app.page.cell.family}:${app.page.cell.config}` : ''}`;
  return { address: location.search, view, length: history.length };
});

async function at(page, view, message) {
  return eventually(async () => {
    const s = await shown(page);
    return s.view === view ? s : null;
  }, message || `the page to show ${view}`);
}

// What the page draws for a sweep cell and a replay, not only what it holds.
const cellShown = (page, family, config) => eventually(async () => {
  const text = await page.locator('#sweep-cell h3').textContent().catch(() => '');
  return text.includes(`Runs of ${config} on ${family}`) && (await page.locator('.sweep-runs tr[data-run]').count()) > 0;
}, `the cell ${config} × ${family} listed`);
const replayAt = (page, seq) => eventually(() => page.evaluate((k) => {
  const s = window.__rrlab.session;
  return s && s.kind === 'replay' && Number(document.getElementById('scrubber').value) === k && s.lanes[0].frame && s.lanes[0].frame.seq === k;
}, seq), `the replay at frame ${seq}`);

// The parameter panel: each parameter's typed value, whether it is disabled, and the note.
const panel = (page) => page.evaluate(() => ({
  values: Object.fromEntries([...document.querySelectorAll('#params .param')].map((div) => {
    const control = div.querySelector('input[type=range], select');
    return [control.id.replace('param-', ''), Number((div.querySelector('input.typed') || control).value)];
  })),
  disabled: [...document.querySelectorAll('#params input, #params button')].every((el) => el.disabled),
  note: document.getElementById('params-recorded').hidden ? null : document.getElementById('params-recorded').textContent,
  lane: document.getElementById('params-lane').textContent,
}));

await suite('history', [
  ['Back and Forward move between paper, sweep, cell and run; a reload shows the same view', async (t) => {
    const started = await t.post('/api/sweeps?jobs=1', SPEC);
    await eventually(async () => (await t.get(`/api/sweeps/${started.id}`)).status === 'completed', { message: 'the sweep to finish', timeout: 60000 });
    const id = started.id;
    await t.page.goto(t.base);
    await eventually(() => t.page.evaluate(() => document.querySelectorAll('#papers-list li').length > 0), 'the papers listed');
    const first = await shown(t.page);
    // start → paper → sweep → cell → re-simulate: one entry each
    await t.page.locator('#papers-section summary').click();
    await t.page.locator('#papers-list li[data-paper="sezgin"] button').click();
    await at(t.page, 'paper:sezgin');
    await t.page.locator(`#sweeps li[data-sweep="${id}"] .open-sweep`).click();
    await at(t.page, `sweep:${id}`);
    await t.page.waitForSelector('.sweep-success td.cell');
    await t.page.locator('.sweep-success td.cell[data-family="planar_clutter"][data-config="closest_point"]').click();
    await at(t.page, `sweep:${id}:planar_clutter:closest_point`);
    await cellShown(t.page, 'planar_clutter', 'closest_point');
    await t.screenshot('cell');
    await t.page.locator('.sweep-runs tr[data-run] .run-open').first().click();
    const run = await eventually(() => t.page.evaluate(() => {
      const s = window.__rrlab.session;
      return s && s.kind === 'replay' && s.lanes[0].frame ? s.runIds[0] : null;
    }), 'the re-simulated run to replay');
    const last = await at(t.page, `run:${run}`);
    check(last.length === first.length + 4, `four new history entries (${first.length} → ${last.length})`);
    check(last.address.startsWith(`?run=${run}`), `the run's address (${last.address})`);

    // Back through every view, then Forward again
    const views = ['start', 'paper:sezgin', `sweep:${id}`, `sweep:${id}:planar_clutter:closest_point`, `run:${run}`];
    for (let i = views.length - 2; i >= 0; --i) {
      await t.page.goBack();
      await at(t.page, views[i], `Back to ${views[i]}`);
    }
    check((await shown(t.page)).address === first.address, 'Back at the first entry: the address the page opened with');
    check(t.page.url().startsWith(t.base), 'Back never left the app');
    for (let i = 1; i < views.length; ++i) {
      await t.page.goForward();
      await at(t.page, views[i], `Forward to ${views[i]}`);
    }
    await t.page.goBack();
    await at(t.page, `sweep:${id}:planar_clutter:closest_point`);
    await cellShown(t.page, 'planar_clutter', 'closest_point');
    // a reload shows the same cell
    await t.page.reload();
    await at(t.page, `sweep:${id}:planar_clutter:closest_point`, 'the cell after a reload');
    await cellShown(t.page, 'planar_clutter', 'closest_point');
    await t.screenshot('cell-reloaded');
    // another cell of the same sweep keeps its page; Back shows the first cell again
    await t.page.locator('.sweep-success td.cell[data-family="planar_clutter"][data-config="pinv"]').click();
    await cellShown(t.page, 'planar_clutter', 'pinv');
    await t.page.goBack();
    await cellShown(t.page, 'planar_clutter', 'closest_point');
    // a case compared across the sweep's methods: a view of its own, Back to the cell, Forward to the compare
    await t.page.locator('.sweep-runs tr[data-run] .run-compare').first().click();
    const group = await eventually(() => t.page.evaluate(() => {
      const s = window.__rrlab.session;
      return s && s.compare && s.kind === 'replay' && s.lanes.every((l) => l.frame) ? s.runIds.join(',') : null;
    }), 'the compare to replay');
    check((await shown(t.page)).address.startsWith(`?compare=${encodeURIComponent(group)}`), 'the compare\'s address');
    await t.page.goBack();
    await cellShown(t.page, 'planar_clutter', 'closest_point');
    await t.page.goForward();
    await at(t.page, `compare:${group}`);
    await eventually(() => t.page.evaluate(() => window.__rrlab.session.lanes.every((l) => l.view && l.frame)), 'the compare drawn again');
    await t.screenshot('compare-forward');
  }],
  ['a replay: scrubbing replaces its frame, a marker click is an entry of its own, Back returns to the frame before it', async (t) => {
    const run = await t.post('/api/runs', { scenario: '01_planar7_obstacles', mode: 'live', paused: true });
    const step = (n) => t.step(run.id, n);
    await step(30);
    await t.request('PATCH', `/api/runs/${run.id}/params`, { gain: 3 });
    await step(30);
    await t.post(`/api/runs/${run.id}/control`, { action: 'stop' });
    const [event] = await t.get(`/api/runs/${run.id}/events`);
    await t.page.goto(`${t.base}/?run=${run.id}&frame=0`);
    await replayAt(t.page, 0);
    const before = await shown(t.page);
    // scrubbing: keys and the scrubber move the frame, the address follows, no entry is added
    await t.page.locator('#scrubber').focus();
    for (let i = 0; i < 5; ++i) await t.page.keyboard.press('.');
    await replayAt(t.page, 5);
    await t.page.locator('#scrubber').fill('12');
    await replayAt(t.page, 12);
    const scrubbed = await eventually(async () => { const s = await shown(t.page); return s.address.includes('frame=12') ? s : null; }, 'the address at frame 12');
    check(scrubbed.length === before.length, `scrubbing added no history entry (${before.length} → ${scrubbed.length})`);
    // a marker click: an entry; Back returns to frame 12, Forward to the marker's frame
    await eventually(async () => (await t.page.locator('#replay-markers .event-marker').count()) === 1, 'the mark on the scrubber');
    await t.page.locator('#replay-markers .event-marker').click();
    await replayAt(t.page, event.seq);
    check((await shown(t.page)).length === before.length + 1, 'a marker click is one history entry');
    await t.page.goBack();
    await replayAt(t.page, 12);
    check((await shown(t.page)).view === `run:${run.id}`, 'Back stays in the same replay');
    await t.page.goForward();
    await replayAt(t.page, event.seq);
    await t.page.reload();
    await replayAt(t.page, event.seq);
    await t.screenshot('marker-reloaded');
  }],
  ['a malformed address opens the start view without an error', async (t) => {
    for (const search of ['?run=x&frame=-1', '?compare=,,0&frame=1e3', '?sweep=abc&family=f&config=c', '?family=f&config=c', '?paper=%E2%9C%97', '?run=1%00']) {
      await t.page.goto(`${t.base}/${search}`);
      await eventually(() => t.page.evaluate(() => document.querySelectorAll('#papers-list li').length > 0), `the page to open ${search}`);
      await at(t.page, 'start', `the start view for ${search}`);
      // the page still works: a paper opens and Back returns to the address
      await t.page.locator('#papers-section summary').click();
      await t.page.locator('#papers-list li[data-paper="chen"] button').click();
      await at(t.page, 'paper:chen');
      await t.page.goBack();
      await at(t.page, 'start', `Back to ${search}`);
    }
    check(t.errors.length === 0, `no console error: ${t.errors.join('; ')}`);
  }],
  ['a replay shows the parameters, obstacles and method recorded at the playhead, and a seek back restores them', async (t) => {
    const run = await t.post('/api/runs', { scenario: '01_planar7_obstacles', mode: 'live', paused: true });
    const step = (n) => t.step(run.id, n);
    await step(20);
    await t.request('PATCH', `/api/runs/${run.id}/params`, { gain: 417 });
    await step(20);
    await t.request('PATCH', `/api/runs/${run.id}/params`, { influence: 0.4 });
    await step(20);
    await t.request('PUT', `/api/runs/${run.id}/obstacles/disc`, { position: [0.5, 1.3, 0] });
    await step(20);
    await t.post(`/api/runs/${run.id}/method`, { name: 'dls' });
    await step(20);
    await t.post(`/api/runs/${run.id}/control`, { action: 'stop' });
    const events = await t.get(`/api/runs/${run.id}/events`);
    const [gain, influence, moved, method] = events;
    await t.page.goto(`${t.base}/?run=${run.id}&frame=0`);
    await replayAt(t.page, 0);
    const start = await eventually(async () => { const p = await panel(t.page); return p.note && p.note.includes('starting values') ? p : null; }, 'the starting values, marked as recorded');
    check(start.values.gain === 5 && start.values.influence === 0.25, `frame 0: the starting values (${JSON.stringify(start.values)})`);
    check(start.disabled, 'a replay takes no inputs: every control disabled');
    await eventually(async () => (await t.page.locator('#replay-markers .event-marker').count()) === 4, 'four marks on the scrubber');
    // the marker "influence = 0.4": influence 0.4 and gain 417 (set earlier)
    const mark = t.page.locator('#replay-markers .event-marker').nth(1);
    check((await mark.getAttribute('title')) === `frame ${influence.seq}: parameters: influence = 0.4`, 'the second mark is the influence change');
    await mark.click();
    await replayAt(t.page, influence.seq);
    const dt = 0.01;
    const atInfluence = await eventually(async () => { const p = await panel(t.page); return p.values.influence === 0.4 ? p : null; }, 'influence 0.4 at its marker');
    check(atInfluence.values.gain === 417, `gain 417, set earlier (${atInfluence.values.gain})`);
    check(atInfluence.note === `recorded at t = ${(influence.seq * dt).toFixed(2)} s (frame ${influence.seq})`, `the note says when: ${atInfluence.note}`);
    await t.screenshot('recorded-influence');
    // the obstacle where it was dragged, then back where it started
    const disc = () => t.page.evaluate(() => window.__rrlab.session.lanes[0].snapshot.obstacles.find((o) => o.id === 'disc').center);
    check(Math.abs((await disc())[0] - 0.3) < 1e-9, 'the disc where it started before its move');
    await t.page.locator('#replay-markers .event-marker').nth(2).click();
    await replayAt(t.page, moved.seq);
    await eventually(async () => Math.abs((await disc())[0] - 0.5) < 1e-9, 'the disc where it was moved');
    // the method switch: the panel names dls with its parameters
    await t.page.locator('#replay-markers .event-marker').nth(3).click();
    await replayAt(t.page, method.seq);
    await eventually(async () => { const p = await panel(t.page); return p.lane.startsWith('dls') && 'lambda' in p.values; }, 'the dls panel at the switch');
    await t.screenshot('recorded-method');
    // back before the changes: the earlier values again
    await t.page.locator('#scrubber').fill(String(gain.seq));
    await replayAt(t.page, gain.seq);
    const atGain = await eventually(async () => { const p = await panel(t.page); return p.lane.startsWith('closest_point') && p.values.influence === 0.25 ? p : null; }, 'closest_point with influence 0.25 again');
    check(atGain.values.gain === 417, 'gain 417 from its own frame on');
    await eventually(async () => Math.abs((await disc())[0] - 0.3) < 1e-9, 'the disc back where it started');
    await t.page.locator('#scrubber').fill(String(gain.seq - 1));
    await replayAt(t.page, gain.seq - 1);
    await eventually(async () => { const p = await panel(t.page); return p.values.gain === 5 && p.note.includes('starting values') ? p : null; }, 'gain 5 one frame before its change');
    await t.screenshot('recorded-start');
  }],
]);
