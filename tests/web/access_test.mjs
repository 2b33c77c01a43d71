// The dashboard on a server started with --token: it asks for the token once
// (kept in the tab's session storage), retries, and everything then works —
// the run list, a live run's WebSocket, its controls — under the page's
// Content-Security-Policy (a violation would be a console error and fail the test).
// Usage: node access_test.mjs   (RRLAB_BINARY, RRLAB_SCREENSHOTS, CHROMIUM)
import { suite, eventually, check, pageState, longScenario } from './harness.mjs';

const TOKEN = 'lab-Token_4711-0123';
const controllerOf = (page) => page.getAttribute('#control-note', 'data-controller');

// Chromium logs every 401 answer as "Failed to load resource": those are the
// answers the page is expected to get before it has the token.
function forgive401(t) {
  const rest = t.errors.filter((e) => !/status of 401/.test(e));
  t.errors.length = 0;
  t.errors.push(...rest);
}

async function typeToken(t, token) {
  await eventually(() => t.page.isVisible('#token-dialog'), 'the token dialog');
  await t.page.fill('#token-input', token);
  await t.page.press('#token-input', 'Enter');
}

await suite('access', [
  ['the page asks for the token once, then the run list loads', async (t) => {
    const run = await t.post('/api/runs', { scenario: '01_planar7_obstacles', mode: 'batch', steps: 20, wait: true });
    const response = await t.page.goto(t.base + '/');
    const csp = response.headers()['content-security-policy'] || '';
    check(csp.includes("default-src 'self'") && !csp.includes('unsafe-inline'), `the page has a strict policy: ${csp}`);
    await eventually(() => t.page.isVisible('#token-dialog'), 'the token dialog');
    check((await t.page.locator('#runs li').count()) === 0, 'no runs are shown before the token');
    await t.screenshot('asks');
    await typeToken(t, TOKEN);
    await eventually(async () => (await t.page.locator(`#runs li[data-run="${run.id}"]`).count()) === 1, 'the run list');
    await eventually(async () => (await t.page.locator('#scenario option').count()) > 3, 'the scenario list');
    check(!(await t.page.isVisible('#token-dialog')), 'the dialog closed');
    check(await t.page.evaluate(() => sessionStorage.getItem('rrlab.token')) === '' + TOKEN, 'the token is in session storage');
    await t.screenshot('loaded');
    // a reload does not ask again
    await t.page.reload();
    await eventually(async () => (await t.page.locator(`#runs li[data-run="${run.id}"]`).count()) === 1, 'the run list after a reload');
    check(!(await t.page.isVisible('#token-dialog')), 'no second prompt');
    forgive401(t);
  }],

  ['a wrong token is asked again, then a live run streams and obeys', async (t) => {
    // 01 for 600 s: still live after the token rounds however slow the machine
    const run = await t.post('/api/runs', { scenario: await longScenario(t), mode: 'live', rate: 1 });
    await t.page.goto(`${t.base}/?run=${run.id}`);
    await typeToken(t, 'wrong-token');
    await eventually(async () => (await t.page.textContent('#token-why')).includes('refused'), 'the refusal in the dialog');
    await t.screenshot('refused');
    await typeToken(t, TOKEN);
    const first = await eventually(() => pageState.lane(t.page), 'the first frame over the WebSocket');
    await eventually(async () => (await pageState.lane(t.page)).step > first.step + 10, 'frames to advance');
    await t.page.click('#controls button[data-action="pause"]');
    await eventually(async () => (await t.get(`/api/runs/${run.id}`)).status === 'paused', 'the run to pause');
    await t.page.click('#controls button[data-action="stop"]');
    await eventually(async () => (await t.get(`/api/runs/${run.id}`)).status === 'stopped', 'the run to stop');
    forgive401(t);
  }],

  ['a second tab watches until it takes control', async (t) => {
    // 01 for 600 s: still live after two page loads with the token however slow the machine
    const run = await t.post('/api/runs', { scenario: await longScenario(t), mode: 'live', rate: 1 });
    const other = await t.page.context().browser().newPage({ viewport: { width: 1400, height: 900 } });
    try {
      // the first tab steers and so holds control
      for (const page of [t.page, other]) {
        await page.goto(`${t.base}/?run=${run.id}`);
        await eventually(() => page.isVisible('#token-dialog'), 'the token dialog');
        await page.fill('#token-input', TOKEN);
        await page.press('#token-input', 'Enter');
        await eventually(() => pageState.lane(page), 'the first frame');
      }
      await t.page.click('#controls button[data-action="pause"]');
      await eventually(async () => (await t.get(`/api/runs/${run.id}`)).status === 'paused', 'the run to pause');
      // each tab hears who holds control before anyone else tries to steer
      await eventually(async () => (await controllerOf(t.page)) === 'you', 'the first tab is told it controls');
      check(await t.page.isVisible('#release-control'), 'the holder is offered Release');
      await eventually(async () => (await controllerOf(other)) === 'other', 'the second tab is told it watches');
      check(await other.isVisible('#control-note') && await other.isVisible('#take-control'), 'the watcher is offered Take control');
      await other.click('#controls button[data-action="start"]');
      // the refusal (409 not_controller) is said in plain words
      await eventually(async () => (await other.textContent('#message')).includes('Another client controls this run'), 'a plain message');
      check((await t.get(`/api/runs/${run.id}`)).status === 'paused', 'the watcher did not steer');
      await t.screenshot('first-tab');
      await other.click('#take-control');
      await eventually(async () => (await controllerOf(t.page)) === 'other', 'the first tab is told control was taken');
      check(await t.page.isVisible('#take-control'), 'the first tab may take it back');
      await other.click('#controls button[data-action="start"]');
      await eventually(async () => (await t.get(`/api/runs/${run.id}`)).status === 'running', 'the new holder starts it');
      await t.screenshot('taken');
      await other.click('#release-control');
      await eventually(async () => (await controllerOf(t.page)) === 'none', 'the first tab is told nobody holds control');
      check(!(await t.page.isVisible('#control-note')), 'nothing to say when nobody holds control');
      await other.click('#controls button[data-action="stop"]');
      await eventually(async () => (await t.get(`/api/runs/${run.id}`)).status === 'stopped', 'the run to stop');
    } finally {
      await other.close();
    }
    forgive401(t);
  }],

  ['the policy refuses inline script and style, and says so in the console', async (t) => {
    await t.page.goto(t.base + '/');
    await typeToken(t, TOKEN);
    await eventually(async () => (await t.page.locator('#scenario option').count()) > 3, 'the scenario list');
    check(await t.page.evaluate(() => Boolean(window.__rrlab)), 'the page\'s modules ran (import map allowed by its hash)');
    await t.page.evaluate(() => {
      const script = document.createElement('script');
      script.textContent = 'window.inlineRan = true;';
      document.body.appendChild(script);
      const div = document.createElement('div');
      div.innerHTML = '<span id="inline-styled" style="color: rgb(255, 0, 0)">x</span>';
      document.body.appendChild(div);
    });
    await eventually(() => t.errors.filter((e) => /Content Security Policy/.test(e)).length >= 2, 'two policy violations in the console');
    check(!(await t.page.evaluate(() => window.inlineRan)), 'the inline script did not run');
    check((await t.page.evaluate(() => getComputedStyle(document.getElementById('inline-styled')).color)) !== 'rgb(255, 0, 0)', 'the inline style was not applied');
    // these violations were provoked; any other console error still fails the test
    const rest = t.errors.filter((e) => !/Content Security Policy/.test(e));
    t.errors.length = 0;
    t.errors.push(...rest);
    forgive401(t);
  }],
], { token: TOKEN });
