// The dashboard's entry: wires the modules together and does nothing else.
// The state and its signals are state.js's, the commands commands.js's; each
// panel subscribes itself to the signals it needs and sends what the user
// does as a command (app.execute). Then the page opens what its address asks
// for (?run=, ?compare=, ?sweep=, ?paper=, ?scenario=&method=), and again
// on Back and Forward.
import { setTokenPrompt } from './api.js';
import { askForToken } from './token_prompt.js';
import { app } from './state.js';
import { commands } from './commands.js';
import { setupLayout } from './layout.js';
import { setupMessageBar } from './message_bar.js';
import { SessionPanel } from './session_panel.js';
import { NewRunPanel } from './new_run.js';
import { setupParams } from './params.js';
import { MetricsPanel } from './metrics.js';
import { RunList } from './runs.js';
import { CompareSetup, setupCompareSummary } from './compare.js';
import { ReplayBar } from './replay.js';
import { FailurePanel } from './failures.js';
import { SceneTools, buildOverlayToggles } from './scene_tools.js';
import { Plots, followSession } from './plots.js';
import { setupJoystick } from './joystick.js';
import { SweepList } from './sweeps.js';
import { SweepPage } from './sweep_view.js';
import { Papers } from './paper_view.js';
import { ExportDialog } from './export_dialog.js';
import { startRenderLoop, fps } from './render_loop.js';
import { StartPreview } from './preview.js';

app.define(commands);
setTokenPrompt(askForToken);
setupLayout();
setupMessageBar();

new SessionPanel();
new NewRunPanel();
new CompareSetup();
setupCompareSummary();
setupParams();
new SceneTools();
buildOverlayToggles();
setupJoystick(document.getElementById('joystick'));
const metrics = new MetricsPanel();
const replayBar = new ReplayBar();
new FailurePanel();
const plots = new Plots(document.getElementById('plots'));
followSession(plots);
plots.onSeek = (t) => replayBar.seekTime(t);
new ExportDialog({ plots, replayBar });
const sweepList = new SweepList();
new RunList({ sweeps: () => sweepList.sweeps });
new SweepPage();
new Papers();
const preview = new StartPreview();
startRenderLoop({ replayBar, plots, metrics, preview });

// For browser tests and for measuring: the state, the session and the frame rate.
window.__rrlab = { app, fps, get session() { return app.session; }, plots, replay: replayBar, preview };

app.execute({ type: 'start' });
// Back and Forward: every view pushed a history entry (state.js writeUrl)
window.addEventListener('popstate', () => app.execute({ type: 'navigate' }));
