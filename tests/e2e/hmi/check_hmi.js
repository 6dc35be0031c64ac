// Browser checks of the virtcom web HMI in real Chromium (Debian's /usr/bin/chromium driven by
// npm playwright-core). Run by tests/e2e/hmi_e2e_test.cpp against a running virtcom:
//   node check_hmi.js served PORT OUTDIR   the gearbox cell under `virtcom serve --http`
//   node check_hmi.js ended PORT OUTDIR    a `virtcom run --hmi` that reaches its end
// Screenshots go to OUTDIR (kept as artifacts). Prints "hmi checks passed" on success.
'use strict';
const assert = require('node:assert/strict');
const { chromium } = require('playwright-core');
const { hmiPage, runMode } = require('./hmi_page.js');

const [mode, port, outDir] = process.argv.slice(2);
const { launch, kLaunch, sleep, virtualNs, api, shot, eventually, openHmi } = hmiPage(port, outDir);
const kGearboxDevices = ['AxisX', 'AxisY', 'Press', 'Robot1', 'Robot2'];

async function everyDeviceIsDrawn(page) {
  const names = await page.$$eval('g.device', (gs) => gs.map((g) => g.dataset.name).sort());
  assert.deepEqual(names, kGearboxDevices);
}

// The cell file's `hmi:` section: its static shapes are drawn, and the press stands where it
// places it, under its label; the table's axes are framed as one group.
async function theCellFilesPlanIsDrawn(page) {
  const kinds = await page.$$eval('#layout g.shape', (gs) => gs.map((g) => g.dataset.kind));
  assert.deepEqual(kinds, ['rect', 'rect', 'rect', 'circle', 'circle', 'line', 'text']);
  assert.equal(await page.textContent('#layout g.shape[data-kind="text"] text'), 'operator side');
  const fence = await page.$eval('#layout g.shape rect', (r) => [r.getAttribute('x'), r.getAttribute('width')]);
  assert.deepEqual(fence, ['-1000', '4800']);
  const press = await page.$eval('g.device[data-name="Press"]', (g) => {
    const body = g.querySelector('rect.body');
    return { x: body.getAttribute('x'), y: body.getAttribute('y'), label: g.querySelector('text').textContent };
  });
  assert.deepEqual(press, { x: '500', y: '-1450', label: 'Servo press' });  // y up: -(950 + 500)
  assert.deepEqual(await page.$$eval('#layout g.group', (gs) => gs.map((g) => g.dataset.group)), ['Positioning table']);
}

// A trend of Robot1.actualX fills with points as the run goes, and zooms in to a shorter window.
async function trendPlotsASignal(page) {
  await page.fill('#trend-name', 'Robot1.actualX');
  await page.click('#trend-form button:not([type])');
  await eventually(() => page.$$eval('#trend-legend li', (l) => l.map((e) => e.dataset.name)), (n) => n.includes('Robot1.actualX'),
                   'the trend lists the signal');
  const points = () => page.$eval('#trend', (c) => Number(c.dataset.points));
  await eventually(points, (n) => n > 3, 'the trend shows points after the run progresses');
  await page.hover('#trend');
  await page.mouse.wheel(0, -200);
  const span = await page.$eval('#trend', (c) => Number(c.dataset.spanNs));
  assert.ok(span > 0, `the mouse wheel zooms in (span ${span} ns)`);
  await page.click('#trend-all');
  assert.equal(await page.$eval('#trend', (c) => Number(c.dataset.spanNs)), 0, '"all" shows the whole run');
  await shot(page, 'trend');
}

async function robotMovesAndGanttGrows(page) {
  const marker = () => page.$eval('circle.tcp[data-device="Robot1"]', (c) => `${c.getAttribute('cx')},${c.getAttribute('cy')}`);
  const bars = () => page.$$eval('#gantt rect.bar', (r) => r.length);
  const firstMarker = await marker(), firstBars = await bars();
  await eventually(marker, (m) => m !== firstMarker, "Robot1's tool centre point moves");
  await eventually(bars, (n) => n > firstBars, 'the Gantt chart grows');
  await eventually(() => page.$$eval('g.device[data-state="busy"]', (g) => g.length), (n) => n > 0, 'a device shows busy');
}

