// The sweep page's fallback section (web/js/sweep_fallback.js) from a
// report's `fallbacks`, as sweep/sweep_report_json.cpp writes them.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { fallbackPair, fallbackSolved, unsolvedText, fallbackHtml } from '../../../web/js/sweep_fallback.js';

const row = (over = {}) => ({
  sweep: 's', family: 'urdf_shelf', cases: 100, solved_by_some: 97, first: 'task_priority', second: 'qp_constraints',
  pair_cases: 100, first_solved: 74, pair_solved: 90, cost_us: 12.14, configs_considered: 12, configs_total: 12,
  unsolved: { total: 3, witness_solves: 3, listed: [{ case: 'gen:urdf_shelf:1:12', seed: 1 }, { case: 'gen:urdf_shelf:1:66', seed: 1 }, { case: 'gen:urdf_shelf:1:93', seed: 1 }],
    generate: ['rrlab generate urdf_shelf --seed 1 --cases 12,66,93 --out unsolved/urdf_shelf-seed1'] },
  ...over,
});

test('a pair, a first choice alone, and no choice', () => {
  assert.equal(fallbackPair(row()), 'task_priority, then qp_constraints');
  assert.equal(fallbackSolved(row()), '74 → 90 of 100');
  assert.equal(fallbackPair(row({ second: null })), 'task_priority alone (no configuration solves a case it fails)');
  assert.equal(fallbackSolved(row({ second: null })), '74 of 100');
  assert.equal(fallbackPair(row({ first: null, second: null })), '—');
});

test('a family nothing solves names no method as its first choice', () => {
  const none = row({ solved_by_some: 0, second: null, first_solved: 0, pair_solved: 0, pair_cases: 3 });
  assert.equal(fallbackPair(none), 'none: no configuration solves any case');
  assert.equal(fallbackSolved(none), '0 of 3');
});

test('unsolved cases with the witness\'s count, and a listing cut short', () => {
  assert.equal(unsolvedText(row()), '3 of 100 (the witness solves 3): gen:urdf_shelf:1:12, gen:urdf_shelf:1:66, gen:urdf_shelf:1:93');
  const cut = row({ unsolved: { total: 60, witness_solves: null, listed: [{ case: 'a', seed: 1 }], generate: [] } });
  assert.equal(unsolvedText(cut), '60 of 100: a (the first 1 of 60)');
});

test('the section names the bound, lists each family and gives the commands', () => {
  const html = fallbackHtml({ fallbacks: [row(), row({ family: 'planar_clutter', unsolved: { total: 0, witness_solves: 0, listed: [], generate: [] } })],
    rules: { fallbacks: 'the <rule>' } });
  assert.match(html, /offline upper bound/);
  assert.match(html, /<tr data-family="urdf_shelf">/);
  assert.match(html, /<tr data-family="planar_clutter">/);
  assert.match(html, /<td>12.1<\/td>/);  // µs per step, 3 digits
  assert.match(html, /<pre class="mono small">rrlab generate urdf_shelf --seed 1 --cases 12,66,93 --out unsolved\/urdf_shelf-seed1<\/pre>/);
  assert.doesNotMatch(html, /class="unsolved" data-family="planar_clutter"/);  // nothing unsolved, nothing listed
  assert.match(html, /the &lt;rule&gt;/);  // escaped
  assert.equal(fallbackHtml({ fallbacks: [] }), '');
});
