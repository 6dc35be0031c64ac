// Browser checks of the HMI's History panel in real Chromium. Run by tests/e2e/hmi_e2e_test.cpp:
//   node check_history.js replay PORT OUTDIR  `virtcom history FILE --http`: the newest run's Gantt
//                                             chart (one bar per recorded activity), a trend drawn
//                                             from history, a zoomed range, the layout at a time
//   node check_history.js live PORT OUTDIR    `serve --history --http`: the past of the running run
// Screenshots go to OUTDIR (kept as artifacts). Prints "hmi checks passed" on success.
'use strict';
const assert = require('node:assert/strict');
const { hmiPage, runMode } = require('./hmi_page.js');

const [mode, port, outDir] = process.argv.slice(2);
const { url, launch, api, shot, eventually, virtualNs, openHmi } = hmiPage(port, outDir);

const bars = (page) => page.$$eval('#gantt rect.bar', (r) => r.length);
const trendPoints = (page) => page.$eval('#trend', (c) => Number(c.dataset.points ?? 0));
const shown = (page) => page.$eval('#history-info', (e) => ({ ...e.dataset }));

async function withBrowser(check) {
  const browser = await launch();
  try {
    await check(browser);
  } finally {
    await browser.close();
  }
}

// The newest run and, among its signals, the one that changed most (read through the API).
async function newestRunAndBusiestSignal() {
  const { json: { runs } } = await api('history/runs');
  const run = runs[runs.length - 1];
  const { json: whole } = await api(`history/range?run=${run.id}`);
  let best = null;
  for (let i = 0; i < whole.signals.length; i += 64) {
    const names = whole.signals.slice(i, i + 64).map(encodeURIComponent).join(',');
    const { json } = await api(`history/range?run=${run.id}&points=3&signals=${names}`);
    for (const s of json.series) if (!best || s.changes > best.changes) best = s;
  }
  return { run, whole, signal: best.name };
}

async function addTrend(page, name) {
  await page.fill('#trend-name', name);
  await page.click('#trend-form button:first-of-type');
}

// The bars drawn are the activities the API gives for the range the page shows.
async function barsMatchTheApi(page, run) {
  const { from, to, activities } = await eventually(() => shown(page), (d) => d.activities !== undefined, 'a range is shown');
  const { json } = await api(`history/range?run=${run.id}&from=${from}&to=${to}`);
  assert.equal(json.activities.length, Number(activities));
  await eventually(() => bars(page), (n) => n === json.activities.length, `one bar per recorded activity (${json.activities.length})`);
  return json.activities.length;
}

