// Sweeps on the page: started from a spec in the dialog (errors name the
// spec's path), listed beside the runs with their progress, and shown at
// /?sweep=ID: the success table with the right counts, a cell's runs, a run
// re-simulated and replayed, a case compared across the sweep's methods; the
// run list groups a sweep's runs under it, named by case; which method when
// reads well in each status, the fallback section lists the unsolved cases
// with their command, and success against obstacle counts is drawn.
// Usage: node sweeps_test.mjs   (RRLAB_BINARY, RRLAB_SCREENSHOTS, CHROMIUM)
import { suite, eventually, check } from './harness.mjs';

const SPEC = {
  name: 'web-sweep',
  scenarios: [{ generator: 'planar_clutter', count: 3, seed: 5 }, '00_demo_avoidance'],
  methods: ['pinv', 'closest_point'],
  success: { max_tracking_error: 0.01, collision: false, joint_limits: true },
  steps: 300,
};

async function finishedSweep(t, spec = SPEC) {
  const started = await t.post('/api/sweeps?jobs=1', spec);
  await eventually(async () => (await t.get(`/api/sweeps/${started.id}`)).status === 'completed', { message: 'the sweep to finish', timeout: 60000 });
  return started.id;
}

// Two generated families that the report reads differently: on 4
// planar_clutter cases closest_point's successes cannot be told from pinv's
// failures (too few cases), and on planar_limits no method succeeds, so its
// cases are unsolved and the report gives the command that writes them.
const FRONTIER = {
  name: 'web-frontier',
  scenarios: [{ generator: 'planar_clutter', count: 4, seed: 5 }, { generator: 'planar_limits', count: 3, seed: 5 }],
  methods: ['pinv', 'dls', 'closest_point', 'witness'],
  success: { max_tracking_error: 0.01, collision: false, joint_limits: true },  // whole runs: the limits are crossed late
};

// Obstacle counts added to planar_clutter's groups, as sweep_report_json.cpp
// writes them, until the generators put them in witness.difficulty.
function withCounts(status) {
  const bins = (successes) => successes.map((k, i) => ({ low: i, high: i === 4 ? null : i, n: 4, successes: k }));
  for (const g of (status.report && status.report.groups) || []) {
    if (g.family !== 'planar_clutter') continue;
    const good = g.config === 'closest_point' || g.config === 'witness';
    g.difficulty_counts = { blocking_obstacles: bins(good ? [4, 4, 3, 2, 1] : [1, 0, 0, 0, 0]), tight_obstacles: bins(good ? [4, 3, 3, 3, 2] : [0, 0, 0, 0, 0]) };
  }
  return status;
}

// Chromium logs a 422 answer as a failed resource load; the test asks for it.
function forgiveRefusals(t) {
  for (let i = t.errors.length - 1; i >= 0; --i) if (/status of 422/.test(t.errors[i])) t.errors.splice(i, 1);
}

