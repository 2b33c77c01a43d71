// The dashboard's time series: stacked uPlot charts with synced cursors
// (task error, minimum distance, manipulability and condition number, step
// time, and one chart per ticked diagnostic), one series per lane.
// Live: frames are pushed as they arrive and render() redraws at most 30
// times a second. Replay: a whole stored run per lane, a cursor line that
// follows the page's scrubber, and a click on a chart seeks.
import uPlot from 'uplot';
import { LaneSeries, chartedMetrics } from './plots_store.js';
import { chartSpecs, chartOptions, extraMetrics, CHART_HEIGHT } from './plots_charts.js';
import { app } from './state.js';

const MIN_REDRAW_MS = 1000 / 30;

// Index of the last value ≤ t in the sorted xs (−1 when t is before them all).
function lastAtOrBefore(xs, t) {
  let lo = 0, hi = xs.length - 1, found = -1;
  while (lo <= hi) {
    const mid = (lo + hi) >> 1;
    if (xs[mid] <= t) { found = mid; lo = mid + 1; } else hi = mid - 1;
  }
  return found;
}

let instances = 0;  // each Plots syncs its own charts only

export class Plots {
  constructor(container) {
    this.container = container;
    this.syncKey = `rrlab-plots-${++instances}`;
    this.onSeek = null;
    this.lanes = [];
    this.names = [];         // diagnostic names offered for ticking
    this.series = [];        // LaneSeries per lane
    this.ticked = new Set(); // diagnostic names with a chart
    this.charts = new Map(); // spec id → { spec, u, box, cursorLine }
    this.mode = 'live';
    this.windowSeconds = 10;
    this.cursorT = null;
    this.dirty = false;
    this.lastRender = -Infinity;

    container.classList.add('plots');
    this.tickList = document.createElement('div');
    this.tickList.className = 'plots-diagnostics';
    this.chartList = document.createElement('div');
    this.chartList.className = 'plots-charts';
    this.note = document.createElement('p');
    this.note.className = 'plots-note';
    container.append(this.tickList, this.chartList, this.note);

    this.width = this.measure();
    this.resizer = new ResizeObserver(() => this.resize());
    this.resizer.observe(container);
  }

  // lanes: [{label, colour, diagnosticNames?}] (a lane's own diagnostic
  // order; default: diagnosticNames). diagnosticNames: the names offered for
  // ticking, for compare the union of the lanes'. Clears all data.
  configure({ lanes, diagnosticNames = [], mode = 'live', windowSeconds = 10 }) {
    this.names = [...diagnosticNames];
    this.lanes = lanes.map((l) => ({
      label: l.label, colour: l.colour,
      diagnosticNames: [...(l.diagnosticNames || diagnosticNames)],
    }));
    const metricKeys = chartedMetrics(app.frameFields);
    this.extras = extraMetrics(app.frameFields, metricKeys);  // offered for ticking, after the diagnostics
    this.series = this.lanes.map((l) => new LaneSeries(l.diagnosticNames, metricKeys));
    this.mode = mode === 'replay' ? 'replay' : 'live';
    this.windowSeconds = windowSeconds > 0 ? windowSeconds : 10;
    this.cursorT = null;
    this.joined = null;
    for (const key of [...this.ticked])
      if (!this.names.includes(key) && !this.extras.some((f) => `metric:${f.name}` === key)) this.ticked.delete(key);
    this.container.classList.toggle('plots-replay', this.mode === 'replay');
    this.buildTickList();
    this.dirty = true;
    this.layout();
  }

  // Live: one WebSocket frame for a lane. Drawn at the next render().
  push(lane, frame) {
    const s = this.series[lane];
    if (!s || !frame) return;
    if (s.appendLive(frame, this.windowSeconds)) this.dirty = true;
  }

  // Replay: a lane's whole stored run, the answer of api.frames (a run's frames)
  // ({run, diagnostic_names, frames: [...]}) or just its frames array; pages
  // of one run may be concatenated into one array first.
  setRun(lane, frames) {
    const s = this.series[lane];
    if (!s) return;
    const list = Array.isArray(frames) ? frames : (frames && Array.isArray(frames.frames) ? frames.frames : []);
    s.setStored(list);
    this.dirty = true;
  }

  // Replay: a vertical line at time t on every chart (null hides it).
  setCursor(t) {
    this.cursorT = Number.isFinite(t) ? t : null;
    for (const chart of this.charts.values()) {
      this.placeCursorLine(chart);
      this.showLegendValues(chart);
    }
  }

