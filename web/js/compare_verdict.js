// The verdict of a compare group, from its runs' summaries: which value of
// each row is best, which rows differ, and each run's pass or fail against a
// success criterion (by default the benchmark suite's: tracking error at most
// 1 cm, no collision, joint limits kept, no non-finite step). Pure: no DOM.

export const DEFAULT_CRITERION = Object.freeze({
  max_tracking_error: 0.01,  // m
  min_distance: null,        // m; null: any clearance passes (a collision still fails)
  collision: false,          // false: a collision fails the run
  joint_limits: true,        // true: a joint-limit violation fails the run
});

// Rows of the summary table: how to read each value and which way is better
// ('low', 'high', 'false': false is better, null: not ranked). `timing` rows
// differ between any two runs and never make methods "differ".
// `tolerance`: a value within it of the best is as good ({abs} in the row's
// unit, or {rel} of the value): "best" is marked only beyond it (8.70e-6 m
// against 8.80e-6 m is noise, not a better method); `stated` says it in words.
export const SUMMARY_ROWS = [
  // an obstacle contact, as the metrics' row (summaries of format 2: collided is either contact)
  { key: 'collided', label: 'collided', get: (s) => s.obstacle_collided ?? s.collided, better: 'false' },
  { key: 'min_distance', label: 'min distance (m)', get: (s) => s.min_distance, better: 'high', tolerance: { abs: 1e-3 }, stated: '1 mm' },
  { key: 'self_collided', label: 'self-collided', get: (s) => s.self_collided, better: 'false' },
  { key: 'min_self_distance', label: 'min self distance (m)', get: (s) => s.min_self_distance, better: 'high', tolerance: { abs: 1e-3 }, stated: '1 mm' },
  { key: 'max_tracking_error', label: 'max tracking error (m)', get: (s) => s.max_tracking_error, better: 'low', tolerance: { abs: 1e-4 }, stated: '0.1 mm' },
  { key: 'final_tracking_error', label: 'final tracking error (m)', get: (s) => s.final_tracking_error, better: 'low', tolerance: { abs: 1e-4 }, stated: '0.1 mm' },
  { key: 'joint_limit_violated', label: 'joint limit violated', get: (s) => s.joint_limit_violated, better: 'false' },
  { key: 'min_joint_limit_margin', label: 'min joint-limit margin', get: (s) => s.min_joint_limit_margin, better: 'high', tolerance: { abs: 1e-3 }, stated: '0.001' },
  { key: 'max_condition_number', label: 'max condition number', get: (s) => s.max_condition_number, better: 'low', tolerance: { rel: 0.01 }, stated: '1 %' },
  { key: 'nonfinite_steps', label: 'non-finite steps', get: (s) => s.nonfinite_steps, better: 'low' },
  { key: 'step_p50', label: 'step p50 (µs)', get: (s) => s.step_us && s.step_us.p50, better: 'low', timing: true, tolerance: { rel: 0.1 }, stated: '10 %' },
  { key: 'step_p99', label: 'step p99 (µs)', get: (s) => s.step_us && s.step_us.p99, better: 'low', timing: true, tolerance: { rel: 0.1 }, stated: '10 %' },
];

// Two numbers the same to display precision (4 significant digits) are not a difference.
const RELATIVE_SAME = 5e-5;
function same(a, b) {
  if (typeof a !== 'number' || typeof b !== 'number') return a === b;
  if (!Number.isFinite(a) || !Number.isFinite(b)) return Object.is(a, b);
  return Math.abs(a - b) <= RELATIVE_SAME * Math.max(Math.abs(a), Math.abs(b), 1e-12);
}

// Indices of the best values (ties share it, and so do values within the
// row's tolerance of it); [] when the row is not ranked, has fewer than two
// values, or all are the same (or within the tolerance).
export function bestOf(values, better, tolerance = null) {
  const known = values.map((v, i) => [v, i]).filter(([v]) => v !== null && v !== undefined && !(typeof v === 'number' && Number.isNaN(v)));
  if (!better || known.length < 2 || !differs(values)) return [];
  let best;
  if (better === 'false') best = known.some(([v]) => v === false) ? false : null;
  else best = known.reduce((b, [v]) => (better === 'low' ? Math.min(b, v) : Math.max(b, v)), better === 'low' ? Infinity : -Infinity);
  if (best === null) return [];
  const near = (v) => same(v, best) || (typeof v === 'number' && tolerance &&
    Math.abs(v - best) <= (tolerance.abs ?? 0) + (tolerance.rel ?? 0) * Math.abs(best));
  const ties = known.filter(([v]) => near(v)).map(([, i]) => i);
  return ties.length === known.length ? [] : ties;
}

