// Which charts the dashboard shows and how each becomes a uPlot: a spec per
// chart (its series per lane, its axes and scales), then the uPlot options.
import uPlot from 'uplot';

const SLATE = '#37474f';
const GREY = '#607d8b';
const RED = '#c62828';
const GRID = '#eceff1';
const TICKS = '#cfd8dc';
const FONT = '12px system-ui, -apple-system, "Segoe UI", Roboto, sans-serif';
const LABEL_FONT = '600 12px system-ui, -apple-system, "Segoe UI", Roboto, sans-serif';
export const CHART_HEIGHT = 160;     // canvas, x axis included; the legend sits below
const AXIS_SIZE = 60;                 // both sides on every chart, so the time axes line up
const SECOND_DASH = [6, 4];           // the second quantity of a chart, per lane

// The metrics the charts below draw; any other metric of the frame field
// table is offered for ticking and gets a chart of its own (extraMetrics).
export const CHARTED_METRICS = ['task_error', 'orientation_error', 'min_distance', 'manipulability',
  'condition_number', 'step_us'];

// The table's metrics without a chart of their own, as fields {name, unit, description}.
export function extraMetrics(fields, metricKeys) {
  return fields.filter((f) => metricKeys.includes(f.name) && !CHARTED_METRICS.includes(f.name));
}

// The charts for the given lanes and options, top to bottom. A spec's
// `signature` changes when its uPlot must be rebuilt (series or axes differ).
// tickedMetrics: extra metrics (fields) ticked for a chart.
export function chartSpecs({ lanes, orientation, stepTimes, ticked, tickedMetrics = [] }) {
  const compare = lanes.length > 1;
  const per = (key, name, short, scale, dash) => lanes.map((lane, i) => ({
    lane: i, key, scale, dash, colour: lane.colour,
    label: compare ? (dash ? `${lane.label} · ${short}` : lane.label) : name,
  }));
  const specs = [];
  const error = {
    id: 'error', title: 'Task error',
    left: { scale: 'm', label: 'position (m)' },
    series: per('task_error', 'position error', 'position', 'm', null),
  };
  if (orientation) {
    error.right = { scale: 'rad', label: 'orientation (rad)' };
    error.series.push(...per('orientation_error', 'orientation error', 'orient.', 'rad', SECOND_DASH));
  }
  specs.push(error);
  specs.push({
    id: 'distance', title: 'Minimum distance to obstacles',
    left: { scale: 'dist', label: 'distance (m)', includeZero: true },
    series: per('min_distance', 'min distance', 'dist', 'dist', null),
    collisionLine: true,
  });
  specs.push({
    id: 'conditioning', title: 'Manipulability w and condition number κ',
    left: { scale: 'w', label: 'manipulability' },
    right: { scale: 'kappa', label: 'κ (log scale)', log: true },
    series: [...per('manipulability', 'manipulability', 'w', 'w', null),
      ...per('condition_number', 'condition number', 'κ', 'kappa', SECOND_DASH)],
  });
  if (stepTimes) {
    specs.push({
      id: 'step', title: 'Step compute time',
      left: { scale: 'us', label: 'time (µs)', includeZero: true, robust: true },  // slow first steps drawn off the top
      series: per('step_us', 'step time', 'µs', 'us', null),
    });
  }
  for (const field of tickedMetrics) {
    specs.push({  // the axis names the unit only: the title names the field
      id: `metric:${field.name}`, title: `${field.name}: ${field.description}`,
      left: { scale: field.name, label: field.unit ? field.unit.replace('|', ' or ') : '' },
      series: per(field.name, field.name, field.name, field.name, null),
    });
  }
  for (const name of ticked) {
    const series = [];
    lanes.forEach((lane, i) => {
      if (lane.diagnosticNames.includes(name))
        series.push({ lane: i, key: `diag:${name}`, scale: 'd', dash: null, colour: lane.colour, label: compare ? lane.label : name });
    });
    specs.push({ id: `diag:${name}`, title: `Diagnostic: ${name}`, left: { scale: 'd', label: '' }, series });
  }
  for (const s of specs)
    s.signature = JSON.stringify([s.left, s.right, s.series.map((x) => [x.lane, x.key, x.label, x.colour])]);
  return specs;
}

