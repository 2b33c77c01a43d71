// The page's state in the address bar (web/js/state.js): which run, comparison,
// scenario, method and frame a link opens, and the query string the page
// writes back as the session changes.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { parseUrlState, formatUrlState, readUrl, writeUrl } from '../../../web/js/state.js';

const DEFAULTS = { run: null, compare: [], sweep: null, family: null, config: null, paper: null, scenario: null, method: null, frame: null };

test('an empty query string opens nothing: every field at its default', () => {
  assert.deepEqual(parseUrlState(''), DEFAULTS);
  assert.deepEqual(parseUrlState('?'), DEFAULTS);
});

test('a run with a frame, with or without the leading "?"', () => {
  const expected = { ...DEFAULTS, run: 12, frame: 40 };
  assert.deepEqual(parseUrlState('?run=12&frame=40'), expected);
  assert.deepEqual(parseUrlState('run=12&frame=40'), expected);
  assert.deepEqual(parseUrlState('?frame=40&run=12'), expected, 'order does not matter');
});

test('a sweep is named by its id', () => {
  assert.deepEqual(parseUrlState('?sweep=4'), { ...DEFAULTS, sweep: 4 });
  assert.equal(parseUrlState('?sweep=x').sweep, null);
  assert.equal(parseUrlState('?sweep=0').sweep, null);
});

test('a comparison lists its runs in order, commas plain or encoded', () => {
  assert.deepEqual(parseUrlState('?compare=3,1,2').compare, [3, 1, 2]);
  assert.deepEqual(parseUrlState('?compare=3%2C1%2C2').compare, [3, 1, 2]);
  assert.deepEqual(parseUrlState('?compare=5').compare, [5]);
});

test('a scenario and a method are taken as written, decoded', () => {
  const url = parseUrlState('?scenario=two%20links&method=closest_point');
  assert.equal(url.scenario, 'two links');
  assert.equal(url.method, 'closest_point');
  assert.equal(parseUrlState('?scenario=a+b').scenario, 'a b', '"+" is a space in a query string');
});

test('run ids that are not positive integers are dropped', () => {
  for (const bad of ['0', '-3', '2.5', 'abc', '', 'NaN', 'Infinity']) {
    assert.equal(parseUrlState(`?run=${bad}`).run, null, `run=${bad}`);
  }
  assert.deepEqual(parseUrlState('?compare=1,x,-2,0,2.5,,3').compare, [1, 3]);
  assert.deepEqual(parseUrlState('?compare=').compare, []);
});

test('run names one run: of a list, the first valid id', () => {
  assert.equal(parseUrlState('?run=5,6').run, 5);
  assert.equal(parseUrlState('?run=x,6').run, 6);
  assert.equal(parseUrlState('?run=0x10').run, null, 'hex is not an id');
  assert.equal(parseUrlState('?run=1e2').run, null, 'an exponent is not an id');
});

test('a frame must be a non-negative integer; frame 0 is a frame', () => {
  assert.equal(parseUrlState('?run=1&frame=0').frame, 0);
  // only decimal digits: an empty value is no frame (not frame 0), nor are hex, exponents or spaces
  for (const bad of ['-1', '2.5', 'abc', 'Infinity', '', '0x10', '1e2', '%203']) {
    assert.equal(parseUrlState(`?run=1&frame=${bad}`).frame, null, `frame=${bad}`);
  }
  assert.equal(parseUrlState('?run=1').frame, null);
});

test('unknown keys are ignored and a repeated key keeps its first value', () => {
  const url = parseUrlState('?foo=1&run=2&bar=&run=3&layout=stacked');
  assert.deepEqual(url, { ...DEFAULTS, run: 2 });
  assert.deepEqual(Object.keys(url).sort(), ['compare', 'config', 'family', 'frame', 'method', 'paper', 'run', 'scenario', 'sweep']);
});

test('formatUrlState writes the given keys in order and drops null, undefined and empty values', () => {
  assert.equal(formatUrlState({}), '');
  assert.equal(formatUrlState({ run: null, compare: undefined, frame: '' }), '');
  assert.equal(formatUrlState({ run: '7', compare: null, frame: 12 }), '?run=7&frame=12');
  assert.equal(formatUrlState({ frame: 0, run: 3 }), '?frame=0&run=3', 'frame 0 is kept');
  assert.equal(formatUrlState({ scenario: 'two links & more', method: 'dls' }), '?scenario=two+links+%26+more&method=dls');
});

