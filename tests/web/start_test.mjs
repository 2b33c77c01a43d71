// The start page as a person meets it: the default scenario drawn at once
// (arm and obstacles, labelled a preview, nothing stored), a header that says
// ready, Start live as the first action; another scenario picked redraws it
// (a 3D arm in three.js); Start live, a replay, a compare, a paper's page and
// deep links replace it cleanly, and an empty centre brings it back; a name
// the server does not know is said in the view.
// Usage: node start_test.mjs   (RRLAB_BINARY, RRLAB_SCREENSHOTS, CHROMIUM)
import { suite, eventually, check, stopIfLive } from './harness.mjs';

const pill = (page) => page.textContent('#connection');

// What the start page shows: the preview's scenario, its view's kind, whether it has drawn.
const preview = (page) => page.evaluate(() => {
  const p = window.__rrlab.preview;
  const cells = [...document.querySelectorAll('#views > .view-cell')];
  return {
    scenario: p.snapshot ? p.snapshot.scenario : null,
    kind: p.view ? (p.view.context ? '2d' : '3d') : null,
    drawn: Boolean(p.view && p.view.frame !== null && !p.view.dirty),
    obstacles: p.snapshot ? p.snapshot.obstacles.length : 0,
    links: p.view && p.view.frame ? p.view.frame.links.length : 0,
    cells: cells.length,
    previewCells: document.querySelectorAll('.preview-cell').length,
    note: document.querySelector('.preview-note') ? document.querySelector('.preview-note').textContent.replace(/\s+/g, ' ').trim() : '',
    message: document.querySelector('.preview-message') ? document.querySelector('.preview-message').textContent : '',
    session: Boolean(window.__rrlab.session),
    select: document.getElementById('scenario').value,
  };
});

// The colours drawn in the 2D preview at each link's middle and each obstacle's position.
const previewPixels = (page) => page.evaluate(() => {
  const view = window.__rrlab.preview.view;
  const ratio = window.devicePixelRatio || 1;
  const at = (p) => {
    const s = view.toScreen(p);
    return [...view.context.getImageData(Math.round(s.x * ratio), Math.round(s.y * ratio), 1, 1).data.slice(0, 3)];
  };
  const links = view.frame.links.map((l) => at([(l[0] + l[3]) / 2, (l[1] + l[4]) / 2]));
  const obstacles = view.snapshot.obstacles.map((o, i) => ({ shape: o.shape, colour: at(view.frame.obstacles[i]) }));
  return { links, obstacles };
});
const white = ([r, g, b]) => r > 245 && g > 245 && b > 245;

// A preview drawn of `scenario` in a view of `kind`, the only thing in the centre.
async function waitForPreview(page, scenario, kind) {
  return eventually(async () => {
    const p = await preview(page);
    return p.scenario === scenario && p.kind === kind && p.drawn && p.cells === 1 && p.previewCells === 1 && !p.session ? p : null;
  }, `the preview of ${scenario} drawn (${kind})`);
}

