// Shared by the ads-client e2e scripts: the connection settings for a virtcom ADS server on
// 127.0.0.1:PORT, and polling until the PLC shows a value (writes and notifications take effect
// at scan boundaries).
'use strict';
const assert = require('node:assert/strict');

const clientSettings = (port) => ({
  targetAmsNetId: '127.0.0.1.1.1', targetAdsPort: 851, routerAddress: '127.0.0.1', routerTcpPort: port,
});
const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));

// Polls `read` every 20 ms until `accept` holds, at most `timeoutMs`.
async function eventually(read, accept, what, timeoutMs) {
  let last;
  for (let waited = 0; waited < timeoutMs; waited += 20) {
    last = await read();
    if (accept(last)) return last;
    await sleep(20);
  }
  assert.fail(`${what}: last value ${JSON.stringify(last)}`);
}

module.exports = { clientSettings, sleep, eventually };
