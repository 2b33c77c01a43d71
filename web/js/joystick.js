// End-effector joystick for joystick tasks: keyboard, an on-screen pad, and a
// gamepad all add into one velocity command, sent only when it changes (at most
// 20 times a second) and as a zero command once everything is released.
// setupJoystick makes the page's: enabled on a live joystick task, its
// commands sent as input commands (state.js: execute).
import { element, isTyping } from './dom.js';
import { app } from './state.js';

const SEND_INTERVAL_MS = 50;          // at most 20 commands a second
const GAMEPAD_DEAD_ZONE = 0.15;
const GAMEPAD_SEARCH_MS = 250;        // how often to look for a pad nobody announced
const ANGULAR_SPEED = 0.5;            // rad/s at full deflection
const LINEAR_SPEED_PER_REACH = 0.1;   // m/s at full deflection, per metre of reach
const QUANTUM = 1 / 64;               // deflections are rounded so analog jitter does not resend

// Keyboard: each key pushes one axis of the deflection; Shift turns the
// linear axes into the angular ones (pose tasks only).
const KEY_AXES = {
  ArrowRight: [0, 1], KeyD: [0, 1], ArrowLeft: [0, -1], KeyA: [0, -1],
  ArrowUp: [1, 1], KeyW: [1, 1], ArrowDown: [1, -1], KeyS: [1, -1],
  KeyE: [2, 1], PageUp: [2, 1], KeyQ: [2, -1], PageDown: [2, -1],
};

const AXIS_NAMES = ['x', 'y', 'z'];

function deadZone(value, zone = GAMEPAD_DEAD_ZONE) {
  const magnitude = Math.abs(value);
  if (!(magnitude > zone)) return 0;
  return Math.sign(value) * Math.min(1, (magnitude - zone) / (1 - zone));
}

// A stick's dead zone is radial, so diagonals are not squashed onto the axes.
function stickDeadZone(x, y, zone = GAMEPAD_DEAD_ZONE) {
  const magnitude = Math.hypot(x, y);
  if (!(magnitude > zone)) return [0, 0];
  const scale = Math.min(1, (magnitude - zone) / (1 - zone)) / magnitude;
  return [x * scale, y * scale];
}

const clamp1 = (v) => Math.max(-1, Math.min(1, v));
const quantize = (v) => Math.round(clamp1(v) / QUANTUM) * QUANTUM || 0;


// A control dragged with the pointer (mouse, pen, touch) that springs back to
// centre on release: a round pad (two axes) or a bar (one axis).
class SpringControl {
  constructor({ shape, label, onChange }) {
    this.shape = shape;  // 'pad' | 'vertical' | 'horizontal'
    this.value = [0, 0]; // [horizontal, vertical] in −1…1, up is +
    this.onChange = onChange;
    this.knob = element('div', { class: 'js-knob' });
    this.root = element('div', { class: `js-spring js-${shape}`, role: 'img', 'aria-label': label, title: label }, [this.knob]);
    this.pointer = null;
    this.root.addEventListener('pointerdown', (e) => this.grab(e));
    this.root.addEventListener('pointermove', (e) => { if (e.pointerId === this.pointer) this.follow(e); });
    for (const type of ['pointerup', 'pointercancel', 'lostpointercapture']) {
      this.root.addEventListener(type, (e) => { if (e.pointerId === this.pointer) this.release(); });
    }
  }

  grab(event) {
    if (this.root.classList.contains('js-disabled') || this.pointer !== null) return;
    event.preventDefault();
    this.pointer = event.pointerId;
    this.root.setPointerCapture(event.pointerId);
    this.root.classList.add('js-active');
    this.follow(event);
  }

  follow(event) {
    const rect = this.root.getBoundingClientRect();
    const knob = this.knob.getBoundingClientRect();
    // the knob's centre may travel to the edge less its own half size
    const rangeX = Math.max(1, (rect.width - knob.width) / 2);
    const rangeY = Math.max(1, (rect.height - knob.height) / 2);
    let x = (event.clientX - (rect.left + rect.width / 2)) / rangeX;
    let y = -(event.clientY - (rect.top + rect.height / 2)) / rangeY;
    if (this.shape === 'vertical') x = 0;
    if (this.shape === 'horizontal') y = 0;
    const length = Math.hypot(x, y);
    if (length > 1) { x /= length; y /= length; }
    this.value = [x, y];
    this.onChange();
  }

