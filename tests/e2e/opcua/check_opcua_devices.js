// Reads the cell's devices as `virtcom serve CELL --opcua` serves them, with the real npm
// node-opcua-client: Objects/Devices holds an object per device, each with a variable per signal
// of its ports, typed as the PLC's variables are; their values follow the running cell (the
// examples/ads-cell clamp's `done` is seen both FALSE and TRUE while it cycles, and its
// `execute` equals the PLC's MAIN.Clamp.execute wired to it whenever both are read in one
// Read); writing a device's signal is refused.
// With `watched` (the server is `virtcom monitor --serve-opcua`, watching such a cell's PLC) there
// is no PLC variable to compare with, and every write is refused.
// Usage: node check_opcua_devices.js PORT [watched]. Prints the devices and their signals; exits non-zero
// with a message on the first failure.
'use strict';
const assert = require('node:assert/strict');
const { OPCUAClient, AttributeIds, DataType, StatusCodes } = require('node-opcua-client');

const url = `opc.tcp://127.0.0.1:${Number(process.argv[2])}`;
const watched = process.argv[3] === 'watched';

(async () => {
  const client = OPCUAClient.create({ endpointMustExist: false, connectionStrategy: { maxRetry: 0 } });
  await client.connect(url);
  const session = await client.createSession();
  const objects = await session.browse('ns=0;i=85');
  assert.ok(objects.references.some((r) => r.browseName.name === 'Devices'), 'Objects has no Devices folder');
  const devices = await session.browse('ns=4;s=|dev|virtcom');
  const names = devices.references.map((r) => r.browseName.name);
  assert.deepEqual(names, ['Clamp', 'Press']);
  for (const device of devices.references) {
    const signals = await session.browse(device.nodeId);
    const types = await session.read(signals.references.map((r) => ({ nodeId: r.nodeId, attributeId: AttributeIds.DataType })));
    const described = signals.references.map((r, i) => `${r.browseName.name}:${DataType[types[i].value.value.value]}`);
    console.log(`device ${device.browseName.name}: ${described.join(' ')}`);
  }
  const done = 'ns=4;s=|dev|virtcom.Clamp.done', execute = 'ns=4;s=|dev|virtcom.Clamp.execute';
  const plcExecute = 'ns=4;s=|var|virtcom.Application.MAIN.Clamp.execute';
  const seen = new Set();
  // Bounded by wall time, not by a count of reads: on a loaded machine (the whole suite with the
  // fuzz smoke beside it) 200 reads 20 ms apart ended before the clamp's first cycle did.
  const deadline = Date.now() + 30000;
  while (Date.now() < deadline && seen.size < 2) {
    const nodes = watched ? [done, execute] : [done, execute, plcExecute];
    const [d, e, p] = await session.read(nodes.map((nodeId) => ({ nodeId, attributeId: AttributeIds.Value })));
    for (const v of [d, e, p].slice(0, nodes.length)) assert.equal(v.statusCode.name, 'Good');
    if (!watched) assert.equal(e.value.value, p.value.value, 'the device execute and the PLC variable wired to it differ in one Read');
    seen.add(d.value.value);
    await new Promise((resolve) => setTimeout(resolve, 20));
  }
  assert.equal(seen.size, 2, 'Clamp.done never changed while the cell ran');
  const write = await session.write({ nodeId: execute, attributeId: AttributeIds.Value,
                                      value: { value: { dataType: DataType.Boolean, value: true } } });
  assert.notEqual(write.name, 'Good', 'writing a device signal was accepted');
  console.log(`write refused: ${write.name}`);
  console.log('devices ok');
  await session.close();
  await client.disconnect();
})().catch((e) => {
  console.error(e);
  process.exit(1);
});
