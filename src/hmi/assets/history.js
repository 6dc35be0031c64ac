// The History panel (docs/hmi.md, "History"): the runs of the history database, and one run's
// Gantt chart and trends over a chosen virtual-time range, read from /api/history/range (the
// server decimates each signal to at most POINTS points, keeping each bucket's min and max).
// Under `virtcom history FILE --http` (model.replay) it is the page's only source: the layout
// shows the devices' states at a chosen time (a click on the Gantt chart, /api/history/state).
// Under serve/run/monitor --history it is a toggle: on, the Gantt chart and the trends show the
// recorded past instead of the live run; off, they follow the live run again. A range that reaches
// the end of a run still recording follows it (the same span, re-read every FOLLOW_MS).
const $ = (id) => document.getElementById(id);
const POINTS = 600;
const MIN_SPAN_NS = 10e6;
const FOLLOW_MS = 2000;
const seconds = (ns) => (ns / 1e9).toFixed(3);

async function getJson(url) {
  const response = await fetch(url);
  const body = await response.json().catch(() => ({}));
  if (!response.ok) throw new Error(body.error ?? `HTTP ${response.status}`);
  return body;
}

export class HistoryView {
  // gantt, trend: the page's panels; showState(state) draws the layout at a time (replay only);
  // onLive() hands the panels back to the live run.
  constructor(model, gantt, trend, showState, onLive) {
    Object.assign(this, { model, gantt, trend, showState, onLive });
    this.active = false;
    this.dirty = false;
    this.runs = [];
    this.run = null;              // the run shown
    this.fromNs = 0;
    this.toNs = 0;
    this.atNs = null;             // the time the layout shows (replay)
    this.activities = new Map();  // as the live page keeps them: index -> [index, trace device, label, ...]
    this.labels = [];
    this.recorded = null;         // the names of the signals the run recorded, once known
    this.following = false;       // the range ends at the end of a run still recording
    this.ticket = 0;              // the newest load's: an older one's answer is dropped
    this.loading = 0;             // loads under way (following waits for them: a slow server is not flooded)
    $('history-panel').hidden = false;
    $('history-toggle').hidden = model.replay;
    $('history-on').onchange = () => ($('history-on').checked ? this.activate() : this.deactivate());
    $('history-run').onchange = () => this.selectRun(Number($('history-run').value));
    $('history-show').onclick = () => this.load(Number($('history-from').value) * 1e9, Number($('history-to').value) * 1e9);
    $('history-zoom-in').onclick = () => this.zoom(0.5);
    $('history-zoom-out').onclick = () => this.zoom(2);
    $('history-all').onclick = () => this.run && this.load(0, this.run.endNs);
    if (!model.replay) setInterval(() => this.follow(), FOLLOW_MS);
    this.gantt.svg.addEventListener('click', (e) => {
      const t = this.active ? this.gantt.timeAt(e) : null;
      if (t !== null) this.showAt(t);
    });
  }

  async activate() {
    this.active = true;
    this.trend.onWindowZoom = (factor) => this.zoom(factor);
    await this.listRuns();
    const newest = this.runs[this.runs.length - 1];
    if (newest) await this.selectRun(newest.id);
  }

  deactivate() {
    this.active = false;
    this.trend.showRange(null);
    this.trend.clear();
    this.onLive();
  }

  async listRuns() {
    this.runs = (await this.fetch('/api/history/runs'))?.runs ?? [];
    const select = $('history-run');
    select.replaceChildren();
    for (const r of this.runs)
      select.add(new Option(`run ${r.id}: ${r.cell}, ${seconds(r.endNs)} s${r.ended ? '' : ' (recording)'}`, r.id));
  }

  async selectRun(id) {
    this.run = this.runs.find((r) => r.id === id) ?? null;
    if (!this.run) return;
    $('history-run').value = id;
    this.atNs = null;
    this.recorded = null;
    // A live run shows its last minute; a finished one, all of it.
    const from = this.model.replay ? 0 : Math.max(0, this.run.endNs - 60e9);
    await this.load(from, this.run.endNs);
  }

  // Zooms about the middle of the range (factor < 1: in), kept inside the run.
  zoom(factor) {
    if (!this.run) return;
    const middle = (this.fromNs + this.toNs) / 2;
    const half = Math.max((this.toNs - this.fromNs) * factor, MIN_SPAN_NS) / 2;
    this.load(Math.max(0, middle - half), Math.min(this.run.endNs, middle + half));
  }

