// Replays as a person uses them: one current frame that the scrubber, the
// readout, the status line, the plot cursor, the address and every lane's
// view follow, however the frame was asked for (scrubber click, keyboard,
// plot click, deep link); Play at the end starts again; a compare group's
// lanes stay on one frame; the trace is rebuilt to the frame shown.
// Usage: node replay_test.mjs   (RRLAB_BINARY, RRLAB_SCREENSHOTS, CHROMIUM)
import { suite, eventually, check } from './harness.mjs';

// What the page says the current frame is, everywhere it says it.
const shown = (page) => page.evaluate(() => {
  const s = window.__rrlab.session;
  const lanes = s ? s.lanes.map((l) => (l.frame ? l.frame.seq : null)) : [];
  const dt = s && s.lanes[0].snapshot ? s.lanes[0].snapshot.dt : null;
  const cursor = window.__rrlab.plots.cursorT;
  return {
    scrubber: Number(document.getElementById('scrubber').value),
    readout: document.getElementById('replay-frame').textContent,
    status: document.getElementById('status').textContent,
    cursor: cursor === null || dt === null ? null : Math.round(cursor / dt),
    address: new URLSearchParams(location.search).get('frame'),
    lanes,
    playing: window.__rrlab.replay.playing,
  };
});

// Every readout names frame k, and every lane (up to its last frame) shows it.
async function allAt(page, k, what) {
  return eventually(async () => {
    const s = await shown(page);
    const ok = s.scrubber === k && s.readout.startsWith(`${k} /`) && s.readout.includes(' s') && s.status.includes(`frame ${k}`) &&
      s.cursor === k && s.address === String(k) && s.lanes.every((seq) => seq === k);
    return ok ? s : null;
  }, `${what}: every readout at frame ${k} (last seen ${JSON.stringify(await shown(page))})`);
}

