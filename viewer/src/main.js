// The viewer page: plays one or two recorded runs in lockstep (tcbench view),
// with seed 001's key map, overlays and a synchronized plot.
import { loadRun, FORCE_NAMES } from './replay.js';
import { RunView, FORCE_COLOURS, VERDICT_COLOURS, DEPTH_COLOURS } from './run_view.js';
import { StepPlot } from './plot.js';
import { startLive } from './live.js';

const $ = (id) => document.getElementById(id);
const state = { runs: [], views: [], frame: 0, playing: false, fps: 30, errors: [], ready: false };
// For tests and the console: what is shown, and a way to drive it.
window.tcbench = state;

function showError(message) {
  state.errors.push(message);
  $('error').textContent = message;
  $('error').hidden = false;
}

// The frame of run r that shows `step`: the last one recorded at or before
// it (its first when it has none that early; the title then says so).
function frameAtStep(run, step) {
  let lo = 0;
  let hi = run.frames.length - 1;
  if (hi < 0 || run.frames[0].step > step) return 0;
  while (lo < hi) {
    const mid = (lo + hi + 1) >> 1;
    if (run.frames[mid].step <= step) lo = mid; else hi = mid - 1;
  }
  return lo;
}

// Every recorded step of any run, in order: the runs may be recorded at
// different steps or lengths, and each view shows its own frame at or
// before the step.
function timelineOf(runs) {
  const steps = new Map();
  for (const run of runs) for (const f of run.frames) if (!steps.has(f.step)) steps.set(f.step, { step: f.step, time_s: f.time_s });
  return [...steps.values()].sort((a, b) => a.step - b.step);
}

// The timeline's index showing `step`: its last entry at or before it.
function indexAtStep(step) {
  let i = 0;
  while (i + 1 < state.timeline.length && state.timeline[i + 1].step <= step) ++i;
  return i;
}

function setFrame(i) {
  if (!state.runs.length) return;  // live: no recording to step through
  const timeline = state.timeline;
  state.frame = Math.max(0, Math.min(timeline.length - 1, Math.round(i)));
  const step = timeline[state.frame].step;
  state.views.forEach((view, r) => view.showFrame(state.runs[r].frames[frameAtStep(state.runs[r], step)]));
  $('scrub').value = state.frame;
  const lines = state.views.map((view, r) => {
    const run = state.runs[r];
    const f = run.frames[frameAtStep(run, step)];
    const col = run.steps && run.steps.columns;
    const row = col ? run.steps.steps.indexOf(f.step) : -1;
    const ms = row >= 0 && col.handling_ms ? col.handling_ms[row] : NaN;
    const budget = row >= 0 && col.budget_ms ? col.budget_ms[row] : NaN;
    const verdicts = Object.entries(view.stats.verdicts).map(([k, v]) => `${k} ${v}`).join(', ');
    const early = f.step > step ? ` (its first frame, step ${f.step}: none recorded by step ${step})` : '';
    return `${run.name}${early}: ${f.contacts.length} colliding points` + (f.oracle ? `, oracle ${f.oracle.length}` : ', oracle did not run')
      + (Number.isFinite(ms) ? `, handling ${ms.toFixed(3)} ms` + (Number.isFinite(budget) ? ` of ${budget} ms` : '') : '')
      + (verdicts ? ` (${verdicts})` : '');
  });
  $('counter').textContent = `frame ${state.frame + 1} / ${timeline.length}, step ${step}, t = ${timeline[state.frame].time_s.toFixed(4)} s`;
  $('details').textContent = lines.join('\n');
  state.plot.setCursor(step);
}

function setOverlay(name, on) {
  for (const view of state.views) { view.overlays[name] = on; view.updateOverlays(); }
  const box = document.querySelector(`input[data-overlay="${name}"]`);
  if (box) box.checked = on;
  if (state.runs.length) setFrame(state.frame);
}

function toggleOverlay(name) { setOverlay(name, !state.views[0].overlays[name]); }

function legend() {
  const by = $('colour-by').value;
  const colours = by === 'oracle' ? VERDICT_COLOURS : by === 'depth' ? DEPTH_COLOURS : FORCE_COLOURS;
  const meaning = by === 'depth'
    ? { border: 'depth at the border', propagated: 'depth propagated', tet_pair: 'depth from a tet pair', none: 'no depth',
      'not held': 'oracle only: not held' }
    : by === 'oracle'
    ? { correct: 'method and oracle', missed: 'oracle only (missed)', false: 'method only (false)',
      touching: 'method only, touching (counted neither way)', unjudged: 'no oracle on this frame' }
    : { computed: 'force computed', held: 'held', extrapolated: 'extrapolated', tracked: 'tracked depth', none: 'no force this step' };
  $('legend').innerHTML = Object.entries(colours).map(([k, c]) =>
    `<span><i style="background:#${c.toString(16).padStart(6, '0')}"></i>${meaning[k]}</span>`).join('');
}

function play() {
  let last = performance.now();
  let carry = 0;
  const tick = (now) => {
    if (!state.playing) return;
    carry += (now - last) * state.fps / 1000;
    last = now;
    if (carry >= 1) {
      const next = state.frame + Math.floor(carry);
      carry -= Math.floor(carry);
      setFrame(next >= state.timeline.length ? 0 : next);
    }
    requestAnimationFrame(tick);
  };
  requestAnimationFrame(tick);
}

