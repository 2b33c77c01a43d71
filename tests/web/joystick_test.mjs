// The end-effector joystick on the dashboard, on a live run of
// 04_planar7_joystick against a real `rrlab serve`: the keyboard, an emulated
// gamepad and the on-screen pad each move the target; release stops it;
// nothing is sent while typing in a field or on a task that is not a joystick.
// Usage: node joystick_test.mjs   (RRLAB_BINARY, RRLAB_SCREENSHOTS, CHROMIUM)
import { join } from 'node:path';
import { suite, eventually, check, pageState, screenshotDir } from './harness.mjs';

const REACH = 2.8;  // seven 0.4 m links: full deflection is 0.1 · reach m/s

async function openLive(t, scenario, extra = {}) {
  const run = await t.post('/api/runs', { scenario, mode: 'live', rate: 1, ...extra });
  await t.page.goto(`${t.base}/?run=${run.id}`);
  await eventually(() => pageState.lane(t.page), 'the first frame');
  return run.id;
}

async function openJoystick(t) {
  const id = await openLive(t, '04_planar7_joystick');
  await t.page.waitForSelector('#joystick-section:not([hidden]) .joystick:not(.js-off)');
  return id;
}

const target = async (t) => (await pageState.lane(t.page)).target;
// Waits (bounded) while a command is held until the page's target has moved
// more than `by` along axis k from `from`: then it is released.
const movedAlong = (t, from, k, by, what) => eventually(async () => (await target(t))[k] - from[k] > by, what);
const joystickEvents = async (t, id) => (await t.get(`/api/runs/${id}/events`)).filter((e) => e.kind === 'joystick');
// The last command stored is a zero one, and the page shows a frame after
// it: the target has stopped.
async function released(t, id) {
  const zero = await eventually(async () => {
    const events = await joystickEvents(t, id);
    return events.length && events.at(-1).payload.linear.every((v) => v === 0) ? events.at(-1) : null;
  }, 'a zero command after release');
  await eventually(async () => (await pageState.lane(t.page)).seq > zero.seq, 'a frame after the zero command');
}
const panelShot = (t, name) => t.page.locator('#joystick-section').screenshot({ path: join(screenshotDir, `joystick-panel-${name}.png`) });

