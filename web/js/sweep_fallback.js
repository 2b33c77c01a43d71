// What to try when the first choice fails, from a sweep report's `fallbacks`
// (sweep/sweep_fallback.hpp): per family the first choice and the fallback
// that together solve the most cases — an offline upper bound, the fallback
// credited with what it did from the start — and the cases no configuration
// solves, with the `rrlab generate … --cases` command that writes them. HTML
// as text; pure: no DOM.
import { escapeHtml } from './dom.js';

const short = (x) => (Number.isFinite(x) ? String(Number(x.toPrecision(3))) : '—');

// "task_priority, then qp_constraints", or the first choice alone and why.
export function fallbackPair(f) {
  if (!f.first) return '—';
  if (f.solved_by_some === 0) return 'none: no configuration solves any case';
  return f.second ? `${f.first}, then ${f.second}` : `${f.first} alone (no configuration solves a case it fails)`;
}

// "79 → 89 of 100": the first choice alone, then with its fallback.
export function fallbackSolved(f) {
  if (!f.first) return '—';
  if (f.solved_by_some === 0) return `0 of ${f.pair_cases}`;
  return f.second ? `${f.first_solved} → ${f.pair_solved} of ${f.pair_cases}` : `${f.first_solved} of ${f.pair_cases}`;
}

// "2 of 100 (the witness solves 2): a, b (the first 50 of 60)".
export function unsolvedText(f) {
  const u = f.unsolved;
  let text = `${u.total} of ${f.cases}${u.witness_solves === null || u.witness_solves === undefined ? '' : ` (the witness solves ${u.witness_solves})`}`;
  if (!u.listed.length) return text;
  text += `: ${u.listed.map((c) => c.case).join(', ')}`;
  if (u.listed.length < u.total) text += ` (the first ${u.listed.length} of ${u.total})`;
  return text;
}

// The section: a table of the families, then each family's unsolved cases
// with their commands. '' when the report has no fallbacks.
export function fallbackHtml(report) {
  const fallbacks = (report && report.fallbacks) || [];
  if (!fallbacks.length) return '';
  const rows = fallbacks.map((f) => `<tr data-family="${escapeHtml(f.family)}"><td>${escapeHtml(f.family)}</td>
    <td>${escapeHtml(fallbackPair(f))}</td><td>${escapeHtml(fallbackSolved(f))}</td><td>${short(f.cost_us)}</td>
    <td>${f.solved_by_some} of ${f.cases}</td><td>${f.unsolved.total}</td></tr>`).join('');
  const unsolved = fallbacks.filter((f) => f.unsolved.total > 0).map((f) => `<div class="unsolved" data-family="${escapeHtml(f.family)}">
    <p class="small"><b>${escapeHtml(f.family)}</b>, unsolved: ${escapeHtml(unsolvedText(f))}</p>
    ${f.unsolved.generate.map((c) => `<pre class="mono small">${escapeHtml(c)}</pre>`).join('')}</div>`).join('');
  const rule = report.rules && report.rules.fallbacks;
  return `<h3>What to try when the first choice fails <span class="muted small">(an offline upper bound)</span></h3>
    <p class="small muted">Per family, the first choice and the fallback that together solve the most cases. An upper
      bound: the fallback is credited with what it did when run from the start, not from where the first choice failed.
      Cost: µs per step, the first choice's plus the fallback's times the first choice's failure share.</p>
    ${rule ? `<details class="rule small"><summary>the rule</summary><p>${escapeHtml(rule)}</p></details>` : ''}
    <table class="sweep-fallbacks"><tr><th>family</th><th>first choice, then fallback</th><th>solved: first alone → with the fallback</th>
      <th>cost (µs/step)</th><th>solved by some configuration</th><th>unsolved</th></tr>${rows}</table>${unsolved}`;
}