await suite('sweeps', [
  ['a sweep\'s page shows its table with the right counts; a cell opens its runs, a run re-simulates and replays', async (t) => {
    const id = await finishedSweep(t);
    await t.page.goto(`${t.base}/?sweep=${id}`);
    await t.page.waitForSelector('.sweep-success td.cell');
    check(await t.page.locator('.sweep-success td.cell').count() === 4, '2 families × 2 methods');
    const cells = await t.page.locator('.sweep-success td.cell').evaluateAll((tds) => tds.map((td) => ({
      family: td.dataset.family, config: td.dataset.config, n: td.querySelector('.n').textContent, best: td.classList.contains('best'),
    })));
    for (const c of cells) check(c.n === (c.family === 'planar_clutter' ? 'n = 3' : 'n = 1'), `${c.family} × ${c.config}: ${c.n}`);
    // on the demo, pinv collides and closest_point does not: closest_point is the column's best
    const demo = cells.filter((c) => c.family === 'file:00_demo_avoidance');
    check(demo.find((c) => c.config === 'closest_point').best && !demo.find((c) => c.config === 'pinv').best, 'the demo column marks closest_point best');
    check((await t.page.textContent('.sweep-verdicts')).includes('closest_point'), 'which method when names closest_point');
    await t.screenshot('report');

    // a cell's runs
    await t.page.locator('.sweep-success td.cell[data-family="planar_clutter"][data-config="pinv"]').click();
    await t.page.waitForSelector('.sweep-runs tr[data-run]');
    check(await t.page.locator('.sweep-runs tr[data-run]').count() === 3, 'the cell lists its 3 runs');
    const cases = await t.page.locator('.sweep-runs tr[data-run] td.mono').allTextContents();
    check(cases.every((c) => c.startsWith('gen:planar_clutter:5:')), `runs named by case: ${cases}`);
    await t.screenshot('cell');

    // a run without frames is re-simulated, then replayed
    const source = Number(await t.page.locator('.sweep-runs tr[data-run]').first().getAttribute('data-run'));
    await t.page.locator('.sweep-runs tr[data-run] .run-open').first().click();
    const lane = await eventually(() => t.page.evaluate(() => {
      const s = window.__rrlab.session;
      return s && s.kind === 'replay' && s.lanes[0].frame ? { run: s.lanes[0].runId, frames: s.frameCount } : null;
    }), 'the re-simulated run to replay');
    const record = await t.get(`/api/runs/${lane.run}`);
    check(record.source_run === source && record.frames === 300, `a re-simulation of run #${source} with its 300 frames (${record.source_run}, ${record.frames})`);
    check(await t.page.isHidden('#sweep-page'), 'the sweep page gives way to the replay');
    await t.screenshot('resimulated');

    // a case compared across the sweep's methods
    await t.page.goto(`${t.base}/?sweep=${id}`);
    await t.page.locator('.sweep-success td.cell[data-family="file:00_demo_avoidance"][data-config="pinv"]').click();
    await t.page.locator('.sweep-runs tr[data-run] .run-compare').first().click();
    const labels = await eventually(() => t.page.evaluate(() => {
      const s = window.__rrlab.session;
      return s && s.compare && s.lanes.every((l) => l.frame) ? s.lanes.map((l) => l.label) : null;
    }), 'the compare of the case');
    check([...labels].sort().join() === 'closest_point,pinv', `the sweep's methods side by side (by rank): ${labels}`);
    await eventually(async () => (await t.page.textContent('.verdict-headline') || '').includes('closest_point passes'), 'the compare verdict');
    await t.screenshot('case-compare');
  }],

  ['a sweep\'s page says which method when in every status, what to try when the first choice fails, and success against obstacle counts', async (t) => {
    const id = await finishedSweep(t, FRONTIER);
    await t.page.route(`**/api/sweeps/${id}`, async (route) => route.fulfill({ response: await route.fetch(), json: withCounts(await (await route.fetch()).json()) }));
    await t.page.goto(`${t.base}/?sweep=${id}`);
    await t.page.waitForSelector('.sweep-fallbacks');
    // which method when: no pick where the cases cannot separate the methods, or none succeeds
    const verdicts = await t.page.locator('.sweep-verdicts tr[data-family]').evaluateAll((trs) => Object.fromEntries(trs.map((tr) => [tr.dataset.family, { status: tr.dataset.status, text: tr.textContent }])));
    check(verdicts.planar_clutter.status === 'too_few_cases'
      && /too few cases to separate the methods \(a difference of 20 points needs about \d+ cases\); best observed, not separated from the others: closest_point \(\d+ %\)/.test(verdicts.planar_clutter.text),
    `planar_clutter: too few cases (${JSON.stringify(verdicts.planar_clutter)})`);
    check(verdicts.planar_limits.status === 'no_success' && verdicts.planar_limits.text.includes('no configuration succeeded on any case'),
      `planar_limits: no success (${JSON.stringify(verdicts.planar_limits)})`);
    // the fallback section: an upper bound, a row per family, the unsolved cases and their command
    check((await t.page.textContent('#sweep-page')).includes('What to try when the first choice fails (an offline upper bound)'), 'the section names the bound');
    check(await t.page.locator('.sweep-fallbacks tr[data-family]').count() === 2, 'a row per family');
    const unsolved = await t.page.textContent('.unsolved[data-family="planar_limits"]');
    check(/unsolved: 3 of 3 \(the witness solves 3\): gen:planar_limits:5:0, gen:planar_limits:5:1, gen:planar_limits:5:2/.test(unsolved), `planar_limits' unsolved cases (${unsolved})`);
    const command = await t.page.textContent('.unsolved[data-family="planar_limits"] pre');
    check(command === 'rrlab generate planar_limits --seed 5 --cases 0,1,2 --out unsolved/planar_limits-seed5', `the command that writes them (${command})`);
    await t.page.locator('.sweep-fallbacks').scrollIntoViewIfNeeded();
    await t.screenshot('fallbacks');
    // success against the obstacle counts: a chart per count, bins 0 … 4+
    for (const measure of ['blocking_obstacles', 'tight_obstacles']) {
      const chart = t.page.locator(`figure.difficulty[data-family="planar_clutter"][data-measure="${measure}"] svg`);
      check(await chart.count() === 1, `a ${measure} chart`);
      const labels = await chart.locator('text[text-anchor="middle"]').allTextContents();
      check(labels.slice(0, 5).join() === '0,1,2,3,4+' && labels[5] === measure, `its bins and measure (${labels})`);
    }
    check(await t.page.locator('figure.difficulty[data-family="planar_limits"][data-measure="blocking_obstacles"]').count() === 0, 'none where the cases carry no counts');
    await t.page.locator('.difficulty-charts').scrollIntoViewIfNeeded();
    await t.screenshot('counts');
  }],

  ['a sweep starts from the dialog, shows its progress, and its runs are grouped in the run list', async (t) => {
    await t.page.goto(t.base + '/');
    await t.page.click('#new-sweep');
    // a spec the server refuses names the path
    await t.page.fill('#sweep-spec', JSON.stringify({ ...SPEC, name: 'dialog-sweep', methods: ['no_such_method'] }));
    await t.page.click('#sweep-start');
    await eventually(async () => (await t.page.textContent('#sweep-error')).includes('methods'), 'the refusal naming the methods');
    forgiveRefusals(t);
    await t.page.fill('#sweep-spec', '{"name": ');
    check((await t.page.textContent('#sweep-syntax')).startsWith('not JSON'), 'a spec that is not JSON says so as it is typed');
    check((await t.page.textContent('#sweep-error')) === '', 'an edit clears the refusal of the spec before it');
    await t.page.fill('#sweep-spec', '{\n  "name": "x",\n  "methods": ["pinv",]\n}');
    check(/^not JSON yet: line 3, column 22/.test(await t.page.textContent('#sweep-syntax')), `the JSON error names its line and column (${await t.page.textContent('#sweep-syntax')})`);
    // every problem, each at its entry, though the server names the first only
    await t.page.fill('#sweep-spec', JSON.stringify({ ...SPEC, name: 'dialog-sweep', methods: ['pinv', 'lamda', 'dls', 'gpmm'] }));
    const problems = () => t.page.locator('#sweep-syntax li').allTextContents();
    await eventually(async () => (await problems()).length === 2, 'the two unknown methods listed');
    const listed = await problems();
    check(/^methods\[1\]/.test(listed[0]) && /lamda/.test(listed[0]) && /^methods\[3\]/.test(listed[1]) && /gpmm/.test(listed[1]), `each at its entry: ${listed.join(' | ')}`);
    check((await t.page.textContent('#sweep-syntax')).includes('2 problems'), 'the count said');
    // checked by the server as it is typed: what is wrong, or what it would run
    await t.page.fill('#sweep-spec', JSON.stringify({ ...SPEC, name: 'dialog-sweep', success: { max_tracking_error: -1 } }));
    await eventually(async () => (await t.page.textContent('#sweep-syntax')).includes('success.max_tracking_error'), 'the server naming the bad field');
    await t.page.fill('#sweep-spec', JSON.stringify({ ...SPEC, name: 'dialog-sweep' }));
    await eventually(async () => (await t.page.textContent('#sweep-syntax')).startsWith('valid: 8 runs'), 'the dialog to say 8 runs');
    await t.page.click('#sweep-start');
    await eventually(() => t.page.evaluate(() => new URLSearchParams(location.search).has('sweep')), 'the new sweep\'s page');
    await t.page.waitForSelector('.sweep-success td.cell', { timeout: 60000 });
    check(await t.page.isVisible('#sweeps li[data-sweep]'), 'the sweep is listed');
    await eventually(async () => (await t.page.textContent('#sweeps li[data-sweep] .progress')).trim() === '8 / 8', 'its progress to read 8 / 8 runs');
    // the run list groups its runs under the sweep, named by case
    const group = t.page.locator('#runs details.sweep-runs[data-sweep="dialog-sweep"]');
    await group.waitFor();
    await group.locator('summary').click();
    await eventually(async () => (await group.locator('li[data-run]').count()) === 8, 'the sweep\'s 8 runs in its group');
    const first = await group.locator('li[data-run] .title').first().textContent();
    check(/gen:planar_clutter|file:00_demo_avoidance/.test(first), `a run named by its case: ${first}`);
    check(await group.locator('li[data-run] button', { hasText: 'Re-simulate' }).count() === 8, 'each offers re-simulation (no frames stored)');
    await t.screenshot('grouped');
    forgiveRefusals(t);  // the refusals the dialog asked for
  }],
]);
