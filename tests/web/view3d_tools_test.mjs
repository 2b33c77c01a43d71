// The 3D view's tools on the dashboard, as a person uses them: Reset returns
// to the first view, Fit frames the scene from where one looks, a click on the
// axes gizmo turns the camera to look along that axis; distance labels carry
// their unit and never overlap; the target is drawn over everything.
// Usage: node view3d_tools_test.mjs   (RRLAB_BINARY, RRLAB_SCREENSHOTS, CHROMIUM)
import { suite, eventually, check, animationFrames } from './harness.mjs';

// Where the camera looks from, as a unit vector from the orbit's target.
const looking = (page) => page.evaluate(() => {
  const v = window.__rrlab.session.lanes[0].view;
  const d = v.camera.position.clone().sub(v.controls.target).normalize();
  return [d.x, d.y, d.z];
});
const near = (a, b, tolerance) => Math.hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]) < tolerance;

await suite('view3d-tools', [
  ['Reset and Fit, a click on the axes gizmo, labels with units that do not overlap, the target on top', async (t) => {
    const run = await t.post('/api/runs', { scenario: '17_chen_sim2_spatial16_window', mode: 'batch', steps: 400 });
    await t.page.goto(`${t.base}/?run=${run.id}&frame=300`);
    await eventually(() => t.page.evaluate(() => {
      const l = window.__rrlab.session && window.__rrlab.session.lanes[0];
      return l && l.view && l.view.renderer && l.frame && l.frame.seq === 300;
    }), 'the 3D replay at frame 300');
    const first = await looking(t.page);
    const norm = Math.hypot(0.45, -1, 0.6);
    check(near(first, [0.45 / norm, -1 / norm, 0.6 / norm], 1e-6), `the first view looks from the front right, above (${first})`);

    // turn the camera by dragging, then Reset
    const canvas = await t.page.locator('#views .view-cell canvas').first().boundingBox();
    await t.page.mouse.move(canvas.x + canvas.width * 0.3, canvas.y + canvas.height * 0.4);
    await t.page.mouse.down();
    for (let i = 1; i <= 6; ++i) await t.page.mouse.move(canvas.x + canvas.width * 0.3 + 25 * i, canvas.y + canvas.height * 0.4);
    await t.page.mouse.up();
    await eventually(async () => !near(await looking(t.page), first, 0.05), 'the camera to turn');
    await t.page.click('.view3d-fit');  // ends the coasting, then frames the scene from there
    const fitted = await looking(t.page);
    await animationFrames(t.page, 10);  // ten draws of the render loop: a coasting orbit would have turned the camera
    check(near(await looking(t.page), fitted, 1e-9), 'the fitted view stays put');
    check(!near(fitted, first, 0.05), `Fit keeps looking from where one turned to (${fitted}), not from the first view`);
    const renders = await t.page.evaluate(() => window.__rrlab.session.lanes[0].view.stats.renders);  // before the click: its draw may come at once
    await t.page.click('.view3d-reset');
    check(near(await looking(t.page), first, 1e-6), 'Reset returns to the first view');

    // a click on the gizmo's x bubble: the camera turns to look along -x, from +x
    await eventually(() => t.page.evaluate((n) => window.__rrlab.session.lanes[0].view.stats.renders > n, renders), 'a draw after Reset (the gizmo turns with the camera)');
    const bubble = await t.page.evaluate(() => {
      const v = window.__rrlab.session.lanes[0].view;
      const p = v.axesGizmo.children.find((c) => c.userData.type === 'posX').getWorldPosition(v.target.position.clone());
      const r = v.renderer.domElement.getBoundingClientRect();
      return { x: r.right - 128 + ((p.x / 2 + 1) / 2) * 128, y: r.bottom - 128 + ((1 - p.y / 2) / 2) * 128 };
    });
    await t.page.mouse.click(bubble.x, bubble.y);
    await eventually(async () => near(await looking(t.page), [1, 0, 0], 0.02), { message: 'the camera to look from +x', timeout: 10000 });
    await t.screenshot('from-x');

    // distance labels: in metres, never overlapping
    const before = await t.page.evaluate(() => window.__rrlab.session.lanes[0].view.stats.renders);
    await t.page.click('.view3d-reset');
    await eventually(() => t.page.evaluate((n) => window.__rrlab.session.lanes[0].view.stats.renders > n, before), 'the view drawn after Reset');
    const labels = await t.page.evaluate(() => [...document.querySelectorAll('.view3d-label')]
      .filter((e) => e.style.display !== 'none' && !e.classList.contains('view3d-label-hidden') && e.getBoundingClientRect().width > 0)
      .map((e) => { const r = e.getBoundingClientRect(); return { text: e.textContent, l: r.left, r: r.right, t: r.top, b: r.bottom }; }));
    check(labels.length >= 1, `distance labels are shown (${labels.length})`);
    check(labels.every((l) => / m$/.test(l.text)), `every distance says its unit: ${labels.map((l) => l.text).join(', ')}`);
    for (let i = 0; i < labels.length; ++i) for (let j = i + 1; j < labels.length; ++j) {
      const a = labels[i], b = labels[j];
      check(a.r <= b.l || b.r <= a.l || a.b <= b.t || b.b <= a.t, `labels ${a.text} and ${b.text} do not overlap`);
    }
    check(await t.page.evaluate(() => {
      const target = window.__rrlab.session.lanes[0].view.target;
      return target.visible && target.material.depthTest === false;
    }), 'the target is drawn over everything');
    await t.screenshot('labels');
  }],
]);
