// The scenario editor's JSON locator (web/js/scenario_editor.js): scanJson maps
// every JSON path to where its key and value sit in the text, locateJsonPath
// finds the span a server error's path names, lineColumn turns an offset into
// a line and column.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { scanJson, splitJsonPath, locateJsonPath, lineColumn } from '../../../web/js/scenario_editor.js';

const SCENARIO = `{
  "name": "two_links",
  "robot": {
    "links": [ { "length": 1.0 }, { "length": -0.4, "mass": 2 } ],
    "base": [0, 0]
  },
  "obstacles": [],
  "task": { "space": "xy", "gains": {}, "on": true, "off": false, "none": null },
  "e": -1.5e+3,
  "s": "a\\"b\\\\c\\u00e9\\n"
}`;

// The value a path names in a parsed document.
const valueAt = (doc, path) => splitJsonPath(path).reduce((v, p) => v[p], doc);

// A syntax error with its offset, as the editor reads it.
function syntaxError(text) {
  try {
    scanJson(text);
  } catch (e) {
    assert.ok(e instanceof Error);
    assert.equal(typeof e.offset, 'number', `no offset on ${e}`);
    return e;
  }
  assert.fail(`scanJson accepted ${JSON.stringify(text)}`);
}

test('scanJson records every value, with the paths the server writes', () => {
  const spans = scanJson(SCENARIO);
  assert.deepEqual([...spans.keys()].sort(), [
    '', 'e', 'name', 'obstacles', 'robot', 'robot.base', 'robot.base[0]', 'robot.base[1]',
    'robot.links', 'robot.links[0]', 'robot.links[0].length', 'robot.links[1]',
    'robot.links[1].length', 'robot.links[1].mass', 's', 'task', 'task.gains', 'task.none',
    'task.off', 'task.on', 'task.space',
  ]);
});

test('every value span parses to the value at its path, every key span to its key', () => {
  const doc = JSON.parse(SCENARIO);
  for (const [path, span] of scanJson(SCENARIO)) {
    assert.deepEqual(JSON.parse(SCENARIO.slice(span.valueStart, span.valueEnd)), valueAt(doc, path), path);
    const last = splitJsonPath(path).at(-1);
    if (typeof last === 'string') {
      assert.equal(JSON.parse(SCENARIO.slice(span.keyStart, span.keyEnd)), last, path);
    } else {
      assert.equal(span.keyStart, null, `${path}: an array entry has no key`);
      assert.equal(span.keyEnd, null);
    }
    const v = valueAt(doc, path);
    assert.equal(span.container, typeof v === 'object' && v !== null, `${path}: container`);
  }
});

test('the root value spans the text without its surrounding white space', () => {
  const text = ' \n\t {"a": 1} \r\n';
  assert.deepEqual(scanJson(text).get(''), { keyStart: null, keyEnd: null, valueStart: 4, valueEnd: 12, container: true });
  assert.deepEqual(scanJson('42').get(''), { keyStart: null, keyEnd: null, valueStart: 0, valueEnd: 2, container: false });
});

test('a root array names its entries [i], nested arrays [i][j]', () => {
  const spans = scanJson('[[1, 2], {"a": [3]}, "x"]');
  assert.deepEqual([...spans.keys()].sort(), ['', '[0]', '[0][0]', '[0][1]', '[1]', '[1].a', '[1].a[0]', '[2]']);
  assert.equal(spans.get('[0][1]').valueStart, 5);
  assert.equal(spans.get('[1].a[0]').valueStart, 16);
});

test('empty containers are recorded as values without entries', () => {
  const spans = scanJson('{"a": {}, "b": []}');
  assert.deepEqual(spans.get('a'), { keyStart: 1, keyEnd: 4, valueStart: 6, valueEnd: 8, container: true });
  assert.deepEqual(spans.get('b'), { keyStart: 10, keyEnd: 13, valueStart: 15, valueEnd: 17, container: true });
  assert.equal(spans.size, 3);
});

test('keys are decoded before they make a path; a repeated key keeps the last one, like JSON.parse', () => {
  const text = '{"a\\u0062": 1, "q\\"": 2, "k": 3, "k": 4}';
  const spans = scanJson(text);
  assert.ok(spans.has('ab'));
  assert.ok(spans.has('q"'));
  assert.equal(spans.get('k').valueStart, text.lastIndexOf('4'));
  assert.equal(JSON.parse('{"k": 3, "k": 4}').k, 4);
});

