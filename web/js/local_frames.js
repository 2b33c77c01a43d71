// A replay's frames held in the page, so that a seek draws at once instead of
// asking the server's replay player for each frame: GET /api/runs/{id}/drawn
// answers stored frames exactly as the player would send them (links, nearest
// obstacles, ellipsoid), with the scene (obstacles, method) wherever it
// changes. Pages are fetched one at a time in the background; each frame is
// kept as its text (about 1.5 KB for a planar arm) and parsed when shown.
//
// Memory: the lanes of a replay share MEMORY_BUDGET bytes of frame text. The
// first FIRST_PAGE frames of a lane measure its frames' size; a lane whose
// frames would not fit its share keeps every stride-th one (and the last),
// and a frame in between is drawn from the held one before it while the
// server is asked for the exact one (replay.js).
export const MEMORY_BUDGET = 96 * 1024 * 1024;
export const FIRST_PAGE = 200;
const PAGE = 2000;  // the server's most per request (kDrawnFramesPerRequest)
const RETRIES = 4, BACK_OFF_MS = 500;  // a busy server: asked again after 0.5, 1, 2 and 4 s

export class LocalFrames {
  // `frames`: how many the run stored; `share`: the bytes this lane may hold;
  // `fetchPage(params)`: resolves to the text of one answer (api.drawnFrames).
  constructor(frames, share, fetchPage) {
    this.frames = frames;
    this.share = share;
    this.fetchPage = fetchPage;
    this.texts = new Array(frames);  // by seq; a hole: not held
    this.scenes = [];                // [{seq, method, obstacles}] in seq order
    this.stride = 1;
    this.held = 0;
    this.bytes = 0;
    this.wanted = frames;            // how many frames the lane will hold
    this.done = frames === 0;
    this.cancelled = false;
    this.next = 0;                   // the next seq to ask for
    this.tail = false;               // the last frame, asked for on its own
  }

  cancel() { this.cancelled = true; }

  // Fetches the next page; false once nothing is left (or cancelled).
  async loadPage() {
    if (this.done || this.cancelled) return false;
    const first = this.next === 0;
    const stride = first || this.tail ? 1 : this.stride;
    const count = first ? FIRST_PAGE : this.tail ? 1 : PAGE;
    const to = Math.min(this.frames - 1, this.next + (count - 1) * stride);
    const text = await this.fetchPage({ from: this.next, to, stride });
    if (this.cancelled) return false;
    const last = this.take(text);
    if (first && this.held > 0) this.chooseStride();
    this.next = last === null ? to + stride : last + stride;
    if (this.next > this.frames - 1) {
      // the stride passed the last frame by: it is asked for on its own
      if (!this.texts[this.frames - 1] && !this.tail) { this.next = this.frames - 1; this.tail = true; return true; }
      this.done = true;
    }
    return !this.done;
  }

  // Keeps an answer's frames and scenes; the last seq it held, or null.
  take(text) {
    let last = null;
    for (const line of text.split('\n')) {
      if (!line) continue;
      if (line.startsWith('{"type":"frame"')) {
        const at = line.indexOf(',"seq":');
        const seq = at < 0 ? NaN : parseInt(line.slice(at + 7, at + 27), 10);
        if (!Number.isInteger(seq) || seq < 0 || seq >= this.frames) continue;
        if (!this.texts[seq]) { this.held += 1; this.bytes += line.length; }
        this.texts[seq] = line;
        last = seq;
      } else {
        const message = JSON.parse(line);
        if (message.type !== 'scene') continue;
        // a page starts with the scene at its first frame: the same as the one before it, most often
        const previous = this.scenes[this.scenes.length - 1];
        if (previous && previous.seq >= message.seq) continue;
        if (previous && previous.method === message.method && JSON.stringify(previous.obstacles) === JSON.stringify(message.obstacles)) continue;
        this.scenes.push({ seq: message.seq, method: message.method, obstacles: message.obstacles });
      }
    }
    return last;
  }

  // From the first page's size per frame: the stride that keeps the lane within its share.
  chooseStride() {
    const perFrame = this.bytes / this.held;
    const rest = this.frames - this.held;
    const fits = Math.max(1, Math.floor((this.share - this.bytes) / perFrame));
    this.stride = rest <= fits ? 1 : Math.ceil(rest / fits);
    this.wanted = this.held + Math.ceil(rest / this.stride) + (this.stride > 1 ? 1 : 0);
  }

  // The held frame at or before `seq` (null when none is near): {seq, text}.
  nearest(seq) {
    const lowest = Math.max(0, seq - this.stride);
    for (let s = seq; s >= lowest; --s) if (this.texts[s]) return s;
    return null;
  }

  // The frame at `seq` (held), parsed; its scene.
  frame(seq) { return JSON.parse(this.texts[seq]); }

  sceneAt(seq) {
    let lo = 0, hi = this.scenes.length - 1, found = null;
    while (lo <= hi) {
      const mid = (lo + hi) >> 1;
      if (this.scenes[mid].seq <= seq) { found = this.scenes[mid]; lo = mid + 1; } else hi = mid - 1;
    }
    return found;
  }

  get progress() { return this.wanted > 0 ? Math.min(1, this.held / this.wanted) : 1; }
}

// Every lane's frames of a replay, loaded a page at a time round the lanes
// (so that all become local together); `onProgress()` after each page.
export class LocalReplay {
  constructor(lanes, fetchPage, onProgress, budget = MEMORY_BUDGET) {
    // lanes: [{key, runId, frames}]
    const loading = lanes.filter((l) => l.frames > 0);
    const share = Math.floor(budget / Math.max(1, loading.length));
    this.byKey = new Map(loading.map((l) => [l.key, new LocalFrames(l.frames, share, (params) => fetchPage(l.runId, params))]));
    this.onProgress = onProgress;
    this.budget = budget;
    this.error = null;
  }

  get(key) { return this.byKey.get(key) || null; }

  // A page the server is too busy for (503, or no answer) is asked again
  // after a back-off, RETRIES times at most; any other refusal stops the
  // loading (the replay asks the server for every frame, and says so).
  async load(wait = (ms) => new Promise((resolve) => setTimeout(resolve, ms))) {
    const all = [...this.byKey.values()];
    let failures = 0;
    try {
      let more = true;
      while (more) {
        more = false;
        for (const local of all) {
          try {
            if (await local.loadPage()) more = true;
            failures = 0;
          } catch (e) {
            if (!(e && (e.status === 503 || e.status === 0)) || ++failures > RETRIES) throw e;
            more = true;
            await wait(BACK_OFF_MS * 2 ** (failures - 1));
          }
          if (local.cancelled) return;
          this.onProgress(this);
        }
      }
    } catch (e) {
      this.error = e;
      this.onProgress(this);
    }
  }

  cancel() { for (const local of this.byKey.values()) local.cancel(); }

  get progress() {
    const all = [...this.byKey.values()];
    return all.length ? all.reduce((s, l) => s + l.progress, 0) / all.length : 1;
  }
  get bytes() { return [...this.byKey.values()].reduce((s, l) => s + l.bytes, 0); }
  get stride() { return Math.max(1, ...[...this.byKey.values()].map((l) => l.stride)); }
  get done() { return [...this.byKey.values()].every((l) => l.done); }
}
