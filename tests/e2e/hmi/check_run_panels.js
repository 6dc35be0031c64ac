// Browser checks of the HMI's reset and of the panels beyond the gearbox's devices, in real
// Chromium. Run by tests/e2e/hmi_e2e_test.cpp against a running virtcom:
//   node check_run_panels.js reset PORT OUTDIR    the gearbox cell under `serve --http`: Reset
//   node check_run_panels.js reset-ended PORT OUTDIR  `run --hmi` ended: Reset starts it again
//   node check_run_panels.js refused PORT OUTDIR  `serve --http --modbus`: reset refused (409)
//   node check_run_panels.js sfc PORT OUTDIR      cell-sfc.yaml: the active SFC steps
//   node check_run_panels.js rules PORT OUTDIR    examples/activity/tank-cell.yaml: fired rules
//   node check_run_panels.js parts PORT OUTDIR    examples/activity/conveyor-cell.yaml: parts, bins
// Screenshots go to OUTDIR (kept as artifacts). Prints "hmi checks passed" on success.
'use strict';
const assert = require('node:assert/strict');
const { hmiPage, runMode } = require('./hmi_page.js');

const [mode, port, outDir] = process.argv.slice(2);
const { launch, sleep, virtualNs, api, shot, eventually, openHmi } = hmiPage(port, outDir);


// Opens the page, runs `check(page)`, closes the browser whatever happens.
async function withPage(check, running = true) {
  const browser = await launch();
  try {
    await check(await openHmi(browser, running));
  } finally {
    await browser.close();
  }
}

const gantt = (page) => page.$$eval('#gantt rect.bar', (r) => r.length);

// Reset of a paused run: the new run waits at its first tick (pause is kept), so the page shows
// exactly time 0 and an empty Gantt chart; Run then goes on in the same page (its stream never
// closed, no script error).
async function reset() {
  await withPage(async (page) => {
    await eventually(async () => [await virtualNs(page), await gantt(page)], ([ns, bars]) => ns > 3e9 && bars > 5,
                     'the run is under way');
    await page.click('#btn-pause');
    await eventually(() => page.textContent('#run-state'), (s) => s === 'paused', 'paused');
    await shot(page, 'before-reset');
    await page.click('#btn-reset');
    await eventually(async () => [await virtualNs(page), await gantt(page)], ([ns, bars]) => ns === 0 && bars === 0,
                     'Reset brings virtual time back to 0 and clears the Gantt chart');
    assert.match(await page.textContent('#message'), /reset/);
    assert.equal(await page.$$eval('#events li', (l) => l.length), 0, 'no faults of the previous run');
    await shot(page, 'after-reset');
    await page.click('#btn-run');
    await eventually(() => virtualNs(page), (ns) => ns > 1e9, 'the new run goes on');
    await eventually(() => gantt(page), (n) => n > 0, 'the Gantt grows again');
    assert.notEqual(await page.textContent('#run-state'), 'reconnecting', 'the stream stayed connected');
    await shot(page, 'running-after-reset');
  });
}

// Reset after `run --hmi` has ended: the run starts again and the page follows it.
async function resetEnded() {
  await withPage(async (page) => {
    await eventually(() => page.textContent('#run-state'), (s) => s === 'ended', 'the run has ended');
    const [endNs, endBars] = [await virtualNs(page), await gantt(page)];
    await page.click('#btn-reset');
    await eventually(() => virtualNs(page), (ns) => ns < endNs, 'virtual time went back');
    await eventually(() => page.textContent('#run-state'), (s) => s === 'ended', 'the new run ends too');
    assert.equal(await gantt(page), endBars, 'the new run has the same operations, not those of both runs');
    await shot(page, 'reset-after-end');
  });
}