test('syntax errors say what is wrong and where', () => {
  const cases = [
    ['', 0, /expected a value, found the end of the text/],
    ['   ', 3, /expected a value, found the end of the text/],
    ['{"a": 1,}', 7, /“,” before “}”.*trailing comma/],
    ['{"a": 1,\n  }', 7, /trailing comma/],
    ['[1, 2,]', 5, /“,” before “]”.*trailing comma/],
    ['{"a": 1 "b": 2}', 7, /missing “,” after the value of "a"/],
    ['[1 2]', 2, /missing “,” between two entries of the array/],
    ['{"a" 1}', 5, /expected “:” after the key "a", found “1”/],
    ['{a: 1}', 1, /expected a "key" in quotes, found “a”/],
    ['{,}', 1, /expected a "key" in quotes/],
    ['{"a": }', 6, /expected a value, found “}”/],
    ['[,1]', 1, /expected a value, found “,”/],
    ['{"a": 1', 7, /expected “,” or “}” after the value of "a", found the end of the text/],
    ['{"a": 1]', 7, /expected “,” or “}” after the value of "a", found “]”/],
    ['[1, 2', 5, /expected “,” or “]” in the array, found the end of the text/],
    ['{"a": "x', 6, /never closed/],
    ['{"a": "x\ny"}', 8, /may not span lines/],
    ['"a\tb"', 2, /control character/],
    ['"\\q"', 1, /unknown escape \\q/],
    ['"\\u12G4"', 1, /four hex digits/],
    ['-', 0, /malformed number/],
    ['-a', 0, /malformed number/],
    ['01', 1, /unexpected “1” after the end of the JSON value/],
    ['1.', 1, /unexpected “.” after the end/],
    ['{} x', 3, /unexpected “x” after the end/],
    ['{}"', 2, /unexpected a string after the end/],
    ['tru', 0, /expected a value, found “t”/],
    ['nul', 0, /expected a value, found “n”/],
    ["{'a': 1}", 1, /expected a "key" in quotes, found “'”/],
  ];
  for (const [text, offset, message] of cases) {
    const e = syntaxError(text);
    assert.equal(e.offset, offset, `offset for ${JSON.stringify(text)}: ${e.message}`);
    assert.match(e.message, message, `message for ${JSON.stringify(text)}`);
    assert.ok(e.offset <= text.length);
  }
});

test('scanJson accepts exactly what JSON.parse accepts (fixed seeds, deterministic mutations)', () => {
  const seeds = [SCENARIO, '[[],{},"",0,-0,1e5,1E-2,0.5,"\\"\\\\\\/\\b\\f\\n\\r\\t\\uD83D\\uDE00"]', ' {"":{"":[true,false,null]}} '];
  const alphabet = '{}[],:"\\u01-.eE+ \nt\tranfls\x01\u2028x'.split('');
  let seed = 20240601;
  const random = (n) => { seed = (seed * 1103515245 + 12345) % 2147483648; return Math.floor((seed / 2147483648) * n); };
  let accepted = 0;
  for (let n = 0; n < 4000; ++n) {
    let s = seeds[random(seeds.length)];
    for (let k = 1 + random(3); k > 0; --k) {
      const p = random(s.length + 1);
      const c = alphabet[random(alphabet.length)];
      const op = random(3);
      s = op === 0 ? s.slice(0, p) + c + s.slice(p) : op === 1 ? s.slice(0, p) + s.slice(p + 1) : s.slice(0, p) + c + s.slice(p + 1);
    }
    let parsed = true;
    try { JSON.parse(s); } catch { parsed = false; }
    let scanned = true;
    try { scanJson(s); } catch (e) {
      scanned = false;
      assert.equal(typeof e.offset, 'number', `a syntax error with an offset for ${JSON.stringify(s)}`);
    }
    assert.equal(scanned, parsed, JSON.stringify(s));
    if (parsed) ++accepted;
  }
  assert.ok(accepted > 100 && accepted < 3900, `both kinds of input were tried (${accepted} valid)`);
});

test('splitJsonPath reads dotted keys, [index] and ["quoted keys"]', () => {
  assert.deepEqual(splitJsonPath('robot.links[3].length'), ['robot', 'links', 3, 'length']);
  assert.deepEqual(splitJsonPath('a["b.c"][0]'), ['a', 'b.c', 0]);
  assert.deepEqual(splitJsonPath('a["q\\"x"]'), ['a', 'q"x']);
  assert.deepEqual(splitJsonPath('[0][12]'), [0, 12]);
  assert.deepEqual(splitJsonPath('a.0'), ['a', '0'], 'a digit key after a dot is a key, not an index');
  assert.deepEqual(splitJsonPath(''), []);
});

test('locateJsonPath marks a scalar with its key, up to the end of its value', () => {
  const where = locateJsonPath(SCENARIO, 'robot.links[1].length');
  assert.equal(where.exact, true);
  assert.equal(SCENARIO.slice(where.start, where.end), '"length": -0.4');
  assert.equal(SCENARIO.slice(where.valueStart, where.valueEnd), '-0.4');
});