  release() {
    if (this.pointer !== null && this.root.hasPointerCapture(this.pointer)) this.root.releasePointerCapture(this.pointer);
    this.pointer = null;
    this.root.classList.remove('js-active');
    this.value = [0, 0];
    this.onChange();
  }

  // Draws the knob where the total command puts it (keys and gamepad too).
  show(x, y) {
    const rect = this.root.getBoundingClientRect();
    const knob = this.knob.getBoundingClientRect();
    const dx = x * Math.max(0, (rect.width - knob.width) / 2);
    const dy = -y * Math.max(0, (rect.height - knob.height) / 2);
    this.knob.style.transform = `translate(${dx}px, ${dy}px)`;
  }

  setEnabled(enabled) {
    this.root.classList.toggle('js-disabled', !enabled);
    if (!enabled && this.pointer !== null) this.release();
  }
}

export class Joystick {
  constructor(container, { send }) {
    this.send = send;
    this.enabled = false;
    this.space = 'xy';
    this.reach = 1;
    this.keys = new Set();     // held key codes
    this.shift = false;
    this.gamepad = null;       // {index, id}
    this.gamepadAxes = { linear: [0, 0, 0], angular: [0, 0, 0] };
    this.lastSent = null;      // the last command sent, as a string
    this.lastSentAt = -Infinity;
    this.pendingTimer = null;
    this.frameRequest = null;
    this.build(container);

    this.onKeyDown = (e) => this.key(e, true);
    this.onKeyUp = (e) => this.key(e, false);
    this.onBlur = () => this.releaseKeys();
    this.onVisibility = () => { if (document.hidden) this.releaseKeys(); };
    this.onGamepadConnected = (e) => this.attachGamepad(e.gamepad);
    this.onGamepadDisconnected = (e) => { if (this.gamepad && e.gamepad.index === this.gamepad.index) this.detachGamepad(); };
    window.addEventListener('keydown', this.onKeyDown);
    window.addEventListener('keyup', this.onKeyUp);
    window.addEventListener('blur', this.onBlur);
    document.addEventListener('visibilitychange', this.onVisibility);
    window.addEventListener('gamepadconnected', this.onGamepadConnected);
    window.addEventListener('gamepaddisconnected', this.onGamepadDisconnected);
    // pads that are plugged in before the page loads, or emulated, fire no event
    this.searchTimer = setInterval(() => { if (!this.gamepad) this.findGamepad(); }, GAMEPAD_SEARCH_MS);
    this.findGamepad();
    this.configure({ enabled: false, space: 'xy', reach: 1 });
  }

  build(container) {
    const changed = () => this.update();
    this.pad = new SpringControl({ shape: 'pad', label: 'Drag to move the target in x (right) and y (up)', onChange: changed });
    this.zBar = new SpringControl({ shape: 'vertical', label: 'Drag up or down to move the target in z', onChange: changed });
    this.rotatePad = new SpringControl({ shape: 'pad', label: 'Drag to rotate about x (right) and y (up)', onChange: changed });
    this.yawBar = new SpringControl({ shape: 'horizontal', label: 'Drag left or right to rotate about z', onChange: changed });

    this.zGroup = element('div', { class: 'js-group' }, [this.zBar.root, element('span', { class: 'js-caption', text: 'z' })]);
    this.rotateGroup = element('div', { class: 'js-row js-rotate' }, [
      element('div', { class: 'js-group' }, [this.rotatePad.root, element('span', { class: 'js-caption', text: 'rotate x · y' })]),
      element('div', { class: 'js-group' }, [this.yawBar.root, element('span', { class: 'js-caption', text: 'rotate z' })]),
    ]);
    this.readout = element('div', { class: 'js-readout', 'aria-live': 'off' });
    this.indicator = element('div', { class: 'js-gamepad', hidden: '' });
    this.status = element('div', { class: 'js-status', role: 'status' });
    this.help = element('details', { class: 'js-help' });
    this.root = element('section', { class: 'joystick', 'aria-label': 'End-effector joystick' }, [
      element('div', { class: 'js-controls' }, [
        element('div', { class: 'js-row' }, [
          element('div', { class: 'js-group' }, [this.pad.root, element('span', { class: 'js-caption', text: 'move x · y' })]),
          this.zGroup,
        ]),
        this.rotateGroup,
      ]),
      this.readout, this.indicator, this.status, this.help,
    ]);
    container.append(this.root);
  }