// With --modbus attached, reset is refused with the reason (409), and the run is untouched.
async function refused() {
  await withPage(async (page) => {
    const reply = await api('control', { action: 'reset' });
    assert.equal(reply.status, 409);
    assert.match(reply.json.error, /--modbus, --ads or --opcua/);
    await page.click('#btn-reset');
    await eventually(() => page.textContent('#message'), (m) => /--modbus, --ads or --opcua/.test(m), 'the page shows why');
    const ns = await virtualNs(page);
    await sleep(300);
    assert.ok(await virtualNs(page) >= ns, 'the run was not reset');
    await shot(page, 'reset-refused');
  });
}

// The SFC panel lists the chart's POU with its active step, which changes as the chart runs.
async function sfc() {
  await withPage(async (page) => {
    assert.equal(await page.isVisible('#sfc-panel'), true);
    assert.equal(await page.isVisible('#rules-panel'), false, 'no activity diagram: no rule panel');
    const active = () => page.$eval('#sfc-steps tr[data-pou="MAIN"] td.active', (td) => td.dataset.steps ?? '');
    const first = await eventually(active, (s) => s !== '', 'MAIN has an active step');
    await eventually(active, (s) => s !== '' && s !== first, `the active step changes (first ${first})`);
    assert.match(await page.textContent('#sfc-steps tr[data-pou="MAIN"] td.active'), /\(\d+\.\d\d s\)/, 'the time in the step');
    await shot(page, 'sfc-steps');
  });
}

// The rule panel lists every rule of the tank's three diagrams with its LU type, and counts them.
async function rules() {
  const model = (await api('model')).json;
  assert.ok(model.rules.length > 5, `the tank's rules (${model.rules.length})`);
  assert.deepEqual([...new Set(model.rules.map((r) => r.diagram))].sort(), ['Drain', 'Reaction', 'Supply']);
  await withPage(async (page) => {
    assert.equal(await page.isVisible('#rules-panel'), true);
    assert.equal(await page.$$eval('#rules tbody tr', (rows) => rows.length), model.rules.length);
    const counts = () => page.$$eval('#rules td.count', (tds) => tds.map((td) => Number(td.textContent)));
    await eventually(counts, (c) => c.filter((n) => n > 0).length >= 2, 'rules fire');
    const lu = await page.$$eval('#rules tbody tr td:nth-child(3)', (tds) => tds.map((td) => td.textContent));
    assert.ok(lu.every((t) => /^[1-4](-[12])?$/.test(t)), `LU types ${lu}`);
    const before = (await counts()).reduce((a, b) => a + b, 0);
    await eventually(async () => (await counts()).reduce((a, b) => a + b, 0), (n) => n > before, 'the counts grow');
    await shot(page, 'fired-rules');
  });
}

// The conveyor cell, served paused (its lot of parts would be through before a slow browser
// has started): Run, then parts drawn on the belt move along it; the bins count what they
// received.
async function parts() {
  await withPage(async (page) => {
    await eventually(() => page.textContent('#run-state'), (s) => s === 'paused', 'served paused');
    await page.click('#btn-run');
    const onBelt = () => page.$$eval('g.device[data-name="Belt"] rect.part', (r) => r.map((e) => Number(e.getAttribute('x'))));
    const first = await eventually(onBelt, (xs) => xs.length > 0, 'a part is drawn on the belt');
    await eventually(onBelt, (xs) => xs.length > 0 && Math.max(...xs) > Math.max(...first), 'the parts move along the belt');
    const bins = await page.$$eval('g.device[data-name="Belt"] g.bin', (g) => g.map((e) => e.dataset.bin));
    assert.deepEqual(bins, ['reject', 'steelGate', 'end']);
    const counted = () => page.$$eval('g.bin text.bin-count', (t) => t.map((e) => Number(e.dataset.count)));
    await eventually(counted, (c) => c.some((n) => n > 0), 'a bin counts a part');
    const kinds = await page.$$eval('rect.part', (r) => r.map((e) => e.dataset.kind));
    assert.ok(kinds.every((k) => ['steel', 'plastic', 'bad_steel', 'bad_plastic'].includes(k)), `part kinds ${kinds}`);
    await shot(page, 'conveyor-parts');
  }, false);
}

runMode({ reset, 'reset-ended': resetEnded, refused, sfc, rules, parts }, mode);
