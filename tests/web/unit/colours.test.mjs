// The nearest-link highlight and the collision colour never coincide with a
// compare lane's colour (a highlighted link of one lane must not read as
// another lane's arm).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { LANE_COLOURS, NEAREST_LINK_COLOUR, COLLIDED_COLOUR } from '../../../web/js/state.js';

const rgb = (hex) => [1, 3, 5].map((i) => parseInt(hex.slice(i, i + 2), 16));
const distance = (a, b) => Math.hypot(...rgb(a).map((v, i) => v - rgb(b)[i]));

test('highlight colours are far from every lane colour', () => {
  for (const lane of LANE_COLOURS) {
    for (const highlight of [NEAREST_LINK_COLOUR, COLLIDED_COLOUR]) {
      assert.ok(distance(lane, highlight) > 80, `${highlight} is too close to lane colour ${lane} (${distance(lane, highlight).toFixed(0)})`);
    }
  }
});
