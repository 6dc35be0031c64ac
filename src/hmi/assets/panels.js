// The panels of the cell's state beyond the layout: the stations (one row per device: its state,
// the operation it is in and for how long, or how long it has been idle), the active SFC steps
// (one row per POU with a chart: its active steps and the time in each) and the fired rules of
// activity-diagram programs (one row per rule: diagram, index, LU type, THEN, how often its IF
// held and when last); the last two are hidden when the program has none. Frames: `stations`
// ([device, label or -1, since ns] of the stations that changed), `steps` ([step index, ms in
// step] of every active step) and `rules` ([rule index, count, last ns] of the rules that
// fired); docs/hmi.md.
const seconds = (ns) => `${(ns / 1e9).toFixed(3)} s`;

function cell(row, text, cls) {
  const td = row.insertCell();
  td.textContent = text;
  if (cls) td.className = cls;
  return td;
}

// "MAIN.fbFeeder.Wait" -> ["MAIN.fbFeeder", "Wait"]
function splitStep(path) {
  const dot = path.lastIndexOf('.');
  return [path.slice(0, dot), path.slice(dot + 1)];
}

export class StationPanel {
  // devices: the model's; labels: the model's operation names.
  constructor(tbody, devices, labels) {
    this.labels = labels;
    this.rows = new Map();  // trace device index -> {row, state, op, elapsed, label, sinceNs}
    for (const d of devices) {
      const row = tbody.insertRow();
      row.dataset.device = d.name;
      cell(row, d.label || d.name, 'station');
      this.rows.set(d.trace, { device: d, row, state: cell(row, 'idle', 'state'), op: cell(row, '–', 'op'),
                               elapsed: cell(row, '–', 'elapsed'), label: -1, sinceNs: 0 });
    }
  }

  // changes: [[trace device, label or -1, since ns], ...]
  update(changes) {
    for (const [device, label, sinceNs] of changes) {
      const r = this.rows.get(device);
      if (!r) continue;
      r.label = label;
      r.sinceNs = sinceNs;
    }
  }

  // Every frame drawn: the elapsed times at virtual time `nowNs`; `stateOf(device)` gives the
  // state the layout colours it by (idle, busy, error, fault) and its text.
  render(nowNs, stateOf) {
    for (const r of this.rows.values()) {
      const { state, op } = stateOf(r.device);
      r.row.dataset.state = r.state.textContent = state;
      r.op.textContent = r.label >= 0 ? this.labels[r.label] ?? '' : state === 'idle' ? '(idle)' : op;
      const elapsed = Math.max(0, nowNs - r.sinceNs);
      r.elapsed.dataset.ns = elapsed;
      r.elapsed.textContent = seconds(elapsed);
    }
  }

  clear() {
    for (const r of this.rows.values()) [r.label, r.sinceNs] = [-1, 0];
  }
}

export class SfcPanel {
  constructor(section, tbody, steps) {
    this.steps = steps.map(splitStep);
    this.rows = new Map();  // POU path -> its row's cell of active steps
    section.hidden = steps.length === 0;
    for (const [pou] of this.steps) {
      if (this.rows.has(pou)) continue;
      const row = tbody.insertRow();
      row.dataset.pou = pou;
      cell(row, pou, 'pou');
      this.rows.set(pou, cell(row, '', 'active'));
    }
  }

  // active: [[step index, ms], ...]
  update(active) {
    const byPou = new Map([...this.rows.keys()].map(pou => [pou, []]));
    for (const [index, ms] of active) {
      const [pou, name] = this.steps[index];
      byPou.get(pou).push([name, ms]);
    }
    for (const [pou, list] of byPou) {
      const td = this.rows.get(pou);
      td.dataset.steps = list.map(([name]) => name).join(' ');
      td.textContent = list.map(([name, ms]) => `${name} (${(ms / 1000).toFixed(2)} s)`).join(', ') || '–';
    }
  }
}

export class RulePanel {
  constructor(section, tbody, rules) {
    section.hidden = rules.length === 0;
    this.rows = rules.map((r, i) => {
      const row = tbody.insertRow();
      row.dataset.rule = i;
      cell(row, r.diagram);
      cell(row, r.index);
      cell(row, r.luType);
      cell(row, r.then, 'then');
      return { row, count: cell(row, '0', 'count'), last: cell(row, '–', 'last') };
    });
  }

  // changes: [[rule index, count, last ns], ...]; the rows that fired in this frame light up.
  update(changes) {
    for (const r of this.rows) r.row.classList.remove('fired');
    for (const [index, count, lastNs] of changes) {
      const r = this.rows[index];
      r.count.textContent = count;
      r.last.textContent = lastNs < 0 ? '–' : seconds(lastNs);
      if (count > 0) r.row.classList.add('fired');
    }
  }

  clear() {
    for (const r of this.rows) {
      r.count.textContent = '0';
      r.last.textContent = '–';
      r.row.classList.remove('fired');
    }
  }
}
