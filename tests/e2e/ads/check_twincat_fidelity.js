// Drives `virtcom exec lib/tc2_system.st ads_twincat/MAIN.st --ads` with the real npm ads-client
// (2.x) on what issue 16 found different from TwinCAT: values by handle read with a larger
// buffer, Tc2_System types, bit-located globals, the %M area the program declares, and the
// first sample of a subscription to a value that never changes.
// Usage: node check_twincat_fidelity.js PORT. Exits non-zero with a message on the first failure.
'use strict';
const assert = require('node:assert/strict');
const { Client } = require('ads-client');
const { clientSettings, eventually } = require('./support');

async function main() {
  const client = new Client(clientSettings(Number(process.argv[2])));
  await client.connect();

  // T_MaxString (STRING(255)) by name and by handle read with a 1024-byte buffer (pyads' size).
  assert.equal((await client.readValue('MAIN.message')).value, 'hello from virtcom');
  const handle = await client.createVariableHandle('MAIN.message');
  const raw = await client.readRawByHandle(handle.handle, 1024);
  assert.equal(raw.byteLength, 256, 'a longer read by handle answers the symbol');
  assert.equal(raw.toString('latin1', 0, raw.indexOf(0)), 'hello from virtcom');
  await client.deleteVariableHandle(handle);

  // Bit-located globals by name; the %M area holds ARRAY[0..1027] OF BYTE AT %MB0.
  await eventually(async () => (await client.readValue('gLamp')).value, (v) => v === true, 'gLamp', 3000);
  assert.equal((await client.readValue('gStart')).value, false);
  assert.ok((await client.readRaw(0x4025, 0, 4)).readUInt32LE(0) >= 1028, '%M size');
  await eventually(async () => (await client.readRaw(0x4020, 1027, 1))[0], (v) => v === 0x5a, '%MB1027', 3000);
  assert.equal((await client.readValue('gBuffer[1027]')).value, 0x5a);

  // On change, and the value never changes: the first sample is the only one.
  const samples = [];
  const sub = await client.subscribeValue('MAIN.maxLevel', (data) => samples.push(data.value), 10, true);
  await eventually(async () => samples.length, (n) => n >= 1, 'first sample of MAIN.maxLevel', 3000);
  assert.deepEqual(samples, [100]);
  await sub.unsubscribe();

  await client.disconnect();
  console.log('ads-client fidelity checks passed');
}

main().catch((err) => {
  console.error(err.stack || String(err));
  process.exit(1);
});
