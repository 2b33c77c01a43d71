// What the sweep page shows, from a sweep's report (api.sweep(id)):
// the method × family success table with its best cells, the failure modes,
// step cost, success against difficulty as an inline SVG, and the method
// configurations as the compare endpoint takes them. Pure: no DOM.
import { escapeHtml } from './dom.js';
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

// Success against difficulty of one family: an SVG (as text) with one line per
// configuration over the bins, and the measure named; null without bins.
export function difficultySvg(groups, colours, { width = 320, height = 140 } = {}) {
  const withBins = groups.filter((g) => g.difficulty && Array.isArray(g.difficulty.bins) && g.difficulty.bins.length);
  if (!withBins.length) return null;
  const measure = withBins[0].difficulty.measure || 'difficulty';
  const lows = withBins.flatMap((g) => g.difficulty.bins.map((b) => b.low));
  const highs = withBins.flatMap((g) => g.difficulty.bins.map((b) => b.high));
  const x0 = Math.min(...lows), x1 = Math.max(...highs);
  const pad = { left: 34, right: 8, top: 8, bottom: 28 };
  const w = width - pad.left - pad.right, h = height - pad.top - pad.bottom;
  const sx = (x) => pad.left + (x1 > x0 ? ((x - x0) / (x1 - x0)) * w : w / 2);
  const sy = (r) => pad.top + (1 - r) * h;
  const lines = withBins.map((g, i) => {
    const points = g.difficulty.bins.filter((b) => b.n > 0).map((b) => [sx((b.low + b.high) / 2), sy(b.successes / b.n), b]);
    const colour = colours[i % colours.length];
    const path = points.map(([x, y], k) => `${k ? 'L' : 'M'}${x.toFixed(1)},${y.toFixed(1)}`).join('');
    const dots = points.map(([x, y, b]) => `<circle cx="${x.toFixed(1)}" cy="${y.toFixed(1)}" r="2.5" fill="${colour}"><title>${escapeHtml(g.config)}: ${b.successes}/${b.n} in [${b.low.toPrecision(3)}, ${b.high.toPrecision(3)}]</title></circle>`).join('');
    return `<path d="${path}" fill="none" stroke="${colour}" stroke-width="1.5"/>${dots}`;
  }).join('');
  const axes = `<line x1="${pad.left}" y1="${sy(0)}" x2="${pad.left + w}" y2="${sy(0)}" stroke="#90a4ae"/>` +
    `<line x1="${pad.left}" y1="${sy(0)}" x2="${pad.left}" y2="${sy(1)}" stroke="#90a4ae"/>` +
    `<text x="${pad.left - 4}" y="${sy(1) + 4}" text-anchor="end" font-size="10">100 %</text>` +
    `<text x="${pad.left - 4}" y="${sy(0) + 4}" text-anchor="end" font-size="10">0</text>` +
    `<text x="${pad.left}" y="${height - 14}" font-size="10">${x0.toPrecision(3)}</text>` +
    `<text x="${pad.left + w}" y="${height - 14}" text-anchor="end" font-size="10">${x1.toPrecision(3)}</text>` +
    `<text x="${pad.left + w / 2}" y="${height - 2}" text-anchor="middle" font-size="10">${escapeHtml(measure)}</text>`;
  return `<svg xmlns="http://www.w3.org/2000/svg" width="${width}" height="${height}" role="img" aria-label="success against ${escapeHtml(measure)}">${axes}${lines}</svg>`;
}
