// Drives `virtcom exec --ads` with the real npm ads-client (2.x), as a TwinCAT user would:
// connect (not raw), values by name, subscriptions, sum reads, handles, symbol and type lists,
// RUN/STOP, refused writes, and several clients at once.
// Usage: node check_ads_client.js PORT. Exits non-zero with a message on the first failure.
'use strict';
const assert = require('node:assert/strict');
const { Client } = require('ads-client');
const { clientSettings, sleep, eventually: poll } = require('./support');

const port = Number(process.argv[2]);
const settings = clientSettings(port);
// at most 3 s: the PLC takes a write at its next scan
const eventually = (read, accept, what) => poll(read, accept, what, 3000);

async function expectAdsError(promise, code, what) {
  try {
    await promise;
  } catch (err) {
    const found = err.adsError?.errorCode ?? err.parentError?.adsError?.errorCode;
    assert.equal(found, code, `${what}: ${err.message}`);
    return;
  }
  assert.fail(`${what}: succeeded, expected ADS error ${code}`);
}

async function values(client) {
  assert.equal((await client.readValue('MAIN.level')).value, 7);
  assert.equal((await client.readValue('main.RATIO')).value, 0.25);
  assert.equal((await client.readValue('MAIN.name')).value, 'virtcom');
  assert.deepEqual((await client.readValue('MAIN.point')).value, { x: 3, y: 1.5, tag: 'p1' });
  assert.deepEqual((await client.readValue('MAIN.values')).value, [10, 20, 30, 40, 50]);
  assert.deepEqual((await client.readValue('MAIN.grid')).value, [[0, 0, 0], [0, 0, 0]]);
  assert.equal((await client.readValue('MAIN.values[2]')).value, 30);
  assert.equal((await client.readValue('MAIN.point.tag')).value, 'p1');
  assert.deepEqual((await client.readValue('MAIN.mode')).value, { name: 'Idle', value: 0 });
  assert.deepEqual((await client.readValue('MAIN.counter')).value, { enable: false, count: 0 });
  assert.equal((await client.readValue('GVL.gSpeed')).value, 1.5);

  await client.writeValue('MAIN.level', 9);
  await eventually(async () => (await client.readValue('MAIN.doubled')).value, (v) => v === 18, 'MAIN.doubled after level := 9');
  await client.writeValue('MAIN.point', { x: -4, y: 2.5, tag: 'moved' });
  assert.deepEqual((await client.readValue('MAIN.point')).value, { x: -4, y: 2.5, tag: 'moved' });
  await client.writeValue('MAIN.values', [1, 2, 3, 4, 5]);
  assert.deepEqual((await client.readValue('MAIN.values')).value, [1, 2, 3, 4, 5]);
  await client.writeValue('MAIN.name', 'hello ads');
  assert.equal((await client.readValue('MAIN.name')).value, 'hello ads');
  await client.writeValue('MAIN.mode', 'Fault');
  assert.deepEqual((await client.readValue('MAIN.mode')).value, { name: 'Fault', value: 5 });
  await client.writeValue('MAIN.run', true);
  await eventually(async () => (await client.readValue('MAIN.counter.count')).value, (v) => v > 2, 'FB counter running');

  await expectAdsError(client.writeValue('MAIN.serial', 1), 1796, 'write to ads_readonly');
  await expectAdsError(client.writeValue('MAIN.kMax', 1), 1796, 'write to CONSTANT');
  await expectAdsError(client.readValue('MAIN.nothing'), 1808, 'unknown symbol');
  assert.equal((await client.readValue('MAIN.serial')).value, 4711);
}

async function subscriptions(client) {
  const changes = [];
  const onChange = await client.subscribeValue('MAIN.ticks', (data) => changes.push(data.value), 10, true);
  const cyclic = [];
  const everyCycle = await client.subscribeValue('MAIN.maxLevel', (data) => cyclic.push(data.value), 20, false);
  await eventually(async () => changes.length, (n) => n >= 5, 'on-change notifications of MAIN.ticks');
  await eventually(async () => cyclic.length, (n) => n >= 4, 'cyclic notifications of MAIN.maxLevel');
  for (let i = 1; i < changes.length; ++i) assert.ok(changes[i] > changes[i - 1], `ticks not increasing: ${changes}`);
  assert.ok(cyclic.every((v) => v === 100), `cyclic values: ${cyclic}`);
  await onChange.unsubscribe();
  await everyCycle.unsubscribe();
}

