// The plot under the 3D views: per-step series from each run's steps.csv,
// one panel per quantity, with a cursor at the current step. Plain canvas:
// a few thousand points a series need no plotting library.

const RUN_COLOURS = ['#1f77b4', '#ff7f0e'];
const PANELS = [
  { title: 'handling time (ms) against the budget (dashed)', series: (c) => c.handling_ms, extra: (c) => c.budget_ms, robust: true },
  // A work budget is a count of work units, not milliseconds (budget_ms is
  // empty then): its panel draws the units each step spent against it.
  { title: 'work units against the work budget (dashed)', series: (c) => c.work_units, robust: true,
    show: (runs) => runs.some((r) => workBudget(r) !== null),
    extra: (c, run) => workBudget(run) !== null && c.work_units && c.work_units.map(() => workBudget(run)) },
  { title: 'recall (oracle frames)', series: (c) => c.recall, fixed: [0, 1] },
  { title: 'max depth (mm)', series: (c) => c.max_depth && c.max_depth.map((x) => x * 1e3) },
  { title: 'kinetic energy (J)', series: (c) => c.kinetic_energy },
  { title: '|probe force| (N)', series: (c) => c.probe_force_x && c.probe_force_x.map((x, i) => Math.hypot(x, c.probe_force_y[i], c.probe_force_z[i])) },
];

// The run's work budget in units, or null (none, or a wall-clock budget).
function workBudget(run) {
  const budget = run && run.run && run.run.budget;
  return budget && budget.kind === 'work' && Number.isFinite(budget.value) ? budget.value : null;
}

export class StepPlot {
  constructor(canvas, onSeek) {
    this.canvas = canvas;
    this.runs = [];
    this.cursorStep = 0;
    canvas.addEventListener('click', (event) => {
      if (!this.range) return;
      const rect = canvas.getBoundingClientRect();
      const fraction = (event.clientX - rect.left - this.left) / (rect.width - this.left - 10);
      onSeek(this.range[0] + Math.max(0, Math.min(1, fraction)) * (this.range[1] - this.range[0]));
    });
  }

  // runs: [{ name, steps: { columns } | null }]
  setRuns(runs) {
    this.runs = runs.filter((r) => r.steps && r.steps.columns.step);
    // A panel no run has a number for (no oracle, no probe) is left out.
    const panels = PANELS.filter((p) => (!p.show || p.show(this.runs)) && this.runs.some((r) => {
      const s = p.series(r.steps.columns, r);
      return s && s.some(Number.isFinite);
    }));
    this.panels = panels;
    let lo = Infinity;
    let hi = -Infinity;
    for (const r of this.runs) for (const s of r.steps.columns.step) { lo = Math.min(lo, s); hi = Math.max(hi, s); }
    this.range = Number.isFinite(lo) ? [lo, Math.max(hi, lo + 1)] : null;
    this.draw();
  }

  setCursor(step) { this.cursorStep = step; this.draw(); }

  draw() {
    const canvas = this.canvas;
    const width = canvas.clientWidth;
    const panels = this.panels ?? [];
    const panelHeight = 64;
    const height = Math.max(panels.length * panelHeight + 18, 30);
    canvas.width = width;
    canvas.height = height;
    canvas.style.height = `${height}px`;
    const g = canvas.getContext('2d');
    g.fillStyle = '#fff';
    g.fillRect(0, 0, width, height);
    g.font = '11px sans-serif';
    if (!this.range) {
      g.fillStyle = '#555';
      g.fillText('no steps.csv beside the replay: nothing to plot', 8, 18);
      return;
    }
    this.left = 56;
    const right = width - 10;
    // Which colour is which run.
    let at = this.left;
    this.runs.forEach((r, i) => {
      g.fillStyle = RUN_COLOURS[i % RUN_COLOURS.length];
      g.fillRect(at, 4, 14, 3);
      g.fillStyle = '#333';
      g.fillText(r.name, at + 18, 10);
      at += g.measureText(r.name).width + 36;
    });
    const x = (step) => this.left + (step - this.range[0]) / (this.range[1] - this.range[0]) * (right - this.left);
    panels.forEach((panel, p) => {
      const top = p * panelHeight + 28;
      const bottom = top + panelHeight - 20;
      const values = [];
      for (const r of this.runs) {
        for (const f of [panel.series, panel.extra]) {
          const s = f && f(r.steps.columns, r);
          if (s) for (const v of s) if (Number.isFinite(v)) values.push(v);
        }
      }
      // No spread of the values into Math.max: a long run has more steps than a call may take arguments.
      const largest = values.reduce((a, v) => Math.max(a, v), -Infinity);
      let [lo, hi] = panel.fixed ?? [values.reduce((a, v) => Math.min(a, v), 0), largest];
      // One slow step (a page fault, a preemption) would flatten every other
      // step of a time series: scale to the 99th percentile and say so.
      let clipped = 0;
      if (panel.robust && values.length > 100) {
        const sorted = Float64Array.from(values).sort();
        const p99 = sorted[Math.floor(0.99 * (sorted.length - 1))] * 1.3;
        if (p99 < hi) { clipped = values.filter((v) => v > p99).length; hi = p99; }
      }
      if (!Number.isFinite(hi) || hi <= lo) hi = lo + 1;
      const y = (v) => bottom - (v - lo) / (hi - lo) * (bottom - top);
      g.fillStyle = '#333';
      g.fillText(clipped ? `${panel.title}; ${clipped} steps above the axis, largest ${largest.toPrecision(3)}` : panel.title, this.left, top - 3);
      g.fillText(hi.toPrecision(3), 2, top + 8);
      g.fillText(lo.toPrecision(3), 2, bottom);
      g.strokeStyle = '#ccc';
      g.strokeRect(this.left, top, right - this.left, bottom - top);
      this.runs.forEach((r, i) => {
        const steps = r.steps.columns.step;
        const lines = [[panel.series(r.steps.columns, r), []], [panel.extra && panel.extra(r.steps.columns, r), [4, 3]]];
        for (const [s, dash] of lines) {
          if (!s) continue;
          g.strokeStyle = RUN_COLOURS[i % RUN_COLOURS.length];
          g.setLineDash(dash);
          // Oracle columns are filled only where the oracle ran (every K
          // steps): the line joins the measured steps and marks each one.
          g.beginPath();
          let pen = false;
          let measured = 0;
          for (let k = 0; k < steps.length; ++k) {
            if (!Number.isFinite(s[k])) continue;
            const v = Math.min(s[k], hi);
            if (pen) g.lineTo(x(steps[k]), y(v)); else g.moveTo(x(steps[k]), y(v));
            pen = true;
            ++measured;
          }
          g.stroke();
          if (measured < steps.length / 2) {
            g.fillStyle = RUN_COLOURS[i % RUN_COLOURS.length];
            for (let k = 0; k < steps.length; ++k) if (Number.isFinite(s[k])) g.fillRect(x(steps[k]) - 1.5, y(s[k]) - 1.5, 3, 3);
          }
        }
        g.setLineDash([]);
      });
      g.strokeStyle = '#000';
      g.beginPath();
      g.moveTo(x(this.cursorStep), top);
      g.lineTo(x(this.cursorStep), bottom);
      g.stroke();
    });
  }
}
