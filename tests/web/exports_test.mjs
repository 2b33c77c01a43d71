// Pictures and videos to take away, as a person makes them from the Export
// dialog: a PNG of a view and of a chart at the requested size, a figure for
// a paper, a WebM of a replay with one frame per stored frame of the range,
// and a compare group's video side by side.
// Usage: node exports_test.mjs   (RRLAB_BINARY, RRLAB_SCREENSHOTS, CHROMIUM)
import { readFileSync, copyFileSync } from 'node:fs';
import { join } from 'node:path';
import { suite, eventually, check, pageState, screenshotDir } from './harness.mjs';
import { webmFrames } from './webm.mjs';

// The width and height in a PNG's IHDR chunk.
function pngSize(bytes) {
  check(bytes.subarray(1, 4).toString() === 'PNG', 'a PNG file');
  return { width: bytes.readUInt32BE(16), height: bytes.readUInt32BE(20) };
}

// Fills the dialog, exports, and returns the downloaded file's bytes (kept beside the screenshots).
async function exportFile(t, what, fields = {}) {
  await t.page.click('#open-export');
  await t.page.selectOption('#export-what', what);
  for (const [id, value] of Object.entries(fields)) await t.page.fill(`#export-${id}`, String(value));
  const [download] = await Promise.all([t.page.waitForEvent('download', { timeout: 120000 }), t.page.click('#export-go')]);
  const file = await download.path();
  copyFileSync(file, join(screenshotDir, `exports-${download.suggestedFilename()}`));
  await eventually(async () => !(await t.page.isDisabled('#export-go')), 'the export to finish');
  await t.page.click('#export-cancel');
  return { bytes: readFileSync(file), name: download.suggestedFilename() };
}

// What the browser's own player makes of a WebM: its size and duration, and a
// frame decoded (in a blank page: the dashboard's security policy plays no media).
async function played(dashboard, bytes) {
  const context = await dashboard.context().browser().newContext();
  const page = await context.newPage();
  return page.evaluate(async (b64) => {
    const data = Uint8Array.from(atob(b64), (c) => c.charCodeAt(0));
    const video = document.createElement('video');
    video.muted = true;
    video.src = URL.createObjectURL(new Blob([data], { type: 'video/webm' }));
    await new Promise((resolve, reject) => { video.onloadeddata = resolve; video.onerror = () => reject(new Error(video.error ? video.error.message : 'cannot play')); });
    return { width: video.videoWidth, height: video.videoHeight, duration: video.duration };
  }, bytes.toString('base64')).finally(() => context.close());
}

