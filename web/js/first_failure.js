// A failed run's first failure, where it happened: the mode, the frame and
// the time it began, and its reason in words ("collision with obstacle post
// at 4.04 s", "tracking error 4.8 cm > 1 cm at 3.20 s"). A sweep's run says
// its own (the sweep's row: failure_mode, failure_t, judged by the sweep's
// criteria); any other run is judged by the compare verdict's criterion
// (compare_verdict.js) and its first failing frame found in its stored
// frames. Pure: no DOM.
import { DEFAULT_CRITERION, judge } from './compare_verdict.js';
import { failureModeText } from './failure_modes.js';

const seconds = (t) => `${t.toFixed(2)} s`;
const centimetres = (m, digits = 2) => `${Number((m * 100).toPrecision(digits))} cm`;
// An error against its bound, each in centimetres, with the digits that tell them apart: "4.8 cm > 1 cm", "1.03 cm > 1 cm".
function errorAgainstBound(error, bound) {
  let digits = 2;
  while (digits < 6 && centimetres(error, digits) === centimetres(bound, digits)) digits += 1;
  return `${centimetres(error, digits)} > ${centimetres(bound)}`;
}

// Does the run fail? From its sweep row when it has one ({success}), else its
// summary against `criterion`. Unknown (no summary): false.
export function runFails({ summary, sweep }, criterion = DEFAULT_CRITERION) {
  if (sweep && typeof sweep.success === 'boolean') return !sweep.success;
  return Boolean(summary && typeof summary === 'object') && !judge(summary, criterion).pass;
}

// The frame nearest seq in the stored frames (sorted by seq; strided ones too).
function frameAt(frames, seq) {
  let best = null;
  for (const f of frames) {
    if (!best || Math.abs(f.seq - seq) < Math.abs(best.seq - seq)) best = f;
    if (f.seq >= seq) break;
  }
  return best;
}

// The modes a frame shows against the criterion, in the sweep's order of
// precedence for equal times (sweep/failure_watch.hpp).
function frameModes(m, c) {
  const modes = [];
  if (!c.collision && (m.collided === true || (Number.isFinite(c.min_distance) && m.min_distance < c.min_distance))) modes.push('collision');
  if (!c.collision && m.self_collided === true) modes.push('self_collision');
  if (c.joint_limits && m.joint_limit_margin < 0) modes.push('joint_limit');
  if (Number.isFinite(c.max_tracking_error) && m.task_error > c.max_tracking_error) modes.push('tracking_lost');
  return modes;
}

// {mode, seq, t, frame, bound} of a run that fails, or null for one that
// passes. run: {summary, sweep}; frames: its stored frames ({seq, metrics},
// sorted by seq); dt: its step. seq is null when the failure has no frame
// (a non-finite step, or a failure the frames do not show).
export function firstFailure(run, frames, dt, criterion = DEFAULT_CRITERION) {
  const c = { ...DEFAULT_CRITERION, ...criterion };
  if (!runFails(run, c)) return null;
  const list = Array.isArray(frames) ? frames.filter((f) => f && Number.isFinite(f.seq) && f.metrics) : [];
  const sweep = run.sweep;
  if (sweep && sweep.failure_mode) {
    const t = Number.isFinite(sweep.failure_t) ? sweep.failure_t : null;
    const seq = t !== null && dt > 0 ? Math.round(t / dt) : null;
    const frame = seq === null ? null : frameAt(list, seq);
    return { mode: sweep.failure_mode, seq, t, frame, bound: null };
  }
  for (const f of list) {
    const modes = frameModes(f.metrics, c);
    if (modes.length) return { mode: modes[0], seq: f.seq, t: dt > 0 ? f.seq * dt : f.t, frame: f, bound: c.max_tracking_error };
  }
  const nonfinite = run.summary && run.summary.nonfinite_steps > 0;
  return { mode: nonfinite ? 'nonfinite' : 'unrecorded', seq: null, t: null, frame: null, bound: null };
}

// The obstacles a view frame's arm touches ({nearest: [[link, obstacle index,
// distance, …]]}), by id: the snapshot's obstacles (or the frame's, when they
// carry ids) name the index; unnamed, the index itself.
export function touchedObstacles(viewFrame, snapshotObstacles = []) {
  if (!viewFrame || !Array.isArray(viewFrame.nearest)) return [];
  const poses = Array.isArray(viewFrame.obstacles) ? viewFrame.obstacles : [];
  const ids = [];
  for (const n of viewFrame.nearest) {
    if (!Array.isArray(n) || typeof n[2] !== 'number' || !(n[2] <= 0)) continue;
    const named = [snapshotObstacles[n[1]], poses[n[1]]].find((o) => o && typeof o === 'object' && o.id !== undefined);
    const id = named ? String(named.id) : String(n[1]);
    if (!ids.includes(id)) ids.push(id);
  }
  return ids;
}

// The reason in words. `obstacles`: the ids the arm touches at the failure
// (touchedObstacles), when known.
export function failureText(failure, obstacles = []) {
  if (!failure) return '';
  const at = failure.t === null || !Number.isFinite(failure.t) ? '' : ` at ${seconds(failure.t)}`;
  const m = failure.frame ? failure.frame.metrics : {};
  switch (failure.mode) {
    case 'collision':
      if (obstacles.length) return `collision with obstacle${obstacles.length > 1 ? 's' : ''} ${obstacles.join(' and ')}${at}`;
      return `collision${at}`;
    case 'self_collision':
      return m.self_link_a > 0 && m.self_link_b > 0 ? `self-collision of links ${m.self_link_a} and ${m.self_link_b}${at}` : `self-collision${at}`;
    case 'tracking_lost':
      if (!Number.isFinite(m.task_error)) return `tracking lost${at}`;
      return Number.isFinite(failure.bound) ? `tracking error ${errorAgainstBound(m.task_error, failure.bound)}${at}`
        : `tracking lost${at} (error ${centimetres(m.task_error)})`;
    case 'joint_limit':
      return `joint limit crossed${at}`;
    case 'nonfinite':
      return `non-finite output${at}`;
    case 'unrecorded':
      return 'fails the criterion (no frame shows where)';
    default:
      return `${failureModeText(failure.mode)}${at}`;
  }
}

// When each way of failing first shows in the stored frames, in seconds:
// {collision, self_collision, joint_limit, tracking_lost, clearance} (a key
// only where it shows). Frames strided beyond 20,000 give the time to a stride.
export function failureTimes(frames, dt, criterion = DEFAULT_CRITERION) {
  const c = { ...DEFAULT_CRITERION, ...criterion };
  const times = {};
  const first = (key, f) => { if (!(key in times)) times[key] = dt > 0 ? f.seq * dt : f.t; };
  for (const f of Array.isArray(frames) ? frames : []) {
    const m = f && f.metrics;
    if (!m || !Number.isFinite(f.seq)) continue;
    if (m.obstacle_collided ?? (m.collided === true && m.self_collided !== true)) first('collision', f);
    if (m.self_collided === true) first('self_collision', f);
    if (m.joint_limit_margin < 0) first('joint_limit', f);
    if (Number.isFinite(c.max_tracking_error) && m.task_error > c.max_tracking_error) first('tracking_lost', f);
    if (Number.isFinite(c.min_distance) && m.min_distance < c.min_distance) first('clearance', f);
  }
  return times;
}
