// The viewer in a real browser: Debian's chromium, headless, WebGL in
// software (SwiftShader), driven by playwright-core.
//   node viewer_test.mjs TCBENCH RUN_DIR_A RUN_DIR_B [SCREENSHOT_DIR]
// Serves the two recordings with `tcbench view`, and checks: the page loads
// without console errors, playing advances the frame counter, each overlay
// and the colouring change the rendered pixels, side by side shows two
// canvases, the server refuses what it must, and Ctrl-C stops it cleanly.
// Exit 77 (ctest: skipped) with a message when no browser can start.
import { spawnSync } from 'node:child_process';
import { mkdtempSync, mkdirSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { startServer, launchBrowser } from '../browser.mjs';

const [tcbench, runA, runB, shots] = process.argv.slice(2);
const failures = [];
const check = (ok, what) => { console.log(`${ok ? 'ok  ' : 'FAIL'} ${what}`); if (!ok) failures.push(what); };

async function pixels(page) {
  return page.locator('#views').screenshot();
}

async function main() {
  // Bad input first: a directory with no replay is exit 2, naming it.
  const empty = mkdtempSync(join(tmpdir(), 'tcbench-view-'));
  const bad = spawnSync(tcbench, ['view', empty, '--port', '0'], { encoding: 'utf8' });
  check(bad.status === 2 && bad.stderr.includes(empty) && bad.stderr.includes('replay.json'),
    `a directory without a replay is exit 2 naming it (got ${bad.status}: ${bad.stderr.trim()})`);
  rmSync(empty, { recursive: true, force: true });

  const launched = await launchBrowser();
  if (launched.skip) { console.log(`SKIP viewer browser test: ${launched.skip}`); process.exit(77); }
  const { browser } = launched;
  const server = startServer(tcbench, ['view', runA, runB, '--port', '0']);
  const url = await server.url;
  try {
    const refused = await fetch(`${url}run/7/replay.json`);
    check(refused.status === 404, `a run index that does not exist is 404 (got ${refused.status})`);
    const outside = await fetch(`${url}run/0/..%2F..%2Fetc%2Fpasswd`);
    check(outside.status === 404, `a file outside the run's whitelist is 404 (got ${outside.status})`);
    // A taken port is an error, not a second server sharing it.
    const port = new URL(url).port;
    const second = spawnSync(tcbench, ['view', runA, '--port', port], { encoding: 'utf8', timeout: 20000 });
    check(second.status === 2 && second.stderr.includes(`127.0.0.1:${port}`), `a second server on port ${port} is exit 2 (got ${second.status}: ${second.stderr.trim()})`);
    const steps = await fetch(`${url}run/0/steps.csv`);
    check(steps.ok && (await steps.text()).startsWith('step,'), 'steps.csv is served');

    const page = await browser.newPage({ viewport: { width: 1400, height: 900 } });
    const consoleErrors = [];
    page.on('console', (m) => { if (m.type() === 'error') consoleErrors.push(m.text()); });
    page.on('pageerror', (e) => consoleErrors.push(String(e)));
    await page.goto(url);
    await page.waitForFunction(() => window.tcbench && (window.tcbench.ready || window.tcbench.errors.length > 0), null, { timeout: 60000 });
    const errors = await page.evaluate(() => window.tcbench.errors);
    check(errors.length === 0, `the page reports no error (${errors.join('; ')})`);
    check(await page.locator('#views canvas').count() === 2, 'side by side: two canvases');

    const before = await page.evaluate(() => window.tcbench.frame);
    await page.click('#play');
    await page.waitForFunction((f) => window.tcbench.frame > f, before, { timeout: 20000 }).catch(() => {});
    const after = await page.evaluate(() => window.tcbench.frame);
    await page.click('#play');
    check(after > before, `playing advances the frame counter (${before} -> ${after})`);
    const counter = await page.textContent('#counter');
    check(/^frame \d+ \/ \d+, step \d+/.test(counter), `the counter reads "${counter}"`);

    // A frame where both runs hold contacts and the oracle ran, so every
    // overlay has something to draw.
    const target = await page.evaluate(() => {
      const [a] = window.tcbench.runs;
      // The deepest such frame, so the penetration vectors are long enough to see.
      const deepest = (g) => Math.max(0, ...g.contacts.map((c) => (Number.isFinite(c.depth) ? c.depth : 0)));
      const f = a.frames.filter((g) => g.contacts.length > 0 && g.oracle && g.oracle.length > 0)
        .sort((g, h) => deepest(h) - deepest(g))[0];
      return f ? window.tcbench.timeline.findIndex((t) => t.step === f.step) : -1;
    });
    check(target >= 0, 'the recording has a frame with contacts and oracle points');
    await page.evaluate((i) => { document.getElementById('scrub').value = i; document.getElementById('scrub').dispatchEvent(new Event('input')); }, Math.max(target, 0));
    const shown = await page.evaluate(() => window.tcbench.views.map((v) => v.frame.step));
    check(shown[0] === shown[1], `lockstep: both views show step ${shown.join(' and ')}`);
    // One camera: orbiting the left view (a left-button drag) turns the right one too.
    const cameraBefore = await page.evaluate(() => window.tcbench.views[1].camera.position.toArray());
    const left = await page.locator('#views canvas').first().boundingBox();
    await page.mouse.move(left.x + left.width / 2, left.y + left.height / 2);
    await page.mouse.down();
    await page.mouse.move(left.x + left.width / 2 + 80, left.y + left.height / 2 + 20, { steps: 4 });
    await page.mouse.up();
    const cameras = await page.evaluate(() => window.tcbench.views.map((v) => v.camera.position.toArray()));
    const turned = Math.hypot(...cameraBefore.map((x, k) => x - cameras[1][k]));
    check(turned > 1e-3 && cameras[0].every((x, k) => Math.abs(x - cameras[1][k]) < 1e-9),
      `the views share one camera: the right one moved ${turned.toFixed(3)} m with the left`);
    for (const [name, key] of [['wireframe', 'w'], ['boxes', 'b'], ['grid', 'g'], ['fourViews', 'v'], ['debug overlays', 'Backspace']]) {
      const a = await pixels(page);
      await page.locator('body').press(key);
      const b = await pixels(page);
      check(!a.equals(b), `toggling ${name} (${key}) changes the rendered pixels`);
      await page.locator('body').press(key);
      const c = await pixels(page);
      check(c.equals(a), `toggling ${name} back restores the same pixels`);
    }
    // Backspace toggles points and vectors together: each checkbox alone too.
    await page.selectOption('#vector-scale', '100');
    for (const name of ['points', 'vectors']) {
      const a = await pixels(page);
      await page.click(`input[data-overlay="${name}"]`);
      const b = await pixels(page);
      await page.click(`input[data-overlay="${name}"]`);
      check(!a.equals(b) && a.equals(await pixels(page)), `the ${name} checkbox alone changes the pixels, and back`);
    }
    await page.selectOption('#vector-scale', '1');
    const a = await pixels(page);
    await page.selectOption('#colour-by', 'oracle');
    const b = await pixels(page);
    check(!a.equals(b), "colouring points by the oracle's verdict changes the pixels");
    const d = await pixels(page);
    await page.selectOption('#colour-by', 'depth');
    check(!d.equals(await pixels(page)), 'colouring points by where their depth came from changes the pixels');
    await page.selectOption('#colour-by', 'oracle');
    const verdicts = await page.evaluate(() => window.tcbench.views[0].stats.verdicts);
    check(Object.keys(verdicts).some((k) => ['correct', 'missed', 'false'].includes(k)), `points are judged: ${JSON.stringify(verdicts)}`);

    // Picking: a click on a drawn point names it and what the oracle said.
    await page.selectOption('#colour-by', 'force');
    const spot = await page.evaluate(() => {
      const view = window.tcbench.views[0];
      const p = view.judged[0];
      const c = view.renderer.domElement;
      const r = c.getBoundingClientRect();
      const v = { x: p.position[0], y: p.position[1], z: p.position[2] };
      const w = c.clientWidth;
      const h = c.clientHeight;
      // The same projection the view uses.
      const q = new view.camera.position.constructor(v.x, v.y, v.z).project(view.camera);
      return { x: r.left + (q.x + 1) / 2 * w, y: r.top + (1 - q.y) / 2 * h, vertex: p.vertex };
    });
    await page.mouse.click(spot.x, spot.y);
    const picked = await page.textContent('#picked');
    check(/vertex \d+ of \w+/.test(picked) && picked.includes('oracle'), `clicking a point picks it: "${picked}"`);

    if (shots) {
      mkdirSync(shots, { recursive: true });
      await page.locator('body').press('b');
      await page.screenshot({ path: join(shots, 'viewer.png') });
      await page.locator('body').press('b');
    }
    check(consoleErrors.length === 0, `no console errors (${consoleErrors.join('; ')})`);
  } finally {
    await browser.close();
    server.child.kill('SIGINT');
    const end = await server.exited;
    check(end.code === 0 && end.out().includes('stopped'), `Ctrl-C stops the server cleanly (exit ${end.code}, signal ${end.signal})`);
  }
  if (failures.length) { console.log(`${failures.length} check(s) failed`); process.exit(1); }
  console.log('all viewer checks passed');
}

main().catch((e) => { console.error(e); process.exit(1); });
