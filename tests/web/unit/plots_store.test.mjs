// The plots' data store (web/js/plots_store.js): one lane's columns, fed by
// live WebSocket frames or by a stored run's frames.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { LaneSeries, chartedMetrics, diagnosticKey } from '../../../web/js/plots_store.js';

// A slice of the frame field table as GET /api/frame-fields gives it.
const field = (name, kind, metric, outputs = ['stored', 'csv', 'json']) =>
  ({ name, unit: '', kind, metric, outputs, description: name });
const FIELDS = [
  field('step', 'count', false), field('t', 'number', false), field('q', 'joints', false),
  field('task_error', 'number', true), field('orientation_error', 'number', true),
  field('min_distance', 'number', true), field('min_distance_link', 'link', true),
  field('collided', 'flag', true), field('joint_limit_margin', 'number', true),
  field('manipulability', 'number', true), field('condition_number', 'number', true),
  field('step_us', 'number', true, ['csv', 'json']), field('diagnostics', 'diagnostics', false),
];
const METRIC_KEYS = chartedMetrics(FIELDS);

const metrics = (x) => ({
  task_error: x, orientation_error: 0, min_distance: 2 * x, manipulability: 3 * x,
  condition_number: 1 + x, step_us: 10 * x,
});
const live = (t, x = t, diagnostics) => ({ t, metrics: metrics(x), ...(diagnostics ? { diagnostics } : {}) });

test('the numeric metrics of the table and diagnosticKey name the columns in order, metrics first', () => {
  assert.deepEqual(METRIC_KEYS, ['task_error', 'orientation_error', 'min_distance', 'joint_limit_margin',
    'manipulability', 'condition_number', 'step_us']);
  // a field frames do not carry as JSON is not charted
  assert.deepEqual(chartedMetrics([field('x', 'number', true, ['stored'])]), []);
  assert.equal(diagnosticKey('gain'), 'diag:gain');
  const s = new LaneSeries(['gain', 'task_error'], METRIC_KEYS);
  assert.deepEqual(s.keys, [...METRIC_KEYS, 'diag:gain', 'diag:task_error']);
  // a diagnostic named like a metric gets its own column
  assert.notEqual(s.column('task_error'), s.column('diag:task_error'));
});

test('a new lane is empty and an unknown key has no column', () => {
  const s = new LaneSeries([], METRIC_KEYS);
  assert.equal(s.length, 0);
  assert.deepEqual(s.t, []);
  assert.equal(s.columns.length, METRIC_KEYS.length);
  for (const k of METRIC_KEYS) assert.deepEqual(s.column(k), []);
  assert.equal(s.column('diag:missing'), null);
  assert.equal(s.column('nope'), null);
  assert.equal(s.orientationSeen, false);
});

test('the constructor copies the diagnostic names', () => {
  const names = ['a'];
  const s = new LaneSeries(names, METRIC_KEYS);
  names.push('b');
  assert.deepEqual(s.diagnosticNames, ['a']);
  assert.equal(s.column('diag:b'), null);
});

test('appendLive adds one row per frame, every column the same length, in order', () => {
  const s = new LaneSeries(['a', 'b'], METRIC_KEYS);
  assert.equal(s.appendLive(live(0.1, 1, [5, 6]), 10), true);
  assert.equal(s.appendLive(live(0.2, 2, [7, 8]), 10), true);
  assert.deepEqual(s.t, [0.1, 0.2]);
  assert.equal(s.length, 2);
  assert.deepEqual(s.column('task_error'), [1, 2]);
  assert.deepEqual(s.column('min_distance'), [2, 4]);
  assert.deepEqual(s.column('manipulability'), [3, 6]);
  assert.deepEqual(s.column('condition_number'), [2, 3]);
  assert.deepEqual(s.column('step_us'), [10, 20]);
  assert.deepEqual(s.column('diag:a'), [5, 7]);
  assert.deepEqual(s.column('diag:b'), [6, 8]);
  for (const col of s.columns) assert.equal(col.length, s.t.length);
});

test('appendLive skips a frame without a finite t and leaves the lane unchanged', () => {
  const s = new LaneSeries([], METRIC_KEYS);
  for (const t of [undefined, null, NaN, Infinity, -Infinity, '1']) {
    assert.equal(s.appendLive({ t, metrics: metrics(1) }, 10), false, `t = ${String(t)}`);
  }
  assert.equal(s.appendLive({}, 10), false);
  assert.equal(s.length, 0);
});

test('appendLive skips a repeated t (the display timer resending the newest frame)', () => {
  const s = new LaneSeries([], METRIC_KEYS);
  assert.equal(s.appendLive(live(1, 1), 10), true);
  assert.equal(s.appendLive(live(1, 99), 10), false);
  assert.deepEqual(s.t, [1]);
  assert.deepEqual(s.column('task_error'), [1]);
});

