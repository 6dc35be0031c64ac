// The Gantt chart: one lane per device, one bar per activity (running ones up to the present),
// redrawn at most once per animation frame. Live, it spans the run so far; over a time range of
// the history (history.js), it spans that range, bars clipped to it, a line at the time the
// layout shows.
const LANE = 22, LABEL = 90, WIDTH = 900;
const escape = (text) => String(text).replace(/[&<>"]/g, c => ({ '&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;' })[c]);

export class Gantt {
  constructor(svg, model) {
    this.svg = svg;
    this.model = model;
    this.lanes = model.devices.map(d => d.name);
    this.laneOf = new Map(model.devices.map((d, i) => [d.trace, i]));
    this.fromNs = 0;
    this.scale = 1;
    svg.setAttribute('viewBox', `0 0 ${WIDTH} ${this.lanes.length * LANE + 20}`);
    svg.setAttribute('height', this.lanes.length * LANE + 20);
  }

  // activities: index -> [index, trace device, label, start, end (-1: running), error]; nowNs:
  // the right edge. A range: {fromNs: the left edge, labels: the activities' label texts (else the
  // model's), markNs: where to draw the line (else nowNs)}.
  render(activities, nowNs, range = {}) {
    const fromNs = range.fromNs ?? 0, labels = range.labels ?? this.model.labels;
    const span = range.fromNs === undefined ? Math.max(nowNs, 1e9) : Math.max(nowNs - fromNs, 1);
    const scale = (WIDTH - LABEL - 10) / span;
    Object.assign(this, { fromNs, scale });
    const x = (t) => LABEL + (Math.min(Math.max(t, fromNs), fromNs + span) - fromNs) * scale;
    const parts = [];
    this.lanes.forEach((name, i) => {
      parts.push(`<g class="lane"><text x="2" y="${i * LANE + 15}">${escape(name)}</text>` +
                 `<line x1="${LABEL}" x2="${WIDTH}" y1="${(i + 1) * LANE}" y2="${(i + 1) * LANE}" stroke="#eee"/></g>`);
    });
    for (const [index, a] of activities) {
      const [, device, label, start, end, error] = a;
      const left = x(start), w = Math.max(x(end < 0 ? nowNs : end) - left, 1);
      const cls = error ? 'bar error' : end < 0 ? 'bar running' : 'bar';
      const lane = this.laneOf.get(device) ?? 0;
      const title = `${escape(labels[label] ?? '')} ${(start / 1e9).toFixed(2)}–${end < 0 ? '…' : (end / 1e9).toFixed(2)} s`;
      parts.push(`<rect class="${cls}" data-index="${index}" x="${left.toFixed(1)}" y="${lane * LANE + 3}" width="${w.toFixed(1)}" height="${LANE - 6}"><title>${title}</title></rect>`);
    }
    const mark = x(range.markNs ?? nowNs);
    parts.push(`<line class="now" x1="${mark}" x2="${mark}" y1="0" y2="${this.lanes.length * LANE}"/>`);
    this.svg.innerHTML = parts.join('');
  }

  // The virtual time under a mouse event on the chart as last drawn; null over the lane names.
  // (The chart's own transform: however the page sizes the SVG, its viewBox keeps its aspect and
  // is centred, so screen and chart x differ by more than a scale.)
  timeAt(event) {
    const { x } = new DOMPoint(event.clientX, event.clientY).matrixTransform(this.svg.getScreenCTM().inverse());
    return x < LABEL ? null : this.fromNs + (x - LABEL) / this.scale;
  }
}
