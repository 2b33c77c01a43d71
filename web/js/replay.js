// The replay bar: play/pause, speed, frame step and seek for every lane of a
// replayed session at once. It holds the one current frame of the page: the
// playhead advances here (not in each lane's server player, whose clocks
// drift apart), every lane is asked for that frame, and the scrubber,
// readout, status line, plot cursor and address follow it on every seek,
// however it was asked for (scrubber, plot click, keyboard, deep link): they
// hear of it through the playhead signal. What it asked each lane's player
// for is its own (a map by lane), not the lane's.
//
// Frames come from the page's own memory once loaded (local_frames.js): a
// seek draws every lane at once; the server's player is asked only for a
// frame the page does not hold (a long run kept at a stride), and its answer
// replaces the nearest held frame drawn meanwhile. A frame the player sends
// that is no longer the one to show is not drawn (Session.frameGate).
import { api } from './api.js';
import { LocalReplay, MEMORY_BUDGET } from './local_frames.js';
import { app } from './state.js';
import { isTyping } from './dom.js';

const $ = (id) => document.getElementById(id);
const URL_EVERY_MS = 1000;      // the address follows a playing replay once a second
const REQUEST_TIMEOUT_MS = 2000; // a frame asked for that never comes does not stall the lane

export class ReplayBar {
  constructor() {
    this.session = null;
    this.players = new Map();  // lane → {wanted, inflight, inflightSince, paused, serverFrame, display, drawn, stored}
    this.local = null;         // the lanes' frames in the page's memory (LocalReplay)
    this.holdFrames = true;    // false: every frame from the server (bench/web/replay_scrub.mjs compares)
    this.memoryBudget = MEMORY_BUDGET;  // bytes of frame text for all lanes (a test lowers it to see a stride)
    this.playing = false;
    this.current = 0;
    this.head = 0;          // fractional playhead while playing, in frames
    this.lastTick = null;
    this.lastUrl = 0;
    this.events = [];         // recorded inputs, marked under the scrubber
    this.failures = [];       // the lanes' first failures, marked and written beside their marks
    this.awaitingFailure = false;  // a failed run opened without a frame: seek to its failure when found
    $('replay-play').onclick = () => this.setPlaying(!this.playing);
    $('replay-back').onclick = () => this.step(-1);
    $('replay-forward').onclick = () => this.step(1);
    const scrubber = $('scrubber');
    scrubber.oninput = () => this.seek(Number(scrubber.value));
    scrubber.onchange = () => this.seek(Number(scrubber.value));
    window.addEventListener('keydown', (e) => {
      if (!this.session || isTyping(e.target, e.key) || e.ctrlKey || e.metaKey || e.altKey) return;
      if (e.key === ',') this.step(-1);
      else if (e.key === '.') this.step(1);
      else if (e.key === ' ') { e.preventDefault(); this.setPlaying(!this.playing); }
      else if (e.key === 'Home') { e.preventDefault(); this.seek(0); }
      else if (e.key === 'End') { e.preventDefault(); this.seek(this.last); }
    });
    const current = (lane) => this.session && this.session === app.session && this.session.lanes.includes(lane);
    app.signals.sessionChanged.add(() => this.detach());
    app.signals.sessionOpened.add((session, { frame, atFailure }) => { if (session.kind === 'replay' && !session.empty) this.attach(session, frame, atFailure); });
    app.signals.frame.add((lane) => { if (current(lane)) this.onFrame(lane, lane.frame); });
    // a replay's snapshot carries the frame its player shows (and the scene there)
    app.signals.snapshot.add((lane) => { if (current(lane)) this.onSnapshot(lane); });
    app.signals.storedFrames.add((lane, data) => { if (current(lane)) this.setStored(lane, data.frames); });
    app.signals.markers.add((markers) => { if (this.session) this.setMarkers(markers); });
    app.signals.failures.add((failures) => { if (this.session) this.setFailures(failures); });
    // Back / Forward to another frame of this replay
    app.signals.seek.add((seq) => { if (this.session) this.seek(seq); });
  }