  // Redraws charts with new data, at most 30 times a second.
  render(now = performance.now()) {
    if (!this.dirty || now - this.lastRender < MIN_REDRAW_MS) return;
    this.lastRender = now;
    this.dirty = false;
    this.joinLanes();
    // the charts themselves may change: orientation error seen, step times present
    const created = this.layout();
    for (const chart of this.charts.values()) {
      if (!created.has(chart)) chart.u.setData(this.chartData(chart.spec));
      this.showLegendValues(chart);
    }
  }

  destroy() {
    this.resizer.disconnect();
    for (const chart of this.charts.values()) chart.u.destroy();
    this.charts.clear();
    this.container.replaceChildren();
    this.container.classList.remove('plots', 'plots-replay');
  }

  // Points per chart (x values held), for tests.
  pointCounts() {
    const counts = {};
    for (const [id, chart] of this.charts) counts[id] = chart.u.data[0].length;
    return counts;
  }

  // -- charts ---------------------------------------------------------------

  // Creates, rebuilds, removes and orders the charts to match the specs;
  // returns the charts it created (already holding the current data).
  layout() {
    const specs = chartSpecs({
      lanes: this.lanes,
      orientation: this.series.some((s) => s.orientationSeen),
      stepTimes: this.mode === 'live' || this.series.some((s) => (s.column('step_us') || []).some((v) => v !== null)),
      ticked: this.names.filter((n) => this.ticked.has(n)),
      tickedMetrics: this.extras.filter((f) => this.ticked.has(`metric:${f.name}`)),
    });
    const wanted = new Set(specs.map((s) => s.id));
    for (const [id, chart] of this.charts) {
      if (!wanted.has(id)) { chart.u.destroy(); chart.box.remove(); this.charts.delete(id); }
    }
    const created = new Set();
    for (const spec of specs) {
      const old = this.charts.get(spec.id);
      if (old && old.spec.signature === spec.signature) continue;
      if (old) { old.u.destroy(); old.box.remove(); }
      const chart = this.createChart(spec);
      this.charts.set(spec.id, chart);
      created.add(chart);
    }
    specs.forEach((spec) => this.chartList.appendChild(this.charts.get(spec.id).box));  // moves into order
    this.note.textContent = this.mode === 'replay' && !specs.some((s) => s.id === 'step')
      ? 'Step compute time is not stored with a run: it is plotted live only.' : '';
    return created;
  }

  createChart(spec) {
    const box = document.createElement('div');
    box.className = 'plots-chart';
    box.dataset.chart = spec.id;
    const title = document.createElement('div');
    title.className = 'plots-title';
    title.textContent = spec.title;
    box.appendChild(title);
    const chart = { spec, box, u: null, cursorLine: null };
    chart.u = new uPlot(chartOptions(spec, {
      width: this.width, syncKey: this.syncKey,
      xRange: (min, max) => this.xRange(min, max),
      onDraw: () => { this.placeCursorLine(chart); this.placeMarkers(chart); },
      onCursor: (u) => { if (u.cursor.left < 0) queueMicrotask(() => this.showLegendValues(chart)); },
    }), this.chartData(spec), box);
    chart.cursorLine = document.createElement('div');
    chart.cursorLine.className = 'plots-cursor';
    chart.u.over.appendChild(chart.cursorLine);
    chart.u.over.addEventListener('click', (e) => this.clicked(chart.u, e));
    this.placeCursorLine(chart);
    return chart;
  }

  // Chart `id` drawn afresh at width × height CSS pixels (an export): a
  // canvas at the device's pixel ratio, with its title; null when no such chart.
  async chartImage(id, width, height) {
    const chart = this.charts.get(id);
    if (!chart) return null;
    const host = document.createElement('div');
    host.className = 'plots-export-host';
    document.body.appendChild(host);
    try {
      const options = chartOptions(chart.spec, { width, syncKey: null, xRange: (min, max) => this.xRange(min, max), onDraw: () => {}, onCursor: () => {} });
      options.height = height;
      options.cursor = { show: false };
      options.legend = { show: false };
      const u = new uPlot(options, this.chartData(chart.spec), host);
      await new Promise((resolve) => requestAnimationFrame(resolve));  // uPlot draws on its next commit
      const source = u.ctx.canvas;
      const out = document.createElement('canvas');
      out.width = source.width;
      out.height = source.height;
      out.getContext('2d').drawImage(source, 0, 0);
      u.destroy();
      return { canvas: out, title: chart.spec.title, series: chart.spec.series.map((x) => ({ label: x.label, colour: x.colour, dash: x.dash })) };
    } finally {
      host.remove();
    }
  }

  chartIds() { return [...this.charts.values()].map((c) => ({ id: c.spec.id, title: c.spec.title })); }