await suite('joystick', [
  ['arrow keys move the target; one command per change; not while typing', async (t) => {
    const id = await openJoystick(t);
    const before = await target(t);
    await t.page.keyboard.down('ArrowRight');  // held until the target has moved
    await movedAlong(t, before, 0, 0.05, 'the target to move in +x while → is held');
    await t.page.keyboard.up('ArrowRight');
    await released(t, id);
    const after = await target(t);
    check(after[0] - before[0] > 0.05, `→ moves the target in +x (${before[0].toFixed(3)} → ${after[0].toFixed(3)})`);
    check(Math.abs(after[1] - before[1]) < 0.02, 'and not in y');
    const events = await joystickEvents(t, id);
    check(events.length === 2, `one command on press, one zero on release (${events.length} stored)`);
    const speed = events[0].payload.linear;
    check(speed.length === 2 && Math.abs(speed[0] - 0.1 * REACH) < 1e-9 && speed[1] === 0, `an xy task sends [vx, vy] at 0.1·reach: ${JSON.stringify(speed)}`);

    await t.page.focus('#switch-method');  // a select: its arrow keys are its own
    await t.page.keyboard.press('ArrowUp');
    await t.page.keyboard.type('wasd');
    // about time: nothing may be sent in the 200 ms after the keys (an upper bound: still 2 commands)
    await t.page.waitForTimeout(200);
    check((await joystickEvents(t, id)).length <= 2, 'nothing sent while a field has the focus');
    await t.page.evaluate(() => document.activeElement.blur());
    await t.post(`/api/runs/${id}/control`, { action: 'stop' });
  }],

  ['an emulated gamepad shows its indicator and its left stick moves the target', async (t) => {
    const id = await openJoystick(t);
    const before = await target(t);
    // no gamepadconnected event: the joystick must find the pad by polling
    await t.page.evaluate(() => {
      window.__pad = { id: 'Emulated pad (STANDARD GAMEPAD)', index: 0, connected: true, mapping: 'standard', axes: [0.8, 0, 0, 0], buttons: [], timestamp: 1 };
      navigator.getGamepads = () => [window.__pad, null, null, null];
    });
    await t.page.waitForSelector('.js-gamepad:not([hidden])');
    check((await t.page.textContent('.js-gamepad')).includes('🎮 gamepad connected: Emulated pad'), 'the indicator names the pad');
    await movedAlong(t, before, 0, 0.05, 'the target to move in +x while the stick is held');
    await t.screenshot('gamepad');
    await panelShot(t, 'gamepad');
    await t.page.evaluate(() => { window.__pad.axes = [0.1, 0.05, 0, 0]; });  // inside the dead zone
    await released(t, id);
    const after = await target(t);
    check(after[0] - before[0] > 0.05, `the left stick moves the target in +x (${before[0].toFixed(3)} → ${after[0].toFixed(3)})`);
    const commands = (await joystickEvents(t, id)).map((e) => e.payload.linear);
    check(commands.length === 2, `one command while the stick is held still, one zero (${commands.length})`);
    const want = 0.1 * REACH * (0.8 - 0.15) / (1 - 0.15);
    check(Math.abs(commands[0][0] - want) < 0.01, `dead zone 0.15, rescaled: vx ${commands[0][0]} (want ≈ ${want.toFixed(3)})`);
    await t.page.evaluate(() => { navigator.getGamepads = () => [null, null, null, null]; });
    await t.page.waitForSelector('.js-gamepad', { state: 'hidden' });
    await t.post(`/api/runs/${id}/control`, { action: 'stop' });
  }],

  ['the on-screen pad dragged with the mouse moves the target and springs back', async (t) => {
    const id = await openJoystick(t);
    const before = await target(t);
    await t.page.locator('.js-pad').first().scrollIntoViewIfNeeded();
    const pad = await t.page.locator('.js-pad').first().boundingBox();
    const cx = pad.x + pad.width / 2, cy = pad.y + pad.height / 2;
    await t.page.mouse.move(cx, cy);
    await t.page.mouse.down();
    await t.page.mouse.move(cx + 12, cy - 60, { steps: 6 });
    await movedAlong(t, before, 1, 0.05, 'the target to move in +y while the pad is held');
    await t.screenshot('drag');
    await panelShot(t, 'drag');
    await t.page.mouse.up();
    await released(t, id);
    const after = await target(t);
    check(after[1] - before[1] > 0.05, `dragging up moves the target in +y (${before[1].toFixed(3)} → ${after[1].toFixed(3)})`);
    const events = await joystickEvents(t, id);
    check(events.length <= 14, `at most 20 commands a second, only on a change (${events.length} for a drag of 6 moves)`);
    check(/translate\(0px, 0px\)/.test(await t.page.$eval('.js-pad .js-knob', (k) => k.style.transform)), 'the knob springs back to the centre');
    await t.post(`/api/runs/${id}/control`, { action: 'stop' });
  }],

  ['a task that is not a joystick gets no commands', async (t) => {
    const id = await openLive(t, '01_planar7_obstacles', { paused: true });  // a paused run stays live: the stop below finds it
    check(await t.page.isHidden('#joystick-section'), 'the joystick panel is hidden');
    await t.page.keyboard.down('ArrowLeft');
    await t.page.keyboard.up('ArrowLeft');
    // about time: nothing may be sent in the 200 ms after the key (an upper bound: no command)
    await t.page.waitForTimeout(200);
    check((await joystickEvents(t, id)).length === 0, 'no joystick command sent');
    // the pose controls, for the eye: a second joystick whose commands go nowhere
    await t.page.evaluate(async () => {
      const { Joystick } = await import('/js/joystick.js');
      const host = Object.assign(document.createElement('section'), { id: 'pose-preview' });
      host.style.cssText = 'position:fixed;left:20px;top:60px;width:17rem;background:#fff;padding:.6rem;border:1px solid #ddd;border-radius:6px;z-index:10';
      document.body.append(host);
      window.__posePreview = new Joystick(host, { send: () => { throw new Error('the preview must not send'); } });
      window.__posePreview.configure({ enabled: true, space: 'pose', reach: 1.2 });
      host.querySelector('.js-help').open = true;
    });
    await t.page.locator('#pose-preview').screenshot({ path: join(screenshotDir, 'joystick-panel-pose.png') });
    await t.page.evaluate(() => window.__posePreview.destroy());
    await t.post(`/api/runs/${id}/control`, { action: 'stop' });
  }],
  ['a pose task gets z and rotation: E raises the target, Shift turns its orientation', async (t) => {
    const id = await openLive(t, '05_dh7_pose_joystick');
    await t.page.waitForSelector('#joystick-section:not([hidden]) .joystick:not(.js-off)');
    const lane = () => t.page.evaluate(() => window.__rrlab.session.lanes[0].frame);
    const before = await lane();
    check(Array.isArray(before.target_quat), 'pose frames carry the target orientation');
    await t.page.locator('#views').click({ position: { x: 5, y: 5 } });
    await t.page.keyboard.down('e');  // held until the target has risen
    await eventually(async () => (await lane()).target[2] > before.target[2] + 0.02, 'the target to rise in z');
    await t.page.keyboard.up('e');
    await t.page.keyboard.down('Shift');  // held until the orientation has turned
    await t.page.keyboard.down('ArrowRight');
    await eventually(async () => {
      const q = (await lane()).target_quat, p = before.target_quat;
      return Math.abs(q[0] * p[0] + q[1] * p[1] + q[2] * p[2] + q[3] * p[3]) < 0.9999;
    }, 'the target orientation to turn');
    await t.page.keyboard.up('ArrowRight');
    await t.page.keyboard.up('Shift');
    const events = await joystickEvents(t, id);
    check(events.some((e) => e.payload.linear.length === 3 && e.payload.linear[2] > 0), 'a command with +z was sent');
    check(events.some((e) => e.payload.angular && e.payload.angular.some((w) => w !== 0)), 'a command with an angular rate was sent');
    await t.screenshot('pose');
    await t.post(`/api/runs/${id}/control`, { action: 'stop' });  // 3600 s otherwise
  }],
]);
