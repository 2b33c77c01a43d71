// A replay's frames held in the page (web/js/local_frames.js): pages fetched
// in order, a stride that keeps a lane within its share of the budget, the
// last frame always held, the nearest held frame and the scene at any frame.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { LocalFrames, LocalReplay, FIRST_PAGE } from '../../../web/js/local_frames.js';

// A server of `frames` frames of about `size` bytes, the disc moved at seq 300
// and the method switched at 500: answers as GET /api/runs/{id}/drawn does.
function server(frames, size = 1500) {
  const asked = [];
  const fetchPage = async ({ from, to, stride }) => {
    asked.push({ from, to, stride });
    const lines = [JSON.stringify({ type: 'drawn', from, to, stride, frames })];
    let scene = null;
    for (let seq = from; seq <= Math.min(to, frames - 1); seq += stride) {
      const now = { method: seq >= 500 ? 'dls' : 'pinv', obstacles: [{ id: 'disc', center: [seq >= 300 ? 0.6 : 0.3, 1, 0] }] };
      if (!scene || JSON.stringify(now) !== JSON.stringify(scene)) { scene = now; lines.push(JSON.stringify({ type: 'scene', seq, ...now })); }
      const frame = `{"type":"frame","run":1,"seq":${seq},"status":"paused","pad":"`;
      lines.push(`${frame}${'x'.repeat(Math.max(0, size - frame.length - 2))}"}`);
    }
    return lines.join('\n') + '\n';
  };
  return { asked, fetchPage };
}

async function loadAll(local) { while (await local.loadPage()); }

test('a lane that fits holds every frame, in pages of at most 2,000', async () => {
  const s = server(5000);
  const local = new LocalFrames(5000, 64 * 1024 * 1024, s.fetchPage);
  await loadAll(local);
  assert.equal(local.held, 5000);
  assert.equal(local.stride, 1);
  assert.equal(local.progress, 1);
  assert.deepEqual(s.asked[0], { from: 0, to: FIRST_PAGE - 1, stride: 1 });
  assert.ok(s.asked.every((a) => a.to - a.from < 2000));
  for (const k of [0, 1, 299, 300, 4999]) assert.equal(local.nearest(k), k);
  assert.equal(local.frame(1234).seq, 1234);
});

test('a lane over its share keeps every stride-th frame and the last, and stays within the share', async () => {
  const frames = 10001, share = 3 * 1024 * 1024;  // 10,001 frames of 1.5 KB: about 15 MB
  const s = server(frames);
  const local = new LocalFrames(frames, share, s.fetchPage);
  await loadAll(local);
  assert.ok(local.stride > 1, `stride ${local.stride}`);
  assert.ok(local.bytes <= share, `${local.bytes} bytes held, share ${share}`);
  assert.ok(local.nearest(frames - 1) === frames - 1, 'the last frame is held');
  assert.equal(local.held, local.wanted);
  // a frame between held ones: the held one before it, at most a stride back
  for (const k of [FIRST_PAGE + 1, 4321, frames - 2]) {
    const held = local.nearest(k);
    assert.ok(held !== null && held <= k && k - held < local.stride, `${k} → ${held}`);
  }
});

test('the scene at a frame is the one recorded at or before it; pages repeat no scene', async () => {
  const s = server(800);
  const local = new LocalFrames(800, 64 * 1024 * 1024, s.fetchPage);
  await loadAll(local);
  assert.deepEqual(local.scenes.map((x) => [x.seq, x.method, x.obstacles[0].center[0]]), [[0, 'pinv', 0.3], [300, 'pinv', 0.6], [500, 'dls', 0.6]]);
  assert.equal(local.sceneAt(299).seq, 0);
  assert.equal(local.sceneAt(300).seq, 300);
  assert.equal(local.sceneAt(799).method, 'dls');
});

test('the lanes share the budget, load in turns, and stop when cancelled', async () => {
  const a = server(3000), b = server(3000);
  const progress = [];
  const replay = new LocalReplay([{ key: 'a', runId: 1, frames: 3000 }, { key: 'b', runId: 2, frames: 3000 }, { key: 'c', runId: 3, frames: 0 }],
    (id, range) => (id === 1 ? a : b).fetchPage(range), (r) => progress.push(r.progress), 4 * 1024 * 1024);
  assert.equal(replay.get('c'), null, 'a lane without frames loads nothing');
  await replay.load();
  assert.ok(replay.done);
  assert.ok(replay.bytes <= 4 * 1024 * 1024, `${replay.bytes} bytes`);
  assert.equal(replay.get('a').stride, replay.get('b').stride);
  assert.deepEqual(a.asked.map((x) => x.from).slice(0, 2), b.asked.map((x) => x.from).slice(0, 2));
  assert.ok(progress.every((p, i) => i === 0 || p >= progress[i - 1]), 'progress only grows');

  const c = server(3000);
  const cancelled = new LocalReplay([{ key: 'a', runId: 1, frames: 3000 }], (id, range) => c.fetchPage(range), () => cancelled.cancel());
  await cancelled.load();
  assert.equal(c.asked.length, 1, 'nothing more is asked once cancelled');
});

test('a failed page stops the loading and says why', async () => {
  const replay = new LocalReplay([{ key: 'a', runId: 1, frames: 100 }], async () => { const e = new Error('409 wrong_state'); e.status = 409; throw e; }, () => {});
  await replay.load();
  assert.equal(replay.error.message, '409 wrong_state');
  assert.equal(replay.get('a').held, 0);
});

test('a busy server is asked again after a back-off; a refusal is not', async () => {
  const s = server(300);
  let busy = 2;
  const waits = [];
  const replay = new LocalReplay([{ key: 'a', runId: 1, frames: 300 }], async (id, range) => {
    if (busy-- > 0) { const e = new Error('busy'); e.status = 503; throw e; }
    return s.fetchPage(range);
  }, () => {});
  await replay.load(async (ms) => { waits.push(ms); });
  assert.equal(replay.error, null);
  assert.ok(replay.done);
  assert.deepEqual(waits, [500, 1000]);

  const refused = new LocalReplay([{ key: 'a', runId: 1, frames: 300 }], async () => { const e = new Error('gone'); e.status = 404; throw e; }, () => {});
  const none = [];
  await refused.load(async (ms) => { none.push(ms); });
  assert.equal(refused.error.message, 'gone');
  assert.deepEqual(none, []);

  const always = new LocalReplay([{ key: 'a', runId: 1, frames: 300 }], async () => { const e = new Error('busy'); e.status = 503; throw e; }, () => {});
  const backoff = [];
  await always.load(async (ms) => { backoff.push(ms); });
  assert.equal(always.error.message, 'busy');
  assert.deepEqual(backoff, [500, 1000, 2000, 4000]);
});
