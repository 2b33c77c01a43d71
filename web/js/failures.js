// A replay's failures where they happened: for each lane whose run fails,
// its first failure (first_failure.js) from the lane's stored frames, told
// to the panels as the `failures` signal ([{lane, seq, t, kind: 'failure',
// text}]): the replay bar marks it on the scrubber with its reason beside
// it, the plots on every chart. A collision's obstacle is named once the
// lane shows the failure's frame (the view frame says what the arm touches).
import { api } from './api.js';
import { app } from './state.js';
import { firstFailure, failureText, touchedObstacles } from './first_failure.js';

// What says whether and where each run failed: {summary, sweep}. A
// re-simulated copy of a sweep's run (which the sweep's cell opens) is judged
// by its source's sweep row, as the sweep judged it. Never rejects.
export async function failureSources(runs) {
  const rows = await Promise.all(runs.map((r) => (!r.sweep && r.source_run
    ? api.run(r.source_run).then((source) => source.sweep || null, () => null)
    : Promise.resolve(r.sweep || null))));
  return runs.map((r, i) => ({ summary: r.summary || null, sweep: rows[i] }));
}

export class FailurePanel {
  constructor() {
    this.session = null;
    this.sources = [];
    this.found = new Map();  // lane → {failure, obstacles}
    const current = (lane) => this.session && this.session === app.session && this.session.lanes.includes(lane);
    app.signals.sessionChanged.add(() => { this.session = null; this.found = new Map(); this.publish(); });
    app.signals.sessionOpened.add((session, { sources }) => {
      this.session = session;
      this.sources = sources || [];
      this.found = new Map();
      this.publish();
    });
    app.signals.storedFrames.add((lane, data) => { if (current(lane)) this.locate(lane, data.frames); });
    app.signals.frame.add((lane) => { if (current(lane)) this.nameObstacles(lane); });
  }

  // The lane's first failure in its stored frames.
  locate(lane, frames) {
    const source = this.sources[lane.index];
    const dt = lane.snapshot ? lane.snapshot.dt : 0;
    const failure = source ? firstFailure(source, frames, dt) : null;
    if (!failure) return;
    this.found.set(lane, { failure, obstacles: [] });
    this.nameObstacles(lane, false);
    this.publish();
  }

  // A collision's obstacles, from the view frame at the failure.
  nameObstacles(lane, publish = true) {
    const entry = this.found.get(lane);
    if (!entry || entry.failure.mode !== 'collision' || entry.obstacles.length || !lane.frame || lane.frame.seq !== entry.failure.seq) return;
    entry.obstacles = touchedObstacles(lane.frame, lane.snapshot ? lane.snapshot.obstacles : []);
    if (entry.obstacles.length && publish) this.publish();
  }

  publish() {
    const s = this.session;
    const list = [...this.found].sort(([a], [b]) => a.index - b.index).map(([lane, { failure, obstacles }]) => {
      const text = failureText(failure, obstacles);
      return { lane: lane.index, seq: failure.seq, t: failure.t, kind: 'failure', mode: failure.mode, text: s && s.compare ? `${lane.label}: ${text}` : text };
    });
    app.signals.failures.dispatch(list);
  }
}
