// Finished runs are replays: a live run (or compare group) that ends keeps
// its views and becomes a replay with the scrubber at its end, which then
// scrubs like any replay and still restarts with its scene; a stored compare
// opened from the run list brings its views into sight.
// Usage: node finished_test.mjs   (RRLAB_BINARY, RRLAB_SCREENSHOTS, CHROMIUM)
import { suite, eventually, check, stopIfLive, animationFrames } from './harness.mjs';

// A catalogue scenario cut to `seconds`: a live run of it ends soon after it plays.
async function shortScenario(t, name, seconds) {
  const scenario = await t.get(`/api/scenarios/${name}`);
  return { ...scenario, duration: seconds };
}

// The session on screen: its kind, its lanes' views (tagged by the test) and frames, the scrubber.
const shown = (page) => page.evaluate(() => {
  const s = window.__rrlab.session;
  return s && {
    kind: s.kind,
    fromLive: s.fromLive,
    frameCount: s.frameCount,
    tags: s.lanes.map((l) => (l.view ? l.view.testTag || null : null)),
    seqs: s.lanes.map((l) => (l.frame ? l.frame.seq : null)),
    barHidden: document.getElementById('replay-bar').hidden,
    scrubber: Number(document.getElementById('scrubber').value),
    scrubberMax: Number(document.getElementById('scrubber').max),
    playing: window.__rrlab.replay.playing,
    address: new URLSearchParams(location.search).get('frame'),
    pill: document.getElementById('connection').textContent,
    title: document.getElementById('session-title').textContent,
    points: Object.values(window.__rrlab.plots.pointCounts()),
  };
});

// Starts the live session paused, tags its views, then plays it with the
// page's Play button and waits until it has become its replay at its end.
async function playToTheEnd(t, lanes) {
  await eventually(async () => { const s = await shown(t.page); return s && s.kind === 'live' && s.seqs.every((q) => q !== null) && s.tags.length === lanes; },
    'the live session with a frame in every lane');
  await t.page.evaluate(() => { window.__rrlab.session.lanes.forEach((l, i) => { l.view.testTag = `view ${i}`; }); });
  const scale = await t.page.evaluate(() => window.__rrlab.session.lanes[0].view.scale);
  await t.page.locator('#controls [data-action="start"]').click();
  const s = await eventually(async () => {
    const now = await shown(t.page);
    const last = now.frameCount - 1;
    const ok = now.kind === 'replay' && now.fromLive && !now.barHidden && !now.playing && now.scrubberMax === last && now.scrubber === last
      && now.address === String(last) && now.seqs.every((q) => q === last) && now.points.some((n) => n === now.frameCount);
    if (!ok) throw new Error(`last seen ${JSON.stringify(now)}`);
    return now;
  }, { timeout: 30000, message: 'the ended run to become its replay at its last frame, its whole run charted' });
  check(s.tags.every((tag, i) => tag === `view ${i}`), `every view is kept (${s.tags})`);
  check(await t.page.evaluate(() => window.__rrlab.session.lanes[0].view.scale) === scale, 'the view keeps its zoom');
  return s;
}