  get last() { return Math.max(0, this.session ? this.session.frameCount - 1 : 0); }
  get seq() { return this.current; }
  get speed() { return Number($('replay-speed').value); }

  // Shows frame `startFrame` paused, or plays from the start when it is
  // null; `atFailure`: paused, at the first failure once it is found.
  attach(session, startFrame, atFailure = false) {
    this.session = session;
    this.events = [];
    this.failures = [];
    this.awaitingFailure = Boolean(atFailure) && (startFrame === null || startFrame === undefined);
    this.players = new Map(session.lanes.map((lane) => [lane, {
      wanted: null, inflight: null, inflightSince: 0, paused: false, serverFrame: lane.frame, display: null, drawn: lane.frame ? lane.frame.seq : null, stored: null,
    }]));
    session.frameGate = (lane, frame) => this.gate(lane, frame);
    this.loadLocal(session);
    $('replay-bar').hidden = false;
    $('scrubber').max = String(this.last);
    const start = startFrame === null || startFrame === undefined ? 0 : startFrame;
    this.playing = (startFrame === null || startFrame === undefined) && !this.awaitingFailure;
    this.lastTick = null;
    this.showPlaying();
    this.show(start, true);
  }

  // The recorded inputs along the scrubber ({seq, kind, text}): each a mark
  // with its words as a tooltip; a click shows its frame.
  setMarkers(markers) {
    this.events = markers;
    this.drawMarks();
  }

  // The lanes' first failures ({lane, seq, kind: 'failure', text}): marked
  // too, each with its reason written under the scrubber beside its mark. A
  // failed run opened without a frame is shown at its failure.
  setFailures(failures) {
    this.failures = failures;
    this.drawMarks();
    const first = this.awaitingFailure && failures.find((f) => f.lane === 0 && Number.isInteger(f.seq));
    if (first) this.seek(first.seq);
  }

  drawMarks() {
    const last = this.last;
    const at = (seq) => `${last > 0 ? (100 * Math.max(0, Math.min(seq, last))) / last : 0}%`;
    const marks = [...this.events, ...this.failures.filter((f) => Number.isInteger(f.seq))].map((m) => {
      const mark = document.createElement('button');
      mark.type = 'button';
      mark.className = `event-marker event-${m.kind}`;
      mark.title = `frame ${m.seq}: ${m.kind === 'failure' ? `first failure: ${m.text}` : m.text}`;
      mark.setAttribute('aria-label', mark.title);
      mark.style.left = at(m.seq);
      mark.onclick = () => this.jump(m.seq);
      return mark;
    });
    $('replay-markers').replaceChildren(...marks);
    // each reason on a line of its own, its text placed at its mark (kept inside the bar)
    const labels = this.failures.map((f) => {
      const line = document.createElement('div');
      line.className = 'failure-label';
      const text = document.createElement('span');
      text.textContent = `✗ ${f.text}`;
      if (Number.isInteger(f.seq)) { text.style.left = at(f.seq); text.style.transform = `translateX(-${at(f.seq)})`; }
      line.appendChild(text);
      return line;
    });
    $('failure-labels').replaceChildren(...labels);
    $('replay-bar').style.setProperty('--failure-lines', String(labels.length));
    $('replay-bar').classList.toggle('has-failure', labels.length > 0);
  }

  // The lanes' frames into the page's memory, in the background; the frame
  // on screen is drawn from there once it is held.
  loadLocal(session) {
    if (this.local) this.local.cancel();
    this.local = null;
    if (!this.holdFrames) { this.showMemory(); return; }
    const lanes = session.lanes.map((lane) => ({ key: lane, runId: lane.runId, frames: session.runs[lane.index].frames }));
    const local = new LocalReplay(lanes, (id, range) => api.drawnFrames(id, range), () => {
      if (this.local !== local) return;
      this.showMemory();
      if (!this.playing) for (const lane of session.lanes) this.drawHeld(lane);
    }, this.memoryBudget);
    this.local = local;
    this.showMemory();
    local.load();
  }

