// The message line under the header: errors stay until closed, news goes
// after 4 s. It shows what app.error / app.info (state.js) dispatch.
import { describeError } from './api.js';
import { app } from './state.js';

const NOT_CONTROLLER = 'Another client controls this run; you are watching. Press “Take control” to steer it.';

export function setupMessageBar() {
  const box = document.getElementById('message');
  box.querySelector('button').onclick = () => { box.hidden = true; };
  app.signals.message.add((what, kind) => {
    // another tab or client steers this run: say so plainly (the control note offers to take over)
    if (what && what.code === 'not_controller') what = NOT_CONTROLLER;
    box.className = kind === 'info' ? 'info' : '';
    box.querySelector('span').textContent = typeof what === 'string' ? what : describeError(what);
    box.hidden = false;
    clearTimeout(box.timer);
    if (kind === 'info') box.timer = setTimeout(() => { box.hidden = true; }, 4000);
  });
}
