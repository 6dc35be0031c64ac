// Browser check of the HMI's Stations panel (each station's state, current operation and the
// time elapsed in it), in real Chromium. Run by tests/e2e/hmi_e2e_test.cpp against a running
// virtcom (`run --hmi`, `serve --http`, or `monitor --http` watching a served plant):
//   node check_stations.js live PORT OUTDIR
// The panel must agree with the Gantt chart, which the stream's activities draw: a busy
// station's operation is its running bar's, since that bar's start (elapsed = now − start), and
// its elapsed time grows with virtual time. Prints "hmi checks passed" on success.
'use strict';
const assert = require('node:assert/strict');
const { hmiPage, runMode } = require('./hmi_page.js');

const [mode, port, outDir] = process.argv.slice(2);
const { launch, api, shot, eventually, openHmi } = hmiPage(port, outDir);

// In one look at the page: virtual time, the stations' rows, the running Gantt bars by lane.
const look = (page) => page.evaluate(() => {
  const nowNs = Number(document.getElementById('vtime').dataset.ns);
  const stations = [...document.querySelectorAll('#stations tbody tr')].map((tr) => ({
    device: tr.dataset.device, state: tr.querySelector('.state').textContent, op: tr.querySelector('.op').textContent,
    elapsedNs: Number(tr.querySelector('.elapsed').dataset.ns) }));
  const running = [...document.querySelectorAll('#gantt rect.bar.running')].map((r) => ({
    lane: Math.round((Number(r.getAttribute('y')) - 3) / 22), title: r.querySelector('title').textContent }));
  return { nowNs, stations, running };
});

// The running bar of lane `lane` as {label, startS}, from its title "Label 1.23–… s".
function barOf(view, lane) {
  const bar = view.running.find((b) => b.lane === lane);
  const m = bar && /^(.*) (\d+\.\d\d)–… s$/.exec(bar.title);
  return m ? { label: m[1], startS: Number(m[2]) } : null;
}

async function live() {
  const model = (await api('model')).json;
  const names = model.devices.map((d) => d.name);
  const browser = await launch();
  try {
    const page = await openHmi(browser);
    const first = await look(page);
    assert.deepEqual(first.stations.map((s) => s.device), names, 'a row per device, in the model\'s order');
    // A busy station whose Gantt bar runs: the same operation, started when the panel says.
    const agreeing = (view) => view.stations.findIndex((s, lane) => {
      const bar = s.state === 'busy' ? barOf(view, lane) : null;
      return bar && bar.label === s.op && s.elapsedNs > 0 &&
             Math.abs((view.nowNs - s.elapsedNs) / 1e9 - bar.startS) <= 0.006;  // the title rounds to 10 ms
    });
    const busy = await eventually(() => look(page), (v) => agreeing(v) >= 0, 'a busy station agrees with its running Gantt bar');
    const lane = agreeing(busy);
    assert.ok(model.labels.includes(busy.stations[lane].op), `an operation of the cell: ${busy.stations[lane].op}`);
    await shot(page, 'stations');
    // Its elapsed time grows with virtual time while it stays in that operation, or it moves on.
    const since = busy.nowNs - busy.stations[lane].elapsedNs;
    const later = await eventually(() => look(page), (v) => v.nowNs > busy.nowNs, 'virtual time goes on');
    const now = later.stations[lane], bar = barOf(later, lane);
    if (now.state === 'busy' && bar && Math.abs(bar.startS - since / 1e9) <= 0.006)  // still in that operation
      assert.equal(later.nowNs - now.elapsedNs, since, 'the same start: elapsed = now − start');
    for (const s of later.stations) {
      assert.ok(['idle', 'busy', 'error', 'fault'].includes(s.state), `${s.device}: state ${s.state}`);
      assert.ok(s.elapsedNs >= 0 && s.elapsedNs <= later.nowNs, `${s.device}: elapsed ${s.elapsedNs} within the run`);
      if (s.state === 'idle') assert.equal(s.op, '(idle)');
    }
  } finally {
    await browser.close();
  }
}

runMode({ live }, mode);