  // How much of the replay the page holds, beside the frame readout.
  showMemory() {
    const out = $('replay-memory');
    const local = this.local;
    if (!local) { out.textContent = ''; return; }
    const mb = (local.bytes / 1048576).toFixed(1);
    const percent = Math.floor(100 * local.progress);
    if (local.error) {
      out.textContent = 'frames from the server';
      out.title = `The frames could not be loaded into the page (${local.error.message}): every seek asks the server.`;
    } else if (!local.done) {
      out.textContent = `loading ${percent} %`;
      out.title = `Loading the frames into the page: ${mb} MB so far, at most ${local.budget / 1048576} MB. Seeks are drawn from the page once their frames are in.`;
    } else {
      out.textContent = local.stride > 1 ? `in memory: 1 in ${local.stride}` : 'in memory';
      out.title = `${mb} MB of frames held in the page (budget ${local.budget / 1048576} MB)` +
        (local.stride > 1 ? `: every ${local.stride}th frame of the longer lanes; the ones between come from the server when paused.` : ': every frame; seeks draw without asking the server.');
    }
    out.dataset.progress = String(percent);
  }

  detach() {
    if (this.session) this.session.frameGate = null;
    if (this.local) this.local.cancel();
    this.local = null;
    this.showMemory();
    this.events = [];
    this.failures = [];
    this.awaitingFailure = false;
    this.drawMarks();
    this.session = null;
    this.players = new Map();
    this.playing = false;
    $('replay-bar').hidden = true;
  }

  setPlaying(playing) {
    if (!this.session) return;
    this.awaitingFailure = false;
    // Play at the end starts again from the first frame
    if (playing && this.current >= this.last) this.show(0, true);
    this.playing = playing;
    this.lastTick = null;
    this.showPlaying();
    // paused: the frame exactly (a lane held at a stride drew the one before it while playing)
    if (!playing) this.show(this.current, true);
  }

  showPlaying() {
    $('replay-play').textContent = this.playing ? '❚❚' : '▶';
    $('replay-play').title = this.playing ? 'pause (space)' : 'play (space)';
  }

  // Seeking pauses: the frame shown is the one asked for.
  seek(seq) {
    if (!this.session) return;
    this.awaitingFailure = false;
    if (this.playing) { this.playing = false; this.showPlaying(); }
    this.show(seq, true);
  }

  step(delta) { this.seek(this.current + delta); }

  // A deliberate seek (a marker clicked): a history entry of its own, so Back
  // returns to the frame shown before it (scrubbing only replaces the frame).
  jump(seq) {
    if (!this.session) return;
    this.session.updateUrl(this.current);
    this.session.updateUrl(Math.max(0, Math.min(this.last, Math.round(Number(seq) || 0))), { push: true });
    this.seek(seq);
  }

  // Seeks to the frame at run time t = seq·dt (a click on a plot).
  seekTime(t) {
    const lane = this.session && this.session.lanes[0];
    if (!lane || !lane.snapshot) return;
    this.seek(t / lane.snapshot.dt);
  }

  // Seeks to `seq` and resolves when every lane shows it (its last frame when
  // it is shorter): a video export draws each frame exactly once.
  showAndWait(seq, timeoutMs = 10000) {
    this.seek(seq);
    const session = this.session;
    const target = this.current;
    const started = performance.now();
    return new Promise((resolve, reject) => {
      const check = () => {
        if (this.session !== session) { reject(new Error('the replay was closed')); return; }
        const ready = session.lanes.every((lane) => {
          const frames = session.runs[lane.index].frames;
          return frames === 0 || (lane.frame && lane.frame.seq === Math.min(target, frames - 1) && lane.view);
        });
        if (ready) { resolve(); return; }
        if (performance.now() - started > timeoutMs) { reject(new Error(`frame ${target} did not arrive in ${timeoutMs / 1000} s`)); return; }
        setTimeout(check, 2);
      };
      check();
    });
  }

