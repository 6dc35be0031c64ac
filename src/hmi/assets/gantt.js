// The Gantt chart growing as the run goes: one lane per device, one bar per activity (running
// ones up to the present), redrawn at most once per animation frame.
const LANE = 22, LABEL = 90, WIDTH = 900;
const escape = (text) => String(text).replace(/[&<>"]/g, c => ({ '&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;' })[c]);

export class Gantt {
  constructor(svg, model) {
    this.svg = svg;
    this.model = model;
    this.lanes = model.devices.map(d => d.name);
    this.laneOf = new Map(model.devices.map((d, i) => [d.trace, i]));
    svg.setAttribute('viewBox', `0 0 ${WIDTH} ${this.lanes.length * LANE + 20}`);
    svg.setAttribute('height', this.lanes.length * LANE + 20);
  }

  render(activities, nowNs) {
    const span = Math.max(nowNs, 1e9);
    const scale = (WIDTH - LABEL - 10) / span;
    const parts = [];
    this.lanes.forEach((name, i) => {
      parts.push(`<g class="lane"><text x="2" y="${i * LANE + 15}">${escape(name)}</text>` +
                 `<line x1="${LABEL}" x2="${WIDTH}" y1="${(i + 1) * LANE}" y2="${(i + 1) * LANE}" stroke="#eee"/></g>`);
    });
    for (const [index, a] of activities) {
      const [, device, label, start, end, error] = a;
      const x = LABEL + start * scale, w = Math.max(((end < 0 ? nowNs : end) - start) * scale, 1);
      const cls = error ? 'bar error' : end < 0 ? 'bar running' : 'bar';
      const lane = this.laneOf.get(device) ?? 0;
      const title = `${escape(this.model.labels[label] ?? '')} ${(start / 1e9).toFixed(2)}–${end < 0 ? '…' : (end / 1e9).toFixed(2)} s`;
      parts.push(`<rect class="${cls}" data-index="${index}" x="${x.toFixed(1)}" y="${lane * LANE + 3}" width="${w.toFixed(1)}" height="${LANE - 6}"><title>${title}</title></rect>`);
    }
    parts.push(`<line class="now" x1="${LABEL + nowNs * scale}" x2="${LABEL + nowNs * scale}" y1="0" y2="${this.lanes.length * LANE}"/>`);
    this.svg.innerHTML = parts.join('');
  }
}