  // Live: the last windowSeconds (from 0 until the window fills). Replay: the run.
  xRange(min, max) {
    if (this.mode === 'live') {
      // from the lanes' own times: uPlot widens a single point to ±100 around it
      const kept = this.series.filter((s) => s.t.length);
      if (kept.length) {
        min = Math.min(...kept.map((s) => s.t[0]));
        max = Math.max(...kept.map((s) => s.t[s.t.length - 1]));
      }
    }
    if (min === null || max === null) return [0, this.mode === 'live' ? this.windowSeconds : 1];
    if (this.mode === 'live') {
      const hi = Math.max(max, min + this.windowSeconds);
      return [hi - this.windowSeconds, hi];
    }
    return max > min ? [min, max] : [min, min + 1];
  }

  // All lanes on one time axis: uPlot.join aligns them (a lane without a
  // point at some t gets undefined there, which uPlot spans; null stays a gap).
  joinLanes() {
    const tables = this.series.map((s) => [s.t, ...s.columns]);
    this.offsets = [];
    let offset = 1;
    for (const s of this.series) { this.offsets.push(offset); offset += s.columns.length; }
    if (tables.length === 0) this.joined = [[]];
    else if (tables.length === 1) this.joined = this.mode === 'live' ? tables[0].map((c) => c.slice()) : tables[0];
    else this.joined = uPlot.join(tables);
  }

  chartData(spec) {
    if (!this.joined) this.joinLanes();
    const x = this.joined[0];
    return [x, ...spec.series.map((s) => {
      const i = this.series[s.lane].index.get(s.key);
      return i === undefined ? new Array(x.length).fill(null) : this.joined[this.offsets[s.lane] + i];
    })];
  }

  // Recorded inputs as marks on every chart ({t, kind, text}), each with its words as a tooltip.
  setMarkers(markers) {
    this.markers = markers;
    for (const chart of this.charts.values()) this.placeMarkers(chart);
  }

  // The lanes' first failures ({t, text}): a red line on every chart, its reason beside it.
  setFailures(failures) {
    this.failures = failures.filter((f) => Number.isFinite(f.t));
    for (const chart of this.charts.values()) this.placeMarkers(chart);
  }

  placeMarkers(chart) {
    if (!chart.markerBox) {
      chart.markerBox = document.createElement('div');
      chart.markerBox.className = 'plots-markers';
      chart.u.over.appendChild(chart.markerBox);
    }
    const list = this.mode === 'replay' ? [...(this.markers || []), ...(this.failures || [])] : [];
    const width = chart.u.over.clientWidth;
    chart.markerBox.replaceChildren(...list.map((m) => {
      const x = chart.u.valToPos(m.t, 'x');
      if (!Number.isFinite(x) || x < 0 || x > width) return null;
      const mark = document.createElement('div');
      mark.className = `plots-marker event-${m.kind}`;
      mark.title = m.kind === 'failure' ? `first failure: ${m.text}` : m.text;
      mark.style.transform = `translateX(${Math.round(x)}px)`;
      if (m.kind === 'failure') {
        // the reason beside the line: on its right, or on its left past the middle
        const label = document.createElement('span');
        label.className = `plots-failure-label${x > width / 2 ? ' left' : ''}`;
        label.textContent = `✗ ${m.text}`;
        mark.appendChild(label);
      }
      return mark;
    }).filter(Boolean));
  }

  placeCursorLine(chart) {
    const line = chart.cursorLine;
    if (!line) return;
    const t = this.cursorT;
    const x = t === null || this.mode !== 'replay' ? null : chart.u.valToPos(t, 'x');
    if (x === null || !Number.isFinite(x) || x < 0 || x > chart.u.over.clientWidth) {
      line.style.display = 'none';
      return;
    }
    line.style.display = 'block';
    line.style.transform = `translateX(${Math.round(x)}px)`;
  }

  // With no pointer over the charts the legends read the newest values
  // (live) or those at the replay cursor, so they always say something.
  showLegendValues(chart) {
    const u = chart.u;
    if (!u || u.cursor.left >= 0) return;  // hovered here or on a synced chart
    const xs = u.data[0];
    if (!xs.length) return;
    let idx = xs.length - 1;
    if (this.mode === 'replay') {
      if (this.cursorT === null) return;
      idx = lastAtOrBefore(xs, this.cursorT);
      if (idx < 0) return;
    }
    // joined lanes may lack a point at this time: take the lane's latest before it
    const idxs = u.data.map((column, s) => {
      let i = idx;
      while (s > 0 && i > 0 && idx - i < 16 && column[i] === undefined) --i;
      return i;
    });
    u.setLegend({ idxs }, false);
  }

