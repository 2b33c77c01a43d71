// What the header and the controls say about the session on screen: its
// title and run ids, the connection pill (live, paused, replay, ended), the
// status line, the live run's controls (play, pause, step, reset, stop), who
// controls it, the ended note and Restart with this scene, and the views'
// Re-simulate buttons. Everything it does goes through app.execute.
import { app } from './state.js';

const $ = (id) => document.getElementById(id);

// One client controls a live run: the line under the controls says who
// ('you': Release; 'other': Take control, the holder is told; 'none': hidden,
// the next input takes it). The server tells every socket at each change.
const CONTROL_TEXT = {
  you: 'You control this run.',
  other: 'Another client controls this run; you are watching.',
};

export class SessionPanel {
  constructor() {
    const signals = app.signals;
    signals.sessionChanged.add((s) => (s ? this.opened(s) : this.closed()));
    signals.pageChanged.add((page) => { if (page) $('connection').textContent = page.name; });
    // nothing opened by the address: the start page, ready for a first run
    signals.started.add(() => { if (!app.session && !app.page) this.ready(); });
    signals.snapshot.add((lane) => { if (this.current(lane)) this.showTitle(app.session); });
    signals.frame.add((lane) => {
      const f = lane.frame;
      if (this.current(lane) && app.session.kind === 'live' && lane.index === 0) $('status').textContent = `t = ${f.t.toFixed(2)} s · step ${f.step} · ${f.status}`;
    });
    signals.playhead.add((seq, frame) => this.showPlayhead(seq, frame));
    signals.status.add((text) => { $('status').textContent = text; });
    signals.connection.add((s) => { if (s === app.session) this.showConnection(s); });
    signals.sessionEnded.add((s) => this.ended(s));
    // a run or group opens with its views in sight (the centre column, or the page on a phone, may be
    // scrolled away: down the charts, a paper's or a sweep's page); an ended run that became its replay stays put
    signals.sessionOpened.add((s) => { if (!s.fromLive) $('views').scrollIntoView({ block: 'nearest' }); });
    signals.control.add((controller) => { if (app.liveSession) this.showControl(controller); });
    signals.controlTaken.add((text) => { this.showControl('other'); app.error(text); });
    signals.message.add((what) => { if (what && what.code === 'not_controller') this.showControl('other'); });

    for (const button of document.querySelectorAll('[data-action]')) {
      button.onclick = () => this.input({ action: button.dataset.action });
    }
    $('take-control').onclick = () => this.input({ action: 'take' }).then((state) => this.controlled(state, 'You control this run now.'), () => {});
    $('release-control').onclick = () => this.input({ action: 'release' })
      .then((state) => this.controlled(state, 'You let go of this run; another client may steer it.'), () => {});
    $('restart-scene').onclick = () => app.execute({ type: 'restart' });
    $('copy-link').onclick = async () => {
      try { await navigator.clipboard.writeText(location.href); app.info('link copied'); } catch { app.info(location.href); }
    };
    // "Re-simulate" in a lane that stored no frames
    $('views').addEventListener('click', (e) => {
      const button = e.target.closest('button[data-resimulate]');
      if (button) { button.disabled = true; app.execute({ type: 'resimulate', id: Number(button.dataset.resimulate) }); }
    });
  }

  current(lane) { return app.session && app.session.lanes.includes(lane); }

  input(payload) { return app.execute({ type: 'input', kind: 'control', payload }); }

  // The answer to take or release: who controls the run now.
  controlled(state, news) {
    if (!state) return;  // no live run on screen
    this.showControl(state.controller || 'none');
    app.info(news);
  }

  opened(s) {
    $('controls').hidden = s.kind !== 'live';
    $('ended-note').hidden = true;
    this.showControl('none');
    for (const el of document.querySelectorAll('#controls button:not(#delete-obstacle), #controls select')) el.disabled = false;
    $('run-id').textContent = s.runIds.map((id) => `#${id}`).join(' ');
    this.showTitle(s);
  }

  closed() {
    $('controls').hidden = true;
    $('session-title').textContent = '';
    $('status').textContent = '';
    this.ready();
  }

  // Nothing on screen: the server answered and a run may start (muted, not a warning).
  ready() {
    $('connection').textContent = 'ready';
    $('connection').className = 'pill muted';
  }

  // After a method switch a lane is named by its new method.
  showTitle(s) {
    $('session-title').textContent = `${s.kind === 'live' ? 'live' : 'replay'} · ${s.runs[0].scenario} · ${s.lanes.map((l) => l.label).join(' vs ')}`;
  }

  // The replay's current frame, on the status line.
  showPlayhead(seq, frame) {
    const lane = app.session && app.session.lanes[0];
    const t = frame ? frame.t : lane && lane.snapshot ? seq * lane.snapshot.dt : null;
    $('status').textContent = `${t === null ? '' : `t = ${t.toFixed(2)} s · `}${frame ? `step ${frame.step} · ` : ''}frame ${seq}`;
  }

  showConnection(s) {
    const states = s.lanes.map((l) => l.streamState);
    const el = $('connection');
    const open = states.every((x) => x === 'open');
    if (s.ended) { el.textContent = `ended (${s.lanes[0].status})`; el.className = 'pill muted'; return; }
    // an ended live run that became its replay still says how it ended
    if (s.fromLive) { el.textContent = `ended (${s.runs[0].status}) · replay`; el.className = 'pill muted'; return; }
    const paused = s.kind === 'live' && s.lanes[0].status === 'paused';
    el.textContent = open ? (s.kind === 'live' ? (paused ? 'paused' : 'live') : 'replay') : states.find((x) => x !== 'open') || '';
    el.className = `pill ${open ? 'ok' : 'warn'}`;
  }

  showControl(controller) {
    const note = $('control-note');
    note.dataset.controller = controller;
    note.hidden = !(controller in CONTROL_TEXT);
    if (note.hidden) return;
    note.querySelector('span').textContent = CONTROL_TEXT[controller];
    $('take-control').hidden = controller !== 'other';
    $('release-control').hidden = controller !== 'you';
  }

  // An ended run takes no more inputs: its controls go quiet, no control
  // notice, the note says it ended and the scene may restart.
  ended(s) {
    this.showControl('none');
    $('ended-note').hidden = false;
    for (const el of document.querySelectorAll('#controls button, #controls select')) el.disabled = true;
    $('restart-scene').disabled = false;
    this.showConnection(s);
  }
}