test('appendLive starts over on an earlier t (the run was reset)', () => {
  const s = new LaneSeries(['a'], METRIC_KEYS);
  s.appendLive({ t: 1, metrics: { ...metrics(1), orientation_error: 0.5 }, diagnostics: [1] }, 10);
  s.appendLive(live(2, 2, [2]), 10);
  assert.equal(s.orientationSeen, true);
  assert.equal(s.appendLive(live(0.5, 7, [3]), 10), true);
  assert.deepEqual(s.t, [0.5]);
  assert.deepEqual(s.column('task_error'), [7]);
  assert.deepEqual(s.column('diag:a'), [3]);
  assert.equal(s.orientationSeen, false, 'a reset forgets the orientation error seen before');
});

test('missing, null, NaN, infinite and non-numeric values become null (a gap)', () => {
  const s = new LaneSeries(['a'], METRIC_KEYS);
  s.appendLive({ t: 0 }, 10);                                  // no metrics at all
  s.appendLive({ t: 1, metrics: null, diagnostics: null }, 10);
  s.appendLive({ t: 2, metrics: { task_error: NaN, min_distance: Infinity, manipulability: '3', step_us: null },
    diagnostics: [-Infinity] }, 10);
  s.appendLive({ t: 3, metrics: { task_error: 0, min_distance: -1 } }, 10);
  assert.deepEqual(s.t, [0, 1, 2, 3]);
  assert.deepEqual(s.column('task_error'), [null, null, null, 0]);
  assert.deepEqual(s.column('min_distance'), [null, null, null, -1], 'a negative distance (penetration) is kept');
  assert.deepEqual(s.column('manipulability'), [null, null, null, null]);
  assert.deepEqual(s.column('step_us'), [null, null, null, null]);
  assert.deepEqual(s.column('diag:a'), [null, null, null, null]);
});

test('the condition number keeps only positive values (it is drawn on a log axis)', () => {
  const s = new LaneSeries([], METRIC_KEYS);
  [1e6, 0, -2, 1, NaN].forEach((c, i) => s.appendLive({ t: i, metrics: { condition_number: c } }, 100));
  assert.deepEqual(s.column('condition_number'), [1e6, null, null, 1, null]);
});

test('orientationSeen turns on with the first non-zero orientation error only', () => {
  const s = new LaneSeries([], METRIC_KEYS);
  s.appendLive({ t: 0, metrics: { orientation_error: 0 } }, 10);
  s.appendLive({ t: 1, metrics: { orientation_error: null } }, 10);
  s.appendLive({ t: 2, metrics: { orientation_error: NaN } }, 10);
  assert.equal(s.orientationSeen, false);
  s.appendLive({ t: 3, metrics: { orientation_error: -0.1 } }, 10);
  assert.equal(s.orientationSeen, true);
  s.appendLive({ t: 4, metrics: { orientation_error: 0 } }, 10);
  assert.equal(s.orientationSeen, true, 'stays on');
  assert.deepEqual(s.column('orientation_error'), [0, null, null, -0.1, 0]);
});

test('live diagnostics are positional: fewer values leave nulls, extra values are ignored', () => {
  const s = new LaneSeries(['a', 'b'], METRIC_KEYS);
  s.appendLive(live(0, 0), 10);                  // no diagnostics yet
  s.appendLive(live(1, 1, [1]), 10);             // only the first
  s.appendLive(live(2, 2, [2, 3, 4]), 10);       // one more than the lane knows
  s.appendLive({ t: 3, metrics: {}, diagnostics: { a: 9, b: 9 } }, 10);  // not an array: none
  assert.deepEqual(s.column('diag:a'), [null, 1, 2, null]);
  assert.deepEqual(s.column('diag:b'), [null, null, 3, null]);
  assert.equal(s.columns.length, METRIC_KEYS.length + 2);
});

test('the live window keeps one point older than the window so the line reaches the left edge', () => {
  const s = new LaneSeries([], METRIC_KEYS);
  for (let t = 0; t <= 10; ++t) s.appendLive(live(t), 3);
  // window [7, 10]: 6 is the one point before it
  assert.deepEqual(s.t, [6, 7, 8, 9, 10]);
  assert.deepEqual(s.column('task_error'), [6, 7, 8, 9, 10]);
  for (const col of s.columns) assert.equal(col.length, s.t.length);
});

test('a zero window keeps the newest point and the one before it', () => {
  const s = new LaneSeries([], METRIC_KEYS);
  for (let t = 0; t < 5; ++t) s.appendLive(live(t), 0);
  assert.deepEqual(s.t, [3, 4]);
});

test('a gap longer than the window still keeps the previous point', () => {
  const s = new LaneSeries([], METRIC_KEYS);
  s.appendLive(live(0), 1);
  s.appendLive(live(100), 1);
  assert.deepEqual(s.t, [0, 100]);
  s.appendLive(live(100.5), 1);
  assert.deepEqual(s.t, [0, 100, 100.5], 'the point before 99.5 is 0');
  s.appendLive(live(102), 1);
  assert.deepEqual(s.t, [100.5, 102]);
});

