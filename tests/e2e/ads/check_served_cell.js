// Drives `virtcom serve examples/ads-cell/cell.yaml --ads` with the real npm ads-client (2.x):
// the cell's soft PLC runs its clamp-press cycle against the simulated devices while a TwinCAT
// client reads its variables by name, sees them change, and subscribes to them.
// Usage: node check_served_cell.js PORT. Exits non-zero with a message on the first failure.
'use strict';
const assert = require('node:assert/strict');
const { Client } = require('ads-client');
const { clientSettings, sleep, eventually: poll } = require('./support');

const port = Number(process.argv[2]);
const settings = clientSettings(port);
// at most 10 s: a cycle of the cell takes about 1.3 s
const eventually = (read, accept, what) => poll(read, accept, what, 10000);

async function main() {
  const client = new Client(settings);
  await client.connect();
  assert.equal(client.metaData.plcDeviceInfo.deviceName, 'Plc30 App');
  const read = async (name) => (await client.readValue(name)).value;

  // The device signals arrive in the PLC's structs through the cell's wiring, and change as
  // the devices run: the clamp gets busy, then the press force rises.
  await eventually(() => read('MAIN.Clamp.busy'), (v) => v === true, 'MAIN.Clamp.busy (the clamp locking)');
  await eventually(() => read('MAIN.Press.actualForce'), (v) => v > 1000, 'MAIN.Press.actualForce (the press pressing)');
  const press = await read('MAIN.Press');
  assert.equal(press.programNumber, 1);
  // A whole cycle completes and is counted; on-change notifications follow MAIN.step.
  const steps = [];
  const sub = await client.subscribeValue('MAIN.step', (data) => steps.push(data.value), 10, true);
  const cycles = await eventually(() => read('MAIN.cycles'), (v) => v >= 1, 'MAIN.cycles (a completed cycle)');
  await eventually(async () => steps.length, (n) => n >= 3, 'notifications of MAIN.step');
  await sub.unsubscribe();
  assert.ok((await read('MAIN.maxForce')) > 4000, 'MAIN.maxForce: the press force');

  // A client write reaches the program at a scan boundary like any other.
  await client.writeValue('MAIN.maxForce', 0);
  await eventually(() => read('MAIN.maxForce'), (v) => v === 0 || v > 1000, 'MAIN.maxForce after the write');
  // STOP freezes the program while the cell's time goes on; RUN resumes it.
  await client.stopPlc();
  await sleep(50);
  const frozen = await read('MAIN.step');
  await sleep(300);
  assert.equal(await read('MAIN.step'), frozen, 'MAIN.step moved while the PLC was stopped');
  await client.startPlc();
  await eventually(() => read('MAIN.cycles'), (v) => v > cycles, 'MAIN.cycles after RUN');
  await client.disconnect();
  console.log('served cell checks passed');
}

main().catch((err) => {
  console.error(err.stack || String(err));
  process.exit(1);
});
