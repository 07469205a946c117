// tcbench live in a real browser (headless chromium, SwiftShader WebGL):
//   node live_test.mjs TCBENCH OUT_DIR [SCREENSHOT.png]
// Starts `tcbench live haptic_probe`, and checks: frames stream into the
// page, malformed probe messages are refused with 400 and a reason, synthetic
// mouse drags move the probe down onto the cow until a non-zero contact force
// comes back, the loop's rate is shown, Ctrl-C stops the server cleanly and
// leaves the run's files and probe_path.csv, and that path replays with
// `tcbench run`. Exit 77 (skipped) with a message when no browser can start.
import { spawnSync } from 'node:child_process';
import { existsSync, readFileSync, rmSync } from 'node:fs';
import { join } from 'node:path';
import { startServer, launchBrowser } from '../browser.mjs';

const [tcbench, out, shot] = process.argv.slice(2);
const failures = [];
const t0 = Date.now();
const check = (ok, what) => { console.log(`${ok ? "ok  " : "FAIL"} ${what} [${((Date.now() - t0) / 1000).toFixed(1)} s]`); if (!ok) failures.push(what); };

async function main() {
  rmSync(out, { recursive: true, force: true });
  const launched = await launchBrowser();
  if (launched.skip) { console.log(`SKIP live browser test: ${launched.skip}`); process.exit(77); }
  const { browser } = launched;
  const server = startServer(tcbench, ['live', 'haptic_probe', '--port', '0', '--out', out, '--seconds', '120']);
  const url = await server.url;
  try {
    for (const [body, why] of [['{"x":1}', 'missing keys'], ['not json', 'not JSON'], ['{"x":0,"y":"a","z":0}', 'a string'],
      ['{"x":0,"y":0,"z":1e308,"w":1}', 'an extra key'], ['{"x":1e6,"y":0,"z":0}', 'beyond reach']]) {
      const r = await fetch(`${url}live/probe`, { method: 'POST', headers: { 'Content-Type': 'application/json' }, body });
      const text = await r.text();
      check(r.status === 400 && text.startsWith('tcbench live:'), `a probe message with ${why} is refused: ${r.status} ${text.trim()}`);
    }
    // A page of another origin can POST text/plain without asking: refused.
    const plain = await fetch(`${url}live/probe`, { method: 'POST', headers: { 'Content-Type': 'text/plain' }, body: '{"x":0,"y":0.3,"z":0}' });
    check(plain.status === 415, `a target not sent as JSON is refused (${plain.status})`);
    const page = await browser.newPage({ viewport: { width: 1000, height: 700 } });
    const consoleErrors = [];
    page.on('console', (m) => { if (m.type() === 'error') consoleErrors.push(m.text()); });
    page.on('pageerror', (e) => consoleErrors.push(String(e)));
    await page.goto(url);
    await page.waitForFunction(() => window.tcbench && window.tcbench.live && window.tcbench.live.frames > 3, null, { timeout: 60000 });
    const start = await page.evaluate(() => ({ target: window.tcbench.live.target, force: window.tcbench.live.force,
      centre: window.tcbench.live.last.probe_centre_m }));
    check(start.force === 0, `the probe starts free of the cow (|F| = ${start.force})`);

    // Drag the probe down onto the cow's back with the mouse, in small moves.
    const canvas = page.locator('#views canvas');
    const box = await canvas.boundingBox();
    const x = box.x + box.width / 2;
    let y = box.y + box.height / 3;
    await page.mouse.move(x, y);
    await page.mouse.down();
    let force = 0;
    for (let i = 0; i < 60 && force === 0; ++i) {
      y += 4;
      await page.mouse.move(x, y);
      await page.waitForTimeout(100);
      force = await page.evaluate(() => window.tcbench.live.force);
    }
    await page.waitForTimeout(300);
    force = Math.max(force, await page.evaluate(() => window.tcbench.live.force));
    if (shot) await page.screenshot({ path: shot });
    await page.mouse.up();
    const live = await page.evaluate(() => ({ target: window.tcbench.live.target, sent: window.tcbench.live.sent, last: window.tcbench.live.last }));
    // Where the simulation has the probe, not where the page wants it.
    const moved = start.centre[1] - live.last.probe_centre_m[1];
    check(live.sent > 0 && moved > 0.01, `the mouse moved the probe down in the simulation by ${(moved * 100).toFixed(1)} cm (${live.sent} messages)`);
    check(force > 0, `pressing into the cow gives a non-zero force (|F| = ${force.toFixed(3)} N)`);
    check(live.last.rate_hz > 0 && /loop \d+ Hz of 1000 Hz/.test(await page.textContent('#counter')), `the loop's rate is shown: ${await page.textContent('#counter')}`);
    check(consoleErrors.length === 0, `no console errors (${consoleErrors.join('; ')})`);
  } finally {
    await browser.close();
    server.child.kill('SIGINT');
  }
  const end = await server.exited;
  check(end.code === 0 && end.out().includes('stopped'), `Ctrl-C stops the server cleanly (exit ${end.code}): ${end.out().trim().split('\n').pop()}`);
  const path = join(out, 'probe_path.csv');
  check(existsSync(join(out, 'run.json')) && existsSync(join(out, 'steps.csv')), 'the live run left run.json and steps.csv');
  const rows = existsSync(path) ? readFileSync(path, 'utf8').trim().split('\n') : [];
  const lowest = Math.min(...rows.slice(1).map((r) => Number(r.split(',')[2])));
  check(rows[0] === 'time_s,x_m,y_m,z_m' && rows.length > 50 && lowest < Number(rows[1].split(',')[2]) - 0.01,
    `the probe path is saved as a trajectory CSV of the drag (${rows.length - 1} samples, down to y = ${lowest.toFixed(3)} m)`);
  if (existsSync(path)) {
    const replay = spawnSync(tcbench, ['run', 'haptic_probe', '--set', `object.probe.trajectory=${path}`, '--steps', '200', '--quiet',
      '--out', join(out, 'replayed')], { encoding: 'utf8' });
    check(replay.status === 0, `tcbench run replays the saved path (exit ${replay.status} ${replay.stderr.trim()})`);
  }
  if (failures.length) { console.log(`${failures.length} check(s) failed`); process.exit(1); }
  console.log('all live checks passed');
}

main().catch((e) => { console.error(e); process.exit(1); });
