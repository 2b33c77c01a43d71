// The Sweeps list beside the runs (name, status, live progress, failures;
// open, stop) and the dialog that starts a sweep from a spec, checked as it
// is typed (JSON) and by the server (422 naming the spec's path).
import { api, describeError } from './api.js';
import { app } from './state.js';
import { escapeHtml } from './dom.js';
import { sweepProblems, jsonErrorAt } from './sweep_problems.js';

const $ = (id) => document.getElementById(id);

const EXAMPLE_SPEC = {
  name: 'my-sweep',
  scenarios: [{ generator: 'planar_clutter', count: 10, seed: 1 }, { generator: 'narrow_passage', count: 10, seed: 1 }],
  methods: ['pinv', 'dls', 'closest_point', 'task_priority'],
  success: { max_tracking_error: 0.01, collision: false, joint_limits: true },
};

export class SweepList {
  constructor() {
    this.sweeps = [];
    this.progress = new Map();  // id → {done, total} of running sweeps
    this.validations = 0;  // the newest server check of the spec wins
    $('new-sweep').onclick = () => this.openDialog();
    $('sweep-cancel').onclick = () => $('sweep-dialog').close();
    $('sweep-spec').oninput = () => this.checkSyntax();
    $('sweep-form').onsubmit = (e) => { e.preventDefault(); this.submit().catch((err) => this.showError(err)); };
    this.timer = setInterval(() => { if (!document.hidden) this.refresh(); }, 2000);
    app.signals.started.add(() => this.refresh());
  }

  open(id) { app.execute({ type: 'openSweep', id }); }

  async refresh() {
    let sweeps;
    try { sweeps = await api.sweeps(); } catch { return; }
    this.sweeps = sweeps;
    // progress of the running ones (the list says total only)
    await Promise.all(sweeps.filter((s) => s.status === 'running').map(async (s) => {
      const status = await api.sweep(s.id).catch(() => null);
      if (status) this.progress.set(s.id, { done: status.done, total: status.total });
    }));
    const list = $('sweeps');
    list.replaceChildren(...[...sweeps].reverse().map((s) => this.item(s)));
    if (!sweeps.length) list.innerHTML = '<li class="muted small">no sweeps yet: start one with “New sweep…”, or <code>rrlab sweep</code> for the command line</li>';
  }

  // The sweep id of a stored sweep's name (the newest job of that name), or null.
  idOf(name) {
    const jobs = this.sweeps.filter((s) => s.name === name);
    return jobs.length ? jobs[jobs.length - 1].id : null;
  }

  item(s) {
    const li = document.createElement('li');
    li.dataset.sweep = String(s.id);
    const progress = this.progress.get(s.id);
    const done = s.status === 'running' && progress ? progress.done : s.total;
    li.innerHTML = `<div class="title">${escapeHtml(s.name)} <span class="muted">#${s.id}</span></div>
      <div class="muted small">${escapeHtml(s.status)} · <span class="progress">${done} / ${s.total}</span> runs${s.failed ? ` · ${s.failed} failed to run` : ''}</div>
      <div class="actions"><button type="button" class="open-sweep">Open</button></div>`;
    if (s.status === 'running') {
      const bar = document.createElement('progress');
      bar.max = s.total;
      bar.value = done;
      li.insertBefore(bar, li.querySelector('.actions'));
      const stop = document.createElement('button');
      stop.type = 'button';
      stop.textContent = 'Stop';
      stop.title = 'workers finish their current run; stored runs stay, and the same spec resumes';
      stop.onclick = () => api.sweepControl(s.id, { action: 'stop' }).then(() => this.refresh(), (e) => app.error(e));
      li.querySelector('.actions').appendChild(stop);
    }
    li.querySelector('.open-sweep').onclick = () => this.open(s.id);
    return li;
  }

  openDialog() {
    const text = $('sweep-spec');
    if (!text.value.trim()) text.value = JSON.stringify(EXAMPLE_SPEC, null, 2);
    $('sweep-error').textContent = '';
    this.checkSyntax();
    $('sweep-dialog').showModal();
  }

  // The spec parses as JSON, or the error says where it does not; once it
  // does, the server checks it as a start would (api.validateSweep,
  // a moment after the typing stops) and says what it would run or what is wrong.
  checkSyntax() {
    const text = $('sweep-spec').value;
    clearTimeout(this.validateTimer);
    $('sweep-error').textContent = '';  // a start refused earlier: about the spec before this edit
    const asked = ++this.validations;
    let spec;
    try {
      spec = JSON.parse(text);
    } catch (e) {
      this.say(`not JSON yet: ${jsonErrorAt(text, e)}`, 'bad');
      return false;
    }
    this.say('valid JSON; checking it with the server…', 'muted');
    this.validateTimer = setTimeout(() => {
      api.validateSweep(spec).then((v) => {
        if (asked !== this.validations) return;
        this.say(`valid: ${v.total} runs (${v.scenario_entries} scenario entries × ${v.configurations} method configurations, cases included)`, 'ok');
      }, async (e) => {
        if (asked !== this.validations) return;
        // every problem, each at its entry (the server names the first only)
        let found;
        try { found = await sweepProblems(spec, (s) => api.validateSweep(s)); } catch (_) { found = { problems: [{ path: e.path, message: describeError(e) }], unchecked: 0 }; }
        if (asked !== this.validations) return;
        const { problems, unchecked } = found;
        if (!problems.length) { this.say(`the server refuses it: ${describeError(e)}`, 'bad'); return; }
        this.say(`the server refuses it (${problems.length === 1 ? 'one problem' : `${problems.length} problems`}${unchecked ? `; ${unchecked} more entries not checked one by one` : ''}):`, 'bad', problems.map((p) => p.message));
      });
    }, 400);
    return true;
  }

  // The line under the spec: a verdict, and the problems as a list.
  say(text, kind, items = []) {
    const out = $('sweep-syntax');
    out.className = `small ${kind}`;
    out.replaceChildren(document.createTextNode(text));
    if (items.length) {
      const list = document.createElement('ul');
      list.className = 'problems';
      for (const item of items) { const li = document.createElement('li'); li.textContent = item; list.appendChild(li); }
      out.appendChild(list);
    }
  }

  showError(e) {
    $('sweep-error').textContent = describeError(e);
  }

  async submit() {
    $('sweep-error').textContent = '';
    if (!this.checkSyntax()) return;
    const spec = JSON.parse($('sweep-spec').value);
    const jobs = Number($('sweep-jobs').value);
    const started = await api.startSweep(spec, jobs);
    $('sweep-dialog').close();
    await this.refresh();
    this.open(started.id);
  }
}
