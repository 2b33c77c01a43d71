// What the sweep page shows, from a sweep's report (api.sweep(id)):
// the method × family success table with its best cells, the failure modes,
// step cost, success against difficulty as an inline SVG, and the method
// configurations as the compare endpoint takes them. Pure: no DOM.
import { escapeHtml, fmt } from './dom.js';
import { failureModeText } from './failure_modes.js';

// "dls{lambda=0.1,damping=fixed}" → {name: 'dls', params: {lambda: 0.1, damping: 'fixed'}};
// a bare name → the name.
export function parseConfig(key) {
  const match = /^([^{]+)(?:\{(.*)\})?$/.exec(key);
  if (!match) return key;
  if (!match[2]) return match[1];
  const params = {};
  for (const part of match[2].split(',')) {
    const at = part.indexOf('=');
    if (at < 0) continue;
    const value = part.slice(at + 1);
    params[part.slice(0, at)] = value !== '' && Number.isFinite(Number(value)) ? Number(value) : value;
  }
  return { name: match[1], params };
}

const unique = (list) => [...new Set(list)];

// {families, configs, cell(family, config) → group|null, best: Map family → Set(config)}:
// a column's best cells are those whose success rate is the column's highest
// (none when every method of the column has the same rate).
export function successTable(report) {
  const groups = report && Array.isArray(report.groups) ? report.groups : [];
  const ranked = report && Array.isArray(report.ranking) ? report.ranking.map((r) => r.config) : [];
  const configs = unique([...ranked, ...groups.map((g) => g.config)]);
  const families = unique(groups.map((g) => g.family)).sort();
  const byKey = new Map(groups.map((g) => [`${g.family}\n${g.config}`, g]));
  const cell = (family, config) => byKey.get(`${family}\n${config}`) || null;
  const best = new Map();
  for (const family of families) {
    const rates = configs.map((c) => cell(family, c)).filter(Boolean).map((g) => g.success_rate);
    const top = Math.max(...rates);
    best.set(family, new Set(rates.length > 1 && rates.some((r) => r !== top)
      ? configs.filter((c) => { const g = cell(family, c); return g && g.success_rate === top; }) : []));
  }
  return { families, configs, cell, best };
}

// A "which method when" row from its verdict (report.verdicts), as text:
// {detects, listed}. Too few cases, or no success, lists no configuration to
// pick (docs/results.md, which method when). cell: successTable's.
export function verdictWords(v, cell) {
  const cost = (config) => { const g = cell(v.family, config); return g && Number.isFinite(g.step_us_p50) ? ` (${fmt(g.step_us_p50)} µs/step)` : ''; };
  const best = cell(v.family, v.best);
  let listed;
  if (v.status === 'too_few_cases') {
    const points = Number.isFinite(v.separable_difference) ? `${Math.round(100 * v.separable_difference)} points` : 'the bound';
    listed = `too few cases to separate the methods (a difference of ${points} needs about ${v.cases_needed} cases); `
      + `best observed, not separated from the others: ${v.best}${best ? ` (${Math.round(100 * best.success_rate)} %)` : ''}`;
  } else if (v.status === 'no_success') {
    listed = 'no configuration succeeded on any case';
  } else {
    const more = (v.not_worse_total || 0) - v.not_worse.length;
    listed = v.not_worse.map((c) => `${c}${cost(c)}`).join(', ') + (more > 0 ? `, and ${more} more` : '');
  }
  const detects = Number.isFinite(v.detectable_difference) ? `${(100 * v.detectable_difference).toFixed(1)} points` : 'none: too few cases for p < 0.05';
  return { detects, listed };
}

// "40 % [19–64 %]": a success rate with its 95 % Wilson interval.
export function formatRate(group) {
  const pct = (x) => `${Math.round(100 * x)}`;
  const [lo, hi] = group.success_interval || [NaN, NaN];
  return `${pct(group.success_rate)} % [${pct(lo)}–${pct(hi)} %]`;
}

// "collision 3 · self-collision 1", most frequent first ('' when none).
export function formatFailureModes(modes) {
  return Object.entries(modes || {}).sort((a, b) => b[1] - a[1]).map(([mode, n]) => `${failureModeText(mode)} ${n}`).join(' · ');
}

// The difficulty measures a family's groups carry, for its charts: null (the
// quartile bins of the witness's clearance or limit margin, g.difficulty),
// then each obstacle count of g.difficulty_counts (blocking_obstacles, …).
export function difficultyMeasures(groups) {
  const measures = groups.some((g) => binsOf(g, null).length) ? [null] : [];
  for (const g of groups) for (const m of Object.keys(g.difficulty_counts || {})) if (!measures.includes(m)) measures.push(m);
  return measures;
}

const binsOf = (g, measure) => {
  const bins = measure === null ? g.difficulty && g.difficulty.bins : g.difficulty_counts && g.difficulty_counts[measure];
  return Array.isArray(bins) ? bins : [];
};

// An obstacle count's bin: "2", or "4+" for the open last one (high null).
export const countBinLabel = (b) => (b.high === null ? `${b.low}+` : b.low === b.high ? `${b.low}` : `${b.low}–${b.high}`);

// Success against difficulty of one family: an SVG (as text) with one line per
// configuration over the bins of `measure` (difficultyMeasures), and the
// measure named; null without bins. Quartile bins sit at their middle value;
// an obstacle count's bins at even steps, labelled 0, 1, …, 4+.
// colours[i] is groups[i]'s.
export function difficultySvg(groups, colours, { measure = null, width = 320, height = 140 } = {}) {
  const withBins = groups.map((g, i) => ({ g, colour: colours[i % colours.length], bins: binsOf(g, measure) })).filter((l) => l.bins.length);
  if (!withBins.length) return null;
  const name = measure || withBins[0].g.difficulty.measure || 'difficulty';
  const pad = { left: 34, right: 8, top: 8, bottom: 28 };
  const w = width - pad.left - pad.right, h = height - pad.top - pad.bottom;
  const sy = (r) => pad.top + (1 - r) * h;
  let sx, ticks;
  if (measure === null) {
    const x0 = Math.min(...withBins.flatMap((l) => l.bins.map((b) => b.low)));
    const x1 = Math.max(...withBins.flatMap((l) => l.bins.map((b) => b.high)));
    const at = (x) => pad.left + (x1 > x0 ? ((x - x0) / (x1 - x0)) * w : w / 2);
    sx = (b) => at((b.low + b.high) / 2);
    ticks = `<text x="${pad.left}" y="${height - 14}" font-size="10">${x0.toPrecision(3)}</text>` +
      `<text x="${pad.left + w}" y="${height - 14}" text-anchor="end" font-size="10">${x1.toPrecision(3)}</text>`;
  } else {
    const bins = withBins[0].bins, step = bins.length > 1 ? w / (bins.length - 1) : 0;
    sx = (b, k) => pad.left + step * k;
    ticks = bins.map((b, k) => `<text x="${(pad.left + step * k).toFixed(1)}" y="${height - 14}" text-anchor="middle" font-size="10">${escapeHtml(countBinLabel(b))}</text>`).join('');
  }
  const lines = withBins.map(({ g, colour, bins }) => {
    const points = bins.map((b, k) => [sx(b, k), b.n > 0 ? sy(b.successes / b.n) : null, b]).filter(([, y]) => y !== null);
    const path = points.map(([x, y], k) => `${k ? 'L' : 'M'}${x.toFixed(1)},${y.toFixed(1)}`).join('');
    const where = (b) => (measure === null ? `in [${b.low.toPrecision(3)}, ${b.high.toPrecision(3)}]` : `with ${countBinLabel(b)}`);
    const dots = points.map(([x, y, b]) => `<circle cx="${x.toFixed(1)}" cy="${y.toFixed(1)}" r="2.5" fill="${colour}"><title>${escapeHtml(g.config)}: ${b.successes}/${b.n} ${escapeHtml(where(b))}</title></circle>`).join('');
    return `<path d="${path}" fill="none" stroke="${colour}" stroke-width="1.5"/>${dots}`;
  }).join('');
  const axes = `<line x1="${pad.left}" y1="${sy(0)}" x2="${pad.left + w}" y2="${sy(0)}" stroke="#90a4ae"/>` +
    `<line x1="${pad.left}" y1="${sy(0)}" x2="${pad.left}" y2="${sy(1)}" stroke="#90a4ae"/>` +
    `<text x="${pad.left - 4}" y="${sy(1) + 4}" text-anchor="end" font-size="10">100 %</text>` +
    `<text x="${pad.left - 4}" y="${sy(0) + 4}" text-anchor="end" font-size="10">0</text>` + ticks +
    `<text x="${pad.left + w / 2}" y="${height - 2}" text-anchor="middle" font-size="10">${escapeHtml(name)}</text>`;
  return `<svg xmlns="http://www.w3.org/2000/svg" width="${width}" height="${height}" role="img" aria-label="success against ${escapeHtml(name)}">${axes}${lines}</svg>`;
}
