// The Papers panel as a researcher uses it: five papers listed with their
// citation; /?paper=KEY shows the paper's examples with the paper's outcome,
// rrlab's result and mark and the scenarios' full descriptions; one click runs
// an example live with its configuration, or as a compare with the paper's
// baselines.
// Usage: node papers_test.mjs   (RRLAB_BINARY, RRLAB_SCREENSHOTS, CHROMIUM)
import { suite, eventually, check } from './harness.mjs';

const laneLabels = (page) => page.evaluate(() => {
  const s = window.__rrlab.session;
  return s && s.lanes.every((l) => l.snapshot) ? s.lanes.map((l) => l.snapshot.method) : null;
});

await suite('papers', [
  ['the panel lists five papers and each opens with its examples, marks and full scenario descriptions', async (t) => {
    await t.page.goto(t.base + '/');
    await t.page.click('#papers-section > summary');
    await eventually(async () => (await t.page.locator('#papers-list li').count()) === 5, 'five papers in the list');
    const listed = await t.page.locator('#papers-list li').evaluateAll((lis) => lis.map((li) => li.dataset.paper));
    check(listed.join() === 'sezgin,chen,qiu,zhang,kapoor', `the five papers: ${listed}`);
    const expected = { sezgin: 30, chen: 4, qiu: 5, zhang: 6, kapoor: 3 };
    for (const key of listed) {
      await t.page.locator(`#papers-list li[data-paper="${key}"] button`).click();
      await eventually(async () => (await t.page.locator('.paper-examples tr[data-example]').count()) === expected[key], `${key}'s ${expected[key]} examples`);
      check(new URLSearchParams(new URL(t.page.url()).search).get('paper') === key, `the address names the paper: ${t.page.url()}`);
      const marks = await t.page.locator('.paper-examples td.mark').allTextContents();
      check(marks.every((m) => /^[✓◐✗]/.test(m)), `${key}: every example has a mark`);
      // the tally (the README's) counts the rows the page shows, and the marks in them
      const tally = await t.page.textContent('.paper-tally');
      const parts = tally.match(/^(\d+) ✓, (\d+) ◐, (\d+) ✗ of (\d+); (\d+) of them \(rrlab\)$/);
      check(parts, `${key}: a tally "N ✓, M ◐, L ✗ of K; R of them (rrlab)": ${tally}`);
      const counted = ['✓', '◐', '✗'].map((m) => marks.filter((x) => x.startsWith(m)).length);
      check(Number(parts[4]) === marks.length && counted.every((n, i) => n === Number(parts[i + 1])) &&
            Number(parts[5]) === marks.filter((m) => /\(rrlab[;)]/.test(m)).length, `${key}: the tally counts the page's rows: ${tally}`);
      // the page says what to use in the paper's setting, and why (rates from its rows)
      const advice = await t.page.textContent('.paper-advice');
      check(/^What to use in this paper's setting: .+, which succeeds on \d+ % of the nudged copies .+ against .+ \d+ %.*\.$/.test(advice), `${key}: the advice: ${advice}`);
    }
    await t.screenshot('kapoor');  // the last one opened, at its top: the tally and the rows
    await t.page.goto(`${t.base}/?paper=sezgin`);
    await t.page.waitForSelector('.paper-title');
    check((await t.page.textContent('.paper-title')) === 'Redundancy utilization for obstacle avoidance of planar robot manipulators', 'the title');
    check((await t.page.textContent('.paper-authors')).includes('U. Sezgin, L. D. Seneviratne and S. W. E. Earles (1997)'), 'authors and year');
    // a scenario's description, in full (the list gives 200 characters)
    const details = t.page.locator('.scenario-text').first();
    await details.locator('summary').click();
    const text = await details.locator('p').textContent();
    check(text.length > 200, `the full description (${text.length} characters)`);
    await t.screenshot('sezgin');
  }],

  ['an example runs live with its configuration, or as a compare with the paper\'s baselines', async (t) => {
    await t.page.goto(`${t.base}/?paper=qiu`);
    await t.page.waitForSelector('.paper-examples tr[data-example]');
    // Ex. 1, Fig. 4 with rrlab's criterion term φ: qp_constraints against pinv
    const row = t.page.locator('.paper-examples tr[data-example]', { hasText: 'Ex. 1, Fig. 4, with rrlab\'s φ' });
    await row.locator('.run-compare').click();
    const labels = await eventually(() => laneLabels(t.page), 'the compare group');
    check(labels.join() === 'qp_constraints,pinv', `qp_constraints beside pinv: ${labels}`);
    const params = await t.page.evaluate(() => window.__rrlab.session.lanes[0].snapshot.params);
    check(params.d_s === 0.1 && params.sigma === 0.2, `the row's parameters reached the run: ${JSON.stringify(params)}`);
    check(await t.page.isHidden('#paper-page'), 'the paper page gives way to the runs');
    await t.screenshot('qiu-compare');
    await t.post(`/api/runs/${await t.page.evaluate(() => window.__rrlab.session.runIds[0])}/control`, { action: 'stop' });

    // the same row beside today's baselines: qp_ik, hqp and diffik with their defaults
    await t.page.goto(`${t.base}/?paper=qiu`);
    await t.page.waitForSelector('.paper-examples tr[data-example]');
    await t.page.locator('.paper-examples tr[data-example]', { hasText: 'Ex. 1, Fig. 4, with rrlab\'s φ' }).locator('.run-modern').click();
    const modern = await eventually(async () => { const l = await laneLabels(t.page); return l && l.length === 4 ? l : null; }, 'the four lanes');
    check(modern.join() === 'qp_constraints,qp_ik,hqp,diffik', `qp_constraints beside today's baselines: ${modern}`);
    await t.screenshot('qiu-todays-baselines');
    await t.post(`/api/runs/${await t.page.evaluate(() => window.__rrlab.session.runIds[0])}/control`, { action: 'stop' });  // the group stops together

    // a Sezgin example live: its CCP configuration (choice parameters by label)
    await t.page.goto(`${t.base}/?paper=sezgin`);
    await t.page.waitForSelector('.paper-examples tr[data-example]');
    await t.page.locator('.paper-examples tr[data-example]', { hasText: 'Fig. 3b, CCP at joint 3' }).first().locator('.run-live').click();
    const live = await eventually(() => laneLabels(t.page), 'the live run');
    check(live.join() === 'ccp_voronoi', `ccp_voronoi runs: ${live}`);
    const ccp = await t.page.evaluate(() => window.__rrlab.session.lanes[0].snapshot.params.ccp_link);
    check(ccp === 3, `the CCP at joint 3 (ccp_link ${ccp})`);
    await t.post(`/api/runs/${await t.page.evaluate(() => window.__rrlab.session.runIds[0])}/control`, { action: 'stop' });
  }],
]);
