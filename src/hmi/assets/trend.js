// The Trends panel: chosen signals (bus tags) and watched PLC variables plotted over virtual time
// on one canvas, fed by the stream's frames. Each series keeps at most MAX_POINTS points (the
// oldest are dropped), so a page left open for days stays small. The time axis zooms with the
// mouse wheel or the buttons: the window always ends at the present, unless a fixed window of the
// history is shown (showRange; the zoom then goes to onWindowZoom, which reads another range).
const MAX_POINTS = 4000;
const COLOURS = ['#1f77b4', '#d62728', '#2ca02c', '#ff7f0e', '#9467bd', '#8c564b', '#e377c2', '#17becf'];
const MIN_SPAN_NS = 100e6;

// A value of the stream as a number to plot: booleans 0/1, numbers as they are, IEC text of a
// number (`42`, `1.5`, `TRUE`); anything else (strings, times) is not plotted.
function plotValue(value) {
  if (typeof value === 'boolean') return value ? 1 : 0;
  if (typeof value === 'number') return value;
  if (value === 'TRUE') return 1;
  if (value === 'FALSE') return 0;
  const n = Number(value);
  return Number.isFinite(n) ? n : null;
}

export class Trend {
  // canvas: the plot; legend: a list the series are shown in (a click removes one).
  constructor(canvas, legend, onChange) {
    this.canvas = canvas;
    this.legend = legend;
    this.onChange = onChange;   // called with the list of series names when it changes
    this.series = new Map();    // name -> {points: [[tNs, v]], colour}
    this.spanNs = 0;            // 0: everything since the start
    this.nowNs = 0;
    this.window = null;         // {fromNs, toNs}: a fixed range of the history
    this.onWindowZoom = null;
    canvas.addEventListener('wheel', (e) => {
      e.preventDefault();
      this.zoom(e.deltaY < 0 ? 0.5 : 2);
    }, { passive: false });
  }

  has(name) { return this.series.has(name); }
  names() { return [...this.series.keys()]; }

  add(name) {
    if (this.series.has(name)) return;
    this.series.set(name, { points: [], colour: COLOURS[this.series.size % COLOURS.length] });
    this.renderLegend();
    this.onChange(this.names());
  }

  remove(name) {
    this.series.delete(name);
    this.renderLegend();
    this.onChange(this.names());
  }

  // A new value of series `name` at virtual time tNs (unchanged values need not be pushed: the
  // plot holds the last value up to the present).
  push(name, tNs, value) {
    const s = this.series.get(name);
    const v = plotValue(value);
    if (!s || v === null) return;
    s.points.push([tNs, v]);
    if (s.points.length > MAX_POINTS) s.points.splice(0, s.points.length - MAX_POINTS);
  }

  clear() {
    for (const s of this.series.values()) s.points.length = 0;
  }

  // factor < 1 zooms in; the span never exceeds the run so far (then it is "all").
  zoom(factor) {
    if (this.window && this.onWindowZoom) return this.onWindowZoom(factor);
    const span = (this.spanNs || this.nowNs) * factor;
    this.spanNs = span >= this.nowNs ? 0 : Math.max(span, MIN_SPAN_NS);
    this.canvas.dataset.spanNs = this.spanNs;
  }

  // Plots [fromNs, toNs] from now on (null: back to the live window ending at the present).
  showRange(fromNs, toNs) {
    this.window = fromNs === null ? null : { fromNs, toNs };
  }

  renderLegend() {
    this.legend.replaceChildren();
    for (const [name, s] of this.series) {
      const li = document.createElement('li');
      li.dataset.name = name;
      li.style.color = s.colour;
      li.textContent = `${name} ×`;
      li.title = 'remove from the trend';
      li.onclick = () => this.remove(name);
      this.legend.appendChild(li);
    }
  }

  render(nowNs) {
    this.nowNs = nowNs;
    const c = this.canvas, ctx = c.getContext('2d');
    const width = c.clientWidth, height = c.clientHeight;
    if (c.width !== width) c.width = width;
    if (c.height !== height) c.height = height;
    ctx.clearRect(0, 0, width, height);
    const t1 = this.window ? Math.max(this.window.toNs, this.window.fromNs + 1) : Math.max(nowNs, 1);
    const t0 = this.window ? this.window.fromNs : this.spanNs ? Math.max(t1 - this.spanNs, 0) : 0;
    let lo = Infinity, hi = -Infinity;
    for (const s of this.series.values())
      for (const [t, v] of s.points) if (t >= t0 || s.points.length === 1) { lo = Math.min(lo, v); hi = Math.max(hi, v); }
    if (lo === Infinity) { lo = 0; hi = 1; }
    if (hi - lo < 1e-9) { lo -= 0.5; hi += 0.5; }
    const left = 50, bottom = 18;
    const x = (t) => left + ((t - t0) / (t1 - t0)) * (width - left - 4);
    const y = (v) => 4 + (1 - (v - lo) / (hi - lo)) * (height - bottom - 8);
    ctx.fillStyle = '#567';
    ctx.font = '11px system-ui, sans-serif';
    ctx.fillText(hi.toPrecision(4), 2, 12);
    ctx.fillText(lo.toPrecision(4), 2, height - bottom);
    ctx.fillText(`${(t0 / 1e9).toFixed(1)} s`, left, height - 4);
    ctx.fillText(`${(t1 / 1e9).toFixed(1)} s`, width - 50, height - 4);
    let drawn = 0;
    for (const s of this.series.values()) {
      ctx.strokeStyle = s.colour;
      ctx.beginPath();
      let last = null;
      for (const [t, v] of s.points) {
        // a step plot: each value holds until the next one
        if (last === null) ctx.moveTo(x(Math.max(t, t0)), y(v));
        else { ctx.lineTo(x(Math.max(t, t0)), y(last)); ctx.lineTo(x(Math.max(t, t0)), y(v)); }
        last = v;
        drawn += t >= t0 ? 1 : 0;
      }
      if (last !== null) ctx.lineTo(x(t1), y(last));
      ctx.stroke();
    }
    c.dataset.points = drawn;  // for the browser test: points inside the window
  }
}