await suite('exports', [
  ['a view, a chart and a figure download as PNGs of the requested size', async (t) => {
    const run = await t.post('/api/runs', { scenario: '00_demo_avoidance', method: 'pinv', mode: 'batch' });
    await t.page.goto(`${t.base}/?run=${run.id}&frame=300`);
    await eventually(async () => { const l = await pageState.lane(t.page); return l && l.seq === 300; }, 'frame 300');
    await eventually(() => t.page.evaluate(() => window.__rrlab.plots.charts.has('distance')), 'the charts');
    // a typed number is read one way only: refused at its field, never a 10× value
    await t.page.click('#open-export');
    await t.page.selectOption('#export-what', 'view');
    await t.page.fill('#export-width', '1234,5');
    await t.page.click('#export-go');
    await eventually(async () => (await t.page.getAttribute('#export-width', 'aria-invalid')) === 'true', 'the width marked');
    const note = await t.page.textContent('#export-dialog .field-error');
    check(/^width: 1234\.5 is not a whole number/.test(note), `the message beside the field: ${note}`);
    check(!(await t.page.isVisible('#message')), 'no banner for a field');
    await t.page.click('#export-cancel');
    const view = await exportFile(t, 'view', { width: 1234, height: 567 });
    const size = pngSize(view.bytes);
    check(size.width === 1234 && size.height === 567, `the view PNG is 1234×567 (${size.width}×${size.height})`);
    check(view.bytes.length > 20000, `the picture has content (${view.bytes.length} bytes)`);
    const chart = await exportFile(t, 'chart:distance', { width: 800, height: 300 });
    const chartSize = pngSize(chart.bytes);
    check(chartSize.width === 800 && chartSize.height === 300, `the chart PNG is 800×300 (${chartSize.width}×${chartSize.height})`);
    const figure = await exportFile(t, 'figure', { width: 1600 });
    const figureSize = pngSize(figure.bytes);
    check(figureSize.width === 1600 && figureSize.height > 1000, `the figure is 1600 px wide with its charts below the view (${figureSize.width}×${figureSize.height})`);
    await t.screenshot('after-exports');
  }],

  ['a 4-lane figure wraps its legend and caption to its width: no text on other text, nothing cut at the edge, labels off the arms', async (t) => {
    const group = await t.post('/api/compare', { scenario: '10_sezgin_ex1_lshape', mode: 'batch', methods: [
      { name: 'ccp_voronoi', params: { ccp_link: 2 } }, { name: 'ccp_voronoi', params: { ccp_link: 3 } },
      { name: 'pinv' }, { name: 'closest_point', params: { influence: 0.3, gain: 7 } }] });
    await t.page.goto(`${t.base}/?compare=${group.runs.map((r) => r.id).join(',')}&frame=150`);
    await eventually(() => t.page.evaluate(() => window.__rrlab.plots.charts.has('distance') && window.__rrlab.session.lanes.every((l) => l.frame && l.view)), 'the charts and views');
    const figure = await exportFile(t, 'figure', { width: 800 });
    const size = pngSize(figure.bytes);
    const layout = await t.page.evaluate(async () => (await import('./js/exports.js')).figurePng.lastLayout);
    check(size.width === 800 && size.height === layout.height, `the figure is as laid out (${size.width}×${size.height}, ${layout.height})`);
    const texts = layout.boxes.filter((b) => b.text !== undefined);
    for (const b of layout.boxes) check(b.x >= 0 && b.x + b.w <= 800 + 0.5 && b.y >= 0 && b.y + b.h <= layout.height + 0.5, `${b.kind} "${b.text || ''}" inside the figure: ${JSON.stringify({ x: b.x, y: b.y, w: b.w, h: b.h })}`);
    const overlap = (a, b) => Math.min(a.x + a.w, b.x + b.w) > Math.max(a.x, b.x) && Math.min(a.y + a.h, b.y + b.h) > Math.max(a.y, b.y);
    const inked = layout.boxes.filter((b) => b.kind !== 'views' && b.kind !== 'chart');
    for (let i = 0; i < inked.length; ++i) for (let j = 0; j < i; ++j) check(!overlap(inked[i], inked[j]), `"${inked[i].text || inked[i].kind}" and "${inked[j].text || inked[j].kind}" do not overlap`);
    check(texts.filter((b) => b.kind === 'caption').length > 2, 'the long caption wraps over several lines');
    for (const label of ['ccp_link=2', 'ccp_link=3']) check(texts.some((b) => b.kind === 'legend' && b.text.includes(label)), `the legend names ${label}`);
    // in every view, each obstacle name and distance is off every link of the arm
    const crossings = await t.page.evaluate(async () => {
      const { segmentHitsBox } = await import('./js/label_layout.js');
      const out = [];
      for (const lane of window.__rrlab.session.lanes) {
        const view = lane.view;
        view.dirty = true;
        view.render();
        for (const box of view.labelBoxes || []) {
          for (const l of lane.frame.links) {
            const a = view.toScreen([l[0], l[1]]), b = view.toScreen([l[3], l[4]]);
            if (segmentHitsBox([a.x, a.y, b.x, b.y], box)) out.push(`${lane.label}: "${box.text}"`);
          }
        }
      }
      return out;
    });
    check(crossings.length === 0, `no label on a link (${crossings.join(', ')})`);
    copyFileSync(join(screenshotDir, `exports-${figure.name}`), join(screenshotDir, 'exports-4-lane-figure.png'));
  }],

  ['a replay exports as a WebM with one frame per stored frame of the range', async (t) => {
    const run = await t.post('/api/runs', { scenario: '01_planar7_obstacles', method: 'dls', mode: 'batch', steps: 300 });
    await t.page.goto(`${t.base}/?run=${run.id}&frame=0`);
    await eventually(() => pageState.lane(t.page), 'the replay');
    const video = await exportFile(t, 'video', { from: 100, to: 139, stride: 1, fps: 30, width: 320, height: 240 });
    const webm = webmFrames(video.bytes);
    check(webm.frames === 40, `40 stored frames give 40 video frames (${webm.frames})`);
    check(webm.width === 320 && webm.height === 240, `320×240 (${webm.width}×${webm.height})`);
    check(video.name.endsWith('frames-100-139-30fps.webm'), `the file says what it holds: ${video.name}`);
    const player = await played(t.page, video.bytes);
    check(player.width === 320 && player.height === 240 && Math.abs(player.duration - 40 / 30) < 0.05,
      `the browser plays it: ${player.width}×${player.height}, ${player.duration} s (40 frames at 30/s: 1.33 s)`);
    // a bad range is refused, naming it
    await t.page.click('#open-export');
    await t.page.selectOption('#export-what', 'video');
    await t.page.fill('#export-from', '200');
    await t.page.fill('#export-to', '100');
    await t.page.click('#export-go');
    await eventually(async () => (await t.page.getAttribute('#export-to', 'aria-invalid')) === 'true', 'the refusal');
    const note = await t.page.textContent('#export-dialog .field-error:not([hidden])');
    check(/^to frame: 100 is out of range: type a number in \[200, 299\]/.test(note), `the range refused at its field: ${note}`);
    await t.screenshot('range-refused');
  }],

  ['a compare group exports side by side, every second frame', async (t) => {
    const group = await t.post('/api/compare', { scenario: '00_demo_avoidance', methods: ['pinv', 'closest_point'], mode: 'batch', steps: 100 });
    await t.page.goto(`${t.base}/?compare=${group.runs.map((r) => r.id).join(',')}&frame=0`);
    await eventually(() => t.page.evaluate(() => window.__rrlab.session && window.__rrlab.session.lanes.every((l) => l.view && l.frame)), 'both lanes');
    const video = await exportFile(t, 'video', { from: 0, to: 19, stride: 2, fps: 10, width: 640, height: 240 });
    const webm = webmFrames(video.bytes);
    check(webm.frames === 10, `frames 0, 2, …, 18: 10 video frames (${webm.frames})`);
    check(webm.width === 640, `the lanes side by side in 640 px (${webm.width})`);
    const still = await exportFile(t, 'view', { width: 1000, height: 400 });
    const size = pngSize(still.bytes);
    check(size.width === 1000 && size.height === 400, `the group's views in one 1000×400 PNG (${size.width}×${size.height})`);
  }],
]);