  configure({ enabled, space, reach }) {
    const wasEnabled = this.enabled;
    this.enabled = Boolean(enabled);
    if (space) this.space = ['xy', 'xyz', 'pose'].includes(space) ? space : 'xy';
    if (Number.isFinite(reach) && reach > 0) this.reach = reach;
    this.zGroup.hidden = this.space === 'xy';
    this.rotateGroup.hidden = this.space !== 'pose';
    this.root.classList.toggle('js-off', !this.enabled);
    for (const control of [this.pad, this.zBar, this.rotatePad, this.yawBar]) control.setEnabled(this.enabled);
    this.writeHelp();
    if (!this.enabled) {
      // nothing is sent while disabled; the next enable starts from rest
      this.releaseKeys(false);
      clearTimeout(this.pendingTimer);
      this.pendingTimer = null;
      this.lastSent = null;
      this.status.textContent = 'Available on joystick tasks of a live run.';
    } else if (!wasEnabled) {
      this.lastSent = JSON.stringify(this.zeroCommand());  // the server's target starts at rest
      this.status.textContent = '';
    }
    this.showCommand(this.deflection());
    this.pollGamepad();
  }

  destroy() {
    this.enabled = false;
    window.removeEventListener('keydown', this.onKeyDown);
    window.removeEventListener('keyup', this.onKeyUp);
    window.removeEventListener('blur', this.onBlur);
    document.removeEventListener('visibilitychange', this.onVisibility);
    window.removeEventListener('gamepadconnected', this.onGamepadConnected);
    window.removeEventListener('gamepaddisconnected', this.onGamepadDisconnected);
    clearInterval(this.searchTimer);
    clearTimeout(this.pendingTimer);
    if (this.frameRequest !== null) cancelAnimationFrame(this.frameRequest);
    this.root.remove();
  }

  writeHelp() {
    const pose = this.space === 'pose';
    const keys = [['← → or A D', 'x'], ['↑ ↓ or W S', 'y']];
    if (this.space !== 'xy') keys.push(['Q E or PgDn PgUp', 'z']);
    if (pose) keys.push(['Shift + those keys', 'rotate about x, y, z']);
    const pad = [['left stick', 'x · y']];
    if (this.space !== 'xy') pad.push(['right stick ↕', 'z']);
    if (pose) pad.push(['right stick ↔', 'rotate z'], ['RT − LT', 'rotate x'], ['RB − LB', 'rotate y']);
    const rows = (list) => list.map(([input, axis]) => element('tr', {}, [element('td', { text: input }), element('td', { text: axis })]));
    const speed = `Full deflection: ${(LINEAR_SPEED_PER_REACH * this.reach).toFixed(2)} m/s${pose ? `, ${ANGULAR_SPEED} rad/s` : ''}.`;
    this.help.replaceChildren(
      element('summary', { text: 'Keys and gamepad' }),
      element('table', {}, [
        element('tr', {}, [element('th', { colspan: '2', text: 'Keyboard' })]), ...rows(keys),
        element('tr', {}, [element('th', { colspan: '2', text: 'Gamepad' })]), ...rows(pad),
      ]),
      element('p', { text: `${speed} Keys are ignored while typing in a field. Releasing everything stops the target.` }),
    );
  }

  // ---- inputs ----------------------------------------------------------------