async function pauseAndStep(page, baseTickNs) {
  await page.click('#btn-pause');
  await eventually(() => page.textContent('#run-state'), (s) => s === 'paused', 'the badge says paused');
  const paused = await virtualNs(page);
  await sleep(400);
  assert.equal(await virtualNs(page), paused, 'virtual time stands still while paused');
  await shot(page, 'paused');
  await page.click('#btn-step');
  await eventually(() => virtualNs(page), (ns) => ns !== paused, 'a step advances virtual time');
  await sleep(300);
  assert.equal(await virtualNs(page), paused + baseTickNs, 'one step is one base tick');
  await page.click('#btn-run');
  await eventually(() => virtualNs(page), (ns) => ns > paused + baseTickNs, 'run resumes');
}

// Forcing MAIN.jobsFinished beyond the job count makes the PLC's own logic report a finished
// cycle (cycleDone := jobsFinished >= jobCount), which the KPI panel counts.
async function forcingChangesThePlc(page) {
  await page.fill('#var-search', 'jobsfinished');
  await page.click('#var-results li[data-name="MAIN.jobsFinished"]');
  const row = page.locator('#watch tr[data-name="MAIN.jobsFinished"]');
  await row.locator('.new-value').fill('99');
  await row.locator('.force').click();
  await eventually(() => row.getAttribute('class'), (c) => (c || '').includes('forced'), 'the forced row is marked');
  await eventually(() => row.locator('.value').textContent(), (v) => v === '99', 'the forced value is shown');
  await eventually(() => page.textContent('#kpi-cycles'), (c) => Number(c) >= 1, 'the PLC completes a cycle because of the force');
  const vars = await api('vars?match=MAIN.jobsFinished');
  assert.equal(vars.json.vars[0].value, '99');
  assert.equal(vars.json.vars[0].forced, true);
  await shot(page, 'forced');
  await page.click('#release-all');
  await eventually(() => row.getAttribute('class'), (c) => !(c || '').includes('forced'), 'release all unmarks the row');
}

async function served() {
  const model = (await api('model')).json;
  assert.deepEqual(model.devices.map((d) => d.name).sort(), kGearboxDevices);
  const browser = await launch();
  const secondServer = await chromium.launchServer(kLaunch);  // its process, to kill it
  const second = await chromium.connect(secondServer.wsEndpoint());
  try {
    const page = await openHmi(browser);
    const other = await openHmi(second);  // two viewers at once
    await everyDeviceIsDrawn(page);
    await everyDeviceIsDrawn(other);
    await theCellFilesPlanIsDrawn(page);
    await robotMovesAndGanttGrows(page);
    await trendPlotsASignal(page);
    await shot(page, 'running');
    await shot(other, 'second-viewer');
    // A browser killed mid-run: the run and the other viewer go on.
    secondServer.process().kill('SIGKILL');
    const before = await virtualNs(page);
    await eventually(() => virtualNs(page), (ns) => ns > before + 500e6, 'the run goes on after a viewer was killed');
    await pauseAndStep(page, model.baseTickNs);
    await forcingChangesThePlc(page);
    await shot(page, 'final');
  } finally {
    await browser.close();
  }
}

async function ended() {
  const browser = await launch();
  try {
    const page = await openHmi(browser);
    await everyDeviceIsDrawn(page);
    await eventually(() => page.textContent('#run-state'), (s) => s === 'ended', 'the page shows the end of the run');
    await eventually(() => page.textContent('#kpi-cycles'), (c) => c === '1', 'one cycle completed');
    const bars = await page.$$eval('#gantt rect.bar', (r) => r.length);
    assert.ok(bars > 20, `the whole cycle's operations are in the Gantt chart (${bars})`);
    await shot(page, 'ended');
  } finally {
    await browser.close();
  }
}

runMode({ served, ended }, mode);
