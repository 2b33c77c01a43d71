// The Papers panel: the five papers rrlab reproduces, each with its
// citation, and on its page (/?paper=KEY) its examples: the paper's outcome,
// what rrlab's shipped scenario gives, the rate over the perturbation family
// and the mark by the reproduction table's rule, the scenario's full
// description, and one click to run the example live or to compare it with
// the baselines the paper compares against. The data is web/data/papers.json,
// written by scripts/reproduction-table --papers-json from the committed sweeps.
import { api } from './api.js';
import { app, PAPER_KEYS } from './state.js';
import { escapeHtml } from './dom.js';
import { parseConfig } from './sweep_report.js';

const $ = (id) => document.getElementById(id);

// "Sezgin et al. (1997)"; the year is omitted where the paper's text gives none.
export function shortCitation(paper) {
  const plural = paper.authors.includes(',') || paper.authors.includes(' and ');
  return `${paper.name}${plural ? ' et al.' : ''}${paper.year ? ` (${paper.year})` : ''}`;
}

export class Papers {
  // Shown while the page in the centre is a paper's (state.js: app.page);
  // the list fills once the page has opened what its address asked for.
  constructor() {
    this.data = null;
    this.key = null;
    app.signals.pageChanged.add((page) => {
      if (!page || page.name !== 'paper') { this.hide(); return; }
      $('papers-section').open = true;
      this.show(page.key).catch((e) => app.error(e));
    });
    app.signals.started.add(() => this.fillList().catch((e) => app.error(e)));
  }

  async load() {
    if (!this.data) this.data = await api.papers();
    return this.data;
  }

  // The list in the left column: one entry per paper.
  async fillList() {
    const data = await this.load();
    $('papers-list').replaceChildren(...data.papers.map((p) => {
      const li = document.createElement('li');
      li.dataset.paper = p.key;
      li.innerHTML = `<button type="button" class="link" title="${escapeHtml(`${p.authors}, “${p.title}”`)}">${escapeHtml(shortCitation(p))}</button>
        <span class="muted small">${escapeHtml(p.method)} · ${p.examples.length} examples</span>`;
      li.querySelector('button').onclick = () => app.execute({ type: 'openPaper', key: p.key });
      return li;
    }));
  }

  get shown() { return this.key !== null; }

  hide() {
    this.key = null;
    if ($('sweep-page').hidden) document.getElementById('center').classList.remove('showing-page');
    $('paper-page').hidden = true;
    $('paper-page').replaceChildren();
  }

  async show(key) {
    this.key = key;  // before any await: a run opened meanwhile hides it (key null) and the page stays hidden
    const data = await this.load();
    if (this.key !== key) return;
    const paper = data.papers.find((p) => p.key === key);
    if (!paper) throw new Error(`no paper "${key}": one of ${PAPER_KEYS.join(', ')}`);
    const page = $('paper-page');
    document.getElementById('center').classList.add('showing-page');
    page.hidden = false;
    const scenarios = [...new Set(paper.examples.map((e) => e.scenario).filter(Boolean))];
    const descriptions = Object.fromEntries(await Promise.all(scenarios.map(async (name) => {
      const s = await api.scenario(name).catch(() => null);
      return [name, s ? s.description || '' : ''];
    })));
    if (this.key !== key) return;
    const rows = paper.examples.map((e, i) => `<tr data-example="${i}">
      <td>${escapeHtml(e.figure)}${e.scenario ? `<div class="mono small muted">${escapeHtml(e.scenario)}</div>` : ''}
        <div class="actions">${e.scenario ? `<button type="button" class="run-live" title="run the shipped scenario live with this configuration">Run live</button>` : ''}
        ${e.scenario && e.config && e.baselines.length ? `<button type="button" class="run-compare" title="${escapeHtml(`side by side with ${e.baselines.map((b) => parseConfigName(b)).join(', ')}`)}">Compare with baselines</button>` : ''}
        ${e.scenario && e.config ? `<button type="button" class="run-modern" title="side by side with ${TODAYS_BASELINES.join(', ')}: the methods practitioners use today, with their defaults (not part of the paper's mark)">Compare with today's baselines</button>` : ''}</div></td>
      <td data-label="the paper">${escapeHtml(e.outcome)}</td>
      <td data-label="rrlab, shipped scenario">${escapeHtml(e.shipped)}</td>
      <td class="rate" data-label="over its nudged copies (95 % CI)">${escapeHtml(e.rate)}${e.paired && e.paired !== '—' ? `<div class="small muted">${escapeHtml(e.paired)}</div>` : ''}${e.harsh && e.harsh !== '—' ? `<div class="small muted harsh">harsh family: ${escapeHtml(e.harsh)}</div>` : ''}${e.today && e.today !== '—' ? `<div class="small muted today">today's baselines: ${escapeHtml(e.today)}</div>` : ''}</td>
      <td class="mark" data-label="mark">${escapeHtml(e.mark)}${e.why ? `<div class="small muted">${escapeHtml(e.why)}</div>` : ''}</td></tr>`).join('');
    const described = scenarios.map((name) => `<details class="scenario-text"><summary>${escapeHtml(name)}</summary><p>${escapeHtml(descriptions[name])}</p></details>`).join('');
    page.innerHTML = `<h2 class="paper-title">${escapeHtml(paper.title)}</h2>
      <p class="paper-authors">${escapeHtml(paper.authors)}${paper.venue ? `, ${escapeHtml(paper.venue)}` : ''}${paper.year ? ` (${paper.year})` : ' (the year is not stated in the paper\'s text)'} · implemented as <code>${escapeHtml(paper.method)}</code></p>
      <h3>Examples: the paper's outcome and what rrlab gets</h3>
      ${paper.tally ? `<p class="paper-tally">${escapeHtml(paper.tally)}</p>` : ''}
      <table class="paper-examples"><tr><th>example</th><th>the paper</th><th>rrlab, shipped scenario</th><th>over its nudged copies (95 % CI)</th><th>mark</th></tr>${rows}</table>
      ${paper.advice ? `<p class="paper-advice">${escapeHtml(paper.advice)}</p>` : ''}
      <p class="small muted rule">${escapeHtml(data.rule.replace(/\*\*/g, ''))}</p>
      <h3>The scenarios</h3>${described}`;
    page.querySelectorAll('tr[data-example]').forEach((tr) => {
      const example = paper.examples[Number(tr.dataset.example)];
      const live = tr.querySelector('.run-live');
      if (live) live.onclick = () => this.run(example, 'live');
      const compare = tr.querySelector('.run-compare');
      if (compare) compare.onclick = () => this.run(example, 'compare');
      const modern = tr.querySelector('.run-modern');
      if (modern) modern.onclick = () => this.run(example, 'modern');
    });
  }

  // The example's configuration (the scenario's own method when the row has none).
  run(example, kind) {
    const own = example.config ? parseConfig(example.config) : null;
    const others = kind === 'modern' ? TODAYS_BASELINES : example.baselines.map(parseConfig);
    const methods = kind === 'live' ? (own ? [own] : []) : [own, ...others].slice(0, 4);
    return app.execute({ type: 'startExample', kind: kind === 'live' ? 'live' : 'compare', scenario: example.scenario, methods });
  }
}

// The baselines practitioners use today (a weighted QP with velocity dampers,
// a strict hierarchical QP, direction-preserving scaling), with their defaults:
// offered beside every example, outside the paper's own comparison.
const TODAYS_BASELINES = ['qp_ik', 'hqp', 'diffik'];

const parseConfigName = (key) => { const c = parseConfig(key); return typeof c === 'string' ? c : c.name; };