async function rawAndSums(client) {
  const level = await client.getSymbol('MAIN.level');
  const ticks = await client.getSymbol('MAIN.ticks');
  const point = await client.getSymbol('MAIN.point');
  assert.equal(level.indexGroup, 0x4040);
  const results = await client.readRawMulti([
    { indexGroup: level.indexGroup, indexOffset: level.indexOffset, size: level.size },
    { indexGroup: ticks.indexGroup, indexOffset: ticks.indexOffset, size: ticks.size },
    { indexGroup: point.indexGroup, indexOffset: point.indexOffset, size: point.size },
    { indexGroup: 0x1234, indexOffset: 0, size: 2 },
  ]);
  assert.ok(results[0].success && results[1].success && results[2].success);
  assert.equal(results[0].value.readInt16LE(0), 9);
  assert.ok(results[1].value.readInt32LE(0) > 0);
  assert.equal(results[2].value.readInt16LE(0), -4);
  assert.equal(results[3].success, false);
  assert.equal(results[3].errorCode, 1794);

  const handle = await client.createVariableHandle('MAIN.values[1]');
  assert.equal(handle.size, 2);
  assert.equal((await client.readRawByHandle(handle)).readInt16LE(0), 2);
  await client.deleteVariableHandle(handle);
  const handles = await client.createVariableHandleMulti(['MAIN.level', 'MAIN.nope']);
  assert.equal(handles[0].success, true);
  assert.equal(handles[1].success, false);
  const deleted = await client.deleteVariableHandleMulti([handles[0].handle]);
  assert.equal(deleted[0].success, true);
  assert.equal((await client.readRawByPath('MAIN.level')).readInt16LE(0), 9);
}

async function listings(client) {
  const symbols = await client.getSymbols();
  for (const name of ['main.level', 'main.point', 'main.counter', 'main.values', 'main.name', 'main.mode', 'gvl.gspeed'])
    assert.ok(symbols[name], `symbol ${name} missing from the upload`);
  assert.equal(symbols['main.point'].type, 'ST_Point');
  const types = await client.getDataTypes();
  for (const name of ['st_point', 'fb_counter', 'e_mode', 'int', 'string(20)'])
    assert.ok(types[name], `data type ${name} missing from the upload`);
}

async function runStop(client) {
  await client.stopPlc();
  assert.equal((await client.readPlcRuntimeState()).adsState, 6);
  await sleep(50);  // STOP takes effect at the next scan boundary; a scan may be under way
  const stopped = (await client.readValue('MAIN.ticks')).value;
  await sleep(100);
  assert.equal((await client.readValue('MAIN.ticks')).value, stopped, 'ticks advanced while stopped');
  await client.startPlc();
  assert.equal((await client.readPlcRuntimeState()).adsState, 5);
  await eventually(async () => (await client.readValue('MAIN.ticks')).value, (v) => v > stopped, 'ticks after start');
}

async function manyClients() {
  const clients = Array.from({ length: 8 }, () => new Client(settings));
  await Promise.all(clients.map((c) => c.connect()));
  const levels = await Promise.all(clients.map((c) => c.readValue('MAIN.level')));
  assert.ok(levels.every((r) => r.value === 9));
  await Promise.all(clients.map((c) => c.disconnect()));
}

async function main() {
  const client = new Client(settings);
  const info = await client.connect();
  assert.equal(info.targetAmsNetId, '127.0.0.1.1.1');
  assert.equal(client.metaData.plcDeviceInfo.deviceName, 'Plc30 App');
  for (const [name, step] of Object.entries({ values, subscriptions, rawAndSums, listings, runStop })) {
    try {
      await step(client);
    } catch (err) {
      err.message = `${name}: ${err.message}`;
      throw err;
    }
  }
  await client.disconnect();
  await manyClients();
  console.log('ads-client checks passed');
}

main().catch((err) => {
  console.error(err.stack || String(err));
  process.exit(1);
});