await suite('finished', [
  ['a live run that ends keeps its view and becomes a replay at its end; it scrubs and restarts with its scene', async (t) => {
    const run = await t.post('/api/runs', { scenario: await shortScenario(t, '01_planar7_obstacles', 1.5), mode: 'live', rate: 1, paused: true });
    await t.page.goto(`${t.base}/?run=${run.id}`);
    const s = await playToTheEnd(t, 1);
    check(s.frameCount === 150, `all 150 frames replayable (${s.frameCount})`);
    check(s.pill.startsWith('ended (completed)') && s.title.startsWith('replay ·'), `the header says it ended and replays (${s.pill}; ${s.title})`);
    check(await t.page.isVisible('#ended-note') && await t.page.isEnabled('#restart-scene'), 'Restart with this scene is still offered');
    await t.screenshot('ended-replay');

    // a drag of the scrubber to the start shows frame 0 in the same view
    const scrubber = await t.page.locator('#scrubber').boundingBox();
    await t.page.mouse.move(scrubber.x + scrubber.width * 0.98, scrubber.y + scrubber.height / 2);
    await t.page.mouse.down();
    await t.page.mouse.move(scrubber.x + 2, scrubber.y + scrubber.height / 2, { steps: 8 });
    await t.page.mouse.up();
    const start = await eventually(async () => { const now = await shown(t.page); return now.seqs[0] === 0 && now.scrubber === 0 ? now : null; }, 'the view at frame 0 after the drag');
    check(start.tags[0] === 'view 0', 'still the same view');
    await t.screenshot('scrubbed');

    // Restart with this scene: a new live run
    await t.page.locator('#restart-scene').click();
    const fresh = await eventually(() => t.page.evaluate((old) => {
      const s = window.__rrlab.session;
      return s && s.kind === 'live' && s.lanes[0].runId !== old && s.lanes[0].frame ? s.lanes[0].runId : null;
    }, run.id), 'the restarted live run, a new one');
    await stopIfLive(t, fresh);
  }],

  ['a live compare that ends keeps its lanes and becomes a replay at its end', async (t) => {
    const scenario = await shortScenario(t, '00_demo_avoidance', 1.5);
    const group = await t.post('/api/compare', { scenario, methods: ['pinv', 'closest_point'], mode: 'live', rate: 1, paused: true });
    await t.page.goto(`${t.base}/?compare=${group.runs.map((r) => r.id).join(',')}`);
    const s = await playToTheEnd(t, 2);
    check(s.frameCount === 150, `150 frames (${s.frameCount})`);
    await eventually(async () => (await t.page.textContent('.verdict-headline') || '').length > 0, 'the verdict');
    await t.screenshot('compare-ended-replay');
  }],

  ['a 3D live run that ends keeps the camera the user turned', async (t) => {
    const run = await t.post('/api/runs', { scenario: await shortScenario(t, '02_spatial_xz_reach', 1), mode: 'live', rate: 1, paused: true });
    await t.page.goto(`${t.base}/?run=${run.id}`);
    await eventually(async () => { const s = await shown(t.page); return s && s.kind === 'live' && s.seqs[0] !== null && s.tags.length === 1; }, 'the live 3D view');
    // turn the camera: a drag across empty space near the view's top
    const cell = await t.page.locator('#views .view-cell').boundingBox();
    await t.page.mouse.move(cell.x + cell.width * 0.2, cell.y + 30);
    await t.page.mouse.down();
    await t.page.mouse.move(cell.x + cell.width * 0.45, cell.y + 40, { steps: 8 });
    await t.page.mouse.up();
    const camera = () => t.page.evaluate(() => window.__rrlab.session.lanes[0].view.rig.camera.position.toArray().map((v) => Number(v.toFixed(6))));
    // the orbit coasts a little after the drag: where it comes to rest
    const settled = (what) => eventually(async () => {
      const before = await camera();
      await animationFrames(t.page, 10);
      return (await camera()).join() === before.join() ? before : null;
    }, what);
    const turned = await settled('the camera to come to rest after the drag');
    check(turned.join() !== '3,-5,3', `the drag turned the camera (${turned})`);
    await t.page.evaluate(() => { window.__rrlab.session.lanes[0].view.testTag = 'view 0'; });
    await t.page.locator('#controls [data-action="start"]').click();
    await eventually(async () => {
      const s = await shown(t.page);
      return s.kind === 'replay' && s.tags[0] === 'view 0' && s.seqs[0] === s.frameCount - 1 && s.scrubber === s.frameCount - 1;
    }, { timeout: 30000, message: 'the ended 3D run to become its replay at its end in the same view' });
    const kept = await settled('the camera at rest in the replay');
    // the orbit's damping may still creep by a micrometre; a re-fit or reset would move it by metres
    const moved = Math.hypot(...kept.map((v, i) => v - turned[i]));
    check(moved < 1e-3, `the camera stays where the user turned it (${kept} vs ${turned}: ${moved} m)`);
    await t.screenshot('3d-ended-replay');
  }],

  ['a run whose replay the server refuses stays as it ended, says why, and still restarts', async (t) => {
    const run = await t.post('/api/runs', { scenario: await shortScenario(t, '01_planar7_obstacles', 1), mode: 'live', rate: 1, paused: true });
    await t.page.route('**/api/runs/*/replay', (route) => route.fulfill({ status: 429, contentType: 'application/json',
      body: JSON.stringify({ error: { code: 'too_many_replays', message: 'too many replays at once', path: '' } }) }));
    await t.page.goto(`${t.base}/?run=${run.id}`);
    await eventually(async () => { const s = await shown(t.page); return s && s.kind === 'live' && s.seqs[0] !== null; }, 'the live run');
    await t.page.locator('#controls [data-action="start"]').click();
    await eventually(async () => (await t.page.textContent('#message span')).includes('too many replays'), 'the refusal on the message line');
    const s = await shown(t.page);
    check(s.kind === 'live' && !s.fromLive && s.barHidden && s.pill.startsWith('ended'), `the session stays as it ended (${JSON.stringify(s)})`);
    await t.screenshot('refused');
    // Chromium logs the refused request as a failed resource load: the test asked for it
    await eventually(() => t.errors.some((e) => /status of 429/.test(e)), 'the refusal in the console');
    for (let i = t.errors.length - 1; i >= 0; --i) if (/status of 429/.test(t.errors[i])) t.errors.splice(i, 1);
    // the restarted run (of 1 s, too) may end and become its replay: the server answers again
    await t.page.unroute('**/api/runs/*/replay');
    await t.page.locator('#restart-scene').click();
    const fresh = await eventually(() => t.page.evaluate((old) => {
      const now = window.__rrlab.session;
      return now && now.kind === 'live' && now.lanes[0].runId !== old && now.lanes[0].frame ? now.lanes[0].runId : null;
    }, run.id), 'the restarted live run');
    await stopIfLive(t, fresh);
  }],

  ['a stored compare opened from the run list brings its views into sight, on a phone too', async (t) => {
    const group = await t.post('/api/compare', { scenario: '00_demo_avoidance', methods: ['pinv', 'closest_point'], mode: 'batch' });
    const first = Math.min(...group.runs.map((r) => r.id));
    const views = t.page.locator('#views');
    const inSight = async () => {
      const box = await views.boundingBox();
      const height = t.page.viewportSize().height;
      return box && box.y >= -1 && box.y < height && box.y + Math.min(box.height, height / 2) <= height;
    };
    const openCompare = async (what) => {
      const compare = t.page.locator(`#runs li[data-run="${first}"] button`, { hasText: 'Compare' });
      await compare.waitFor({ timeout: 15000 });
      await compare.scrollIntoViewIfNeeded();
      check(!(await inSight()), `the views are out of sight before (${what})`);
      await compare.click();
      await eventually(async () => {
        const s = await shown(t.page);
        return s && s.kind === 'replay' && s.seqs.length === 2 && s.seqs.every((q) => q !== null) && (await inSight());
      }, { timeout: 20000, message: `the compare opened with its views in sight (${what})` });
    };
    // at 1400 × 900: a replay whose centre column is scrolled down to its last chart
    await t.page.goto(`${t.base}/?run=${first}&frame=0`);
    await eventually(() => t.page.evaluate(() => window.__rrlab.plots.charts.size >= 3), 'the replay\'s charts');
    await t.page.locator('#plots .plots-chart').last().scrollIntoViewIfNeeded();
    await openCompare('the centre column scrolled down');
    await t.screenshot('desktop-compare');
    // on a phone the run list is below everything: scroll to it as a person does
    await t.page.setViewportSize({ width: 390, height: 844 });
    await t.page.goto(`${t.base}/`);
    await openCompare('a phone');
    await t.screenshot('phone-compare');
  }],
]);
