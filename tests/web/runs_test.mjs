// Runs as a person meets them: the header says live, paused or ended; an
// ended run's scene is read-only on screen (nothing drags or deletes) and
// can be restarted with its scene; runs are found by the scenario's
// catalogue name, the one name the page shows everywhere.
// Usage: node runs_test.mjs   (RRLAB_BINARY, RRLAB_SCREENSHOTS, CHROMIUM)
import { suite, eventually, check, pageState, longScenario, drag as dragMouse } from './harness.mjs';

const pill = (page) => page.textContent('#connection');

// Drags obstacle `index` of lane 0 by (dx, dy) pixels with the mouse.
async function drag(page, index, dx, dy) {
  const lane = await pageState.lane(page);
  const from = await pageState.toClient(page, lane.obstacles[index]);
  await dragMouse(page, from, { x: from.x + dx, y: from.y + dy }, 8);
}

await suite('runs', [
  ['the header says paused, then ended; an ended run cannot be dragged and restarts with its scene', async (t) => {
    const scenario = await longScenario(t);
    const run = await t.post('/api/runs', { scenario, mode: 'live', rate: 1, paused: true });
    await t.page.goto(`${t.base}/?run=${run.id}`);
    await eventually(() => pageState.lane(t.page), 'the first frame');
    await eventually(async () => (await pill(t.page)) === 'paused', 'the header to say paused');
    await t.post(`/api/runs/${run.id}/control`, { action: 'start' });
    await eventually(async () => (await pill(t.page)) === 'live', 'the header to say live once it plays');
    await t.post(`/api/runs/${run.id}/control`, { action: 'pause' });
    await eventually(async () => (await pill(t.page)) === 'paused', 'the header to say paused again');

    // while it runs, a drag moves the disc on the server
    const index = (await t.page.evaluate(() => window.__rrlab.session.lanes[0].snapshot.obstacles)).findIndex((o) => o.id === 'disc');
    await drag(t.page, index, 40, 0);
    await eventually(async () => (await t.get(`/api/runs/${run.id}/events`)).some((e) => e.kind === 'obstacle'), 'the drag to reach the server');
    await t.post(`/api/runs/${run.id}/control`, { action: 'step' });
    const moved = await eventually(async () => {
      const l = await pageState.lane(t.page);
      const drawn = await t.page.evaluate((i) => window.__rrlab.session.lanes[0].view.positionOf(i), index);
      return Math.hypot(l.obstacles[index][0] - drawn[0], l.obstacles[index][1] - drawn[1]) < 1e-9 ? l.obstacles[index] : null;
    }, 'the frames to show the disc where it was dropped');

    await t.post(`/api/runs/${run.id}/control`, { action: 'stop' });
    await eventually(async () => (await pill(t.page)).startsWith('ended'), 'the header to say ended');
    check(await t.page.isVisible('#ended-note'), 'the page says the run has ended');
    check(await t.page.isHidden('#control-note'), 'no control notice after the end');
    const events = (await t.get(`/api/runs/${run.id}/events`)).length;
    // a drag on the ended run moves nothing, on screen or on the server
    await drag(t.page, index, 60, 60);
    const drawn = await t.page.evaluate((i) => window.__rrlab.session.lanes[0].view.positionOf(i), index);
    check(Math.hypot(drawn[0] - moved[0], drawn[1] - moved[1]) < 1e-9, `the disc stays where the run left it (${drawn} vs ${moved})`);
    check((await t.get(`/api/runs/${run.id}/events`)).length === events, 'no input reaches the server');
    check(await t.page.isDisabled('#delete-obstacle'), 'Delete is disabled');
    await t.screenshot('ended');

    // restart with this scene: a new live run whose disc starts where this one left it
    await t.page.locator('#restart-scene').click();
    await eventually(async () => { const l = await pageState.lane(t.page); return l && l.runId !== run.id ? l : null; }, 'the new run');
    const fresh = await pageState.lane(t.page);
    const record = await t.get(`/api/runs/${fresh.runId}/record`);
    const disc = record.scenario.obstacles.find((o) => o.id === 'disc');
    check(Math.hypot(disc.center[0] - moved[0], disc.center[1] - moved[1]) < 1e-6,  // the stream sends 7 digits
      `the new run's disc starts at ${moved} (${disc.center})`);
    check(record.scenario.name === scenario.name, 'the same scenario name');
    await t.post(`/api/runs/${fresh.runId}/control`, { action: 'stop' });
  }],

  ['runs are found by the catalogue name the picker shows', async (t) => {
    const run = await t.post('/api/runs', { scenario: '01_planar7_obstacles', method: 'pinv', mode: 'batch', steps: 20 });
    const other = await t.post('/api/runs', { scenario: '04_planar7_joystick', method: 'pinv', mode: 'batch', steps: 20 });
    await t.page.goto(t.base + '/');
    await t.page.waitForSelector('#filter-scenario option[value="01_planar7_obstacles"], #filter-scenario option:text-is("01_planar7_obstacles")', { state: 'attached' });
    await t.page.selectOption('#filter-scenario', '01_planar7_obstacles');
    // both before the filter; after it, the one run only (the list refreshes after the choice: wait for that)
    await eventually(async () => (await t.page.locator(`#runs li[data-run="${run.id}"]`).count()) === 1 &&
      (await t.page.locator(`#runs li[data-run="${other.id}"]`).count()) === 0, 'the run under its catalogue name, the other scenario\'s filtered out');
    check((await t.page.textContent(`#runs li[data-run="${run.id}"] .title`)).includes('01_planar7_obstacles'), 'the list names the run by its catalogue name');
    // the replay's header names it the same way
    await t.page.locator(`#runs li[data-run="${run.id}"] button`, { hasText: 'Replay' }).click();
    await eventually(async () => (await t.page.textContent('#session-title')).includes('01_planar7_obstacles'), 'the header to name the catalogue scenario');
    await t.screenshot('filtered');
  }],
]);
