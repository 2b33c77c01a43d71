// The dashboard as a person uses it, against a real `rrlab serve`: deep links,
// a live planar run, dragging an obstacle, sliders and the method switch,
// the keyboard joystick, compare, the replay scrubber, the run list, and
// reconnecting after the socket drops.
// Usage: node dashboard_test.mjs   (RRLAB_BINARY, RRLAB_SCREENSHOTS, CHROMIUM)
import { suite, eventually, check, pageState, longScenario, storedLongScenario, drag } from './harness.mjs';

const canvasPixels = (page, lane = 0) => page.evaluate((i) => window.__rrlab.session.lanes[i].view.canvas.toDataURL(), lane);

async function openLive(t, scenario, extra = {}) {
  const run = await t.post('/api/runs', { scenario, mode: 'live', rate: 1, ...extra });
  await t.page.goto(`${t.base}/?run=${run.id}`);
  await eventually(() => pageState.lane(t.page), 'the first frame');
  return run.id;
}

await suite('dashboard', [
  ['a live run opens from its link and animates', async (t) => {
    const id = await openLive(t, await longScenario(t));  // 01 for 600 s: live however slow the machine
    const first = await pageState.lane(t.page);
    const before = await canvasPixels(t.page);
    await t.screenshot('live');
    await eventually(async () => (await pageState.lane(t.page)).step > first.step + 30, 'frames to advance');
    check((await canvasPixels(t.page)) !== before, 'the canvas changes while the run plays');
    check(t.page.url().endsWith(`/?run=${id}`), `the address names the run: ${t.page.url()}`);
    // the run list shows it live, with Watch, and a frame count that grows
    const frames = async () => Number(await t.page.textContent(`#runs li[data-run="${id}"] .frames`));
    await eventually(async () => (await t.page.locator(`#runs li[data-run="${id}"] button`, { hasText: 'Watch' }).count()) === 1, 'a Watch button');
    const n = await frames();
    await eventually(async () => (await frames()) > n, 'the frame count to grow');
    // the scale bar is drawn in metres and the view fits the scene: the arm spans a good part of the canvas
    const span = await t.page.evaluate(() => {
      const lane = window.__rrlab.session.lanes[0], v = lane.view;
      const xs = lane.frame.links.flatMap((l) => [l[0], l[3]]);
      return (Math.max(...xs) - Math.min(...xs)) * v.scale / v.width;
    });
    check(span > 0.2, `the arm fills the view (spans ${(span * 100).toFixed(0)}% of its width)`);
    await t.post(`/api/runs/${id}/control`, { action: 'stop' });
  }],

  ['dragging an obstacle moves it on the server and it stays', async (t) => {
    const id = await openLive(t, '01_planar7_obstacles', { paused: true });
    const snapshot = await t.page.evaluate(() => window.__rrlab.session.lanes[0].snapshot);
    const index = snapshot.obstacles.findIndex((o) => o.id === 'disc');
    const lane = await pageState.lane(t.page);
    const from = lane.obstacles[index];
    const discDistance = (f) => f.nearest.filter((n) => n[1] === index).reduce((m, n) => Math.min(m, n[2]), Infinity);
    const before = discDistance(await t.page.evaluate(() => window.__rrlab.session.lanes[0].frame));
    // drag the disc next to the middle of link 3
    const link = await t.page.evaluate(() => window.__rrlab.session.lanes[0].frame.links[2]);
    // beside the middle of link 3, on the side away from the base, clear of it by 0.1 m
    const radius = snapshot.obstacles[index].radius;
    const mid = [(link[0] + link[3]) / 2, (link[1] + link[4]) / 2];
    const along = [link[3] - link[0], link[4] - link[1]], length = Math.hypot(along[0], along[1]);
    let normal = [-along[1] / length, along[0] / length];
    if (normal[0] * mid[0] + normal[1] * mid[1] < 0) normal = [-normal[0], -normal[1]];
    const clearance = 0.1 + radius + snapshot.model.links[2].radius;
    const goal = [mid[0] + normal[0] * clearance, mid[1] + normal[1] * clearance];
    const a = await pageState.toClient(t.page, from), b = await pageState.toClient(t.page, goal);
    // where the page drops the disc: its last move (sent at the release, unless the frames showed it already)
    await t.page.evaluate(() => {
      const view = window.__rrlab.session.lanes[0].view, sendMove = view.onObstacleDrag;
      view.onObstacleDrag = (i, position, phase) => { window.__dropped = position; sendMove(i, position, phase); };
    });
    await drag(t.page, a, b, 10);
    const dropped = await t.page.evaluate(() => window.__dropped);
    // the step comes after the drop has reached the server: its distances count the disc where it was dropped
    await eventually(async () => {
      const last = (await t.get(`/api/runs/${id}/events`)).filter((e) => e.kind === 'obstacle').at(-1);
      return last && Math.hypot(last.payload.position[0] - dropped[0], last.payload.position[1] - dropped[1]) < 1e-9;
    }, 'the drop to reach the server');
    await t.post(`/api/runs/${id}/control`, { action: 'step' });
    const moved = await eventually(async () => {
      const l = await pageState.lane(t.page);
      return Math.hypot(l.obstacles[index][0] - goal[0], l.obstacles[index][1] - goal[1]) < 0.02 ? l : null;
    }, 'the page to show the server at the dragged position');
    // the stored events carry the drag; the step's distance reflects the new place
    const events = await t.get(`/api/runs/${id}/events`);
    check(events.some((e) => e.kind === 'obstacle'), 'obstacle events are stored');
    const frame = await eventually(async () => {
      const f = await t.page.evaluate(() => window.__rrlab.session.lanes[0].frame);
      return f.metrics.min_distance <= discDistance(f) + 1e-6 ? f : null;
    }, 'a stepped frame whose minimum distance counts the dragged disc');
    const disc = discDistance(frame);
    check(disc < 0.2 && disc < before - 0.05, `the disc's distance reflects the drag (${before.toFixed(3)} m before, ${disc.toFixed(3)} m after)`);
    // it does not jump back: once the page draws the server's frames rather than the dragged position, it is there
    await eventually(() => t.page.evaluate(() => window.__rrlab.session.lanes[0].view.pending === null), 'the page to let go of the dragged position');
    const drawn = await t.page.evaluate((i) => window.__rrlab.session.lanes[0].view.positionOf(i), index);
    check(Math.hypot(drawn[0] - moved.obstacles[index][0], drawn[1] - moved.obstacles[index][1]) < 1e-6, 'the drawn obstacle stays where it was dropped');
    await t.screenshot('dragged');
  }],

  ['a 3D scenario renders in WebGL on the page, changes while it runs, and its obstacles drag in 3D', async (t) => {
    const id = await openLive(t, '17_chen_sim2_spatial16_window');
    await eventually(() => t.page.evaluate(() => window.__rrlab.session.lanes[0].view && window.__rrlab.session.lanes[0].view.renderer), 'the three.js view');
    check(await t.page.evaluate(() => window.__rrlab.session.lanes[0].view.renderer.getContext() instanceof WebGL2RenderingContext), 'a WebGL 2 context');
    const cell = t.page.locator('#views .view-cell').first();
    const first = await cell.screenshot();
    await t.screenshot('3d');
    await eventually(async () => !(await cell.screenshot()).equals(first), 'the 3D picture to change while the run plays');
    // the drag acts on a paused run (inputs to it are applied): live however slow the machine (the run lasts 75 s)
    await t.post(`/api/runs/${id}/control`, { action: 'pause' });
    await eventually(async () => (await t.get(`/api/runs/${id}`)).status === 'paused', 'the run to pause');
    const grab = await t.page.evaluate(() => {
      const lane = window.__rrlab.session.lanes[0], view = lane.view;
      const index = lane.snapshot.obstacles.findIndex((o) => o.id === 'target_block');
      const centre = view.worldToClient(lane.frame.obstacles[index]);
      for (let r = 0; r <= 30; r += 3) for (let a = 0; a < 8; ++a) {
        const at = { x: centre.x + r * Math.cos(a * Math.PI / 4), y: centre.y + r * Math.sin(a * Math.PI / 4) };
        if (view.obstacleAt(at.x, at.y) === index) return at;
      }
      return null;
    });
    check(grab, 'the cube can be grabbed near its centre');
    await drag(t.page, grab, { x: grab.x + 48, y: grab.y - 32 }, 8);
    await eventually(async () => (await t.get(`/api/runs/${id}/events`)).some((e) => e.kind === 'obstacle' && e.payload.id === 'target_block'), 'the 3D drag to reach the server');
    await t.screenshot('3d-dragged');
    await t.post(`/api/runs/${id}/control`, { action: 'stop' });
  }],

  ['multi_preview ghosts are drawn as arms from the server\'s link segments', async (t) => {
    await openLive(t, '31_zhang_multi_preview');
    const ghosts = await eventually(() => t.page.evaluate(() => {
      const f = window.__rrlab.session.lanes[0].frame;
      return f.overlays && f.overlays.ghost_links && f.overlays.ghost_links.length ? f.overlays.ghost_links : null;
    }), 'ghost link segments in the frames');
    check(ghosts.every((links) => links.length > 0), 'every ghost has its links');
    check(await t.page.isChecked('input[data-overlay=ghosts]'), 'the ghosts toggle is on');
    const drawn = () => t.page.evaluate(() => !window.__rrlab.session.lanes[0].view.dirty);
    await eventually(drawn, 'a frame with ghosts drawn');
    await t.screenshot('ghosts');
    // the toggle turns them off and on: the picture changes with it
    await t.page.click('[data-action=pause]');
    await eventually(async () => (await t.page.textContent('#connection')) === 'paused' && drawn(), 'the paused run\'s last frame drawn');
    const cell = t.page.locator('#views .view-cell').first();
    const on = await cell.screenshot();
    await t.page.uncheck('input[data-overlay=ghosts]');
    await eventually(async () => !(await cell.screenshot()).equals(on), 'turning the ghosts off to change the picture');
    await t.page.check('input[data-overlay=ghosts]');
  }],

  ['qp_ik draws its active velocity dampers as segments between link and obstacle', async (t) => {
    // Sezgin's narrow gap: links come within the dampers' reach from step 51 on; a tenth of real time keeps it live
    await openLive(t, '13_sezgin_ex3_narrow_gap', { method: 'qp_ik', rate: 0.1 });
    const segments = await eventually(() => t.page.evaluate(() => {
      const f = window.__rrlab.session.lanes[0].frame;
      return f.overlays && f.overlays.segments && f.overlays.segments.length ? f.overlays.segments : null;
    }), 'an active damper in the frames');
    check(segments.every(([a, b]) => a.length >= 2 && b.length >= 2), 'each damper is a segment of two points');
    check(await t.page.isChecked('input[data-overlay=method]'), 'the method overlay toggle is on');
    await t.page.click('[data-action=pause]');
    const drawn = () => t.page.evaluate(() => !window.__rrlab.session.lanes[0].view.dirty);
    await eventually(async () => (await t.page.textContent('#connection')) === 'paused' && drawn(), 'the paused run\'s last frame drawn');
    const paused = await t.page.evaluate(() => window.__rrlab.session.lanes[0].frame.overlays.segments.length);
    await t.screenshot('qp-ik-dampers');
    if (paused) {  // the paused frame has a damper: turning the overlay off changes the picture
      const cell = t.page.locator('#views .view-cell').first();
      const on = await cell.screenshot();
      await t.page.uncheck('input[data-overlay=method]');
      await eventually(async () => !(await cell.screenshot()).equals(on), 'turning the method overlay off to change the picture');
      await t.page.check('input[data-overlay=method]');
    }
  }],

  ['a typed decimal comma is a decimal point; text read two ways is refused at its field', async (t) => {
    const id = await openLive(t, '01_planar7_obstacles', { paused: true });  // closest_point: influence in m
    const typed = t.page.locator('.param:has(#param-influence) input.typed');
    const events = async () => (await t.get(`/api/runs/${id}/events`)).filter((e) => e.kind === 'params');
    const type = async (text) => { await typed.click({ clickCount: 3 }); await t.page.keyboard.type(text); await t.page.keyboard.press('Tab'); };
    await type('0,3');
    await eventually(async () => (await events()).some((e) => e.payload.influence === 0.3), 'influence 0.3 stored (not 3)');
    check((await events()).every((e) => e.payload.influence !== 3), 'never 3 m');
    await eventually(async () => (await typed.inputValue()) === '0.3', 'the field to show 0.3');
    // read two ways: refused beside the field, which shows the current value again
    const count = (await events()).length;
    await type('0,3.5');
    await eventually(async () => (await typed.getAttribute('aria-invalid')) === 'true', 'the field marked');
    const note = t.page.locator('.param:has(#param-influence) .field-error');
    check(await note.isVisible() && (await note.textContent()).includes('two ways'), `the message beside the field: ${await note.textContent()}`);
    check((await typed.inputValue()) === '0.3', `the field back to the current value: ${await typed.inputValue()}`);
    const [fieldBox, noteBox] = [await typed.boundingBox(), await note.boundingBox()];
    check(Math.abs(noteBox.y - (fieldBox.y + fieldBox.height)) < 40, 'the message right under the field');
    await t.screenshot('refused');
    check((await events()).length === count, 'nothing sent for the refused text');
    // a good value clears the mark
    await type('0,35');
    await eventually(async () => (await events()).some((e) => e.payload.influence === 0.35), 'influence 0.35 stored');
    check(!(await typed.getAttribute('aria-invalid')) && !(await note.isVisible()), 'the mark cleared');
  }],

  ['a slider and the method switch change the run on the server', async (t) => {
    const id = await openLive(t, '01_planar7_obstacles', { paused: true });  // a paused run stays live and takes inputs
    const slider = t.page.locator('.param input[type=range]').first();
    const name = (await slider.getAttribute('id')).replace('param-', '');
    const spec = await t.page.evaluate((n) => window.__rrlab.session.lanes[0].snapshot.param_specs.find((p) => p.name === n), name);
    const start = await t.page.evaluate((n) => window.__rrlab.session.lanes[0].snapshot.params[n], name);
    const typed = t.page.locator(`.param:has(#param-${name}) input.typed`);
    // nothing is marked changed before it is touched (the scenario's value is the start, not the method's default)
    check(await t.page.locator('.param.changed').count() === 0, 'no parameter shows as changed at the start');
    // a typed value goes to the run as typed
    const value = Number((spec.min + (spec.max - spec.min) * 0.37).toPrecision(6));
    await typed.fill(String(value));
    await typed.dispatchEvent('change');
    await eventually(async () => (await t.get(`/api/runs/${id}/events`)).some((e) => e.kind === 'params'), 'a params event');
    const stored = (await t.get(`/api/runs/${id}/events`)).find((e) => e.kind === 'params');
    check(Math.abs(stored.payload[name] - value) <= 1e-6 * Math.max(1, Math.abs(value)), `the stored ${name} is the typed value: ${JSON.stringify(stored.payload)}`);
    await eventually(async () => (await t.page.locator(`.param.changed:has(#param-${name})`).count()) === 1, 'the parameter marked changed');
    // another client's change comes as a params message: the same controls show it (the panel is not rebuilt)
    await slider.evaluate((el) => { el.dataset.kept = 'yes'; });
    await t.request('PATCH', `/api/runs/${id}/params`, { [name]: spec.max });
    await eventually(async () => Number(await typed.inputValue()) === spec.max && Number(await slider.inputValue()) === Number(await slider.getAttribute('max')), `the controls to show ${spec.max}`);
    check(await slider.evaluate((el) => el.dataset.kept === 'yes'), 'the panel was updated in place, not rebuilt');
    // a slider moved by the mouse sends its value (2 significant digits on a log slider)
    const box = await slider.boundingBox();
    await slider.click({ position: { x: box.width * 0.5, y: box.height / 2 } });
    await eventually(async () => {
      const events = await t.get(`/api/runs/${id}/events`);
      const last = events[events.length - 1].payload[name];
      return Math.abs(last - Number(await typed.inputValue())) <= 1e-9 * Math.max(1, Math.abs(last)) && last !== spec.max;
    }, 'the slider click stored as the typed field shows it');
    // back to the run's starting value
    const count = (await t.get(`/api/runs/${id}/events`)).length;
    await t.page.locator(`button.reset[aria-label="reset ${name} to its starting value"]`).click();
    await eventually(async () => {
      const events = await t.get(`/api/runs/${id}/events`);
      return events.length > count && events[events.length - 1].payload[name] === start;
    }, 'the reset to the starting value to be stored');
    await eventually(async () => (await t.page.locator('.param.changed').count()) === 0, 'nothing marked changed after the reset');
    await t.page.selectOption('#switch-method', 'dls');
    await t.page.click('#switch-method-go');
    await eventually(async () => (await pageState.lane(t.page)).method === 'dls', 'the stream to report the new method');
    check((await t.get(`/api/runs/${id}/events`)).some((e) => e.kind === 'method'), 'the method switch is stored');
    check((await t.page.textContent('#params-lane')).includes('dls'), 'the parameter panel shows the new method');
    await t.screenshot('switched');
  }],

  ['a log slider says so, steps by a fraction of a decade and records one event per settled change', async (t) => {
    const id = await openLive(t, '01_planar7_obstacles', { paused: true });
    const slider = t.page.locator('.param input[type=range][data-scale=log]').first();
    const name = (await slider.getAttribute('id')).replace('param-', '');
    const mark = t.page.locator(`.param:has(#param-${name}) .scale-mark`);
    check((await mark.textContent()) === 'log' && await mark.isVisible(), 'the log scale is marked');
    const typed = t.page.locator(`.param:has(#param-${name}) input.typed`);
    const start = Number(await typed.inputValue());
    const params = async () => (await t.get(`/api/runs/${id}/events`)).filter((e) => e.kind === 'params');
    const before = (await params()).length;
    await slider.focus();
    for (let i = 0; i < 6; i++) await slider.press('ArrowRight');
    const up = Number(await typed.inputValue());
    check(up > start * 1.5 && up < start * 2.5, `six steps right: ${start} to ${up} (about ×2, a fraction of a decade each)`);
    // keys pressed faster than they settle make one event (on a machine slow enough to pause between two
    // presses, one per pause: never one per step)
    await eventually(async () => { const p = await params(); return p.length > before && p.at(-1).payload[name] === up; }, 'the settled value stored');
    const afterRight = (await params()).length;
    check(afterRight - before < 6, `fewer events than steps: ${afterRight - before}`);
    for (let i = 0; i < 6; i++) await slider.press('ArrowLeft');
    check(Number(await typed.inputValue()) === start, `six steps back return to ${start} exactly`);
    await eventually(async () => { const p = await params(); return p.length > afterRight && p.at(-1).payload[name] === start; },
      'back at the starting value, stored');
    check((await params()).length - afterRight < 6, 'fewer events than steps on the way back');
    await eventually(async () => (await t.page.locator('.param.changed').count()) === 0, 'nothing marked changed');
    await t.screenshot('log-slider');
  }],

  ['the keyboard joystick moves the target', async (t) => {
    const id = await openLive(t, '04_planar7_joystick');
    const before = (await pageState.lane(t.page)).target;
    await t.page.locator('#views').click({ position: { x: 5, y: 5 } });
    await t.page.keyboard.down('ArrowUp');  // held until the target has moved
    await eventually(async () => (await pageState.lane(t.page)).target[1] > before[1] + 0.01, 'the target to move up');
    await t.page.keyboard.up('ArrowUp');
    check((await t.get(`/api/runs/${id}/events`)).some((e) => e.kind === 'joystick'), 'joystick events are stored');
    // the release is sent too (rate-limited, maybe later): stopping before it
    // arrives would refuse it (409) on a slow or busy machine
    await eventually(async () => {
      const events = (await t.get(`/api/runs/${id}/events`)).filter((e) => e.kind === 'joystick');
      return events.length && events.at(-1).payload.linear.every((v) => v === 0);
    }, 'the released key to send a zero command');
    await t.post(`/api/runs/${id}/control`, { action: 'stop' });  // 3600 s otherwise
  }],

  ['a compare link animates both arms and a drag reaches both runs', async (t) => {
    const group = await t.post('/api/compare', { scenario: await longScenario(t), methods: ['pinv', 'closest_point'], mode: 'live', rate: 1, paused: true });
    const [a, b] = group.runs.map((r) => r.id);
    await t.page.goto(`${t.base}/?compare=${a},${b}`);
    await eventually(async () => (await pageState.lane(t.page, 0)) && (await pageState.lane(t.page, 1)), 'frames of both lanes');
    await t.page.click('[data-action=start]');
    const s0 = (await pageState.lane(t.page, 0)).step, s1 = (await pageState.lane(t.page, 1)).step;
    await eventually(async () => (await pageState.lane(t.page, 0)).step > s0 + 20 && (await pageState.lane(t.page, 1)).step > s1 + 20, 'both arms to animate');
    // paused for the drag (inputs to a paused run are applied): the arms stand still under the mouse
    await t.post(`/api/runs/${a}/control`, { action: 'pause' });
    await eventually(async () => (await t.get(`/api/runs/${a}`)).status === 'paused' && (await t.get(`/api/runs/${b}`)).status === 'paused', 'the group to pause');
    check(await t.page.evaluate(() => document.querySelectorAll('#views .view-cell canvas').length) === 2, 'two views side by side');
    const lane = await pageState.lane(t.page, 1);
    const index = 1;
    const from = lane.obstacles[index];
    const p = await pageState.toClient(t.page, from, 1);
    await drag(t.page, p, { x: p.x + 48, y: p.y + 30 }, 6);
    await eventually(async () => (await t.get(`/api/runs/${a}/events`)).some((e) => e.kind === 'obstacle') &&
      (await t.get(`/api/runs/${b}/events`)).some((e) => e.kind === 'obstacle'), 'the drag to reach both runs');
    check((await t.page.locator('#metrics th').count()) === 3, 'the metrics table has a column per method');
    await t.screenshot('compare');
    await t.post(`/api/runs/${a}/control`, { action: 'stop' });
    await eventually(async () => !(await t.page.isHidden('#compare-summary')), 'the summary table at the end');
    check((await t.page.locator('#summary-table tr').count()) > 5, 'the summary lists the metrics');
    await t.screenshot('compare-summary');
  }],

  ['overlaid compare draws every arm on one view', async (t) => {
    // 01 stored for 600 s: its last lane's socket still finds it live however slow the page
    await t.page.goto(`${t.base}/?scenario=${await storedLongScenario(t)}`);
    await t.page.waitForSelector('#compare-rows .compare-row');
    await t.page.click('#compare-add');
    await t.page.locator('#compare-rows .compare-row select').nth(1).selectOption('dls');
    await t.page.locator('#compare-rows .compare-row select').nth(2).selectOption('closest_point');
    await t.page.locator('#compare-rows .compare-row input').nth(1).fill('lambda=0.2');
    await t.page.selectOption('#compare-layout', 'overlay');
    await t.page.click('#start-compare');
    await eventually(async () => (await pageState.lane(t.page, 2)) !== null, 'three lanes');
    check(await t.page.evaluate(() => document.querySelectorAll('#views .view-cell').length) === 1, 'one view');
    check(t.page.url().includes('compare='), 'the address names the group');
    const params = await t.page.evaluate(() => window.__rrlab.session.lanes[1].snapshot.params.lambda);
    check(Math.abs(params - 0.2) < 1e-12, `the typed parameter reached the lane: ${params}`);
    await eventually(() => t.page.evaluate(() => {
      const s = window.__rrlab.session, view = s.lanes[0].view;
      return s.lanes.every((l) => l.frame) && view.lanes.length === 2 && !view.dirty;
    }), 'every arm drawn on the one view');
    await t.screenshot('overlay');
    await t.post(`/api/runs/${await t.page.evaluate(() => window.__rrlab.session.runIds[0])}/control`, { action: 'stop' });  // the whole group
  }],

  ['a 3D compare overlaid draws every lane; overlay toggles redraw', async (t) => {
    // 02 stored for 600 s: both lanes' sockets still find it live however slow the page
    await t.page.goto(`${t.base}/?scenario=${await storedLongScenario(t, '02_spatial_xz_reach')}`);
    await t.page.waitForSelector('#compare-rows .compare-row');
    await t.page.selectOption('#compare-layout', 'overlay');
    await t.page.click('#start-compare');
    await eventually(async () => (await pageState.lane(t.page, 1)) !== null, 'both lanes');
    check(await t.page.evaluate(() => document.querySelectorAll('#views .view-cell').length) === 1, 'one 3D view');
    for (const key of ['nearest', 'manipulability', 'trace']) { await t.page.uncheck(`input[data-overlay=${key}]`); await t.page.check(`input[data-overlay=${key}]`); }
    const points = async () => (await t.page.evaluate(() => window.__rrlab.plots.pointCounts()));
    await eventually(async () => { const c = await points(); return Object.keys(c).length && Object.values(c).every((n) => n > 0); },
      'plots to gain points for both lanes');
    await t.screenshot('3d-overlay');
    await t.post(`/api/runs/${await t.page.evaluate(() => window.__rrlab.session.runIds[0])}/control`, { action: 'stop' });  // the whole group
  }],

  ['an ended run takes no more inputs; a run with no frames says so', async (t) => {
    const id = await openLive(t, '04_planar7_joystick');
    await t.post(`/api/runs/${id}/control`, { action: 'stop' });
    await eventually(async () => (await t.page.textContent('#connection')).startsWith('ended'), 'the page to show the run ended');
    check(await t.page.isHidden('#joystick-section'), 'the joystick is hidden');
    check(await t.page.isDisabled('[data-action=start]'), 'the controls are disabled');
    await t.page.keyboard.press('ArrowUp');  // nothing may be sent: a 409 would be a console error
    const empty = await t.post('/api/runs', { scenario: '01_planar7_obstacles', mode: 'live', paused: true });
    await t.post(`/api/runs/${empty.id}/control`, { action: 'stop' });
    await t.page.goto(`${t.base}/?run=${empty.id}`);
    await t.page.waitForSelector('.empty-lane');
    check(await t.page.isHidden('#replay-bar'), 'no scrubber for a run without frames');
  }],

  ['a stored run replays and the scrubber shows frame k exactly', async (t) => {
    const run = await t.post('/api/runs', { scenario: '01_planar7_obstacles', method: 'dls', mode: 'batch' });
    await t.page.goto(`${t.base}/?run=${run.id}`);
    await eventually(() => pageState.lane(t.page), 'the replay to start');
    await t.page.waitForSelector('#replay-bar:not([hidden])');
    const k = 137;
    await t.page.locator('#scrubber').fill(String(k));
    await t.page.locator('#scrubber').dispatchEvent('change');
    const shown = await eventually(async () => { const l = await pageState.lane(t.page); return l.seq === k ? l : null; }, `frame ${k}`);
    const stored = (await t.get(`/api/runs/${run.id}/frames?from=${k}&to=${k}`)).frames[0];
    shown.q.forEach((q, i) => check(Math.abs(q - stored.q[i]) <= 1e-6 * Math.max(1, Math.abs(stored.q[i])), `q${i + 1} drawn ${q} vs stored ${stored.q[i]}`));
    check(t.page.url().includes(`frame=${k}`), `the frame is in the address: ${t.page.url()}`);
    // one frame forward with the keyboard
    await t.page.locator('#views').click({ position: { x: 5, y: 5 } });
    await t.page.keyboard.press('.');
    await eventually(async () => (await pageState.lane(t.page)).seq === k + 1, 'frame k + 1');
    await t.screenshot('replay');
    // the link reopens that frame
    await t.page.goto(`${t.base}/?run=${run.id}&frame=40`);
    await eventually(async () => { const l = await pageState.lane(t.page); return l && l.seq === 40; }, 'the linked frame');
  }],

  ['a scenario and method are preselected from the address; runs can be filtered and deleted', async (t) => {
    const run = await t.post('/api/runs', { scenario: '01_planar7_obstacles', method: 'pinv', mode: 'batch' });
    await t.page.goto(`${t.base}/?scenario=04_planar7_joystick&method=dls`);
    await t.page.waitForSelector('#scenario option', { state: 'attached' });
    await eventually(async () => (await t.page.inputValue('#scenario')) === '04_planar7_joystick', 'the scenario preselected');
    check((await t.page.inputValue('#method')) === 'dls', 'the method preselected');
    await t.page.selectOption('#filter-status', 'completed');
    await eventually(async () => (await t.page.locator(`#runs li[data-run="${run.id}"]`).count()) === 1, 'the stored run in the filtered list');
    t.page.once('dialog', (d) => d.accept());
    await t.page.locator(`#runs li[data-run="${run.id}"] button`, { hasText: 'Delete' }).click();
    await eventually(async () => (await t.page.locator(`#runs li[data-run="${run.id}"]`).count()) === 0, 'the run to leave the list');
    const gone = await t.request('GET', `/api/runs/${run.id}`).then(() => false, () => true);
    check(gone, 'the run is deleted on the server');
  }],

  ['the stream reconnects after it drops and resyncs', async (t) => {
    const id = await openLive(t, await longScenario(t));  // outlives the drop and the back-off however slow the machine
    await t.page.evaluate(() => window.__rrlab.session.lanes[0].stream.socket.close());
    await eventually(async () => (await t.page.textContent('#connection')) !== 'live', 'the drop to show');
    const step = (await pageState.lane(t.page)).step;
    await eventually(async () => (await t.page.textContent('#connection')) === 'live', 'the stream to reconnect');
    await eventually(async () => (await pageState.lane(t.page)).step > step + 10, 'frames after reconnecting');
    await t.post(`/api/runs/${id}/control`, { action: 'stop' });
  }],
]);
