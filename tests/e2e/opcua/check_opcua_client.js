// Drives `virtcom exec --opcua` (tests/e2e/data/opcua) with the real npm node-opcua-client, as a
// SCADA or simulation tool would: connect with security None, browse the whole address space,
// read every type and the attributes a browser shows, write, refused writes, TranslateBrowsePath.
// Usage: node check_opcua_client.js PORT. Exits non-zero with a message on the first failure.
'use strict';
const assert = require('node:assert/strict');
const {
  OPCUAClient, AttributeIds, DataType, StatusCodes, NodeClass, BrowseDirection, makeBrowsePath,
  ClientSubscription, ClientMonitoredItem, TimestampsToReturn, DataChangeFilter, DataChangeTrigger, DeadbandType,
} = require('node-opcua-client');

const port = Number(process.argv[2]);
const url = `opc.tcp://127.0.0.1:${port}`;
const id = (path) => `ns=4;s=|var|virtcom.Application.${path}`;
const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));

async function value(session, path) {
  const dv = await session.read({ nodeId: id(path), attributeId: AttributeIds.Value });
  assert.equal(dv.statusCode.value, StatusCodes.Good.value, `${path}: ${dv.statusCode.toString()}`);
  return dv.value;
}

// Polls until `accept` holds (writes take effect at the next scan), at most 3 s.
async function eventually(read, accept, what) {
  let last;
  for (let waited = 0; waited < 3000; waited += 20) {
    last = await read();
    if (accept(last)) return last;
    await sleep(20);
  }
  assert.fail(`${what}: last value ${JSON.stringify(last)}`);
}

// Every node reachable from Root through hierarchical references, each browsed (with
// continuation points: at most 3 references per answer).
async function browseAll(session) {
  const seen = new Map();
  const queue = ['ns=0;i=84'];
  while (queue.length) {
    const nodeId = queue.shift();
    let result = await session.browse({
      nodeId, browseDirection: BrowseDirection.Forward, referenceTypeId: 'HierarchicalReferences',
      includeSubtypes: true, resultMask: 63,
    });
    assert.equal(result.statusCode.value, 0, `browse ${nodeId}: ${result.statusCode.toString()}`);
    const refs = [...result.references];
    for (const r of refs) {
      const target = r.nodeId.toString();
      if (seen.has(target)) continue;
      seen.set(target, r);
      queue.push(target);
    }
  }
  return seen;
}

async function browseInPieces(session) {
  // RequestedMaxReferencesPerNode 1 on MAIN: every reference comes through BrowseNext.
  const all = await session.browse({ nodeId: id('MAIN'), resultMask: 63, referenceTypeId: 'HierarchicalReferences', includeSubtypes: true });
  assert.ok(all.references.length > 20, 'MAIN has its variables');
  const names = [];
  const request = { nodesToBrowse: [{ nodeId: id('MAIN'), resultMask: 63, referenceTypeId: 'ns=0;i=33', includeSubtypes: true }], requestedMaxReferencesPerNode: 1 };
  const response = await session.performMessageTransaction(new (require('node-opcua-client').BrowseRequest)(request));
  let r = response.results[0];
  names.push(...r.references.map((x) => x.browseName.name));
  while (r.continuationPoint && r.continuationPoint.length) {
    const next = await session.browseNext([r.continuationPoint], false);
    r = next[0] || next;
    names.push(...r.references.map((x) => x.browseName.name));
  }
  assert.deepEqual(names, all.references.map((x) => x.browseName.name), 'BrowseNext pieces = one Browse');
}

async function readEveryType(session) {
  const expect = {
    'MAIN.vBool': [DataType.Boolean, true], 'MAIN.vSint': [DataType.SByte, -5], 'MAIN.vUsint': [DataType.Byte, 200],
    'MAIN.vInt': [DataType.Int16, -1234], 'MAIN.vUint': [DataType.UInt16, 60000], 'MAIN.vDint': [DataType.Int32, -100000],
    'MAIN.vUdint': [DataType.UInt32, 4000000000], 'MAIN.vReal': [DataType.Float, 0.25], 'MAIN.vLreal': [DataType.Double, 2.5],
    'MAIN.vByte': [DataType.Byte, 0xab], 'MAIN.vWord': [DataType.UInt16, 0xf0], 'MAIN.vDword': [DataType.UInt32, 0xdeadbeef],
    'MAIN.vTime': [DataType.UInt32, 1500], 'MAIN.vString': [DataType.String, 'virtcom'], 'MAIN.vWstring': [DataType.String, 'héllo'],
    'MAIN.point.x': [DataType.Int16, 3], 'MAIN.point.y': [DataType.Float, 1.5], 'MAIN.point.tag': [DataType.String, 'p1'],
    'MAIN.kMax': [DataType.Int16, 999], 'GVL.gSpeed': [DataType.Double, 1.5], 'GVL.gStart': [DataType.Boolean, false],
  };
  for (const [path, [type, v]] of Object.entries(expect)) {
    const got = await value(session, path);
    assert.equal(got.dataType, type, `${path} data type`);
    assert.deepEqual(got.value, v, `${path} value`);
    const dt = await session.read({ nodeId: id(path), attributeId: AttributeIds.DataType });
    assert.equal(dt.value.value.value, type, `${path} DataType attribute`);
  }
  // 64-bit integers come as [high, low] unsigned 32-bit words in node-opcua.
  assert.deepEqual((await value(session, 'MAIN.vLint')).value, [0xfffffffe, 3589934592]);
  assert.deepEqual((await value(session, 'MAIN.vUlint')).value, [2, 1410065408]);
  const values = await value(session, 'MAIN.values');
  assert.equal(values.arrayType, 1 /* Array */);
  assert.deepEqual(Array.from(values.value), [10, 20, 30, 40, 50]);
  const grid = await value(session, 'MAIN.grid');
  assert.deepEqual(grid.dimensions, [2, 3], 'matrix dimensions');
  const rank = await session.read({ nodeId: id('MAIN.grid'), attributeId: AttributeIds.ValueRank });
  assert.equal(rank.value.value, 2);
  const dims = await session.read({ nodeId: id('MAIN.values'), attributeId: AttributeIds.ArrayDimensions });
  assert.deepEqual(Array.from(dims.value.value), [5]);
}

