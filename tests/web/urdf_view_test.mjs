// The dashboard's 3D view draws the URDF arms (scenarios 40 iiwa 14, 41 Panda,
// 42 Gen3) against a real `rrlab serve`: a live run, paused at its first
// frame, opened from its link. For each arm: the view is three.js (WebGL 2),
// 7 link capsules are drawn, each link mesh and joint sphere sits where the
// server's frame puts that link, the drawn tip is the frame's end-effector
// and lies on the scenario's task circle,
// and the camera frames the arm (every link end inside the picture, the arm
// its link axes over a quarter of the picture's height). Then the run plays and the drawn
// tip follows the frames. Screenshots: $RRLAB_SCREENSHOTS/urdf-view-*.png.
// Usage: node urdf_view_test.mjs   (exit 0 on success)
import { join } from 'node:path';
import { suite, eventually, check, screenshotDir } from './harness.mjs';

const arms = [['40_urdf_iiwa14_pose', 'iiwa14'], ['41_urdf_panda_pose', 'panda'], ['42_urdf_gen3_pose', 'gen3']];

// What the page draws against what the server sent, after a forced draw of
// the view's latest frame: the largest distance (m) between a drawn part
// (cylinder centre, joint sphere, end cap) and the frame's segment. A
// zero-length link (the Panda's joints 1 and 2 share an origin) has no
// cylinder, only its spheres.
const drawnVsFrame = (page) => page.evaluate(() => {
  const lane = window.__rrlab.session.lanes[0], view = lane.view, arm = view.arm;
  view.dirty = true;
  view.render();
  const frame = view.frame;
  const dist = (v, p) => Math.hypot(v.x - p[0], v.y - p[1], v.z - p[2]);
  let worst = 0, visible = 0, nonzero = 0;
  frame.links.forEach((l, i) => {
    const s = [l[0], l[1], l[2]], e = [l[3], l[4], l[5]], mid = s.map((x, k) => (x + e[k]) / 2);
    const length = Math.hypot(e[0] - s[0], e[1] - s[1], e[2] - s[2]);
    if (length > 1e-9) { nonzero += 1; worst = Math.max(worst, dist(arm.links[i].position, mid)); }
    if (arm.links[i].visible) visible += 1;
    if (arm.joints[i].visible && arm.caps[i].visible) worst = Math.max(worst, dist(arm.joints[i].position, s), dist(arm.caps[i].position, e));
    else worst = Infinity;
  });
  const tip = arm.caps[frame.links.length - 1].position;
  // the arm's picture: its base and every link end projected to the page, against the view's canvas
  const rect = view.renderer.domElement.getBoundingClientRect();
  const points = [view.worldToClient(lane.snapshot.model.base)]
    .concat(frame.links.flatMap((l) => [view.worldToClient([l[0], l[1], l[2]]), view.worldToClient([l[3], l[4], l[5]])]));
  const xs = points.map((p) => p.x), ys = points.map((p) => p.y);
  return {
    step: frame.step, dof: lane.snapshot.model.dof, kind: lane.snapshot.model.kind,
    modelLinks: lane.snapshot.model.links.length, meshes: arm.links.length, visible, nonzero, worst,
    tipError: dist(tip, frame.ee), tip: [tip.x, tip.y, tip.z], ee: frame.ee,
    webgl2: view.renderer.getContext() instanceof WebGL2RenderingContext,
    picture: { left: Math.min(...xs) - rect.left, right: Math.max(...xs) - rect.left, top: Math.min(...ys) - rect.top,
      bottom: Math.max(...ys) - rect.top, width: rect.width, height: rect.height },
  };
});

