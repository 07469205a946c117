// tcbench live: frames streamed from the running simulation (server-sent
// events), the mouse driving the probe as in seed 001 (drag: x and y, wheel:
// z), the probe's force drawn as an arrow and plotted with the loop's pace.
import * as THREE from 'three';
import { RunView } from './run_view.js';
import { StepPlot } from './plot.js';

const KEEP_FRAMES = 600;  // the plot's window: about 20 s at 30 frames a second

export async function startLive(state, $) {
  const scene = await (await fetch('live/scene.json')).json();
  const vertexCount = scene.surface_body.length;
  const surfaceMap = new Uint32Array(2 * vertexCount);
  scene.surface_body.forEach((b, i) => { surfaceMap[2 * i] = b; });
  const replay = { bodies: scene.bodies, triangles: new Uint32Array(scene.triangles), surfaceMap, vertexCount, cellSize: null };
  const cell = document.createElement('div');
  cell.className = 'view';
  $('views').appendChild(cell);
  const view = new RunView(cell, replay, `live: ${scene.bodies.map((b) => b.name).join(', ')} (drag the probe; wheel: z)`);
  state.views = [view];
  document.body.classList.add('live');
  for (const id of ['back', 'play', 'forward', 'scrub', 'fps']) $(id).disabled = true;
  const arrow = new THREE.ArrowHelper(new THREE.Vector3(0, 1, 0), new THREE.Vector3(), 0.01, 0xd62728);
  arrow.visible = false;
  view.scene.add(arrow);
  // The left button drives the probe, the wheel its z; the right button
  // orbits, the middle one pans (the wheel is taken, so no zoom).
  view.controls.mouseButtons = { LEFT: null, MIDDLE: THREE.MOUSE.PAN, RIGHT: THREE.MOUSE.ROTATE };
  view.controls.enableZoom = false;

  const live = { frames: 0, force: 0, forceMax: 0, target: null, sent: 0, refused: 0, last: null };
  state.live = live;
  const columns = { step: [], handling_ms: [], budget_ms: [], probe_force_x: [], probe_force_y: [], probe_force_z: [] };
  const plot = new StepPlot($('plot'), () => {});
  state.plot = plot;

  // Mouse to probe target: one request in flight, the newest target wins.
  let pending = null;
  let inFlight = false;
  const send = async () => {
    if (inFlight || !pending) return;
    inFlight = true;
    const target = pending;
    pending = null;
    try {
      const response = await fetch('live/probe', { method: 'POST', headers: { 'Content-Type': 'application/json' },
        body: JSON.stringify({ x: target[0], y: target[1], z: target[2] }) });
      if (response.ok) live.sent += 1;
      else {
        // Refused (out of reach): the mouse starts again from where the probe is.
        live.refused += 1;
        $('details').textContent = await response.text();
        if (live.last) live.target = live.last.probe_target_m;
      }
    } catch (e) {
      $('details').textContent = `the server did not answer: ${e.message}`;
    } finally {
      inFlight = false;
    }
    send();
  };
  const moveTarget = (dx, dy, dz) => {
    if (!live.target) return;
    live.target = [live.target[0] + dx, live.target[1] + dy, live.target[2] + dz];
    pending = live.target;
    send();
  };
  const canvas = view.renderer.domElement;
  let drag = null;
  canvas.addEventListener('pointerdown', (e) => { if (e.button === 0) drag = { x: e.clientX, y: e.clientY }; });
  window.addEventListener('pointerup', () => { drag = null; });
  canvas.addEventListener('pointermove', (e) => {
    if (!drag) return;
    const metresPerPixel = (view.radius ?? 0.5) / 400;
    moveTarget((e.clientX - drag.x) * metresPerPixel, -(e.clientY - drag.y) * metresPerPixel, 0);
    drag = { x: e.clientX, y: e.clientY };
  });
  canvas.addEventListener('wheel', (e) => {
    e.preventDefault();
    moveTarget(0, 0, -Math.sign(e.deltaY) * (view.radius ?? 0.5) / 100);
  }, { passive: false });

  // Only the newest frame is drawn, once per display frame: a page slower
  // than the stream (software WebGL) skips frames instead of falling behind.
  let newest = null;
  const events = new EventSource('live/events');
  events.onmessage = (message) => {
    const first = newest === null && live.frames === 0;
    newest = message.data;
    if (first) requestAnimationFrame(draw);
  };
  const draw = () => {
    if (newest !== null) { show(JSON.parse(newest)); newest = null; }
    requestAnimationFrame(draw);
  };
  const show = (f) => {
    live.frames += 1;
    live.last = f;
    if (!live.target) live.target = f.probe_target_m;
    const frame = {
      step: f.step, time_s: f.time_s, positions: Float32Array.from(f.positions), oracle: null, aabbs: null, cells: null,
      contacts: f.contacts.map((c, i) => ({ body: -1, vertex: i, position: c.slice(0, 3), depth: c[3], direction: c.slice(4, 7), force: c[7] })),
    };
    view.showFrame(frame);
    const force = new THREE.Vector3(...f.probe_force_n);
    live.force = force.length();
    live.forceMax = Math.max(live.forceMax, live.force);
    arrow.visible = live.force > 0;
    if (arrow.visible) {
      arrow.position.set(...f.probe_centre_m);
      arrow.setDirection(force.clone().normalize());
      const length = (view.radius ?? 0.5) * 0.4 * live.force / Math.max(live.forceMax, 1e-12);
      arrow.setLength(length, length * 0.25, length * 0.15);
    }
    view.render();
    for (const [k, v] of [['step', f.step], ['handling_ms', f.handling_ms], ['budget_ms', f.budget_ms ?? NaN],
      ['probe_force_x', f.probe_force_n[0]], ['probe_force_y', f.probe_force_n[1]], ['probe_force_z', f.probe_force_n[2]]]) {
      columns[k].push(v);
      if (columns[k].length > KEEP_FRAMES) columns[k].shift();
    }
    plot.setRuns([{ name: 'live', steps: { columns } }]);
    plot.setCursor(f.step);
    const budget = f.budget_ms ? ` of ${f.budget_ms} ms (over budget: ${(100 * f.over_budget_share).toFixed(1)} % of steps, worst overshoot in the last second ${f.overshoot_max_ms.toFixed(3)} ms)` : ' (no budget)';
    $('counter').textContent = `step ${f.step}, t = ${f.time_s.toFixed(3)} s, loop ${f.rate_hz.toFixed(0)} Hz of ${f.target_rate_hz.toFixed(0)} Hz`;
    $('details').textContent = `handling ${f.handling_ms.toFixed(3)} ms${budget}\n`
      + `probe force ${live.force.toFixed(3)} N, ${f.contacts.length} colliding points`;
    state.ready = true;
  };
  // The stream ends when the run does (Ctrl-C, --seconds, or unstable: the
  // terminal says which); the browser would retry forever, so stop it.
  events.onerror = () => {
    events.close();
    $('counter').textContent += ' (ended)';
    $('details').textContent = 'the live run has ended or the server stopped: its terminal says why';
  };
}