function setPlaying(on) {
  if (!state.runs.length) return;
  state.playing = on;
  $('play').textContent = on ? 'Pause' : 'Play';
  if (on) play();
}

function layout() {
  document.body.classList.toggle('side-by-side', state.views.length > 1);
  for (const view of state.views) view.resize();
  state.plot.draw();
}

function bindControls() {
  $('play').onclick = () => setPlaying(!state.playing);
  $('back').onclick = () => setFrame(state.frame - 1);
  $('forward').onclick = () => setFrame(state.frame + 1);
  $('scrub').oninput = (e) => setFrame(Number(e.target.value));
  $('fps').onchange = (e) => { state.fps = Number(e.target.value); };
  $('colour-by').onchange = (e) => {
    for (const view of state.views) { view.colourBy = e.target.value; view.updateOverlays(); }
    legend();
    if (state.runs.length) setFrame(state.frame);
  };
  $('vector-scale').onchange = (e) => {
    for (const view of state.views) { view.vectorScale = Number(e.target.value); view.updateOverlays(); }
  };
  for (const box of document.querySelectorAll('input[data-overlay]')) box.onchange = () => setOverlay(box.dataset.overlay, box.checked);
  // Seed 001's keys, where they still make sense.
  window.addEventListener('keydown', (event) => {
    if (event.target.tagName === 'SELECT' || event.target.type === 'range') return;
    const key = event.key.toLowerCase();
    if (key === 'w') toggleOverlay('wireframe');
    else if (key === 'b') toggleOverlay('boxes');
    else if (key === 'g') toggleOverlay('grid');
    else if (key === 'v') { toggleOverlay('fourViews'); layout(); }
    else if (event.key === 'Backspace') {
      const on = !(state.views[0].overlays.points || state.views[0].overlays.vectors);
      setOverlay('points', on);
      setOverlay('vectors', on);
    } else if (event.key === ' ') setPlaying(!state.playing);
    else if (event.key === 'ArrowRight') setFrame(state.frame + 1);
    else if (event.key === 'ArrowLeft') setFrame(state.frame - 1);
    else return;
    event.preventDefault();
  });
  window.addEventListener('resize', layout);
}

async function main() {
  const mode = await (await fetch('mode.json')).json();
  if (mode.mode === 'live') {
    bindControls();
    legend();
    await startLive(state, $);
    layout();
    return;
  }
  const list = await (await fetch('runs.json')).json();
  state.runs = await Promise.all(list.map(async (entry, i) => ({ ...(await loadRun(`run/${i}`)), name: entry.name })));
  document.title = `tcbench view: ${state.runs.map((r) => r.name).join(' | ')}`;
  const container = $('views');
  state.views = state.runs.map((run) => {
    const cell = document.createElement('div');
    cell.className = 'view';
    container.appendChild(cell);
    const method = run.run && run.run.method ? ` (${run.run.method.name ?? run.run.method}${run.run.budget ? `, ${run.run.budget.label ?? ''}` : ''})` : '';
    return new RunView(cell, run, run.name + method);
  });
  const debug = state.runs.some((r) => r.cellSize);
  for (const name of ['boxes', 'grid']) {
    const box = document.querySelector(`input[data-overlay="${name}"]`);
    box.disabled = !debug;
    box.parentElement.title = debug ? '' : 'recorded without --record-debug';
  }
  state.plot = new StepPlot($('plot'), (step) => setFrame(indexAtStep(step)));
  // One camera for all views: orbiting one orbits the others.
  for (const view of state.views) {
    view.onCameraChange = (source) => {
      for (const other of state.views) {
        if (other === source) continue;
        other.syncing = true;
        other.camera.position.copy(source.camera.position);
        other.camera.up.copy(source.camera.up);
        other.controls.target.copy(source.controls.target);
        other.controls.update();
        other.syncing = false;
      }
    };
  }
  // Picking: a click on a point says what the method and the oracle said of it.
  state.views.forEach((view, r) => {
    view.renderer.domElement.addEventListener('click', (event) => {
      const rect = event.target.getBoundingClientRect();
      const p = view.pick(event.clientX - rect.left, event.clientY - rect.top);
      state.picked = p;
      if (!p) return;
      const body = state.runs[r].bodies[p.body]?.name ?? p.body;
      const mm = (x) => (Number.isFinite(x) ? `${(x * 1e3).toFixed(3)} mm` : 'none');
      $('picked').textContent = `${state.runs[r].name}: vertex ${p.vertex} of ${body}`
        + (p.method ? `, inside ${state.runs[r].bodies[p.other]?.name ?? p.other} (tet ${p.tet}), depth ${mm(p.depth)}, force ${FORCE_NAMES[p.force]}` : ', not held by the method')
        + (p.verdict ? `; oracle: ${p.truth ? `inside, true depth ${mm(p.trueDepth)}` : 'outside'} (${p.verdict})` : '; no oracle on this frame');
    });
  });
  for (const run of state.runs)
    if (run.frames.length === 0) throw new Error(`${run.name}: the replay holds no frames (was the run shorter than --record N steps?)`);
  state.timeline = timelineOf(state.runs);
  $('scrub').max = state.timeline.length - 1;
  bindControls();
  legend();
  layout();
  state.plot.setRuns(state.runs);
  setFrame(0);
  state.ready = true;
}

window.addEventListener('error', (e) => showError(String(e.message)));
main().catch((e) => showError(`tcbench view: ${e.message}`));