await suite('replay', [
  ['a scrubber click, the keyboard and a deep link move every readout together', async (t) => {
    const run = await t.post('/api/runs', { scenario: '01_planar7_obstacles', method: 'dls', mode: 'batch' });
    await t.page.goto(`${t.base}/?run=${run.id}&frame=250`);
    await allAt(t.page, 250, 'the deep link');
    check(!(await shown(t.page)).playing, 'a deep link to a frame opens paused');
    await t.screenshot('deep-link');

    // a click on the scrubber, a third of the way along
    const scrubber = t.page.locator('#scrubber');
    const box = await scrubber.boundingBox();
    await scrubber.click({ position: { x: box.width / 3, y: box.height / 2 } });
    const clicked = (await shown(t.page)).scrubber;
    check(Math.abs(clicked - 800 / 3) < 60, `the click lands about a third of the way (${clicked})`);
    await allAt(t.page, clicked, 'the scrubber click');

    // the scrubber keeps focus, and the shortcuts still work
    check(await scrubber.evaluate((el) => el === document.activeElement), 'the scrubber has focus');
    await t.page.keyboard.press('.');
    await allAt(t.page, clicked + 1, 'one frame on with "."');
    await t.page.keyboard.press(',');
    await t.page.keyboard.press(',');
    await allAt(t.page, clicked - 1, 'two frames back with ","');
    await t.page.keyboard.press(' ');
    await eventually(async () => (await shown(t.page)).playing && (await shown(t.page)).scrubber > clicked + 5, 'space plays from there');
    await t.page.keyboard.press(' ');
    const paused = (await shown(t.page)).scrubber;
    await allAt(t.page, paused, 'space pauses, every readout at the frame it stopped on');
    await t.screenshot('after-keys');

    // the view shows the stored frame itself
    const stored = (await t.get(`/api/runs/${run.id}/frames?from=${paused}&to=${paused}`)).frames[0];
    const q = await t.page.evaluate(() => window.__rrlab.session.lanes[0].frame.q);
    // the stream sends joint values to 7 significant digits
    q.forEach((v, i) => check(Math.abs(v - stored.q[i]) <= 1e-6 * Math.max(1, Math.abs(stored.q[i])), `q${i + 1} drawn ${v}, stored ${stored.q[i]}`));
  }],

  ['Play at the last frame starts again; the trace is rebuilt to the frame shown', async (t) => {
    const run = await t.post('/api/runs', { scenario: '01_planar7_obstacles', method: 'dls', mode: 'batch' });
    await t.page.goto(`${t.base}/?run=${run.id}&frame=799`);
    await allAt(t.page, 799, 'the last frame');
    // the trace of a replay opened at its end is the whole path, once the stored run is loaded
    const trace = () => t.page.evaluate(() => window.__rrlab.session.lanes[0].view.traceCount);
    await eventually(async () => (await trace()) === 800, 'the trace to hold all 800 frames');
    await t.page.locator('#replay-play').click();
    await eventually(async () => { const s = await shown(t.page); return s.playing && s.scrubber < 400 ? s : null; }, 'play at the end to start from the first frame');
    await t.page.locator('#replay-play').click();
    // a seek back rebuilds the trace to that frame instead of clearing it
    await t.page.locator('#scrubber').fill('600');
    await t.page.locator('#scrubber').dispatchEvent('change');
    await allAt(t.page, 600, 'the seek to 600');
    await eventually(async () => (await trace()) === 601, 'the trace rebuilt to frames 0–600');
    await t.screenshot('trace-rebuilt');
  }],

  ['a compare group replays its lanes on one frame, and a plot click seeks them all', async (t) => {
    const group = await t.post('/api/compare', { scenario: '01_planar7_obstacles', methods: ['pinv', 'dls', 'gpm'], mode: 'batch' });
    const ids = group.runs.map((r) => r.id);
    // opened at frame 0, paused; played by hand (an autoplay could reach the end before a slow test acts)
    await t.page.goto(`${t.base}/?compare=${ids.join(',')}&frame=0`);
    await allAt(t.page, 0, 'the group at frame 0');
    await t.page.locator('#replay-play').click();
    await eventually(async () => { const s = await shown(t.page); return s.playing && s.scrubber > 20; }, 'the group to play');
    await t.page.locator('#replay-play').click();
    const paused = (await shown(t.page)).scrubber;
    check(!(await shown(t.page)).playing, 'Play again pauses');
    await allAt(t.page, paused, 'every lane on the frame the group paused at');
    // a click on a chart seeks every lane
    await eventually(() => t.page.evaluate(() => window.__rrlab.plots.charts.get('distance') !== undefined), 'the distance chart');
    const over = t.page.locator('#plots .plots-chart[data-chart="distance"] .u-over');
    await over.scrollIntoViewIfNeeded();
    const box = await over.boundingBox();
    await over.click({ position: { x: box.width * 0.75, y: box.height / 2 } });
    const sought = (await shown(t.page)).scrubber;
    check(Math.abs(sought - 600) < 60, `the click three quarters along the chart seeks near frame 600 (${sought})`);
    await allAt(t.page, sought, 'the plot click');
    await t.screenshot('compare-synced');
  }],
  ['once its frames are in the page, a 3-lane replay seeks and plays without asking the server for a frame', async (t) => {
    const group = await t.post('/api/compare', { scenario: '01_planar7_obstacles', methods: ['pinv', 'dls', 'gpm'], mode: 'batch' });
    const ids = group.runs.map((r) => r.id);
    // every frame the page asks a replay player for: a WebSocket control, or POST /api/replays/{id}/control
    const asked = [];
    t.page.on('websocket', (ws) => ws.on('framesent', (f) => { if (String(f.payload).includes('"control"')) asked.push(String(f.payload)); }));
    t.page.on('request', (r) => { if (/\/api\/replays\/\d+\/control/.test(r.url())) asked.push(r.url()); });
    await t.page.goto(`${t.base}/?compare=${ids.join(',')}&frame=0`);
    await allAt(t.page, 0, 'the group at frame 0');
    const memory = t.page.locator('#replay-memory');
    await eventually(async () => (await memory.textContent()) === 'in memory', 'the frames to be held in the page');
    check(/every frame/.test(await memory.getAttribute('title')), `the memory readout says what it holds: ${await memory.getAttribute('title')}`);
    const before = asked.length;
    const picture = () => t.page.evaluate(() => window.__rrlab.session.lanes.map((l) => JSON.stringify(l.frame.links)));
    const start = await picture();
    await t.page.locator('#scrubber').focus();
    await t.page.keyboard.press('End');
    await allAt(t.page, 799, 'End, from the page');
    const end = await picture();
    check(end.every((links, i) => links !== start[i]), 'every lane drew its last frame');
    for (const k of [400, 123, 124, 5]) {
      await t.page.evaluate((k) => window.__rrlab.replay.seek(k), k);
      await allAt(t.page, k, `a seek to ${k}`);
    }
    await t.page.locator('#replay-play').click();
    await eventually(async () => { const s = await shown(t.page); return s.playing && s.scrubber > 40; }, 'the group to play');
    await t.page.locator('#replay-play').click();
    await allAt(t.page, (await shown(t.page)).scrubber, 'paused where it stopped');
    check(asked.length === before, `no frame asked of the server once held (${asked.slice(before).join(' | ')})`);
    // the frame drawn is the stored one, as the player would send it
    const stored = (await t.get(`/api/runs/${ids[1]}/frames?from=5&to=5`)).frames[0];
    await t.page.evaluate(() => window.__rrlab.replay.seek(5));
    await allAt(t.page, 5, 'frame 5');
    const q = await t.page.evaluate(() => window.__rrlab.session.lanes[1].frame.q);
    q.forEach((v, i) => check(Math.abs(v - stored.q[i]) <= 1e-6 * Math.max(1, Math.abs(stored.q[i])), `q${i + 1} drawn ${v}, stored ${stored.q[i]}`));
    await t.screenshot('local-frames');
  }],
  ['a replay over its memory budget holds every N-th frame: a frame between is drawn at once, then exactly from the server', async (t) => {
    const run = await t.post('/api/runs', { scenario: '01_planar7_obstacles', method: 'dls', mode: 'batch' });
    await t.page.goto(t.base + '/');
    await eventually(() => t.page.evaluate(() => Boolean(window.__rrlab && window.__rrlab.replay)), 'the page');
    // 600 KB for 800 frames of about 1.5 KB: the first 200 held, then every third
    await t.page.evaluate((id) => {
      window.__rrlab.replay.memoryBudget = 600 * 1024;
      window.__rrlab.app.execute({ type: 'open', ids: [id], layout: 'side', frame: 0 });
    }, run.id);
    const memory = t.page.locator('#replay-memory');
    await eventually(async () => /^in memory: 1 in \d+$/.test(await memory.textContent()), 'the frames held at a stride');
    const stride = Number((await memory.textContent()).match(/1 in (\d+)/)[1]);
    check(stride >= 2 && stride <= 4, `a stride that fits the budget (${stride})`);
    const local = await t.page.evaluate(() => ({ bytes: window.__rrlab.replay.local.bytes, last: Boolean(window.__rrlab.replay.local.get(window.__rrlab.session.lanes[0]).texts[799]) }));
    check(local.bytes <= 600 * 1024 && local.last, `within the budget, the last frame held (${local.bytes} bytes)`);
    // a frame between held ones: the exact one in the end, from the server
    const between = 200 + stride * 100 + 1;
    await t.page.evaluate((k) => window.__rrlab.replay.seek(k), between);
    await allAt(t.page, between, `frame ${between}, between held ones`);
    const stored = (await t.get(`/api/runs/${run.id}/frames?from=${between}&to=${between}`)).frames[0];
    const q = await t.page.evaluate(() => window.__rrlab.session.lanes[0].frame.q);
    q.forEach((v, i) => check(Math.abs(v - stored.q[i]) <= 1e-6 * Math.max(1, Math.abs(stored.q[i])), `q${i + 1} drawn ${v}, stored ${stored.q[i]}`));
    // played, then paused: the frame it paused on, exactly
    await t.page.locator('#replay-play').click();
    await eventually(async () => (await shown(t.page)).scrubber > between + 20, 'the replay to play on');
    await t.page.locator('#replay-play').click();
    await allAt(t.page, (await shown(t.page)).scrubber, 'paused on an exact frame');
  }],
  ['a replay drawn from the page moves its obstacles as recorded, and asks the server across a method switch', async (t) => {
    const run = await t.post('/api/runs', { scenario: '01_planar7_obstacles', mode: 'live', paused: true });
    const step = (n) => t.step(run.id, n);
    await step(10);
    await t.request('PUT', `/api/runs/${run.id}/obstacles/disc`, { position: [0.6, 1.0, 0] });
    await step(10);
    await t.post(`/api/runs/${run.id}/method`, { name: 'dls' });
    await step(10);
    await t.post(`/api/runs/${run.id}/control`, { action: 'stop' });
    const events = await t.get(`/api/runs/${run.id}/events`);
    const moved = events.find((e) => e.kind === 'obstacle').seq, switched = events.find((e) => e.kind === 'method').seq;
    await t.page.goto(`${t.base}/?run=${run.id}&frame=0`);
    const memory = t.page.locator('#replay-memory');
    await eventually(async () => (await memory.textContent()) === 'in memory', 'the frames to be held in the page');
    const disc = () => t.page.evaluate(() => {
      const s = window.__rrlab.session.lanes[0].snapshot;
      return s.obstacles.find((o) => o.id === 'disc').center[0];
    });
    const method = () => t.page.evaluate(() => window.__rrlab.session.lanes[0].snapshot.method);
    const at = async (k) => { await t.page.evaluate((k) => window.__rrlab.replay.seek(k), k); await allAt(t.page, k, `frame ${k}`); };
    await at(moved - 1);
    check(Math.abs((await disc()) - 0.3) < 1e-9, `the disc where the scenario puts it before it was moved (${await disc()})`);
    await at(moved);
    await eventually(async () => Math.abs((await disc()) - 0.6) < 1e-9, 'the disc where it was moved to');
    await at(switched);
    await eventually(async () => (await method()) === 'dls', 'the switched method, from the server');
    await at(moved - 1);
    await eventually(async () => (await method()) === 'closest_point' && Math.abs((await disc()) - 0.3) < 1e-9, 'back before both');
  }],
  ['recorded inputs are marked on the scrubber and the charts, each named, and a mark seeks to its frame', async (t) => {
    const run = await t.post('/api/runs', { scenario: '01_planar7_obstacles', mode: 'live', paused: true });
    const step = (n) => t.step(run.id, n);
    await step(20);
    await t.request('PATCH', `/api/runs/${run.id}/params`, { gain: 3 });
    await step(20);
    await t.post(`/api/runs/${run.id}/method`, { name: 'dls' });
    await step(20);
    await t.post(`/api/runs/${run.id}/control`, { action: 'stop' });
    const events = await t.get(`/api/runs/${run.id}/events`);
    await t.page.goto(`${t.base}/?run=${run.id}&frame=0`);
    await eventually(async () => (await t.page.locator('#replay-markers .event-marker').count()) === 2, 'two marks on the scrubber');
    const titles = await t.page.locator('#replay-markers .event-marker').evaluateAll((els) => els.map((e) => e.title));
    const params = events.find((e) => e.kind === 'params'), method = events.find((e) => e.kind === 'method');
    check(titles[0] === `frame ${params.seq}: parameters: gain = 3`, `the parameter change is named: ${titles[0]}`);
    check(titles[1] === `frame ${method.seq}: method switched to dls`, `the method switch is named: ${titles[1]}`);
    await eventually(() => t.page.evaluate(() => document.querySelectorAll('#plots .plots-chart[data-chart="distance"] .plots-marker').length === 2), 'two marks on the distance chart');
    await t.page.locator('#replay-markers .event-marker').nth(1).click();
    await allAt(t.page, method.seq, 'a click on the method mark');
    await t.screenshot('markers');
  }],
]);
