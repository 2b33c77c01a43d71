// A run shared as one file (GET /api/runs/{id}/export.html, issue 42 item 13):
// the export of a batch run of the planar demo, written to a file and opened
// from disk with every network request refused, draws the arm, has a
// scrubber, and seeking to the end changes the picture; a compare group's
// export draws every lane; the dashboard's Export dialog downloads it.
import { mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { pathToFileURL } from 'node:url';
import { suite, eventually, check, animationFrames } from './harness.mjs';

const MAX_PLANAR_DEMO_BYTES = 3 * 1024 * 1024;

// The export of `path` as text, with its answer's headers.
async function fetchExport(t, path) {
  const response = await fetch(t.base + path);
  check(response.ok, `GET ${path}: ${response.status} ${await response.clone().text()}`);
  return { text: await response.text(), type: response.headers.get('content-type'), disposition: response.headers.get('content-disposition') };
}

// Opens `html` from a file with the network refused; returns the requests it tried.
async function openOffline(t, html, name) {
  const dir = mkdtempSync(join(tmpdir(), 'rrlab-export-'));
  const file = join(dir, name);
  writeFileSync(file, html);
  const url = pathToFileURL(file).href;
  const refused = [];
  await t.page.route('**/*', (route) => {
    if (route.request().url() === url) return route.continue();
    refused.push(route.request().url());
    return route.abort('blockedbyclient');
  });
  await t.page.context().setOffline(true);
  process.on('exit', () => rmSync(dir, { recursive: true, force: true }));
  await t.page.goto(url);
  await eventually(() => t.page.evaluate(() => document.body.dataset.ready === 'true'), 'the viewer to have read its data');
  return refused;
}

// Pixels of a lane's canvas: how many look like the arm (#37474f), and a hash of the whole.
const lanePixels = (page, index) => page.evaluate((i) => {
  const canvas = document.querySelectorAll('.lane canvas')[i];
  const data = canvas.getContext('2d').getImageData(0, 0, canvas.width, canvas.height).data;
  let arm = 0, hash = 0;
  for (let p = 0; p < data.length; p += 4) {
    if (Math.abs(data[p] - 0x37) < 6 && Math.abs(data[p + 1] - 0x47) < 6 && Math.abs(data[p + 2] - 0x4f) < 6) arm++;
    hash = (hash * 31 + data[p] + 7 * data[p + 1] + 13 * data[p + 2]) | 0;
  }
  return { arm, hash, width: canvas.width, height: canvas.height };
}, index);

await suite('html_export', [
  ['a batch run of the planar demo replays from a file with the network refused', async (t) => {
    const run = await t.post('/api/runs', { scenario: '01_planar7_obstacles', method: 'dls', mode: 'batch' });
    const exported = await fetchExport(t, `/api/runs/${run.id}/export.html`);
    console.log(`     export of run ${run.id} (${run.frames} frames): ${exported.text.length} bytes`);
    check(exported.text.length <= MAX_PLANAR_DEMO_BYTES, `the planar demo's export is ${exported.text.length} bytes, over 3 MB`);
    check(/^text\/html/.test(exported.type), `content type ${exported.type}`);
    check(/attachment; filename="rrlab-run-\d+\.html"/.test(exported.disposition || ''), `disposition ${exported.disposition}`);
    check(!/<script[^>]*\ssrc=|<link\b|<img\b|type="module"|\bimport\s*\(|\bfetch\(|XMLHttpRequest/.test(exported.text), 'the export loads nothing from elsewhere');

    const refused = await openOffline(t, exported.text, `rrlab-run-${run.id}.html`);
    const page = t.page;
    const range = page.locator('input[type="range"]');
    check(await range.count() === 1, 'one range input');
    check(Number(await range.getAttribute('max')) === run.frames - 1, `the scrubber spans the run's ${run.frames} frames`);
    const start = await eventually(async () => { const p = await lanePixels(page, 0); return p.arm > 200 && p; }, 'the arm drawn in the view');
    await t.screenshot('start');

    // to the end as a person does: focus the scrubber, press End
    await range.focus();
    await page.keyboard.press('End');
    await eventually(async () => Number(await range.inputValue()) === run.frames - 1, 'the scrubber at its end');
    const end = await eventually(async () => { const p = await lanePixels(page, 0); return p.hash !== start.hash && p; }, 'the picture to change at the end');
    check(end.arm > 200, 'the arm still drawn at the end');
    check(/frame \d+ of \d+/.test(await page.locator('#time').textContent()), 'the time label names the frame');
    await t.screenshot('end');

    // Play from the start moves the scrubber on its own
    await range.focus();
    await page.keyboard.press('Home');
    await page.getByRole('button', { name: 'play or pause' }).click();
    await eventually(async () => Number(await range.inputValue()) > 10, { message: 'playing to move the scrubber', timeout: 20000 });
    await page.getByRole('button', { name: 'play or pause' }).click();
    await animationFrames(page);
    check(refused.length === 0, `the export asked the network for ${refused.join(', ')}`);
  }],

  ['a compare group replays from a file, every lane drawn, and a small cap decimates with a note', async (t) => {
    const compare = await t.post('/api/compare', { scenario: '01_planar7_obstacles', methods: ['pinv', 'dls', 'closest_point'], mode: 'batch' });
    const group = compare.group;
    check(group === Math.min(...compare.runs.map((r) => r.id)), 'the group is its first run');
    const exported = await fetchExport(t, `/api/compare/${group}/export.html`);
    console.log(`     export of compare group ${group}: ${exported.text.length} bytes`);
    const refused = await openOffline(t, exported.text, `rrlab-compare-${group}.html`);
    const page = t.page;
    check(await page.locator('.lane canvas').count() === 3, 'three lanes');
    for (let i = 0; i < 3; i++) await eventually(async () => (await lanePixels(page, i)).arm > 100 || (await lanePixels(page, i)).hash !== 0, `lane ${i} drawn`);
    const before = await lanePixels(page, 2);
    await page.locator('input[type="range"]').focus();
    await page.keyboard.press('End');
    await eventually(async () => (await lanePixels(page, 2)).hash !== before.hash, 'the third lane to change at the end');
    await t.screenshot('compare-end');
    check(refused.length === 0, `the export asked the network for ${refused.join(', ')}`);

    // the same group under a cap that needs one frame in a few: a note says so
    const small = await fetchExport(t, `/api/compare/${group}/export.html?max_bytes=200000`);
    check(small.text.length <= 200000, `the decimated export is ${small.text.length} bytes, over its cap`);
    await page.setContent(small.text);
    await eventually(() => page.evaluate(() => document.body.dataset.ready === 'true'), 'the decimated viewer to have read its data');
    const note = await page.locator('#note').textContent();
    check(/Decimated to fit the cap of 200000 bytes/.test(note), `the note: ${note}`);
    await t.screenshot('decimated');
  }],

  ['the dashboard\'s Export dialog downloads the run as one HTML file', async (t) => {
    const run = await t.post('/api/runs', { scenario: '01_planar7_obstacles', method: 'dls', mode: 'batch' });
    const page = t.page;
    await page.goto(`${t.base}/?run=${run.id}`);
    await eventually(() => page.locator('#open-export').isEnabled(), { message: `the Export button enabled (${t.errors.join('; ')})`, timeout: 30000 });
    await page.locator('#open-export').click();
    const what = page.locator('#export-what');
    await eventually(async () => (await what.locator('option[value="html"]').count()) === 1, 'the HTML option');
    await what.selectOption('html');
    check(/no network/.test(await page.locator('#export-note').textContent()), 'the note says it opens offline');
    await t.screenshot('dialog');
    const [download] = await Promise.all([page.waitForEvent('download'), page.locator('#export-go').click()]);
    check(download.suggestedFilename() === `rrlab-run-${run.id}.html`, `file name ${download.suggestedFilename()}`);
    const text = readFileSync(await download.path(), 'utf8');
    check(text.includes('RRLAB_EXPORT') && text.includes('type="range"'), 'the download is the export');
    await eventually(async () => /downloaded/.test(await page.locator('#export-progress').textContent()), 'the dialog to say downloaded');
    await page.locator('#export-cancel').click();

    // a compare group opened whole: the group's file
    const compare = await t.post('/api/compare', { scenario: '01_planar7_obstacles', methods: ['pinv', 'dls'], mode: 'batch' });
    await page.goto(`${t.base}/?compare=${compare.runs.map((r) => r.id).join(',')}`);
    await eventually(() => page.locator('#open-export').isEnabled(), { message: 'the Export button enabled for the compare', timeout: 30000 });
    await page.locator('#open-export').click();
    await eventually(async () => (await what.locator('option[value="html"]').count()) === 1, 'the HTML option for the compare');
    await what.selectOption('html');
    check(/compare as one HTML file/.test(await what.locator('option[value="html"]').textContent()), 'the option names the compare');
    const [groupDownload] = await Promise.all([page.waitForEvent('download'), page.locator('#export-go').click()]);
    check(groupDownload.suggestedFilename() === `rrlab-compare-${compare.group}.html`, `file name ${groupDownload.suggestedFilename()}`);
    const groupText = readFileSync(await groupDownload.path(), 'utf8');
    check((groupText.match(/RRLAB_EXPORT\.lanes\.push\(/g) || []).length === 2, 'both lanes in the file');
  }],
]);