export function differs(values) {
  return values.some((v) => !same(v, values[0]));
}

// A summary's contacts as words: 'collided' (an obstacle), 'self-collision'.
// `collided` is either since summaries of format 2; before, obstacles only.
export function contacts(summary) {
  const obstacle = summary.obstacle_collided ?? (summary.collided && !summary.self_collided);
  return [obstacle ? 'collided' : '', summary.self_collided ? 'self-collision' : ''].filter(Boolean);
}

// A length in words: 4.8 cm, 1 cm, 0.3 mm.
export function lengthWords(metres) {
  if (!Number.isFinite(metres)) return String(metres);
  const a = Math.abs(metres);
  return a >= 0.01 ? `${Number((metres * 100).toPrecision(2))} cm` : `${Number((metres * 1000).toPrecision(2))} mm`;
}

// {pass, reasons: [text]} of one summary against a criterion; each reason
// says the value and the bound it broke, and when it first happened where
// `times` says (first_failure.js failureTimes: seconds by way of failing).
export function judge(summary, criterion = DEFAULT_CRITERION, times = null) {
  const reasons = [];
  const c = { ...DEFAULT_CRITERION, ...criterion };
  const at = (key) => (times && Number.isFinite(times[key]) ? ` at ${times[key].toFixed(2)} s` : '');
  if (!c.collision) {
    for (const contact of contacts(summary)) {
      const deep = contact === 'collided' && summary.min_distance < 0;
      reasons.push(contact === 'collided' ? `collision${at('collision')}${deep ? `, ${lengthWords(-summary.min_distance)} deep` : ''}` : `${contact}${at('self_collision')}`);
    }
  }
  if (c.joint_limits && summary.joint_limit_violated) reasons.push(`crossed a joint limit${at('joint_limit')}`);
  if (summary.nonfinite_steps > 0) reasons.push('non-finite output');
  // a NaN error or distance never passes a bound
  if (Number.isFinite(c.max_tracking_error) && !(summary.max_tracking_error <= c.max_tracking_error)) {
    reasons.push(`tracking error ${lengthWords(summary.max_tracking_error)} > ${lengthWords(c.max_tracking_error)}${at('tracking_lost')}`);
  }
  if (Number.isFinite(c.min_distance) && !(summary.min_distance >= c.min_distance)) {
    reasons.push(`clearance ${lengthWords(summary.min_distance)} < ${lengthWords(c.min_distance)}${at('clearance')}`);
  }
  return { pass: reasons.length === 0, reasons };
}

// The table's content and one sentence: rows with their best indices and
// whether they differ, each run's verdict, and the headline.
// `times`: each lane's failureTimes, when its stored frames are loaded.
export function compareVerdict(summaries, labels, criterion = DEFAULT_CRITERION, times = []) {
  const rows = SUMMARY_ROWS.map((row) => {
    const values = summaries.map((s) => row.get(s));
    return { ...row, values, best: bestOf(values, row.better, row.tolerance), differs: !row.timing && differs(values) };
  });
  const verdicts = summaries.map((s, i) => judge(s, criterion, times[i] || null));
  const passed = labels.filter((_, i) => verdicts[i].pass);
  const failed = labels.map((label, i) => [label, verdicts[i]]).filter(([, v]) => !v.pass);
  const why = failed.map(([label, v]) => `${label} (${v.reasons.join(', ')})`).join('; ');
  let headline;
  if (!rows.some((r) => r.differs)) headline = `No difference: ${labels.join(', ')} give the same result on this scenario (to 4 digits).`;
  else if (!failed.length) headline = `All pass; they differ in ${rows.filter((r) => r.differs).map((r) => r.label.replace(/ \(.*\)$/, '')).join(', ')}.`;
  else if (!passed.length) headline = `All fail: ${why}.`;
  else headline = `${passed.join(', ')} pass${passed.length === 1 ? 'es' : ''}; ${failed.map(([label, v]) => `${label} fails (${v.reasons.join(', ')})`).join('; ')}.`;
  return { rows, verdicts, headline };
}