  // Called at the display rate: advances the playhead at the chosen speed.
  tick(now) {
    this.retryLost(performance.now());
    if (!this.session || !this.playing) { this.lastTick = null; return; }
    const lane = this.session.lanes.find((l) => l.snapshot);  // a lane without frames has none
    const dt = lane ? lane.snapshot.dt : null;
    if (this.lastTick === null || !dt) { this.lastTick = now; this.head = this.current; return; }
    this.head += (this.speed * (now - this.lastTick)) / 1000 / dt;
    this.lastTick = now;
    let seq = Math.floor(this.head);
    if (seq >= this.last) { seq = this.last; this.playing = false; this.showPlaying(); }
    if (seq !== this.current) this.show(seq, !this.playing);
  }

  // The one place the current frame changes: every readout follows at once,
  // every lane draws the frame (its last one when it is shorter) from the
  // page's memory, or asks the server for it.
  show(seq, writeAddress) {
    seq = Math.max(0, Math.min(this.last, Math.round(Number(seq) || 0)));
    this.current = seq;
    this.head = seq;
    $('scrubber').value = String(seq);
    this.present(null);
    const now = performance.now();
    if (writeAddress || now - this.lastUrl > URL_EVERY_MS) { this.lastUrl = now; this.session.updateUrl(seq); }
    for (const lane of this.session.lanes) {
      const frames = this.session.runs[lane.index].frames;
      if (frames === 0) continue;
      const p = this.players.get(lane);
      p.display = Math.min(seq, frames - 1);
      const drawn = this.drawHeld(lane);
      // the exact frame from the server when the page holds only one near it (not while playing)
      p.wanted = drawn === p.display || (drawn !== null && this.playing) ? null : p.display;
      if (p.wanted !== null) this.request(lane);
    }
    const first = this.session.lanes[0];
    if (first.frame && first.frame.seq === this.players.get(first).display) this.present(first.frame);
  }

  // Draws the lane's frame to show from what the page holds: the exact frame
  // (held, or the player's last), else the held one before it. The seq drawn,
  // or null (nothing near is held, or its method is not the lane's: the
  // player's snapshot brings a switched method's panel).
  drawHeld(lane) {
    const p = this.players.get(lane);
    if (!p || p.display === null || !lane.snapshot) return null;
    if (p.drawn === p.display) return p.drawn;
    if (p.serverFrame && p.serverFrame.seq === p.display) { this.session.frame(lane, p.serverFrame, true); return p.display; }
    const local = this.local && this.local.get(lane);
    const seq = local ? local.nearest(p.display) : null;
    if (seq === null) return null;
    const scene = local.sceneAt(seq);
    if (!scene || scene.method !== lane.snapshot.method) return null;
    if (lane.localScene !== scene) {
      this.session.sceneChanged(lane, { obstacles: scene.obstacles, scene_version: lane.snapshot.scene_version });
      lane.localScene = scene;
    }
    this.session.frame(lane, local.frame(seq), true);
    return seq;
  }

  // A frame the lane's player sent: its state noted, drawn only when it is
  // the frame to show (one asked for earlier, or sent while the player still
  // played on its own clock, is not); the newest wish goes out.
  gate(lane, frame) {
    const p = this.players.get(lane);
    if (!p) return true;
    this.heard(p, frame);
    const draw = frame.seq === p.display && p.drawn !== frame.seq;
    if (!draw) this.request(lane);
    return draw;
  }

  // The frame the lane's player shows now: the one asked for has come.
  heard(p, frame) {
    p.serverFrame = frame;
    if (p.inflight === frame.seq) p.inflight = null;
  }