// Short numbers for ticks and the legend: 3 significant digits, exponents
// for the very small and very large.
export function formatValue(v) {
  if (v === null || v === undefined || !Number.isFinite(v)) return '—';
  const a = Math.abs(v);
  if (a === 0) return '0';
  if (a >= 1e5 || a < 1e-3) return v.toExponential(1).replace('e+', 'e');
  return String(Number(v.toPrecision(3)));
}

// Linear-axis ticks in one style per axis: exponents when every tick is tiny
// or huge, else as many decimals as the tick step needs (0.25 → 2).
function axisValues(u, splits) {
  const ticks = splits.filter((v) => v !== null && Number.isFinite(v));
  const maxAbs = Math.max(0, ...ticks.map(Math.abs));
  if (maxAbs >= 1e5 || (maxAbs > 0 && maxAbs < 1e-3))
    return splits.map((v) => (v === null ? '' : v === 0 ? '0' : v.toExponential(1).replace('e+', 'e')));
  let step = Infinity;
  for (let i = 1; i < ticks.length; ++i) step = Math.min(step, Math.abs(ticks[i] - ticks[i - 1]));
  const fraction = Number.isFinite(step) ? String(Number(step.toPrecision(6))).split('.')[1] : '';
  const decimals = Math.min(6, fraction ? fraction.length : 0);
  return splits.map((v) => (v === null ? '' : Math.abs(v) < 1e-12 ? '0' : v.toFixed(decimals)));
}

// Log-axis ticks: decades when the range spans a few, else 1-2-5 or every
// integer mantissa, thinned so labels never overlap a ~110 px tall plot.
const MAX_LOG_TICKS = 5;
function logSplits(u, axisIdx, min, max) {
  const lo = Math.floor(Math.log10(min));
  const hi = Math.ceil(Math.log10(max));
  let ticks = [];
  for (const mantissas of [[1], [1, 2, 5], [1, 2, 3, 4, 5, 6, 7, 8, 9]]) {
    ticks = [];
    for (let e = lo; e <= hi; ++e) {
      for (const m of mantissas) {
        const v = m * 10 ** e;
        if (v >= min * 0.9999 && v <= max * 1.0001) ticks.push(v);
      }
    }
    if (ticks.length >= 3) break;
  }
  if (ticks.length < 3) ticks = linearTicks(min, max);  // a near-constant κ: under a factor of 2
  const every = Math.ceil(ticks.length / MAX_LOG_TICKS);
  return ticks.filter((v, i) => i % every === 0);
}

function linearTicks(min, max) {
  const raw = (max - min) / 3;
  const magnitude = 10 ** Math.floor(Math.log10(raw));
  const step = [1, 2, 5, 10].map((m) => m * magnitude).find((x) => x >= raw);
  const ticks = [];
  for (let v = Math.ceil(min / step) * step; v <= max; v += step) ticks.push(Number(v.toPrecision(6)));
  return ticks;
}

function formatLogTick(v) {
  if (v === null) return '';
  return v >= 1e4 ? v.toExponential(0).replace('e+', 'e') : String(Number(v.toPrecision(3)));
}

function linearRange(includeZero) {
  return (u, min, max) => {
    if (min === null || max === null || !Number.isFinite(min)) return includeZero ? [0, 1] : [0, 1];
    let lo = includeZero ? Math.min(0, min) : min;
    let hi = includeZero ? Math.max(0, max) : max;
    if (hi - lo < 1e-12) { const d = Math.abs(hi) * 0.1 || 0.1; lo -= d; hi += d; }
    const pad = (hi - lo) * 0.08;
    return [lo - pad, hi + pad];
  };
}

// 15 % (multiplicative) around the data; a near-constant κ still shows ticks.
function logRange(u, min, max) {
  if (min === null || max === null || !(min > 0)) return [1, 10];
  return [min / 1.15, max * 1.15];
}

// A range that a few outliers do not flatten (the first steps of a run, which
// warm caches and build the method's state, can take 100× a later one): up to
// 1.3 × the 98th percentile of the scale's values, when the largest is above it.
// The outliers are drawn off the top. Exported for its unit test.
export function robustMax(values) {
  const finite = values.filter((v) => Number.isFinite(v)).sort((a, b) => a - b);
  if (finite.length < 20) return finite.length ? finite[finite.length - 1] : null;
  const p98 = finite[Math.floor(0.98 * (finite.length - 1))];
  return Math.min(finite[finite.length - 1], 1.3 * p98);
}