test('locateJsonPath marks an object or array by its key only, and spans its whole value', () => {
  const where = locateJsonPath(SCENARIO, 'robot.links');
  assert.equal(where.exact, true);
  assert.equal(SCENARIO.slice(where.start, where.end), '"links"');
  const value = SCENARIO.slice(where.valueStart, where.valueEnd);
  assert.ok(value.startsWith('[ {') && value.endsWith('} ]'));
});

test('locateJsonPath marks an array entry by its value: a scalar whole, a container by its opening bracket', () => {
  const scalar = locateJsonPath(SCENARIO, 'robot.base[1]');
  assert.equal(SCENARIO.slice(scalar.start, scalar.end), '0');
  assert.equal(scalar.exact, true);
  const entry = locateJsonPath(SCENARIO, 'robot.links[0]');
  assert.equal(SCENARIO.slice(entry.start, entry.end), '{');
  assert.equal(SCENARIO.slice(entry.valueStart, entry.valueEnd), '{ "length": 1.0 }');
});

test('locateJsonPath falls back to the nearest enclosing value for a missing key or index', () => {
  const missingKey = locateJsonPath(SCENARIO, 'robot.links[0].mass');
  assert.equal(missingKey.exact, false);
  assert.equal(SCENARIO.slice(missingKey.start, missingKey.end), '{');
  assert.equal(SCENARIO.slice(missingKey.valueStart, missingKey.valueEnd), '{ "length": 1.0 }');

  const missingIndex = locateJsonPath(SCENARIO, 'robot.links[7].length');
  assert.equal(missingIndex.exact, false);
  assert.equal(SCENARIO.slice(missingIndex.start, missingIndex.end), '"links"');

  const missingTop = locateJsonPath(SCENARIO, 'dt');
  assert.equal(missingTop.exact, false);
  assert.deepEqual([missingTop.start, missingTop.end], [0, 1], 'the root object, by its opening brace');

  const throughScalar = locateJsonPath(SCENARIO, 'name.first');
  assert.equal(throughScalar.exact, false);
  assert.equal(SCENARIO.slice(throughScalar.start, throughScalar.end), '"name": "two_links"');
});

test('locateJsonPath with no path, or an empty one, names the root value', () => {
  for (const path of ['', null, undefined]) {
    const where = locateJsonPath(SCENARIO, path);
    assert.deepEqual(where, { start: 0, end: 1, exact: true, valueStart: 0, valueEnd: SCENARIO.length });
  }
  assert.deepEqual(locateJsonPath(' 7 ', ''), { start: 1, end: 2, exact: true, valueStart: 1, valueEnd: 2 });
});

test('locateJsonPath resolves a ["quoted"] key and takes precomputed spans', () => {
  const text = '{"a": {"b.c": [1, 2]}}';
  const where = locateJsonPath(text, 'a["b.c"][1]');
  assert.equal(where.exact, true);
  assert.equal(text.slice(where.start, where.end), '2');
  const spans = scanJson(text);
  assert.deepEqual(locateJsonPath('ignored when spans are given', 'a', spans), locateJsonPath(text, 'a'));
  assert.equal(locateJsonPath(text, 'zzz', new Map()), null, 'nothing found at all');
});

test('locateJsonPath gives the span of the "name" string the editor rewrites', () => {
  const where = locateJsonPath(SCENARIO, 'name');
  assert.equal(SCENARIO.slice(where.valueStart, where.valueEnd), '"two_links"');
  const renamed = SCENARIO.slice(0, where.valueStart) + JSON.stringify('new') + SCENARIO.slice(where.valueEnd);
  assert.equal(JSON.parse(renamed).name, 'new');
  assert.deepEqual({ ...JSON.parse(renamed), name: 'two_links' }, JSON.parse(SCENARIO));
});

test('locateJsonPath throws the syntax error of text that is not JSON', () => {
  assert.throws(() => locateJsonPath('{"a": ', 'a'), (e) => e.offset === 6 && /expected a value/.test(e.message));
});

test('lineColumn counts lines and columns from 1; a newline belongs to the line it ends', () => {
  const text = 'ab\ncd\n\nef';
  assert.deepEqual(lineColumn(text, 0), { line: 1, column: 1 });
  assert.deepEqual(lineColumn(text, 2), { line: 1, column: 3 });
  assert.deepEqual(lineColumn(text, 3), { line: 2, column: 1 });
  assert.deepEqual(lineColumn(text, 6), { line: 3, column: 1 });
  assert.deepEqual(lineColumn(text, 8), { line: 4, column: 2 });
  assert.deepEqual(lineColumn('', 0), { line: 1, column: 1 });
  const e = syntaxError('{\n  "a": 1,\n}');
  assert.deepEqual(lineColumn('{\n  "a": 1,\n}', e.offset), { line: 2, column: 9 });
});