  // The player's snapshot (on connecting, or when its scene changed) drew its
  // own frame and obstacles: the frame to show is drawn again over it.
  onSnapshot(lane) {
    const p = this.players.get(lane);
    if (!p) return;
    const frame = lane.snapshot && lane.snapshot.frame;
    lane.localScene = null;
    if (frame) this.heard(p, frame);
    if (lane.frame && (p.display === null || lane.frame.seq === p.display)) this.onFrame(lane, lane.frame);
    else if (p.display !== null) { p.drawn = null; this.drawHeld(lane); }
    this.request(lane);
  }

  // A frame asked for that has not come within REQUEST_TIMEOUT_MS (a control
  // lost while the server's player was still starting, on a loaded machine)
  // is asked for again, paused or playing: the lane never stays on a frame
  // the scrubber has left.
  retryLost(now) {
    if (!this.session) return;
    for (const [lane, p] of this.players) if (p.inflight !== null && now - p.inflightSince >= REQUEST_TIMEOUT_MS) this.request(lane);
  }

  // One request in flight per lane; the newest wish is sent when it is
  // answered. The first always goes: it pauses the lane's server player,
  // which starts out playing on its own clock.
  request(lane) {
    const p = this.players.get(lane);
    const now = performance.now();
    if (p.inflight !== null && now - p.inflightSince < REQUEST_TIMEOUT_MS) return;
    p.inflight = null;
    if (p.wanted === null) return;
    const shown = p.serverFrame !== null && p.wanted === p.serverFrame.seq;  // the server shows it already: no frame will come
    if (shown && p.paused) return;
    p.paused = true;
    if (!shown) { p.inflight = p.wanted; p.inflightSince = now; }
    const body = { action: 'pause', seq: p.wanted };  // one command: a separate pause could land after the seek
    if (lane.stream && lane.stream.send({ type: 'control', ...body })) return;
    if (!lane.replayId) { p.inflight = null; return; }
    api.replayControl(lane.replayId, body).catch((e) => { p.inflight = null; app.error(e); });
  }

  // A lane drew a frame (from the page's memory or the player; its view has it already).
  onFrame(lane, frame) {
    if (!this.session || !this.session.lanes.includes(lane)) return;
    const p = this.players.get(lane);
    const previous = p.drawn;
    p.drawn = frame.seq;
    // a jump (a seek, or frames skipped at speed): the trace is rebuilt up to this frame, not cleared
    if (lane.view && frame.seq !== previous && frame.seq !== (previous === null ? 0 : previous + 1)) this.rebuildTrace(lane, frame.seq);
    if (lane.index === 0 && frame.seq === Math.min(this.current, this.session.runs[0].frames - 1)) this.present(frame);
  }

  // A lane's stored frames (strided): its trace up to any frame, after a seek.
  setStored(lane, frames) {
    const p = this.players.get(lane);
    p.stored = frames.map((f) => ({ seq: f.seq, ee: f.ee }));
    if (p.drawn !== null && lane.view) this.rebuildTrace(lane, p.drawn);
  }

  rebuildTrace(lane, seq) {
    const stored = this.players.get(lane).stored;
    if (!stored || !lane.view.rebuildTrace) return;
    const points = [];
    for (const f of stored) { if (f.seq > seq) break; points.push(f.ee); }
    lane.view.rebuildTrace(points);
  }

  // The readout; the page's status line and plot cursor hear of it (playhead).
  present(frame) {
    const lane = this.session && this.session.lanes[0];
    const t = frame ? frame.t : lane && lane.snapshot ? this.current * lane.snapshot.dt : null;
    const time = t === null ? '' : ` · ${t.toFixed(2)} s`;
    $('replay-frame').textContent = `${this.current} / ${this.last}${time}`;
    app.setPlayhead(this.current, frame);
  }
}
