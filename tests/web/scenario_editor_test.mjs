// The scenario editor on the dashboard, against a real `rrlab serve`: a bad
// field is named and selected at its key; fixed, saved and started, its run
// exists; a taken name gets a new one offered; a syntax error is placed by
// line and column; uploads are read locally and size-limited.
// Usage: node scenario_editor_test.mjs   (RRLAB_BINARY, RRLAB_SCREENSHOTS, CHROMIUM)
import { suite, eventually, check, pageState } from './harness.mjs';

const button = (t, label) => t.page.getByRole('button', { name: label, exact: true });
const message = (t) => t.page.textContent('.se-message');

// A refused scenario is an answer, not a fault: drop the browser's note of
// the 422 (a bad field) and of a 405/404 (a server without /validate).
function forgetExpectedRefusals(t) {
  for (let i = t.errors.length - 1; i >= 0; --i) {
    if (/status of (404|405|422)/.test(t.errors[i])) t.errors.splice(i, 1);
  }
}

async function openEditor(t, scenario = '04_planar7_joystick') {
  await t.page.goto(`${t.base}/?scenario=${scenario}`);
  await eventually(async () => (await t.page.inputValue('#scenario')) === scenario, 'the scenario preselected');
  await t.page.click('#open-editor');
  await t.page.waitForSelector('dialog.scenario-editor[open] .se-textarea');
  await eventually(async () => (await t.page.inputValue('.se-textarea')).includes('"robot"'), 'the scenario in the editor');
}

// Waits for the editor's answer to an action (its message leaves "busy").
async function answer(t, kind) {
  await t.page.waitForSelector(`.se-message.se-${kind}`, { timeout: 10000 });
  return message(t);
}

async function scenarioText(t, name, edit = () => {}) {
  const scenario = await t.get('/api/scenarios/04_planar7_joystick');
  scenario.name = name;
  edit(scenario);
  return JSON.stringify(scenario, null, 2);
}