  clicked(u, event) {
    if (this.mode !== 'replay' || !this.onSeek) return;
    const x = event.clientX - u.over.getBoundingClientRect().left;
    const t = u.posToVal(x, 'x');
    const xs = u.data[0];
    if (!xs.length || !Number.isFinite(t)) return;
    this.onSeek(Math.min(Math.max(t, xs[0]), xs[xs.length - 1]));
  }

  // -- diagnostic check boxes ----------------------------------------------

  // The diagnostics to chart: a folded list ("Diagnostics: 2 of 25 charted"),
  // open at first when there are few, so a long list never pushes the charts away.
  buildTickList() {
    this.tickList.replaceChildren();
    this.tickGroup('Diagnostics', this.names.map((name) => ({ key: name, label: name })));
    this.tickGroup('More metrics', this.extras.map((f) => ({ key: `metric:${f.name}`, label: f.name, title: f.description })));
  }

  // One group of tick boxes (charts to add), with its count.
  tickGroup(heading, entries) {
    if (!entries.length) return;
    const details = document.createElement('details');
    details.open = entries.length <= 6;
    const summary = document.createElement('summary');
    summary.className = 'plots-diagnostics-heading';
    const count = () => {
      summary.textContent = `${heading}: ${entries.filter((e) => this.ticked.has(e.key)).length} of ${entries.length} charted`;
    };
    count();
    const choices = document.createElement('div');
    choices.className = 'plots-diagnostics-choices';
    for (const entry of entries) {
      const label = document.createElement('label');
      if (entry.title) label.title = entry.title;
      const box = document.createElement('input');
      box.type = 'checkbox';
      box.value = entry.key;
      box.checked = this.ticked.has(entry.key);
      box.addEventListener('change', () => {
        if (box.checked) this.ticked.add(entry.key); else this.ticked.delete(entry.key);
        count();
        this.layout();  // the new chart comes filled with the data already kept
      });
      label.append(box, ` ${entry.label}`);
      choices.appendChild(label);
    }
    details.append(summary, choices);
    this.tickList.appendChild(details);
  }

  // -- size -------------------------------------------------------------------

  measure() {
    return Math.max(200, Math.floor(this.container.clientWidth || 600));
  }

  resize() {
    if (!this.container.clientWidth) return;  // hidden: keep the last size
    const width = this.measure();
    if (width === this.width) return;
    this.width = width;
    for (const chart of this.charts.values()) chart.u.setSize({ width, height: CHART_HEIGHT });
  }
}

// The page's plots follow the session on screen (state.js signals): one
// series per lane, each lane's diagnostics in its method's order; live
// frames as they come, a replay's whole stored run, its markers and cursor.
export function followSession(plots) {
  let shownNames = [];  // per lane, the diagnostic names the charts were set up with
  const current = (lane) => app.session && app.session.lanes.includes(lane);
  const configure = (s, namesPerLane) => {
    shownNames = namesPerLane.map((names) => names.join('\n'));
    plots.configure({
      lanes: s.lanes.map((l, i) => ({ label: l.label, colour: l.colour, diagnosticNames: namesPerLane[i] })),
      diagnosticNames: [...new Set(namesPerLane.flat())],
      mode: s.kind,
      windowSeconds: 10,
    });
  };
  app.signals.sessionChanged.add((s) => { if (s) configure(s, s.runs.map((r) => r.diagnostic_names || [])); });
  app.signals.frame.add((lane) => { if (current(lane) && app.session.kind === 'live') plots.push(lane.index, lane.frame); });
  // a method switch changes the diagnostics: the plots start again with the new names
  app.signals.snapshot.add((lane) => {
    const s = app.session;
    if (!current(lane) || s.kind !== 'live' || shownNames[lane.index] === lane.snapshot.diagnostic_names.join('\n')) return;
    configure(s, s.lanes.map((l, i) => (l.snapshot ? l.snapshot.diagnostic_names : s.runs[i].diagnostic_names || [])));
  });
  app.signals.storedFrames.add((lane, data) => { if (current(lane)) plots.setRun(lane.index, data); });
  app.signals.markers.add((markers) => plots.setMarkers(markers));
  app.signals.failures.add((failures) => plots.setFailures(failures));
  // a live session that ended became its replay: the whole stored run, as any replay
  app.signals.sessionOpened.add((s) => { if (s.kind === 'replay' && plots.mode !== 'replay') configure(s, s.runs.map((r) => r.diagnostic_names || [])); });
  app.signals.playhead.add((seq) => {
    const lane = app.session && app.session.lanes[0];
    if (lane && lane.snapshot) plots.setCursor(seq * lane.snapshot.dt);
  });
}