  key(event, down) {
    if (event.key === 'Shift') {
      this.shift = down;
      if (this.keys.size) this.update();
      return;
    }
    const axis = KEY_AXES[event.code];
    if (!axis) return;
    if (!down) {
      if (this.keys.delete(event.code)) this.update();
      return;
    }
    if (!this.enabled || isTyping(event.target, event.key) || event.ctrlKey || event.altKey || event.metaKey) return;
    if (axis[0] === 2 && this.space === 'xy') return;  // no z in the plane
    event.preventDefault();  // arrows and PageUp/Down would scroll the page
    this.shift = event.shiftKey;
    if (this.keys.has(event.code)) return;  // auto-repeat
    this.keys.add(event.code);
    this.update();
  }

  releaseKeys(update = true) {
    this.shift = false;
    if (!this.keys.size) return;
    this.keys.clear();
    if (update) this.update();
  }

  findGamepad() {
    const pads = navigator.getGamepads ? Array.from(navigator.getGamepads() || []) : [];
    const pad = pads.find((p) => p && p.connected !== false);
    if (pad) this.attachGamepad(pad);
  }

  attachGamepad(pad) {
    if (this.gamepad && this.gamepad.index === pad.index) return;
    this.gamepad = { index: pad.index, id: pad.id || 'gamepad' };
    this.indicator.textContent = `🎮 gamepad connected: ${this.gamepad.id}`;
    this.indicator.hidden = false;
    this.pollGamepad();
  }

  detachGamepad() {
    this.gamepad = null;
    this.indicator.hidden = true;
    this.gamepadAxes = { linear: [0, 0, 0], angular: [0, 0, 0] };
    this.update();
  }

  // Polled each animation frame while a pad is attached and the joystick is on.
  pollGamepad() {
    if (this.frameRequest !== null || !this.gamepad || !this.enabled) return;
    const frame = () => {
      this.frameRequest = null;
      if (!this.gamepad || !this.enabled) return;
      const pads = navigator.getGamepads ? Array.from(navigator.getGamepads() || []) : [];
      const pad = pads.find((p) => p && p.index === this.gamepad.index) || pads.find((p) => p);
      if (!pad || pad.connected === false) { this.detachGamepad(); return; }
      if (pad.index !== this.gamepad.index) this.attachGamepad(pad);
      this.readGamepad(pad);
      this.update();
      this.frameRequest = requestAnimationFrame(frame);
    };
    this.frameRequest = requestAnimationFrame(frame);
  }

  // Standard mapping: axes 0/1 left stick, 2/3 right stick (down is +),
  // buttons 4/5 bumpers, 6/7 triggers (analog .value).
  readGamepad(pad) {
    const axes = pad.axes || [];
    const button = (i) => { const b = (pad.buttons || [])[i]; return b ? (typeof b === 'object' ? b.value ?? (b.pressed ? 1 : 0) : Number(b)) : 0; };
    const [lx, ly] = stickDeadZone(axes[0] || 0, axes[1] || 0);
    const rightX = deadZone(axes[2] || 0);
    const rightY = deadZone(axes[3] || 0);
    this.gamepadAxes = {
      linear: [lx, -ly, -rightY],
      angular: [deadZone(button(7) - button(6)), button(5) - button(4), rightX],
    };
  }

  // ---- the command -------------------------------------------------------------

  // Deflections in −1…1: {linear:[3], angular:[3]}, summed over every input.
  deflection() {
    const linear = [0, 0, 0], angular = [0, 0, 0];
    if (!this.enabled) return { linear, angular };
    const angularKeys = this.space === 'pose' && this.shift;
    for (const code of this.keys) {
      const [axis, sign] = KEY_AXES[code];
      (angularKeys ? angular : linear)[axis] += sign;
    }
    linear[0] += this.pad.value[0];
    linear[1] += this.pad.value[1];
    linear[2] += this.zBar.value[1];
    angular[0] += this.rotatePad.value[0];
    angular[1] += this.rotatePad.value[1];
    angular[2] += this.yawBar.value[0];
    if (this.gamepad) {
      for (let i = 0; i < 3; ++i) linear[i] += this.gamepadAxes.linear[i];
      for (let i = 0; i < 3; ++i) angular[i] += this.gamepadAxes.angular[i];
    }
    if (this.space === 'xy') linear[2] = 0;
    if (this.space !== 'pose') angular.fill(0);
    return { linear: linear.map(quantize), angular: angular.map(quantize) };
  }

