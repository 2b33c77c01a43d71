// The replay scrubber: play/pause, speed, frame step and seek for every lane
// of a replayed session at once. The frame number follows in the address.
import { api } from './api.js';
import { app } from './state.js';
import { isTyping } from './dom.js';

const $ = (id) => document.getElementById(id);

export class ReplayBar {
  constructor() {
    this.session = null;
    this.playing = true;
    this.lastSeek = 0;
    this.lastUrl = 0;
    $('replay-play').onclick = () => this.setPlaying(!this.playing);
    $('replay-back').onclick = () => this.step(-1);
    $('replay-forward').onclick = () => this.step(1);
    $('replay-speed').onchange = () => this.control({ action: this.playing ? 'play' : 'pause', speed: Number($('replay-speed').value) });
    const scrubber = $('scrubber');
    scrubber.oninput = () => {
      this.scrubbing = true;
      const now = performance.now();
      if (now - this.lastSeek > 50) { this.lastSeek = now; this.seek(Number(scrubber.value)); }
    };
    scrubber.onchange = () => { this.scrubbing = false; this.seek(Number(scrubber.value)); };
    window.addEventListener('keydown', (e) => {
      if (!this.session || isTyping(e.target)) return;
      if (e.key === ',') this.step(-1);
      else if (e.key === '.') this.step(1);
      else if (e.key === ' ') { e.preventDefault(); this.setPlaying(!this.playing); }
    });
  }

  attach(session, startFrame) {
    this.session = session;
    this.pendingSeq = null;
    $('replay-bar').hidden = false;
    const last = Math.max(0, session.frameCount - 1);
    $('scrubber').max = String(last);
    this.playing = startFrame === null || startFrame === undefined;
    this.showPlaying();
    if (!this.playing) this.seek(Math.min(startFrame, last));
  }

  detach() {
    this.session = null;
    $('replay-bar').hidden = true;
  }

  get seq() { return Number($('scrubber').value); }

  // Every lane's player gets the same command (socket if open, else REST).
  async control(body) {
    if (!this.session) return;
    await Promise.all(this.session.lanes.map((lane) => {
      if (lane.stream && lane.stream.send({ type: 'control', ...body })) return null;
      return api('POST', `/api/replays/${lane.replayId}/control`, body).catch((e) => { this.pendingSeq = null; app.error(e); });
    }));
  }

  setPlaying(playing) {
    this.playing = playing;
    this.pendingSeq = null;
    this.showPlaying();
    this.control({ action: playing ? 'play' : 'pause', speed: Number($('replay-speed').value) });
    if (!playing) this.session.updateUrl(this.seq);
  }

  showPlaying() {
    $('replay-play').textContent = this.playing ? '❚❚' : '▶';
    $('replay-play').title = this.playing ? 'pause (space)' : 'play (space)';
  }

  // Seeking pauses: the frame shown is the one asked for.
  seek(seq) {
    if (!this.session) return;
    seq = Math.max(0, Math.min(Number($('scrubber').max), Math.round(seq)));
    $('scrubber').value = String(seq);
    if (this.playing) { this.playing = false; this.showPlaying(); }
    this.pendingSeq = seq;  // frames sent before the seek must not move the scrubber back
    this.control({ action: 'pause', seq });  // one command: a separate pause could land after the seek
    this.session.updateUrl(seq);
    for (const lane of this.session.lanes) if (lane.view) lane.view.resetTrace();
  }

  step(delta) { this.seek(this.seq + delta); }

  // Seeks to the frame at run time t = seq·dt (a click on a plot).
  seekTime(t) {
    const lane = this.session && this.session.lanes[0];
    if (!lane || !lane.snapshot) return;
    this.seek(t / lane.snapshot.dt);
  }

  // A frame of lane 0 arrived: move the scrubber and the readout.
  onFrame(frame) {
    if (!this.session) return;
    if (this.pendingSeq !== null && this.pendingSeq !== undefined) {
      if (frame.seq !== this.pendingSeq) return;
      this.pendingSeq = null;
    }
    if (!this.scrubbing) $('scrubber').value = String(frame.seq);
    $('replay-frame').textContent = `${frame.seq} / ${$('scrubber').max} · ${frame.t.toFixed(2)} s`;
    if (frame.seq >= Number($('scrubber').max) && this.playing) { this.playing = false; this.showPlaying(); }
    const now = performance.now();
    if (this.playing && now - this.lastUrl > 1000) { this.lastUrl = now; this.session.updateUrl(frame.seq); }
  }
}
