// The page's drawing loop at the display rate (requestAnimationFrame): the
// replay's playhead advances, the session's views draw (each only when
// something changed), then the plots and the metrics; the frame rate and the
// time spent drawing are measured for the tests and bench/web.
import { app } from './state.js';

export const fps = { frames: 0, since: performance.now(), value: 0, renderMs: 0 };

// replayBar, plots, metrics: the page's (tick(now), render(now), render(now));
// preview: the start page's (render()), drawn while no session is on screen.
export function startRenderLoop({ replayBar, plots, metrics, preview }) {
  const tick = (now) => {
    const t0 = performance.now();
    replayBar.tick(now);
    if (app.session) app.session.render();
    else if (preview) preview.render();
    plots.render();
    metrics.render(now);
    fps.renderMs = 0.9 * fps.renderMs + 0.1 * (performance.now() - t0);
    fps.frames++;
    if (now - fps.since >= 1000) { fps.value = (fps.frames * 1000) / (now - fps.since); fps.frames = 0; fps.since = now; }
    requestAnimationFrame(tick);
  };
  requestAnimationFrame(tick);
}