async function attributes(session) {
  const read = (nodeId, attributeId) => session.read({ nodeId, attributeId });
  assert.equal((await read(id('MAIN.level'), AttributeIds.NodeClass)).value.value, NodeClass.Variable);
  assert.equal((await read(id('MAIN'), AttributeIds.NodeClass)).value.value, NodeClass.Object);
  assert.equal((await read(id('MAIN.level'), AttributeIds.BrowseName)).value.value.toString(), '4:level');
  assert.equal((await read(id('MAIN.level'), AttributeIds.DisplayName)).value.value.text, 'level');
  assert.equal((await read(id('MAIN.level'), AttributeIds.AccessLevel)).value.value, 3);
  assert.equal((await read(id('MAIN.level'), AttributeIds.UserAccessLevel)).value.value, 3);
  assert.equal((await read(id('MAIN.kMax'), AttributeIds.AccessLevel)).value.value, 1, 'CONSTANT read only');
  assert.equal((await read(id('MAIN.level'), AttributeIds.ValueRank)).value.value, -1);
  assert.equal((await read(id('MAIN'), AttributeIds.Value)).statusCode.value, StatusCodes.BadAttributeIdInvalid.value);
  assert.equal((await read(id('MAIN.nothing'), AttributeIds.Value)).statusCode.value, StatusCodes.BadNodeIdUnknown.value);
  const ns = await read('ns=0;i=2255', AttributeIds.Value);
  assert.equal(ns.value.value.length, 5);
  assert.equal(ns.value.value[4], 'urn:virtcom:Application');
  const state = await read('ns=0;i=2259', AttributeIds.Value);
  assert.equal(state.value.value, 0, 'ServerStatus.State Running');
  const status = await read('ns=0;i=2256', AttributeIds.Value);
  assert.equal(status.statusCode.value, 0);
  assert.equal(status.value.value.state, 0);
  assert.ok(status.value.value.currentTime instanceof Date);
}

async function writes(session) {
  const write = (path, dataType, v) => session.write({ nodeId: id(path), attributeId: AttributeIds.Value, value: { value: { dataType, value: v } } });
  assert.equal((await write('MAIN.level', DataType.Int16, 9)).value, 0);
  await eventually(async () => (await value(session, 'MAIN.doubled')).value, (v) => v === 18, 'MAIN.doubled after level := 9');
  assert.equal((await write('MAIN.vString', DataType.String, 'hello ua')).value, 0);
  assert.equal((await value(session, 'MAIN.vString')).value, 'hello ua');
  assert.equal((await write('MAIN.vWstring', DataType.String, 'grüß')).value, 0);
  assert.equal((await value(session, 'MAIN.vWstring')).value, 'grüß');
  assert.equal((await write('MAIN.point.y', DataType.Float, -2.5)).value, 0);
  assert.equal((await value(session, 'MAIN.point.y')).value, -2.5);
  assert.equal((await session.write({ nodeId: id('MAIN.values'), attributeId: AttributeIds.Value,
    value: { value: { dataType: DataType.Int16, arrayType: 1, value: new Int16Array([1, 2, 3, 4, 5]) } } })).value, 0);
  assert.deepEqual(Array.from((await value(session, 'MAIN.values')).value), [1, 2, 3, 4, 5]);
  assert.equal((await write('GVL.gStart', DataType.Boolean, true)).value, 0);
  await eventually(async () => (await value(session, 'GVL.gLamp')).value, (v) => v === true, 'GVL.gLamp follows %IX0.0');
  assert.equal((await write('MAIN.run', DataType.Boolean, true)).value, 0);
  await eventually(async () => (await value(session, 'MAIN.counter.count')).value, (v) => v > 2, 'FB counter running');

  assert.equal((await write('MAIN.kMax', DataType.Int16, 1)).value, StatusCodes.BadNotWritable.value, 'CONSTANT');
  assert.equal((await write('MAIN.level', DataType.Double, 1)).value, StatusCodes.BadTypeMismatch.value, 'wrong type');
  assert.equal((await write('MAIN.vString', DataType.String, 'x'.repeat(21))).value, StatusCodes.BadOutOfRange.value, 'too long');
  assert.equal((await write('MAIN.nothing', DataType.Int16, 1)).value, StatusCodes.BadNodeIdUnknown.value);
  assert.equal((await value(session, 'MAIN.kMax')).value, 999);
}