async function replay() {
  const { run, whole, signal } = await newestRunAndBusiestSignal();
  assert.equal(whole.activities.length, run.activities, 'the range of the whole run has every recorded activity');
  assert.ok(run.activities > 5, `a run with activities (${run.activities})`);
  await withBrowser(async (browser) => {
    const page = await browser.newPage({ viewport: { width: 1500, height: 1000 } });
    page.on('pageerror', (error) => { throw error; });
    await page.goto(url);
    await page.waitForSelector('g.device');
    assert.equal(await page.textContent('#run-state'), 'history');
    assert.equal(await page.isVisible('#btn-run'), false, 'no run controls without a live run');
    assert.equal(await page.isVisible('#history-toggle'), false, 'browsing needs no toggle');
    await eventually(() => bars(page), (n) => n === run.activities, `the Gantt chart has the ${run.activities} recorded activities`);
    await barsMatchTheApi(page, run);
    await addTrend(page, signal);
    await eventually(() => trendPoints(page), (n) => n > 1, `the trend of ${signal} is drawn from history`);
    await shot(page, 'history-whole-run');
    // Zoom in twice: a quarter of the run, fewer bars, each the API's.
    for (let i = 0; i < 2; ++i) {
      const before = await shown(page);
      await page.click('#history-zoom-in');
      await eventually(() => shown(page), (d) => Number(d.to) - Number(d.from) < Number(before.to) - Number(before.from), 'zoomed in');
    }
    const zoomed = await barsMatchTheApi(page, run);
    assert.ok(zoomed < run.activities, `fewer bars in a quarter of the run (${zoomed} of ${run.activities})`);
    await eventually(() => trendPoints(page), (n) => n > 0, 'the trend follows the zoom');
    await shot(page, 'history-zoomed');
    // A click on the Gantt chart shows the layout at that time: the devices busy then. Clicked in
    // the middle of the widest bar, the time is inside that activity (the page is wider than the
    // chart's 900 units, which are centred in it: the click goes through the chart's transform).
    const bar = await page.$$eval('#gantt rect.bar:not(.running)', (rects) => {
      const widest = rects.reduce((a, r) => (r.getBoundingClientRect().width > a.getBoundingClientRect().width ? r : a));
      const b = widest.getBoundingClientRect();
      const [, start, end] = widest.textContent.match(/([\d.]+)–([\d.]+) s$/);
      return { x: b.x + b.width / 2, y: b.y + b.height / 2, start: Number(start), end: Number(end) };
    });
    const endNs = await virtualNs(page);  // the layout showed the end of the run so far
    await page.mouse.click(bar.x, bar.y);
    const atNs = await eventually(() => virtualNs(page), (ns) => ns > 0 && ns !== endNs, 'the layout shows a chosen time');
    assert.ok(atNs / 1e9 >= bar.start - 0.01 && atNs / 1e9 <= bar.end + 0.01,
              `the click on the bar of ${bar.start}–${bar.end} s shows a time inside it (${atNs / 1e9} s)`);
    const { json: state } = await api(`history/state?run=${run.id}&at=${Math.round(atNs)}`);
    const busy = new Set(state.activities.map((a) => state.devices[a[1]].name));
    await eventually(() => page.$$eval('g.device[data-state=busy]', (g) => g.map((e) => e.dataset.name).sort()),
                     (names) => JSON.stringify(names) === JSON.stringify([...busy].sort()), `the devices busy at ${atNs} ns`);
    await shot(page, 'history-layout-at-a-time');
    // Back to the whole run.
    await page.click('#history-all');
    await eventually(() => bars(page), (n) => n === run.activities, 'the whole run again');
  });
}

async function live() {
  await withBrowser(async (browser) => {
    const page = await openHmi(browser);
    await eventually(() => virtualNs(page), (ns) => ns > 4e9, 'the run is under way');
    const { run, signal } = await newestRunAndBusiestSignal();
    assert.equal(run.ended, false, 'the newest run is the one running');
    await addTrend(page, signal);
    assert.equal(await page.isVisible('#history-toggle'), true);
    await page.check('#history-on');
    const first = await eventually(() => shown(page), (d) => d.to !== undefined, 'a range is shown');
    // The range reaches the end of the recording run: it follows the run on its own.
    await eventually(() => shown(page), (d) => Number(d.to) > Number(first.to), 'the range grows with the run');
    await eventually(() => trendPoints(page), (n) => n > 1, `the trend of ${signal} comes from history`);
    await shot(page, 'live-history-on');
    // Zoomed in, the range stays where it is: its bars are the API's.
    const { from, to } = await shown(page);
    await page.click('#history-zoom-in');
    await eventually(() => shown(page), (d) => Number(d.to) - Number(d.from) < Number(to) - Number(from), 'zoomed in');
    const recorded = await barsMatchTheApi(page, run);
    assert.ok(recorded > 0, 'the recorded past has activities');
    await shot(page, 'live-history-zoomed');
    // Off: the panels follow the live run again, which went on meanwhile.
    const liveNs = await virtualNs(page);
    await page.uncheck('#history-on');
    await eventually(() => virtualNs(page), (ns) => ns > liveNs, 'the live run goes on');
    await eventually(() => bars(page), (n) => n > 0, 'the live Gantt chart is back');
    await shot(page, 'live-history-off');
  });
}

runMode({ replay, live }, mode);