  zeroCommand() {
    return this.command({ linear: [0, 0, 0], angular: [0, 0, 0] });
  }

  // The payload of a joystick input (api.js INPUT_KINDS), in m/s and rad/s.
  command({ linear, angular }) {
    const speed = LINEAR_SPEED_PER_REACH * this.reach;
    const round = (v) => Math.round(v * 1e6) / 1e6 || 0;
    const out = { linear: linear.slice(0, this.space === 'xy' ? 2 : 3).map((v) => round(v * speed)) };
    if (this.space === 'pose') out.angular = angular.map((v) => round(v * ANGULAR_SPEED));
    return out;
  }

  update() {
    const deflection = this.deflection();
    this.showCommand(deflection);
    if (!this.enabled) return;
    this.flush();
  }

  // Sends the current command if it differs from the last one sent, now or
  // as soon as the rate limit allows (the latest command wins).
  flush() {
    if (!this.enabled || this.pendingTimer !== null) return;
    const command = this.command(this.deflection());
    const text = JSON.stringify(command);
    if (text === this.lastSent) return;
    const wait = this.lastSentAt + SEND_INTERVAL_MS - performance.now();
    if (wait > 0) {
      this.pendingTimer = setTimeout(() => { this.pendingTimer = null; this.flush(); }, wait);
      return;
    }
    this.lastSent = text;
    this.lastSentAt = performance.now();
    let result;
    try {
      result = this.send(command);
    } catch (error) {
      this.showSendError(error);
      return;
    }
    if (result && typeof result.then === 'function') {
      result.then(() => { if (this.status.classList.contains('js-error')) this.status.textContent = ''; this.status.classList.remove('js-error'); },
        (error) => this.showSendError(error));
    }
  }

  showSendError(error) {
    this.lastSent = null;  // resend once the problem is gone
    this.status.classList.add('js-error');
    this.status.textContent = `⚠ joystick command not accepted: ${error && error.message ? error.message : error}`;
  }

  showCommand({ linear, angular }) {
    this.pad.show(linear[0], linear[1]);
    this.zBar.show(0, linear[2]);
    this.rotatePad.show(angular[0], angular[1]);
    this.yawBar.show(angular[2], 0);
    const command = this.command({ linear, angular });
    const line = (label, values) => `${label} ${values.map((v, i) => `${AXIS_NAMES[i]} ${v >= 0 ? ' ' : ''}${v.toFixed(2)}`).join('  ')}`;
    const lines = [line('v m/s  ', command.linear)];
    if (command.angular) lines.push(line('ω rad/s', command.angular));
    this.readout.textContent = this.enabled ? lines.join('\n') : '';
    this.root.classList.toggle('js-moving', [...linear, ...angular].some((v) => v !== 0));
  }
}

// The page's joystick in `container`: shown and enabled while the live run
// on screen has a joystick task, quiet once it ended or closed.
export function setupJoystick(container) {
  const joystick = new Joystick(container, {
    // its own status line shows a refusal: not the page's message line
    send: (command) => app.execute({ type: 'input', kind: 'joystick', payload: command, report: false }),
  });
  const section = document.getElementById('joystick-section');
  const quiet = (space = 'xy') => {
    joystick.configure({ enabled: false, space, reach: 1 });
    section.hidden = true;
  };
  app.signals.snapshot.add((lane) => {
    const s = app.session;
    if (!s || !s.lanes.includes(lane) || lane.index !== 0) return;
    const enabled = lane.snapshot.task.trajectory === 'joystick' && s.kind === 'live' && !s.ended;
    section.hidden = !enabled;
    joystick.configure({ enabled, space: lane.snapshot.task.space, reach: lane.snapshot.model.reach });
  });
  app.signals.sessionChanged.add((s) => { if (!s) quiet(); });
  app.signals.sessionEnded.add((s) => quiet(s.lanes[0].snapshot ? s.lanes[0].snapshot.task.space : 'xy'));
  return joystick;
}