await suite('scenario editor', [
  ['a bad field is named and selected; fixed, saved and started, its run exists', async (t) => {
    await openEditor(t);
    const name = `editor_test_${Date.now()}`;
    const text = await scenarioText(t, name, (s) => { s.robot.links[3].length = -0.4; });
    await t.page.fill('.se-textarea', text);  // as pasted
    await button(t, 'Validate').click();
    await t.page.waitForSelector('.se-message:not(.se-busy)');
    if (!(await t.page.locator('.se-message.se-error').count())) {
      // a server without /api/scenarios/validate: Save is where it checks
      check(/syntax is fine/.test(await message(t)), `the editor says why it did not check: ${await message(t)}`);
      await button(t, 'Save').click();
    }
    const words = await answer(t, 'error');
    check(/must be > 0/.test(words), `the error in words: ${words}`);
    check(words.includes('robot.links[3].length'), `the error names the field: ${words}`);
    let fourthLength = -1;
    for (let k = 0; k < 4; ++k) fourthLength = text.indexOf('"length"', fourthLength + 1);
    const selection = await t.page.$eval('.se-textarea', (e) => ({ start: e.selectionStart, end: e.selectionEnd, focused: document.activeElement === e }));
    check(selection.start === fourthLength, `the selection starts at the 4th link's "length" key (${selection.start}, want ${fourthLength})`);
    check(text.slice(selection.start, selection.end) === '"length": -0.4', `the key and value are selected: ${text.slice(selection.start, selection.end)}`);
    check(selection.focused, 'the textarea has the focus, so the selection shows');
    check(await t.page.isVisible('.se-band'), 'the error line is marked');
    await t.screenshot('field-error');
    forgetExpectedRefusals(t);

    // type the fix over the selection; validate; save and start
    await t.page.keyboard.insertText('"length": 0.4');
    check(!(await t.page.isVisible('.se-band')), 'editing clears the mark');
    await button(t, 'Validate').click();
    await t.page.waitForSelector('.se-message:not(.se-busy)');
    const valid = await message(t);
    check(/✓ Valid: planar, 7 DOF, 3 obstacles, xy joystick task|syntax is fine/.test(valid), `valid now: ${valid}`);
    await t.screenshot('valid');
    await button(t, 'Save & start').click();
    await t.page.waitForSelector('dialog.scenario-editor', { state: 'hidden' });
    const run = await eventually(async () => (await t.get('/api/runs')).find((r) => r.scenario === name), 'a run of the saved scenario on the server');
    const lane = await eventually(() => pageState.lane(t.page), 'the new run on the page');
    check(lane.runId === run.id, `the page shows the run (${lane.runId}, want ${run.id})`);
    check((await t.page.inputValue('#scenario')) === name, 'the saved scenario is listed and selected');
    await t.post(`/api/runs/${run.id}/control`, { action: 'stop' });
    forgetExpectedRefusals(t);
  }],

  ['a taken name gets a new one offered; a syntax error is placed by line and column', async (t) => {
    const name = `editor_taken_${Date.now()}`;
    const text = await scenarioText(t, name);
    await t.post('/api/scenarios', JSON.parse(text));
    await openEditor(t);
    await t.page.fill('.se-textarea', text);
    await button(t, 'Save').click();
    const words = await answer(t, 'error');
    check(words.includes(`"${name}" exists already`) && words.includes(`"${name}_2"`), `the name is taken, a new one offered: ${words}`);
    const selected = await t.page.$eval('.se-textarea', (e) => e.value.slice(e.selectionStart, e.selectionEnd));
    check(selected === `"name": "${name}"`, `the name is selected: ${selected}`);
    await t.screenshot('name-taken');
    await button(t, `Rename to ${name}_2`).click();
    check((await t.page.inputValue('.se-textarea')).includes(`"name": "${name}_2"`), 'renamed in the text');
    await button(t, 'Save').click();
    await answer(t, 'ok');
    check((await t.get('/api/scenarios?limit=1000')).scenarios.some((s) => s.name === `${name}_2`), 'saved under the new name');

    // a missing comma: line and column where it belongs, and the caret there
    const broken = text.replace('"dt": 0.01,', '"dt": 0.01');
    await t.page.fill('.se-textarea', broken);
    await button(t, 'Validate').click();
    const syntax = await answer(t, 'error');
    const missing = broken.indexOf('"dt": 0.01') + '"dt": 0.01'.length;
    const line = broken.slice(0, missing).split('\n').length;
    check(syntax.includes(`syntax error at line ${line}, column 13: missing “,” after the value of "dt"`), `the syntax error placed: ${syntax}`);
    check((await t.page.$eval('.se-textarea', (e) => e.selectionStart)) === missing, 'the caret where the comma belongs');
    check((await t.page.textContent('.se-position')).startsWith(`Line ${line}, column 13`), 'the line/column readout follows');
    await t.screenshot('syntax-error');
    forgetExpectedRefusals(t);
  }],

  ['an uploaded file is read here, pretty-printed and size-limited; Esc closes', async (t) => {
    await openEditor(t);
    const compact = JSON.stringify({ ...(await t.get('/api/scenarios/01_planar7_obstacles')), name: 'uploaded_one' });
    await t.page.setInputFiles('.se-file', { name: 'mine.json', mimeType: 'application/json', buffer: Buffer.from(compact) });
    await eventually(async () => (await t.page.inputValue('.se-textarea')).includes('"name": "uploaded_one"'), 'the file in the editor, pretty-printed');
    check((await message(t)).includes('Loaded mine.json'), 'the editor says what it loaded');
    await t.page.setInputFiles('.se-file', { name: 'huge.json', mimeType: 'application/json', buffer: Buffer.alloc(1024 * 1024 + 1, 32) });
    check((await answer(t, 'error')).includes('up to 1 MiB'), 'a file over 1 MiB is refused');
    check((await t.page.inputValue('.se-textarea')).includes('"name": "uploaded_one"'), 'and the text is kept');
    await t.page.keyboard.press('Escape');
    await t.page.waitForSelector('dialog.scenario-editor', { state: 'hidden' });
  }],
]);