async function translate(session) {
  const [r] = await session.translateBrowsePath([makeBrowsePath('ns=0;i=85', '/4:MAIN.4:point.4:tag')]);
  assert.equal(r.statusCode.value, 0, r.statusCode.toString());
  assert.equal(r.targets[0].targetId.toString(), id('MAIN.point.tag'));
  const [missing] = await session.translateBrowsePath([makeBrowsePath('ns=0;i=85', '/4:MAIN.4:nothing')]);
  assert.equal(missing.statusCode.value, StatusCodes.BadNoMatch.value);
}

async function subscriptions(session) {
  const subscription = ClientSubscription.create(session, {
    requestedPublishingInterval: 50, requestedLifetimeCount: 100, requestedMaxKeepAliveCount: 10,
    maxNotificationsPerPublish: 100, publishingEnabled: true, priority: 1,
  });
  await new Promise((resolve, reject) => { subscription.once('started', resolve); subscription.once('error', reject); });
  const monitor = async (path, parameters) => {
    const item = ClientMonitoredItem.create(subscription, { nodeId: id(path), attributeId: AttributeIds.Value },
      { samplingInterval: 20, discardOldest: true, queueSize: 10, ...parameters }, TimestampsToReturn.Both);
    const changes = [];
    item.on('changed', (dv) => changes.push(dv.value.value));
    await new Promise((resolve, reject) => { item.once('initialized', resolve); item.once('err', reject); });
    return { item, changes };
  };
  const ticks = await monitor('MAIN.ticks');
  await eventually(async () => ticks.changes.length, (n) => n >= 5, 'MAIN.ticks changes arrive');
  for (let i = 1; i < ticks.changes.length; ++i) assert.ok(ticks.changes[i] > ticks.changes[i - 1], 'ticks grow');
  const doubled = await monitor('MAIN.doubled');
  await session.write({ nodeId: id('MAIN.level'), attributeId: AttributeIds.Value, value: { value: { dataType: DataType.Int16, value: 21 } } });
  await eventually(async () => doubled.changes, (c) => c.includes(42), 'MAIN.doubled change after level := 21');
  // An absolute deadband of 100 on a counter that grows by one per scan: few notifications.
  const coarse = await monitor('MAIN.ticks', {
    filter: new DataChangeFilter({ trigger: DataChangeTrigger.StatusValue, deadbandType: DeadbandType.Absolute, deadbandValue: 100 }),
  });
  await sleep(500);
  assert.ok(coarse.changes.length >= 1 && coarse.changes.length <= 3, `deadband: ${coarse.changes.length} changes`);
  for (let i = 1; i < coarse.changes.length; ++i) assert.ok(coarse.changes[i] - coarse.changes[i - 1] > 100, 'deadband respected');
  await ticks.item.terminate();
  const settled = ticks.changes.length;
  await sleep(300);
  assert.ok(ticks.changes.length <= settled + 1, 'no changes after DeleteMonitoredItems');
  await subscription.terminate();
}

(async () => {
  const client = OPCUAClient.create({ endpointMustExist: false, connectionStrategy: { maxRetry: 0 } });
  await client.connect(url);
  const endpoints = await client.getEndpoints();
  assert.equal(endpoints.length, 1);
  assert.equal(endpoints[0].securityPolicyUri, 'http://opcfoundation.org/UA/SecurityPolicy#None');
  const servers = await client.findServers();
  assert.equal(servers[0].applicationUri, 'urn:virtcom:plc');
  const session = await client.createSession();

  const nodes = await browseAll(session);
  const names = [...nodes.keys()];
  for (const expected of ['ns=0;i=85', 'ns=0;i=2253', 'ns=0;i=2256', 'ns=0;i=2255', id('MAIN'), id('GVL'), id('MAIN.vWstring'),
    id('MAIN.point'), id('MAIN.point.tag'), id('MAIN.counter.count'), id('GVL.gStart'), id('MAIN.grid')])
    assert.ok(names.includes(expected), `browse reaches ${expected}`);
  // Every variable found by browsing reads.
  for (const [nodeId, ref] of nodes) {
    if (ref.nodeClass !== NodeClass.Variable) continue;
    const dv = await session.read({ nodeId, attributeId: AttributeIds.Value });
    assert.equal(dv.statusCode.value, 0, `read ${nodeId}: ${dv.statusCode.toString()}`);
  }
  await browseInPieces(session);
  await readEveryType(session);
  await attributes(session);
  await writes(session);
  await translate(session);
  await subscriptions(session);
  await session.close();
  await client.disconnect();
  console.log(`ok: ${nodes.size} nodes browsed`);
})().catch((e) => {
  console.error('FAIL', e);
  process.exit(1);
});