await suite('urdf view', arms.map(([scenario, arm]) => [`${scenario} draws the arm where the server's frame puts it`, async (t) => {
  const run = await t.post('/api/runs', { scenario, mode: 'live', rate: 1, paused: true });
  await t.page.goto(`${t.base}/?run=${run.id}`);
  await eventually(() => t.page.evaluate(() => {
    const lane = window.__rrlab.session && window.__rrlab.session.lanes[0];
    return lane && lane.frame && lane.view && lane.view.arm && lane.view.renderer;
  }), 'the 3D view with a frame');
  // a draw after the first frame
  await eventually(() => t.page.evaluate(() => { const v = window.__rrlab.session.lanes[0].view; return v.stats.renders > 0 && !v.dirty; }), 'the first frame drawn');
  const d = await drawnVsFrame(t.page);
  console.log(`  ${arm}: ${d.visible} of ${d.meshes} link cylinders drawn (${d.nonzero} links of non-zero length), worst offset ${d.worst.toExponential(1)} m, `
    + `tip [${d.tip.map((x) => x.toFixed(4))}] vs ee [${d.ee.map((x) => x.toFixed(4))}]; arm's picture x ${d.picture.left.toFixed(0)}–${d.picture.right.toFixed(0)} `
    + `of ${d.picture.width.toFixed(0)}, y ${d.picture.top.toFixed(0)}–${d.picture.bottom.toFixed(0)} of ${d.picture.height.toFixed(0)} px`);
  check(d.webgl2, 'a WebGL 2 context');
  check(d.kind === 'urdf' && d.dof === 7 && d.modelLinks === 7, `a 7-link urdf model (${d.kind}, ${d.dof} joints, ${d.modelLinks} links)`);
  check(d.meshes === 7, `7 links in the drawn arm (${d.meshes})`);
  check(d.visible === d.nonzero && d.nonzero >= 6, `a cylinder for every link of non-zero length (${d.visible} drawn, ${d.nonzero} such links)`);
  check(d.worst < 1e-9, `every drawn link sits on the frame's segment (worst ${d.worst} m)`);
  check(d.tipError < 1e-9, `the drawn tip is the frame's end-effector (${d.tipError} m apart)`);
  // and it lies where the scenario file says the task starts: on its circle (the scenarios put the
  // circle through the tool at q0; measured task error at step 0: 2.8e-5, 3.8e-5, 1.4e-5 m)
  const { center, radius, normal } = (await t.get(`/api/scenarios/${scenario}`)).task.trajectory;
  const n = Math.hypot(...normal), rel = d.tip.map((x, k) => x - center[k]);
  const off = rel.reduce((a, x, k) => a + x * normal[k], 0) / n;
  const inPlane = Math.sqrt(Math.max(0, rel.reduce((a, x) => a + x * x, 0) - off * off));
  check(Math.abs(off) < 1e-3 && Math.abs(inPlane - radius) < 1e-3,
    `the drawn tip is on the scenario's circle (${off.toExponential(1)} m off its plane, ${(inPlane - radius).toExponential(1)} m off its radius)`);
  const p = d.picture;
  check(p.left >= 0 && p.top >= 0 && p.right <= p.width && p.bottom <= p.height, `the arm is inside the picture (${JSON.stringify(p)})`);
  // measured: link axes span 30% (iiwa), 42% (Panda), 34% (Gen3) of the height; the view frames the
  // whole scene (arm, ball, table, path), and the capsules' thickness adds to what the eye sees
  check(p.bottom - p.top > 0.25 * p.height, `the arm is not tiny: ${(p.bottom - p.top).toFixed(0)} of ${p.height.toFixed(0)} px high`);
  await t.page.locator('#views .view-cell').first().screenshot({ path: join(screenshotDir, `urdf-view-${arm}.png`) });

  // playing: the drawn tip follows the frames
  await t.page.click('[data-action=start]');
  await eventually(async () => (await drawnVsFrame(t.page)).step > d.step + 100, 'the run to play 100 steps');
  const later = await drawnVsFrame(t.page);
  check(later.worst < 1e-9 && later.tipError < 1e-9, `while playing, the drawing follows the frame (worst ${later.worst}, tip ${later.tipError} m)`);
  const moved = Math.hypot(...later.tip.map((x, k) => x - d.tip[k]));
  check(moved > 0.01, `the drawn tip moves along the circle (${moved.toFixed(3)} m)`);
}]));
