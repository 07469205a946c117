// A screenshot of the viewer for the report (tcbench reproduce calls it):
//   node screenshot.mjs TCBENCH OUT.png STEP RUN_DIR [RUN_DIR]
// Serves the runs with `tcbench view`, shows the recorded frame at or before
// STEP with the points coloured by the oracle's verdict (where the oracle
// ran on that frame; else by how their force was made) and the penetration
// vectors at 5x, and writes the page to OUT.png. Exit 77 with the reason when
// no browser can start, 1 on any other failure.
import { startServer, launchBrowser } from './browser.mjs';

const [tcbench, out, step, ...runs] = process.argv.slice(2);
if (!tcbench || !out || !step || runs.length === 0 || runs.length > 2) {
  console.error('usage: node screenshot.mjs TCBENCH OUT.png STEP RUN_DIR [RUN_DIR]');
  process.exit(2);
}

const launched = await launchBrowser();
if (launched.skip) { console.error(`screenshot.mjs: ${launched.skip}`); process.exit(77); }
const server = startServer(tcbench, ['view', ...runs, '--port', '0']);
let status = 0;
try {
  const url = await server.url;
  const page = await launched.browser.newPage({ viewport: { width: 1600, height: 1000 } });
  await page.goto(url);
  await page.waitForFunction(() => window.tcbench && (window.tcbench.ready || window.tcbench.errors.length > 0), null, { timeout: 120000 });
  const errors = await page.evaluate(() => window.tcbench.errors);
  if (errors.length) throw new Error(errors.join('; '));
  const frame = await page.evaluate((s) => {
    const timeline = window.tcbench.timeline;
    let i = 0;
    while (i + 1 < timeline.length && timeline[i + 1].step <= s) ++i;
    const scrub = document.getElementById('scrub');
    scrub.value = i;
    scrub.dispatchEvent(new Event('input'));
    return { index: i, oracle: window.tcbench.views.every((v) => v.frame && !!v.frame.oracle) };
  }, Number(step));
  if (frame.oracle) await page.selectOption('#colour-by', 'oracle');
  await page.selectOption('#vector-scale', '5');
  await page.screenshot({ path: out });
  console.log(`screenshot.mjs: ${out} (frame ${frame.index + 1}, ${frame.oracle ? "points by the oracle's verdict" : 'points by how their force was made'})`);
} catch (e) {
  console.error(`screenshot.mjs: ${e.message}`);
  status = 1;
} finally {
  await launched.browser.close();
  server.child.kill('SIGINT');
  await server.exited;
}
process.exit(status);
