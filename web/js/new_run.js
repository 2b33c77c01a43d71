// The new-run panel: the scenario and method pickers (the choice kept in
// app.choice and, with nothing on screen, in the address), the scenario's
// description, the rate, Start live and Batch; and the scenario editor,
// opened on the chosen scenario (or the run on screen's) from the header.
import { api } from './api.js';
import { app } from './state.js';
import { escapeHtml } from './dom.js';
import { ScenarioEditor } from './scenario_editor.js';

const $ = (id) => document.getElementById(id);

export class NewRunPanel {
  constructor() {
    app.signals.scenariosChanged.add(() => this.fillScenarios());
    app.signals.methodsChanged.add(() => this.fillMethods());
    // a session on screen: its controls come first, the pickers fold away
    app.signals.sessionChanged.add((session) => { if (session) $('new-run').open = false; });
    $('scenario').onchange = () => { this.describe(); app.execute({ type: 'choose', scenario: $('scenario').value, method: $('method').value }); };
    $('method').onchange = () => app.execute({ type: 'choose', scenario: $('scenario').value, method: $('method').value });
    $('rate').onchange = () => app.execute({ type: 'choose', rate: Number($('rate').value) });
    app.execute({ type: 'choose', rate: Number($('rate').value) });
    $('scenario-more').onclick = () => this.describeFully();
    $('start-live').onclick = () => app.execute({ type: 'startLive', ...this.choice() });
    $('start-batch').onclick = () => app.execute({ type: 'startBatch', ...this.choice() });
    this.editor = new ScenarioEditor($('editor-host'), {
      api,
      // saved: listed and chosen, then started live
      onStart: async (name) => {
        await app.execute({ type: 'loadScenarios', select: name, report: false });
        await app.execute({ type: 'startLive', ...this.choice(), report: false });
      },
    });
    $('open-editor').onclick = () => this.openEditor().catch((e) => app.error(e));
  }

  choice() { return { scenario: $('scenario').value, method: $('method').value, rate: Number($('rate').value) }; }

  fillScenarios() {
    const chosen = app.choice.scenario;
    $('scenario').innerHTML = app.scenarios.map((s) => `<option value="${escapeHtml(s.name)}" ${s.name === chosen ? 'selected' : ''}>${escapeHtml(s.name)}</option>`).join('');
    this.describe();
  }

  fillMethods() {
    $('method').innerHTML = '<option value="">(the scenario\'s own)</option>' +
      app.methods.map((m) => `<option value="${escapeHtml(m.name)}" title="${escapeHtml(m.description)}">${escapeHtml(m.name)}</option>`).join('');
    if (app.choice.method) $('method').value = app.choice.method;
  }

  // The list gives the first 200 characters of a description; "read all" fetches the rest.
  describe() {
    const s = app.scenarios.find((x) => x.name === $('scenario').value);
    $('scenario-description').textContent = s ? s.description : '';
    $('scenario-more').hidden = !s || s.description.length < 199;
  }

  async describeFully() {
    const name = $('scenario').value;
    try {
      const full = await api.scenario(name);
      if ($('scenario').value === name) { $('scenario-description').textContent = full.description || ''; $('scenario-more').hidden = true; }
    } catch (e) { app.error(e); }
  }

  // The run on screen's scenario as it was run, or the chosen one.
  async openEditor() {
    const s = app.session;
    const scenario = s ? (await api.record(s.runIds[0])).scenario : await api.scenario($('scenario').value);
    this.editor.open(scenario);
  }
}
