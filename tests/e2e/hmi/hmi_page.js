// What the browser checks of the web HMI share (check_hmi.js, check_run_panels.js): launching
// Debian's chromium through npm playwright-core, the API, polling, screenshots into OUTDIR.
'use strict';
const assert = require('node:assert/strict');
const path = require('node:path');
const { chromium } = require('playwright-core');

const kTimeoutMs = 30000;
const kLaunch = {
  executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
  args: ['--no-sandbox', '--disable-gpu', '--disable-dev-shm-usage'],
};

const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));

// Polls `read` until `accept` holds (30 s at most).
async function eventually(read, accept, what) {
  let last;
  for (let waited = 0; waited < kTimeoutMs; waited += 50) {
    last = await read();
    if (accept(last)) return last;
    await sleep(50);
  }
  assert.fail(`${what}: last value ${JSON.stringify(last)}`);
}

// The helpers for the HMI served on `port`, screenshots going to `outDir`.
function hmiPage(port, outDir) {
  const url = `http://127.0.0.1:${port}/`;
  const virtualNs = (page) => page.$eval('#vtime', (e) => Number(e.dataset.ns));
  const api = async (route, body) => {
    const response = await fetch(`${url}api/${route}`, body === undefined ? {} : {
      method: 'POST', headers: { 'Content-Type': 'application/json' }, body: JSON.stringify(body) });
    return { status: response.status, json: await response.json() };
  };
  const shot = (page, name) => page.screenshot({ path: path.join(outDir, `${name}.png`), fullPage: true });
  // A page that shows the running cell (`running` false: a run started paused, at time 0); an
  // error in the page's script fails the check.
  async function openHmi(browser, running = true) {
    const page = await browser.newPage({ viewport: { width: 1500, height: 1000 } });
    page.on('pageerror', (error) => { throw error; });
    await page.goto(url);
    await page.waitForSelector('g.device');
    if (running) await eventually(() => virtualNs(page), (ns) => ns > 0, 'the page shows virtual time');
    return page;
  }
  return { url, kLaunch, launch: () => chromium.launch(kLaunch), sleep, virtualNs, api, shot, eventually, openHmi };
}

// Runs the check named `mode` among `checks`; prints "hmi checks passed" or fails the process.
function runMode(checks, mode) {
  (checks[mode] ?? (() => assert.fail(`unknown mode ${mode}`)))()
    .then(() => console.log('hmi checks passed'))
    .catch((error) => {
      console.error(error);
      process.exit(1);
    });
}

module.exports = { hmiPage, runMode };
