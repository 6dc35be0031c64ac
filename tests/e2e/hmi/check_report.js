// Layout checks of a virtcom HTML report in real Chromium at 1400 x 1000 px (issue 16: at this
// width the device table scrolled sideways and the cycle-time label was cut off). Run by
// tests/e2e/run_e2e_test.cpp:
//   node check_report.js REPORT.html OUTDIR
// Fails on a panel or card wider than its box (a horizontal scroll bar) and on chart text that
// reaches outside its SVG (clipped). Screenshot to OUTDIR. Prints "report checks passed".
'use strict';
const path = require('node:path');
const { chromium } = require('playwright-core');

const [report, outDir] = process.argv.slice(2);

(async () => {
  const browser = await chromium.launch({
    executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
    args: ['--no-sandbox', '--disable-gpu', '--disable-dev-shm-usage'],
  });
  try {
    const page = await browser.newPage({ viewport: { width: 1400, height: 1000 } });
    await page.goto(`file://${path.resolve(report)}`);
    await page.screenshot({ path: path.join(outDir, 'report-1400.png'), fullPage: true });
    const problems = await page.evaluate(() => {
      const found = [];
      const name = (e) => (e.querySelector('h2, .k') || e).textContent.trim().slice(0, 40);
      for (const box of document.querySelectorAll('section.panel, .card')) {
        if (box.scrollWidth > box.clientWidth + 1)
          found.push(`"${name(box)}" scrolls sideways: ${box.scrollWidth} px of content in ${box.clientWidth} px`);
      }
      for (const svg of document.querySelectorAll('svg.chart')) {
        const frame = svg.getBoundingClientRect();
        for (const text of svg.querySelectorAll('text')) {
          const r = text.getBoundingClientRect();
          if (r.width > 0 && (r.left < frame.left - 1 || r.right > frame.right + 1))
            found.push(`"${text.firstChild ? text.firstChild.textContent : ''}" is clipped: ` +
                       `${Math.round(r.left)}..${Math.round(r.right)} outside ${Math.round(frame.left)}..${Math.round(frame.right)}`);
        }
      }
      return found;
    });
    if (problems.length > 0) {
      console.log(problems.join('\n'));
      process.exitCode = 1;
      return;
    }
    console.log('report checks passed');
  } finally {
    await browser.close();
  }
})().catch((e) => {
  console.log(e.stack || String(e));
  process.exitCode = 1;
});
