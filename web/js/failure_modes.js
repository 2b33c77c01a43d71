// A sweep run's first failure mode (sweep/failure_watch.cpp's names) in the
// words the page shows: the run list, a sweep's cells and its runs. Pure.
const WORDS = {
  collision: 'collision',
  self_collision: 'self-collision',
  joint_limit: 'joint limit',
  joint_speed: 'joint speed',
  tracking_lost: 'tracking lost',
  stalled: 'stalled',
  nonfinite: 'non-finite',
  unrecorded: 'unrecorded',  // runs stored before modes were
};

// A mode the page does not know yet reads as its name with spaces.
export function failureModeText(mode) {
  return WORDS[mode] || String(mode).replace(/_/g, ' ');
}

// "fail: self-collision at 0.00 s", "fail", or "pass".
export function outcomeText({ success, failure_mode: mode, failure_t: t }) {
  if (success) return 'pass';
  if (!mode) return 'fail';
  return `fail: ${failureModeText(mode)}${Number.isFinite(t) ? ` at ${t.toFixed(2)} s` : ''}`;
}