function robustRange(scale) {
  const linear = linearRange(true);
  return (u, min, max) => {
    const values = [];
    u.series.forEach((s, i) => { if (i > 0 && s.scale === scale && u.data[i]) for (const v of u.data[i]) values.push(v); });
    const top = robustMax(values);
    return linear(u, min, top === null ? max : Math.min(max, top));
  };
}

function scaleOptions(side) {
  if (side.log) return { distr: 3, log: 10, range: logRange };
  if (side.robust) return { range: robustRange(side.scale) };
  return { range: linearRange(side.includeZero) };
}

function axis(side, scale, label) {
  return {
    scale, side, label, size: AXIS_SIZE, labelSize: 18, labelFont: LABEL_FONT, font: FONT, stroke: SLATE,
    grid: { show: side === 3, stroke: GRID, width: 1 },
    ticks: { stroke: TICKS, width: 1, size: 4 },
  };
}

// The y axes: the left one always, the right one for a second quantity or
// blank (same width) so every chart's plot area spans the same times.
function yAxes(spec) {
  const left = { ...axis(3, spec.left.scale, spec.left.label), values: axisValues };
  if (!spec.right) return [left, { ...axis(1, spec.left.scale, ''), values: () => [], ticks: { show: false } }];
  const right = axis(1, spec.right.scale, spec.right.label);
  if (spec.right.log) {
    right.splits = logSplits;
    right.filter = (u, splits) => splits;  // uPlot's own log filter would blank ours
    right.values = (u, splits) => splits.map(formatLogTick);
  } else {
    right.values = axisValues;
  }
  return [left, right];
}

// A red line at zero distance, labelled: below it the arm is in collision.
function drawCollisionLine(u) {
  const y = Math.round(u.valToPos(0, 'dist', true)) + 0.5;
  const { left, top, width, height } = u.bbox;
  if (y < top || y > top + height) return;
  const ctx = u.ctx;
  const px = uPlot.pxRatio;
  ctx.save();
  ctx.strokeStyle = RED;
  ctx.lineWidth = 1.5 * px;
  ctx.setLineDash([]);
  ctx.beginPath();
  ctx.moveTo(left, y);
  ctx.lineTo(left + width, y);
  ctx.stroke();
  ctx.fillStyle = RED;
  ctx.font = `600 ${Math.round(11 * px)}px system-ui, sans-serif`;
  ctx.textAlign = 'right';
  ctx.textBaseline = 'bottom';
  ctx.fillText('collision', left + width - 4 * px, y - 2 * px);
  ctx.restore();
}

// uPlot options for a spec. `xRange(min, max)` picks the visible times
// (rolling window or whole run); `onDraw(u)` runs after every redraw,
// `onCursor(u)` after every cursor move (and when it leaves the chart).
// Lanes drawn later are thinner, so a lane hidden under an identical one
// still shows as a border.
const laneWidth = (lane) => 2.25 - 0.35 * lane;

export function chartOptions(spec, { width, syncKey, xRange, onDraw, onCursor }) {
  const scales = { x: { time: false, range: (u, min, max) => xRange(min, max) } };
  scales[spec.left.scale] = scaleOptions(spec.left);
  if (spec.right) scales[spec.right.scale] = scaleOptions(spec.right);
  const draw = [onDraw];
  if (spec.collisionLine) draw.unshift(drawCollisionLine);
  return {
    width, height: CHART_HEIGHT,
    scales,
    series: [
      { label: 'time', value: (u, v) => (v === null || v === undefined ? '—' : `${v.toFixed(2)} s`) },
      ...spec.series.map((s) => ({
        label: s.label, scale: s.scale, stroke: s.colour, width: laneWidth(s.lane), dash: s.dash || undefined,
        points: { show: false }, spanGaps: false,
        value: (u, v) => formatValue(v),
      })),
    ],
    axes: [
      {
        ...axis(2, 'x', ''), size: 28, labelSize: 0,
        grid: { show: true, stroke: GRID, width: 1 },
        values: (u, splits) => splits.map((v) => `${formatValue(v)} s`),
      },
      ...yAxes(spec),
    ],
    cursor: {
      sync: { key: syncKey, setSeries: false },
      drag: { x: false, y: false },
      y: false,  // a horizontal hair means nothing on the other, synced charts
      points: { size: 6 },
    },
    legend: {
      live: true,
      markers: { width: 2, dash: (u, i) => (u.series[i].dash ? 'dashed' : 'solid') },
    },
    hooks: { draw, setCursor: [onCursor] },
  };
}
