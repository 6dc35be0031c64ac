// The panels of the PLC's program state: the active SFC steps (one row per POU with a chart:
// its active steps and the time in each) and the fired rules of activity-diagram programs (one
// row per rule: diagram, index, LU type, THEN, how often its IF held and when last). Both are
// hidden when the program has none. Frames: `steps` ([step index, ms in step] of every active
// step) and `rules` ([rule index, count, last ns] of the rules that fired); docs/hmi.md.
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