test('a live lane holds at most 2000 rows whatever the window, dropping the oldest', () => {
  const s = new LaneSeries(['a'], METRIC_KEYS);
  for (let i = 0; i < 2500; ++i) s.appendLive(live(i * 0.01, i, [i]), 1e9);
  assert.equal(s.length, 2000);
  assert.equal(s.column('task_error')[0], 500);
  assert.equal(s.column('task_error')[1999], 2499);
  assert.equal(s.column('diag:a')[0], 500);
  for (const col of s.columns) assert.equal(col.length, 2000);
});

test('setStored reads the stream\'s shape: nested metrics, diagnostics an array in the lane\'s order', () => {
  const s = new LaneSeries(['a', 'b'], METRIC_KEYS);
  s.setStored([
    { t: 0, metrics: { task_error: 1, orientation_error: 0, min_distance: 0.5, manipulability: 0.1, condition_number: 4 },
      diagnostics: [10, 20] },
    { t: 0.01, metrics: { task_error: 2 }, diagnostics: [null, 21, 99] },  // a null, one beyond the names
    { t: 0.02, metrics: { task_error: 3 } },                               // no diagnostics
    { t: 0.03, metrics: { task_error: 4 }, diagnostics: null },
    { t: 0.04, task_error: 5, diagnostics: { a: 1 } },                     // not the frame shape: nothing read
  ]);
  assert.deepEqual(s.t, [0, 0.01, 0.02, 0.03, 0.04]);
  assert.deepEqual(s.column('task_error'), [1, 2, 3, 4, null]);
  assert.deepEqual(s.column('min_distance'), [0.5, null, null, null, null]);
  assert.deepEqual(s.column('condition_number'), [4, null, null, null, null]);
  assert.deepEqual(s.column('step_us'), [null, null, null, null, null], 'step times are not stored');
  assert.deepEqual(s.column('diag:a'), [10, null, null, null, null]);
  assert.deepEqual(s.column('diag:b'), [20, 21, null, null, null]);
});

test('a stored frame and the same live frame make the same row', () => {
  const frame = { t: 0.5, metrics: { task_error: 1e-3, min_distance: 0.2, condition_number: 3 }, diagnostics: [7] };
  const stored = new LaneSeries(['a'], METRIC_KEYS), live = new LaneSeries(['a'], METRIC_KEYS);
  stored.setStored([frame]);
  live.appendLive(frame, 10);
  assert.deepEqual(stored.columns, live.columns);
});

test('setStored replaces what the lane held, skips frames without a finite t and keeps the whole run', () => {
  const s = new LaneSeries([], METRIC_KEYS);
  for (let t = 0; t < 5; ++t) s.appendLive(live(t), 10);
  s.setStored([{ t: 'x', metrics: { task_error: 1 } }, { metrics: { task_error: 2 } }, { t: 7, metrics: { task_error: 3 } }, { t: NaN }]);
  assert.deepEqual(s.t, [7]);
  assert.deepEqual(s.column('task_error'), [3]);

  const frames = Array.from({ length: 3000 }, (_, i) => ({ t: i * 0.01, metrics: { task_error: i } }));
  s.setStored(frames);
  assert.equal(s.length, 3000, 'no live cap for a stored run');
  assert.equal(s.column('task_error')[2999], 2999);

  s.setStored([]);
  assert.equal(s.length, 0);
  for (const col of s.columns) assert.deepEqual(col, []);
});

test('setStored keeps frames in the order given, neither sorted nor deduplicated', () => {
  const s = new LaneSeries([], METRIC_KEYS);
  s.setStored([{ t: 2 }, { t: 1 }, { t: 1 }]);
  assert.deepEqual(s.t, [2, 1, 1]);
});

test('setStored notes a non-zero orientation error and forgets an earlier one', () => {
  const s = new LaneSeries([], METRIC_KEYS);
  s.setStored([{ t: 0, metrics: { orientation_error: 0 } }, { t: 1, metrics: { orientation_error: 0.2 } }]);
  assert.equal(s.orientationSeen, true);
  s.setStored([{ t: 0, metrics: { orientation_error: 0 } }]);
  assert.equal(s.orientationSeen, false);
});

test('clear empties every column and keeps the keys', () => {
  const s = new LaneSeries(['a'], METRIC_KEYS);
  s.appendLive(live(1, 1, [1]), 10);
  const keys = s.keys.slice();
  s.clear();
  assert.equal(s.length, 0);
  assert.deepEqual(s.keys, keys);
  for (const col of s.columns) assert.deepEqual(col, []);
  assert.equal(s.appendLive(live(0.5, 1, [1]), 10), true, 'any t is new after a clear');
});
