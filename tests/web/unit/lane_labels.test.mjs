// Lane labels (web/js/lane_labels.js): the method alone when it is unique,
// else the method plus the parameters in which the lanes differ.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { laneLabels, formatValue } from '../../../web/js/lane_labels.js';

test('a method unique among the lanes is its own label', () => {
  assert.deepEqual(laneLabels([{ method: 'pinv', params: { lambda: 0.1 } }, { method: 'dls', params: { lambda: 0.1 } }]), ['pinv', 'dls']);
});

test('lanes sharing a method name the parameters in which they differ', () => {
  const lanes = [
    { method: 'ccp_voronoi', params: { ccp_link: 3, gain: 5 } },
    { method: 'ccp_voronoi', params: { ccp_link: 2, gain: 5 } },
    { method: 'pinv', params: { gain: 5 } },
  ];
  assert.deepEqual(laneLabels(lanes), ['ccp_voronoi · ccp_link=3', 'ccp_voronoi · ccp_link=2', 'pinv']);
});

test('several differing parameters are sorted by name', () => {
  const lanes = [
    { method: 'dls', params: { lambda: 0.05, gain: 8, damping_max: 1 } },
    { method: 'dls', params: { lambda: 0.1, gain: 4, damping_max: 1 } },
  ];
  assert.deepEqual(laneLabels(lanes), ['dls · gain=8, lambda=0.05', 'dls · gain=4, lambda=0.1']);
});

test('a parameter one lane leaves out is its default', () => {
  assert.deepEqual(laneLabels([{ method: 'dls', params: {} }, { method: 'dls', params: { lambda: 0.2 } }]),
    ['dls · lambda=default', 'dls · lambda=0.2']);
});

test('lanes alike in everything are numbered', () => {
  assert.deepEqual(laneLabels([{ method: 'pinv' }, { method: 'pinv' }, { method: 'dls' }]), ['pinv · #1', 'pinv · #2', 'dls']);
});

test('values are compact', () => {
  assert.equal(formatValue(0.30000000000000004), '0.3');
  assert.equal(formatValue(1234567), '1235000');
  assert.equal(formatValue([0.1, 2]), '[0.1,2]');
  assert.equal(formatValue(true), 'true');
  assert.equal(formatValue('soft'), 'soft');
});
