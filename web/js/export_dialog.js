// The Export dialog: what to export (a view, a chart, a figure, a video of a
// replay, the run or compare group as one HTML file that replays offline),
// its size, and for a video the frame range, stride and rate; the file
// downloads when it is ready, with progress for a video.
import { api } from './api.js';
import { app } from './state.js';
import { escapeHtml } from './dom.js';
import { parseTypedNumber, mark, accept } from './typed_number.js';
import { viewPng, chartPng, figurePng, recordVideo, checkRange, download, LIMITS } from './exports.js';

const $ = (id) => document.getElementById(id);

// The server's HTML export of what is shown: one run, or a compare group
// when the lanes are exactly the runs one compare started (null otherwise).
function htmlLink(session) {
  const runs = session.runs.filter((r) => r.frames > 0);
  if (runs.length !== session.runs.length || runs.length === 0) return null;
  if (!session.compare) return api.exportLink(runs[0].id);
  const group = runs[0].compare_group;
  return group && runs.every((r) => r.compare_group === group) && Math.min(...session.runIds) === group ? api.groupExportLink(group) : null;
}

export class ExportDialog {
  // plots and replayBar: the page's (charts to draw, frames to show for a video)
  constructor({ plots, replayBar }) {
    this.plots = plots;
    this.replayBar = replayBar;
    this.busy = false;
    this.cancel = false;
    $('open-export').onclick = () => this.open();
    $('export-what').onchange = () => this.showFields();
    for (const id of ['export-width', 'export-height']) $(id).addEventListener('input', () => { this.sizeTouched = true; });
    $('export-cancel').onclick = () => { if (this.busy) this.cancel = true; else $('export-dialog').close(); };
    $('export-form').onsubmit = (e) => { e.preventDefault(); this.run().catch((err) => this.failed(err)); };
    // enabled while a run or group with a view is on screen
    app.signals.sessionChanged.add((session) => { $('open-export').disabled = !session; });
  }

  open() {
    const session = app.session;
    if (!session) return;
    const options = [['view', session.compare ? 'the views, side by side (PNG)' : 'the view (PNG)']];
    for (const c of this.plots.chartIds()) options.push([`chart:${c.id}`, `chart: ${c.title} (PNG)`]);
    options.push(['figure', 'a figure for a paper: views, charts, legend, metadata (PNG)']);
    if (session.kind === 'replay' && !session.empty) options.push(['video', 'a video of the replay (WebM)']);
    if (htmlLink(session)) options.push(['html', session.compare ? 'the compare as one HTML file that replays offline' : 'the run as one HTML file that replays offline']);
    $('export-what').innerHTML = options.map(([v, t]) => `<option value="${escapeHtml(v)}">${escapeHtml(t)}</option>`).join('');
    const last = Math.max(0, session.frameCount - 1);
    $('export-from').value = '0';
    $('export-to').value = String(last);
    $('export-from').max = $('export-to').max = String(last);
    $('export-progress').textContent = '';
    this.showFields();
    $('export-dialog').showModal();
  }

  showFields() {
    const what = $('export-what').value;
    $('export-video').hidden = what !== 'video';
    $('export-height-label').hidden = what === 'figure' || what === 'html';
    $('export-width').parentElement.hidden = what === 'html';
    const notes = {
      view: 'Drawn afresh at this size (3D: distance and lane labels are HTML and are left out).',
      figure: 'The height follows from the width and the lanes.',
      video: 'One video frame per stored frame of the range (every N-th), at the chosen rate; drawn from the frames the page holds, it records faster than the video lasts.',
      html: 'One file with the stored frames, views, scrubber and charts: it opens from disk with no network (a run over 20 MB is decimated, with a note in the file).',
    };
    $('export-note').textContent = notes[what] || 'The chart drawn afresh at this size, with its title.';
    if (what === 'view' || what === 'video') {
      const cell = document.querySelector('#views .view-cell');
      if (cell && !this.sizeTouched) {
        const r = document.getElementById('views').getBoundingClientRect();
        $('export-width').value = String(Math.min(4096, Math.round(r.width * 2 / 2) * 2));
        $('export-height').value = String(Math.min(4096, Math.round(r.height * 2 / 2) * 2));
      }
    }
  }

  failed(error) {
    this.busy = false;
    $('export-go').disabled = false;
    $('export-progress').textContent = `Not exported: ${error.message || error}`;
    if (!error.field) app.error(`export: ${error.message || error}`);  // a field's refusal is said beside it
  }