  // The range [fromNs, toNs]; with spanToEnd instead, the last spanToEnd of the run as recorded now.
  async load(fromNs, toNs, spanToEnd = null) {
    if (!this.run || (spanToEnd === null && !(toNs >= fromNs))) return;
    ++this.loading;
    try {
      await this.loadRange(fromNs, toNs, spanToEnd);
    } finally {
      --this.loading;
    }
  }

  // endBefore: the run's end when the range was chosen (a range up to it follows the run).
  async loadRange(fromNs, toNs, spanToEnd, endBefore = this.run.endNs) {
    const ticket = ++this.ticket;
    if (!this.model.replay) await this.refreshRun();  // the live run has grown
    if (spanToEnd !== null) [fromNs, toNs] = [Math.max(0, this.run.endNs - spanToEnd), this.run.endNs];
    const following = !this.model.replay && !this.run.ended && toNs >= endBefore;
    // Only what the run recorded (the trend may hold names of another run or PLC variables).
    const first = this.recorded === null;
    const names = this.trend.names().filter((n) => this.recorded?.has(n)).map(encodeURIComponent).join(',');
    const url = `/api/history/range?run=${this.run.id}&from=${Math.round(fromNs)}&to=${Math.round(toNs)}` +
                `&points=${POINTS}&signals=${names}`;
    const data = await this.fetch(url);
    if (!data || ticket !== this.ticket) return;
    this.following = following;
    this.fromNs = data.from;
    this.toNs = Math.max(data.to, data.from);
    $('history-from').value = seconds(this.fromNs);
    $('history-to').value = seconds(this.toNs);
    this.labels = data.labels;
    this.fillChoices(data.signals);
    this.recorded = new Set(data.signals);
    if (first && this.trend.names().some((n) => this.recorded.has(n))) return this.loadRange(fromNs, toNs, null, endBefore);
    const traceOf = data.devices.map((d) => this.model.devices.find((m) => m.name === d.name)?.trace ?? -1);
    this.activities = new Map();
    for (const a of data.activities) if (traceOf[a[1]] >= 0) this.activities.set(a[0], [a[0], traceOf[a[1]], ...a.slice(2)]);
    this.trend.clear();
    this.trend.showRange(this.fromNs, this.toNs);
    for (const s of data.series) {
      this.trend.push(s.name, this.fromNs, s.before);
      for (const [t, v] of s.points) this.trend.push(s.name, t, v);
    }
    const decimated = data.series.filter((s) => s.decimated).map((s) => s.name);
    $('history-info').textContent = `${data.activities.length} activities` +
        (decimated.length ? `; decimated (min/max per bucket): ${decimated.join(', ')}` : '');
    Object.assign($('history-info').dataset, { activities: data.activities.length, from: this.fromNs, to: this.toNs });
    this.dirty = true;
    if (this.model.replay) await this.showAt(this.atNs ?? this.toNs);
  }

  follow() {
    if (this.active && this.following && this.run && this.loading === 0) this.load(null, null, this.toNs - this.fromNs);
  }

  // Trending a new signal reads the range again.
  reload() {
    if (this.active && this.run) this.load(this.fromNs, this.toNs);
  }

  async refreshRun() {
    await this.listRuns();
    this.run = this.runs.find((r) => r.id === this.run.id) ?? this.run;
    $('history-run').value = this.run.id;
  }

  async showAt(tNs) {
    if (!this.model.replay || !this.run) return;
    const state = await this.fetch(`/api/history/state?run=${this.run.id}&at=${Math.round(tNs)}`);
    if (!state) return;
    this.atNs = state.at;
    this.showState(state);
    this.dirty = true;
  }

  fillChoices(names) {
    const list = $('trend-choices');
    const known = new Set([...list.options].map((o) => o.value));
    for (const n of names) if (!known.has(n)) list.appendChild(new Option(n));
  }

  async fetch(url) {
    try {
      return await getJson(url);
    } catch (error) {
      $('message').textContent = `history: ${error.message}`;
      return null;
    }
  }

  render() {
    if (!this.active || !this.dirty) return;
    this.dirty = false;
    this.gantt.render(this.activities, this.toNs, { fromNs: this.fromNs, labels: this.labels, markNs: this.atNs });
    this.trend.render(this.toNs);
  }
}