test('what the page writes reads back as the same state', () => {
  const cases = [
    [{ run: '7', compare: null, frame: 12 }, { ...DEFAULTS, run: 7, frame: 12 }],
    [{ run: '7', compare: null, frame: null }, { ...DEFAULTS, run: 7 }],
    [{ run: null, compare: '4,9,2', frame: 0 }, { ...DEFAULTS, compare: [4, 9, 2], frame: 0 }],
    [{ run: null, compare: [4, 9], frame: null }, { ...DEFAULTS, compare: [4, 9] }],
    [{ scenario: 'a b&c=d?#', method: 'gpm' }, { ...DEFAULTS, scenario: 'a b&c=d?#', method: 'gpm' }],
    [{}, DEFAULTS],
  ];
  for (const [params, state] of cases) {
    assert.deepEqual(parseUrlState(formatUrlState(params)), state, JSON.stringify(params));
  }
});

test('readUrl reads location.search; writeUrl replaces the address only when it changes', (t) => {
  const saved = { location: globalThis.location, history: globalThis.history };
  t.after(() => Object.assign(globalThis, saved));
  const calls = [];
  globalThis.location = { pathname: '/', search: '?run=3&frame=5' };
  globalThis.history = { replaceState: (...args) => calls.push(args) };

  assert.deepEqual(readUrl(), { ...DEFAULTS, run: 3, frame: 5 });
  writeUrl({ run: 3, compare: null, frame: 5 });
  assert.deepEqual(calls, [], 'the same address: no replaceState');
  writeUrl({ run: 3, frame: 6 });
  assert.deepEqual(calls, [[null, '', '/?run=3&frame=6']]);

  calls.length = 0;
  globalThis.location = { pathname: '/dash/', search: '?scenario=x' };
  writeUrl({});
  assert.deepEqual(calls, [[null, '', '/dash/']], 'no state: the bare path');
  globalThis.location = { pathname: '/dash/', search: '' };
  writeUrl({ scenario: '' });
  assert.equal(calls.length, 1, 'already bare: nothing to replace');
});

test("a sweep's cell: family and config together, and only with a sweep", () => {
  assert.deepEqual(parseUrlState('?sweep=4&family=planar_clutter&config=dls%20%C2%B7%20lambda%3D0.1'),
    { ...DEFAULTS, sweep: 4, family: 'planar_clutter', config: 'dls · lambda=0.1' });
  assert.equal(parseUrlState('?sweep=4&family=f').family, null, 'a family without a config is no cell');
  assert.equal(parseUrlState('?family=f&config=c').config, null, 'a cell without a sweep is nothing');
  assert.equal(parseUrlState('?sweep=x&family=f&config=c').family, null, 'nor with a malformed sweep id');
});

test('writeUrl pushes a history entry for a new view and replaces for a frame or a pick', (t) => {
  const saved = { location: globalThis.location, history: globalThis.history };
  t.after(() => Object.assign(globalThis, saved));
  const calls = [];
  const go = (search) => { globalThis.location = { pathname: '/', search }; };
  globalThis.history = {
    pushState: (_, __, url) => { calls.push(['push', url]); go(url.slice(1)); },
    replaceState: (_, __, url) => { calls.push(['replace', url]); go(url.slice(1)); },
  };
  go('');
  writeUrl({ scenario: 'a', method: 'dls' });  // the start view still
  writeUrl({ paper: 'sezgin' });
  writeUrl({ sweep: 3 });
  writeUrl({ sweep: 3, family: 'f', config: 'c' });
  writeUrl({ run: 9 });
  writeUrl({ run: 9, frame: 0 });
  writeUrl({ run: 9, frame: 40 });
  writeUrl({ run: 9, frame: 41 }, { push: true });  // a marker clicked
  writeUrl({ compare: '9,10' });
  writeUrl({}, { replace: true });  // the compare's run was deleted
  assert.deepEqual(calls, [
    ['replace', '/?scenario=a&method=dls'], ['push', '/?paper=sezgin'], ['push', '/?sweep=3'],
    ['push', '/?sweep=3&family=f&config=c'], ['push', '/?run=9'], ['replace', '/?run=9&frame=0'],
    ['replace', '/?run=9&frame=40'], ['push', '/?run=9&frame=41'], ['push', '/?compare=9%2C10'], ['replace', '/'],
  ]);
});