  // A typed number of the dialog (a decimal comma is a decimal point, never
  // dropped): refused at its field, with the message beside it.
  read(id, { min, max, integer = true, what }) {
    const field = $(id);
    const read = parseTypedNumber(field.value, { min, max });
    let message = read.error;
    if (!message && integer && !Number.isInteger(read.value)) message = `${read.value} is not a whole number`;
    if (message) {
      mark(field, `${what}: ${message}`, field.closest('label') || field);
      const error = new Error(`${what}: ${message}`);
      error.field = id;
      throw error;
    }
    return read.value;
  }

  async run() {
    const session = app.session;
    if (!session || this.busy) return;
    const what = $('export-what').value;
    for (const id of ['export-width', 'export-height', 'export-from', 'export-to', 'export-stride', 'export-fps']) accept($(id));
    const size = { min: LIMITS.minSide, max: LIMITS.maxSide };
    const width = what === 'html' ? 0 : this.read('export-width', { ...size, what: 'width' });
    const height = what === 'view' || what === 'video' || what.startsWith('chart:') ? this.read('export-height', { ...size, what: 'height' }) : 0;
    const name = `rrlab-run-${session.runIds.join('-')}`;
    this.busy = true;
    this.cancel = false;
    $('export-go').disabled = true;
    $('export-progress').textContent = 'drawing…';
    if (what === 'html') {
      const a = document.createElement('a');
      a.href = htmlLink(session);
      a.download = session.compare ? `rrlab-compare-${session.runIds[0]}.html` : `${name}.html`;
      document.body.appendChild(a);
      a.click();
      a.remove();
    } else if (what === 'view') download(await viewPng(session, width, height), `${name}-view-${width}x${height}.png`);
    else if (what.startsWith('chart:')) download(await chartPng(this.plots, what.slice(6), width, height), `${name}-${what.slice(6)}-${width}x${height}.png`);
    else if (what === 'figure') download(await figurePng(session, this.plots, { width, meta: this.metadata(session) }), `${name}-figure.png`);
    else if (what === 'video') {
      const last = Math.max(0, session.frameCount - 1);
      const from = this.read('export-from', { min: 0, max: last, what: 'from frame' });
      const to = this.read('export-to', { min: from, max: last, what: 'to frame' });
      const stride = this.read('export-stride', { min: 1, max: Math.max(1, to - from + 1), what: 'every' });
      const fps = this.read('export-fps', { min: 1, max: LIMITS.maxFps, integer: false, what: 'rate' });
      checkRange(from, to, Math.max(0, session.frameCount - 1), fps);
      if (!Number.isInteger(stride) || stride < 1) throw new Error('"every" takes a whole number of frames, 1 or more');
      const started = performance.now();
      const result = await recordVideo(session, (seq) => this.replayBar.showAndWait(seq), {
        from, to, stride, fps, width, height,
        onProgress: (done, total) => { $('export-progress').textContent = videoProgress(done, total, (performance.now() - started) / 1000); },
        cancelled: () => this.cancel,
      });
      download(result.blob, `${name}-frames-${from}-${to}${stride > 1 ? `-every-${stride}` : ''}-${fps}fps.webm`);
      $('export-progress').textContent = `${result.frames} frames recorded`;
    }
    if (what !== 'video') $('export-progress').textContent = 'downloaded';
    this.busy = false;
    $('export-go').disabled = false;
  }

  // What the figure says about itself, for a caption.
  metadata(session) {
    const lanes = session.lanes.map((l) => {
      const params = l.snapshot && l.snapshot.params ? Object.entries(l.snapshot.params).map(([k, v]) => `${k}=${v}`).join(', ') : '';
      return `${l.label}${params ? ` (${params})` : ''}, run #${l.runId}`;
    });
    const frame = session.lanes[0].frame;
    return [
      `scenario ${session.runs[0].scenario}; ${lanes.join('; ')}`,
      frame ? `shown: t = ${frame.t.toFixed(2)} s (frame ${frame.seq ?? frame.step}); drawn by rrlab ${app.version || ''}`.trim() : 'drawn by rrlab',
    ];
  }
}

// "recording frame 40 of 201 · about 12 s left": the time left at the pace so far.
export function videoProgress(done, total, seconds) {
  const text = `recording frame ${done} of ${total}`;
  if (done < 5 || !(seconds > 0)) return `${text}…`;
  const left = Math.max(0, Math.round((seconds / done) * (total - done)));
  return `${text} · about ${left < 60 ? `${left} s` : `${Math.floor(left / 60)} min ${left % 60} s`} left`;
}