await suite('start', [
  ['the start page draws the default scenario at once, says ready and offers Start live; a new pick redraws it', async (t) => {
    await t.page.goto(t.base);
    const first = (await t.get('/api/scenarios')).scenarios[0].name;
    const p = await waitForPreview(t.page, first, '2d');
    check(p.select === first, `the picker shows the scenario drawn (${p.select})`);
    check(p.obstacles > 0 && p.links > 0, `the arm (${p.links} links) and obstacles (${p.obstacles}) drawn`);
    check(/^Preview · .* at its start: not a run\. Press Start live/.test(p.note), `labelled a preview: "${p.note}"`);
    const pixels = await previewPixels(t.page);
    check(pixels.links.every((c) => !white(c)), `every link drawn (${JSON.stringify(pixels.links)})`);
    const filled = pixels.obstacles.filter((o) => o.shape === 'sphere' || o.shape === 'point');  // a polygon's position is an offset
    check(filled.length > 0 && filled.every((o) => !white(o.colour)), `the obstacles drawn (${JSON.stringify(pixels.obstacles)})`);
    check((await pill(t.page)) === 'ready', `the header says ready (${await pill(t.page)})`);
    check(!(await t.page.getAttribute('#connection', 'class')).includes('warn'), 'the pill is not a warning');
    const start = await t.page.evaluate(() => {
      const b = document.getElementById('start-live');
      return { primary: b.classList.contains('primary'), background: getComputedStyle(b).backgroundColor, other: getComputedStyle(document.getElementById('start-batch')).backgroundColor };
    });
    check(start.primary && start.background !== start.other, `Start live stands out (${JSON.stringify(start)})`);
    check((await t.page.evaluate(() => location.search)) === '', 'the address stays the start page\'s');
    check((await t.get('/api/runs')).length === 0, 'nothing stored: no run');
    await t.screenshot('start');

    // another scenario: drawn in its place
    await t.page.selectOption('#scenario', '01_planar7_obstacles');
    const second = await waitForPreview(t.page, '01_planar7_obstacles', '2d');
    const scenario = await t.get('/api/scenarios/01_planar7_obstacles');
    check(second.obstacles === scenario.obstacles.length && second.links === scenario.robot.links.length,
      `01_planar7_obstacles: ${second.links} links, ${second.obstacles} obstacles`);
    check(second.note.includes('01_planar7_obstacles'), `the label names it: "${second.note}"`);
    await t.screenshot('picked');

    // a 3D arm: three.js, as a run of it would be
    await t.page.selectOption('#scenario', '03_dh7_pose');
    await waitForPreview(t.page, '03_dh7_pose', '3d');
    await eventually(() => t.page.evaluate(() => window.__rrlab.preview.view.stats.renders > 0), 'the 3D preview rendered');
    await t.screenshot('picked-3d');

    // the next steps: Papers unfolds its section
    await t.page.locator('.preview-note button[data-goto="papers-section"]').click();
    check(await t.page.evaluate(() => document.getElementById('papers-section').open), 'Papers unfolds');

    // Start live: the run replaces the preview (one view, no preview left, no console error)
    await t.page.selectOption('#scenario', '01_planar7_obstacles');
    await waitForPreview(t.page, '01_planar7_obstacles', '2d');
    await t.page.locator('#start-live').click();
    const live = await eventually(async () => {
      const s = await t.page.evaluate(() => {
        const session = window.__rrlab.session, lane = session && session.lanes[0];
        return lane && lane.view && lane.frame ? { runId: lane.runId, kind: session.kind } : null;
      });
      const now = await preview(t.page);
      return s && now.previewCells === 0 && now.cells === 1 && now.kind === null ? s : null;
    }, 'the live run in place of the preview');
    check(/^(live|paused|ended)/.test(await pill(t.page)), `the header follows the run (${await pill(t.page)})`);
    check(await t.page.evaluate(() => document.querySelectorAll('#views canvas').length === 1), 'one canvas: the run\'s');
    await t.screenshot('live');
    await stopIfLive(t, live.runId);
  }],

  ['a replay, a compare, a paper and deep links replace the preview; an empty centre brings it back', async (t) => {
    const run = await t.post('/api/runs', { scenario: '01_planar7_obstacles', method: 'dls', mode: 'batch', steps: 20 });
    const group = await t.post('/api/compare', { scenario: '00_demo_avoidance', methods: ['pinv', 'dls'], mode: 'batch', steps: 20 });
    const ids = group.runs.map((r) => r.id).join(',');
    const replaced = async (what) => eventually(async () => {
      const p = await preview(t.page);
      return p.session && p.previewCells === 0 && p.kind === null ? p : null;
    }, `${what} in place of the preview`);

    // a deep link to a run: its replay, never the preview
    await t.page.goto(`${t.base}/?run=${run.id}`);
    await eventually(() => t.page.evaluate(() => { const l = window.__rrlab.session && window.__rrlab.session.lanes[0]; return l && l.view && l.frame; }), 'the replay drawn');
    await replaced('the replay');
    check((await t.page.evaluate(() => new URLSearchParams(location.search).get('run'))) === String(run.id), 'the address keeps the run');

    // closing it: the preview is back
    await t.page.evaluate(() => window.__rrlab.app.execute({ type: 'close' }));
    await waitForPreview(t.page, '00_demo_avoidance', '2d');
    check((await pill(t.page)) === 'ready', 'ready again');

    // a compare's deep link
    await t.page.goto(`${t.base}/?compare=${ids}`);
    await eventually(() => t.page.evaluate(() => { const s = window.__rrlab.session; return s && s.lanes.length === 2 && s.lanes.every((l) => l.view && l.frame); }), 'both lanes drawn');
    const compare = await replaced('the compare');
    check(compare.cells === 2, `two cells, the lanes' (${compare.cells})`);

    // a paper's page from the start page: no view left in the centre
    await t.page.goto(t.base);
    await waitForPreview(t.page, '00_demo_avoidance', '2d');
    await t.page.locator('#papers-section summary').click();
    await t.page.locator('#papers-list li[data-paper="sezgin"] button').click();
    await eventually(async () => {
      const p = await preview(t.page);
      return (await t.page.isVisible('#paper-page')) && p.previewCells === 0 && p.kind === null && p.cells === 0;
    }, 'the paper page without the preview');
    check((await pill(t.page)) === 'paper', 'the header says paper');
    await t.screenshot('paper');

    // a deep link to a paper, then the address of a scenario
    await t.page.goto(`${t.base}/?paper=qiu`);
    await eventually(() => t.page.isVisible('#paper-page'), 'the paper page');
    check((await preview(t.page)).previewCells === 0, 'no preview under a paper');
    await t.page.goto(`${t.base}/?scenario=01_planar7_obstacles`);
    const linked = await waitForPreview(t.page, '01_planar7_obstacles', '2d');
    check(linked.select === '01_planar7_obstacles', 'the picker shows the linked scenario');
  }],

  ['a scenario the server cannot preview is said in the view, not as a crash', async (t) => {
    await t.page.goto(t.base);
    await waitForPreview(t.page, '00_demo_avoidance', '2d');
    await t.page.evaluate(() => window.__rrlab.app.execute({ type: 'choose', scenario: 'no_such_scenario' }));
    const unknown = await eventually(async () => { const p = await preview(t.page); return p.message ? p : null; }, 'the message in the view');
    check(/No preview of no_such_scenario: there is no scenario "no_such_scenario"/.test(unknown.message), unknown.message);
    check(unknown.kind === null && unknown.cells === 1, 'no view left of the last preview');
    await t.page.evaluate(() => window.__rrlab.app.execute({ type: 'choose', scenario: 'bad name' }));
    const bad = await eventually(async () => { const p = await preview(t.page); return /bad name/.test(p.message) ? p : null; }, 'the bad name in the view');
    check(/letters, digits/.test(bad.message), bad.message);
    await t.screenshot('unknown');
    // a good pick draws again; on a phone too, its label inside the view
    await t.page.selectOption('#scenario', '01_planar7_obstacles');
    await waitForPreview(t.page, '01_planar7_obstacles', '2d');
    await t.page.setViewportSize({ width: 390, height: 844 });
    await eventually(async () => (await preview(t.page)).drawn, 'the preview redrawn at phone size');
    const fits = await t.page.evaluate(() => {
      const note = document.querySelector('.preview-note').getBoundingClientRect();
      const cell = document.querySelector('.preview-cell').getBoundingClientRect();
      return note.left >= cell.left && note.right <= cell.right && note.bottom < cell.top + cell.height / 3;
    });
    check(fits, 'the label fits the view on a phone and leaves it most of its height');
    await t.screenshot('phone');
    // Chromium logs the refusals (404, 400) as failed loads: expected here, nothing else is
    const rest = t.errors.filter((e) => !/status of 40[04]/.test(e));
    check(t.errors.length - rest.length === 2, `two refusals in the console (${t.errors.join('; ')})`);
    t.errors.length = 0;
    t.errors.push(...rest);
  }],
]);
