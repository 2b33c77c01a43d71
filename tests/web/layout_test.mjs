// The layout as people meet it: column borders that drag and are remembered
// in this browser; a 390 px phone in portrait with the views stacked and
// nothing wider than the screen (start page, a run, a compare, a paper, a
// sweep); the keyboard shortcut list on "?".
// Usage: node layout_test.mjs   (RRLAB_BINARY, RRLAB_SCREENSHOTS, CHROMIUM)
import { suite, eventually, check, pageState } from './harness.mjs';

const overflow = (page) => page.evaluate(() => ({
  page: document.documentElement.scrollWidth, screen: window.innerWidth,
  widest: [...document.querySelectorAll('body *')].filter((e) => e.getBoundingClientRect().right > window.innerWidth + 0.5 && e.getClientRects().length)
    .filter((e) => !e.closest('#sweep-page, #paper-page, #compare-summary, .uplot'))
    .slice(0, 3).map((e) => `${e.tagName.toLowerCase()}#${e.id}.${e.className} ${Math.round(e.getBoundingClientRect().right)}`),
}));

async function fitsThePhone(t, what) {
  const o = await overflow(t.page);
  check(o.page <= o.screen && o.widest.length === 0, `${what}: the page is ${o.page} px wide on a ${o.screen} px screen (${o.widest.join('; ')})`);
}

await suite('layout', [
  ['a column border drags, and the width is remembered after a reload', async (t) => {
    await t.page.goto(t.base + '/');
    await t.page.waitForSelector('#scenario option', { state: 'attached' });
    const width = () => t.page.evaluate(() => document.getElementById('left').getBoundingClientRect().width);
    const before = await width();
    const box = await t.page.locator('.splitter[data-side="left"]').boundingBox();
    await t.page.mouse.move(box.x + box.width / 2, box.y + 200);
    await t.page.mouse.down();
    for (let i = 1; i <= 5; ++i) await t.page.mouse.move(box.x + box.width / 2 + 20 * i, box.y + 200);
    await t.page.mouse.up();
    const dragged = await width();
    check(Math.abs(dragged - (before + 100)) <= 2, `the column widens by the drag (${before} → ${dragged})`);
    await t.page.reload();
    await t.page.waitForSelector('#scenario option', { state: 'attached' });
    check(Math.abs((await width()) - dragged) <= 1, 'the width is remembered');
    // the keyboard moves a focused border too
    await t.page.focus('.splitter[data-side="left"]');
    await t.page.keyboard.press('ArrowLeft');
    check(Math.abs((await width()) - (dragged - 16)) <= 1, 'ArrowLeft narrows it by 16 px');
    // "?" lists the shortcuts
    await t.page.locator('#views').click({ position: { x: 5, y: 5 } });
    await t.page.keyboard.press('?');
    check(await t.page.isVisible('#keys-dialog'), 'the shortcut list opens on "?"');
    check((await t.page.textContent('#keys-dialog')).includes('one frame back'), 'it lists the replay keys');
    await t.screenshot('keys');
    await t.page.keyboard.press('Escape');
    check(await t.page.isHidden('#keys-dialog'), 'Escape closes it');
  }],

  ['a 390 px phone in portrait: views stacked first, nothing overflows', async (t) => {
    await t.page.setViewportSize({ width: 390, height: 844 });
    await t.page.goto(t.base + '/');
    await t.page.waitForSelector('#scenario option', { state: 'attached' });
    await fitsThePhone(t, 'the start page');
    const order = await t.page.evaluate(() => ['center', 'left', 'right'].map((id) => document.getElementById(id).getBoundingClientRect().top));
    check(order[0] < order[1] && order[1] < order[2], `the views come first, then the controls, then the runs (${order})`);
    await t.screenshot('phone-start');

    const run = await t.post('/api/runs', { scenario: '01_planar7_obstacles', mode: 'batch', steps: 200 });
    await t.page.goto(`${t.base}/?run=${run.id}&frame=100`);
    await eventually(() => pageState.lane(t.page), 'the replay');
    const view = await t.page.locator('#views').boundingBox();
    check(view.width >= 370 && view.height >= 240, `the view fills the width (${view.width}×${view.height})`);
    await fitsThePhone(t, 'a replay');
    await t.screenshot('phone-replay');

    const spatial = await t.post('/api/runs', { scenario: '17_chen_sim2_spatial16_window', mode: 'batch', steps: 40 });
    await t.page.goto(`${t.base}/?run=${spatial.id}&frame=20`);
    await eventually(() => t.page.evaluate(() => { const s = window.__rrlab.session; return s && s.lanes[0].view && s.lanes[0].frame && s.lanes[0].frame.seq === 20; }), 'the 3D replay');
    await fitsThePhone(t, 'a 3D replay');
    await eventually(() => t.page.evaluate(() => { const l = document.querySelector('.view3d-legend'); return l && !l.hidden; }), 'the ellipsoid\'s legend');
    const legendInside = await t.page.evaluate(() => {
      const l = document.querySelector('.view3d-legend').getBoundingClientRect(), v = document.getElementById('views').getBoundingClientRect();
      return l.bottom <= v.bottom + 0.5 && l.right <= v.right + 0.5;
    });
    check(legendInside, 'the 3D legend inside the view, not cut off');
    await t.screenshot('phone-3d');

    const group = await t.post('/api/compare', { scenario: '01_planar7_obstacles', methods: ['pinv', 'dls', 'gpm'], mode: 'batch', steps: 100 });
    await t.page.goto(`${t.base}/?compare=${group.runs.map((r) => r.id).join(',')}&frame=50`);
    await eventually(() => t.page.evaluate(() => window.__rrlab.session && window.__rrlab.session.lanes.every((l) => l.view)), 'three views');
    await fitsThePhone(t, 'a compare of three');
    const cells = await t.page.locator('#views .view-cell').evaluateAll((els) => els.map((e) => e.getBoundingClientRect()).map((r) => ({ x: r.x, w: r.width })));
    check(cells.every((c) => c.w >= 170), `the lanes two abreast, each half the screen (${cells.map((c) => Math.round(c.w))})`);
    // scrubbing: the scrubber and every lane on one screen
    await t.page.locator('#scrubber').scrollIntoViewIfNeeded();
    const onScreen = await t.page.evaluate(() => {
      const boxes = [...document.querySelectorAll('#views .view-cell, #scrubber')].map((e) => e.getBoundingClientRect());
      return boxes.every((r) => r.top >= -0.5 && r.bottom <= window.innerHeight + 0.5);
    });
    check(onScreen, 'every lane and the scrubber on screen together');
    await t.page.locator('#scrubber').focus();
    await t.page.keyboard.press('End');
    await eventually(() => t.page.evaluate(() => window.__rrlab.session.lanes.every((l) => l.frame && l.frame.seq === 99)), 'every lane at the end');
    await t.screenshot('phone-compare');

    await t.page.goto(`${t.base}/?paper=qiu`);
    await t.page.waitForSelector('.paper-examples');
    await fitsThePhone(t, 'a paper');
    check(await t.page.evaluate(() => document.getElementById('paper-page').getBoundingClientRect().right <= window.innerWidth + 0.5), 'the paper page fits');
    // each example a card: the mark and the buttons on screen, not in a scrolled-off column
    const offscreen = await t.page.evaluate(() => [...document.querySelectorAll('.paper-examples td.mark, .paper-examples .actions button')]
      .filter((el) => el.getBoundingClientRect().right > window.innerWidth + 0.5).length);
    check(offscreen === 0, `every mark and button within the screen (${offscreen} outside)`);
    await t.screenshot('phone-paper');
  }],
]);
