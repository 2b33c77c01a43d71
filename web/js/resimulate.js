// Re-simulating a stored run that kept no frames (a sweep's, by default):
// a replay request {mode: resimulate} (api.replayRun) answers when the new
// run is stored; meanwhile its frame count is polled, so the page can show
// progress. The command 'resimulate' (commands.js) then opens it.
import { api } from './api.js';

// Resolves with the new run's id; onProgress(done, total) while it runs.
export async function resimulate(runId, onProgress = () => {}) {
  const source = await api.run(runId);
  const total = source.summary && source.summary.steps ? source.summary.steps : null;
  let finished = false;
  const poll = async () => {
    while (!finished) {
      const runs = await api.runs({ limit: 20 }).catch(() => []);
      const copy = runs.find((r) => r.source_run === runId && r.mode === 'resimulation' && r.status === 'running');
      if (copy && !finished) onProgress(copy.frames, total);
      await new Promise((r) => setTimeout(r, 300));
    }
  };
  onProgress(0, total);
  const polling = poll();
  try {
    const verification = await api.replayRun(runId, { mode: 'resimulate' });
    return verification.run;
  } finally {
    finished = true;
    await polling;
  }
}
