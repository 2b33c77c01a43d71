// Compare as a newcomer meets it: the page opens on a scenario and a preset
// that separate the methods; the summary gives a verdict (best values, rows
// that differ, pass/fail against an editable criterion, "no difference"
// when there is none); 2–4 lanes lay out without empty cells; the plots keep
// their height beside the summary; a layout change applies to the group.
// Usage: node compare_test.mjs   (RRLAB_BINARY, RRLAB_SCREENSHOTS, CHROMIUM)
import { suite, eventually, check } from './harness.mjs';

const summaryCells = (page) => page.evaluate(() => [...document.querySelectorAll('#summary-table tr')].map((tr) => ({
  row: tr.dataset.row || tr.className,
  cells: [...tr.querySelectorAll('td')].slice(1).map((td) => ({ text: td.textContent, classes: td.className })),
})));

await suite('compare', [
  ['the opening preset separates the methods and the summary gives a verdict', async (t) => {
    await t.page.goto(t.base + '/');
    await t.page.waitForSelector('#compare-rows .compare-row');
    check((await t.page.inputValue('#scenario')) === '00_demo_avoidance', 'the page opens on the demo scenario');
    check((await t.page.inputValue('#compare-scenario')) === '00_demo_avoidance', 'the compare panel picks its own scenario, the demo first');
    const preset = await t.page.locator('#compare-rows select').evaluateAll((selects) => selects.map((s) => s.value));
    check(preset.join() === 'pinv,closest_point', `the preset compares pinv with an avoidance method (${preset})`);
    await t.page.selectOption('#rate', '0');  // as fast as possible: the group ends at once
    await t.page.click('#start-compare');
    await eventually(async () => !(await t.page.isHidden('#compare-summary')), 'the summary at the end');
    // the verdict says why, in words: when the contact began (once the stored frames are in) and its depth
    const said = /^closest_point passes; pinv fails \(collision at [\d.]+ s, [\d.]+ (cm|mm) deep\)\.$/;
    await eventually(async () => said.test(await t.page.textContent('.verdict-headline')), 'the headline with the time of the collision');
    const rows = await summaryCells(t.page);
    const verdict = rows.find((r) => r.row === 'verdict-row');
    check(verdict.cells.map((c) => c.text.slice(0, 4)).join() === 'fail,pass', `pass/fail per run: ${JSON.stringify(verdict.cells)}`);
    check(verdict.cells[0].text.includes('collision') && verdict.cells[1].text === 'pass', `the failing lane's reason beside it: ${verdict.cells[0].text}`);
    const distance = rows.find((r) => r.row === 'min_distance');
    check(distance.cells[1].classes.includes('best') && !distance.cells[0].classes.includes('best'), 'closest_point\'s clearance is marked best');
    check(await t.page.locator('#summary-table tr[data-row="min_distance"].differs').count() === 1, 'the clearance row is marked as differing');
    check(await t.page.locator('#summary-table tr[data-row="max_tracking_error"].differs').count() === 0, 'the tracking row is not (both 3 mm)');
    // the charts keep their height beside the summary
    const heights = await t.page.locator('#plots .plots-chart canvas').evaluateAll((cs) => cs.map((c) => c.getBoundingClientRect().height));
    check(heights.length >= 3 && heights.every((h) => h >= 100), `every chart keeps its height (${heights.map((h) => h.toFixed(0))})`);
    await t.screenshot('verdict');
    // a stricter criterion, typed on the page: both fail
    await t.page.fill('#crit-error', '0.001');
    await t.page.locator('#crit-error').dispatchEvent('change');
    const allFail = async () => /^All fail: pinv \(collision at [\d.]+ s, .* deep, tracking error [\d.]+ (cm|mm) > 1 mm at [\d.]+ s\); closest_point \(tracking error [\d.]+ (cm|mm) > 1 mm at [\d.]+ s\)\.$/.test(await t.page.textContent('.verdict-headline'));
    await eventually(allFail, 'the verdict under a 1 mm criterion, with each reason');
    // a decimal comma is a decimal point; text read two ways is refused beside the field
    await t.page.fill('#crit-error', '0,001');
    await t.page.press('#crit-error', 'Tab');
    await eventually(allFail, 'the verdict under "0,001"');
    await t.page.fill('#crit-error', '0,1.0');
    await t.page.press('#crit-error', 'Tab');
    await eventually(async () => (await t.page.getAttribute('#crit-error', 'aria-invalid')) === 'true', 'the criterion field marked');
    check((await t.page.inputValue('#crit-error')) === '0.001', `the field back to the criterion in use: ${await t.page.inputValue('#crit-error')}`);
    check((await t.page.textContent('.criterion + .field-error')).includes('two ways'), 'the message beside the field');
    await t.screenshot('criterion-refused');
    await t.page.click('#crit-default');
    await eventually(async () => (await t.page.textContent('.verdict-headline')).startsWith('closest_point passes'), 'the default criterion back');
    check(!(await t.page.getAttribute('#crit-error', 'aria-invalid')) && !(await t.page.isVisible('.criterion + .field-error')), 'the default clears the mark');
    await t.screenshot('criterion');
  }],

  ['lanes of one method are named by the parameters in which they differ', async (t) => {
    await t.page.goto(t.base + '/');
    await t.page.waitForSelector('#compare-rows .compare-row');
    await t.page.selectOption('#compare-scenario', '01_planar7_obstacles');
    const rows = t.page.locator('#compare-rows .compare-row');
    for (const [i, link] of [[0, 2], [1, 3]]) {
      await rows.nth(i).locator('select').selectOption('ccp_voronoi');
      await rows.nth(i).locator('input').fill(`ccp_link=${link}`);
    }
    await t.page.selectOption('#rate', '0');
    await t.page.click('#start-compare');
    await eventually(async () => !(await t.page.isHidden('#compare-summary')), 'the summary at the end');
    const texts = (selector) => t.page.locator(selector).evaluateAll((els) => els.map((e) => e.textContent.trim()));
    const want = ['ccp_voronoi · ccp_link=2', 'ccp_voronoi · ccp_link=3'];
    await eventually(async () => (await texts('#lane-tabs button')).join('|') === want.join('|'), 'the parameter tabs named by ccp_link');
    check((await texts('#summary-table th[data-lane]')).join('|') === want.join('|'), `the summary's columns: ${await texts('#summary-table th[data-lane]')}`);
    const headline = await t.page.textContent('.verdict-headline');
    // the verdict names lanes only when they part (one passes, another fails); then by these labels
    check(!headline.includes('ccp_voronoi') || (headline.includes('ccp_link=2') && headline.includes('ccp_link=3')), `the verdict names both lanes apart: ${headline}`);
    check((await texts('#metrics thead th')).slice(1).join('|') === want.join('|'), `the metric columns: ${await texts('#metrics thead th')}`);
    check(await t.page.evaluate(() => window.__rrlab.session.lanes.map((l) => l.view && l.view.label).join('|')) === want.join('|'), 'the views\' captions');
    await eventually(async () => {
      const list = await texts('#runs li .muted');
      return want.every((label) => list.some((line) => line.startsWith(label)));
    }, 'the run list names both runs by ccp_link');
    const page = await t.page.textContent('body');
    check(page.includes('ccp_link=2') && page.includes('ccp_link=3'), 'ccp_link=2 and ccp_link=3 on the page');
    await t.screenshot('labels');
  }],
  ['a parameter the server refuses is marked at its row, in words, and the row keeps what was typed', async (t) => {
    await t.page.goto(t.base + '/');
    await t.page.waitForSelector('#compare-rows .compare-row');
    const rows = t.page.locator('#compare-rows .compare-row');
    await rows.nth(1).locator('select').selectOption('dls');
    await rows.nth(1).locator('input').fill('lamda=0.1');
    await t.page.click('#start-compare');
    const note = rows.nth(1).locator('.field-error');
    await eventually(async () => (await note.count()) === 1 && (await note.textContent()).length > 0, 'the message at the second row');
    const text = await note.textContent();
    check(/^method 2 \(dls\): lamda: unknown parameter of dls \(known: .*lambda/.test(text), `said at the row, without the API path: ${text}`);
    check((await rows.nth(1).locator('input').getAttribute('aria-invalid')) === 'true' && (await rows.nth(1).locator('input').inputValue()) === 'lamda=0.1', 'the field marked, its text kept');
    check(!(await t.page.isVisible('#message')) && !text.includes('methods['), 'no banner, no path');
    await t.screenshot('row-refused');
    // a list that is not name=value: said at its row before anything is sent
    await rows.nth(0).locator('input').fill('lambda');
    await t.page.click('#start-compare');
    await eventually(async () => /^method 1 \(pinv\): write parameters as name=value/.test(await rows.nth(0).locator('.field-error').textContent()), 'the first row\'s message');
    check(!(await rows.nth(1).locator('.field-error').isVisible()), 'the second row\'s old message cleared');
    // corrected: the group starts, the marks go
    await rows.nth(0).locator('input').fill('');
    await rows.nth(1).locator('input').fill('lambda=0.1');
    await t.page.selectOption('#rate', '0');
    await t.page.click('#start-compare');
    await eventually(() => t.page.evaluate(() => Boolean(window.__rrlab.session && window.__rrlab.session.compare)), 'the group started');
    check(await rows.nth(1).locator('input').getAttribute('aria-invalid') === null, 'the mark cleared');
    for (let i = t.errors.length - 1; i >= 0; --i) if (/status of 400/.test(t.errors[i])) t.errors.splice(i, 1);  // the refusal the test asked for
  }],

  ['methods that give the same result are said to give no difference', async (t) => {
    // damped least squares without damping is the pseudoinverse
    const group = await t.post('/api/compare', { scenario: '01_planar7_obstacles', methods: ['pinv', { name: 'dls', params: { lambda: 0 } }], mode: 'batch' });
    await t.page.goto(`${t.base}/?compare=${group.runs.map((r) => r.id).join(',')}`);
    await eventually(async () => !(await t.page.isHidden('#compare-summary')), 'the summary of a stored group');
    const headline = await t.page.textContent('.verdict-headline');
    check(headline.startsWith('No difference'), `the headline: ${headline}`);
    check(await t.page.locator('#summary-table tr:not([data-row^="step"]) td.best').count() === 0, 'no result is marked best (only the faster step time)');
  }],

  ['three and four lanes fill their grid; the layout applies to the group on screen', async (t) => {
    for (const methods of [['pinv', 'dls', 'closest_point'], ['pinv', 'dls', 'closest_point', 'gpm']]) {
      const group = await t.post('/api/compare', { scenario: '00_demo_avoidance', methods, mode: 'batch', steps: 50 });
      await t.page.goto(`${t.base}/?compare=${group.runs.map((r) => r.id).join(',')}&frame=10`);
      await eventually(() => t.page.evaluate((n) => window.__rrlab.session && window.__rrlab.session.lanes.filter((l) => l.view).length === n, methods.length), `${methods.length} views`);
      const cells = await t.page.locator('#views .view-cell').evaluateAll((els) => els.map((e) => { const r = e.getBoundingClientRect(); return { x: r.x, y: r.y, w: r.width, h: r.height }; }));
      const views = await t.page.locator('#views').evaluate((e) => { const r = e.getBoundingClientRect(); return { x: r.x, y: r.y, w: r.width, h: r.height }; });
      const area = cells.reduce((a, c) => a + c.w * c.h, 0);
      check(area > 0.9 * views.w * views.h, `${methods.length} lanes fill the view area (${(100 * area / (views.w * views.h)).toFixed(0)} %)`);
      // the metrics are readable: no cell cut short ("0.23…", "clos…"), every lane's parameter tab on screen
      await eventually(async () => (await t.page.locator('#metrics tbody tr').count()) > 5, 'the metrics');
      const cut = await t.page.locator('#metrics th, #metrics td').evaluateAll((els) => els.filter((e) => e.scrollWidth > e.clientWidth + 1).map((e) => e.textContent));
      check(cut.length === 0, `${methods.length} lanes: no metric cut short (${cut.join(' | ')})`);
      const tabs = await t.page.locator('#lane-tabs button').evaluateAll((els) => els.map((e) => e.getBoundingClientRect().right <= window.innerWidth && e.offsetParent !== null));
      check(tabs.length === methods.length && tabs.every(Boolean), `every lane's parameter tab shown (${tabs})`);
      await t.screenshot(`${methods.length}-lanes`);
    }
    await t.page.click('#compare-setup > summary');  // the panel folds away while a session is on screen
    await t.page.selectOption('#compare-layout', 'overlay');
    await eventually(async () => (await t.page.locator('#views .view-cell').count()) === 1, 'the group on screen overlaid');
    await eventually(() => t.page.evaluate(() => window.__rrlab.replay.seq === 10), 'the frame kept across the layout change');
    await t.screenshot('overlaid');
  }],
]);
