// Which links a frame marks, for the 2D and the 3D view alike: the link
// nearest an obstacle ('nearest', red 'collided' when it touches it) and, when
// the arm touches itself, both links of the nearest self pair ('collided').
// The pair's colour is the whole mark: its two links cross where they touch,
// so a segment between them would have no length to show. Pure: no DOM.

// One entry per link: '' (the lane's own colour), 'nearest' or 'collided'.
export function linkMarks(metrics, count) {
  const marks = new Array(count).fill('');
  if (!metrics) return marks;
  const nearest = metrics.min_distance_link - 1;  // 1-based, 0: none
  if (nearest >= 0 && nearest < count) marks[nearest] = metrics.collided ? 'collided' : 'nearest';
  if (metrics.self_collided) {
    for (const link of [metrics.self_link_a, metrics.self_link_b])
      if (link >= 1 && link <= count) marks[link - 1] = 'collided';
  }
  return marks;
}
