// Drives `virtcom exec --opcua --opcua-users FILE` with the real npm node-opcua-client: the
// endpoint announces UserName identities only (the client then cannot even try anonymous; the
// server's own refusal is a unit test), a wrong password is refused, a read-write user writes
// and a read-only user reads but may not write. With `anonymous-read` (the server run with
// `--opcua-anonymous read` too): anonymous is announced, reads and may not write. With
// `anonymous-only` (the server run with neither option): only anonymous is announced, and it
// reads but may not write (the default).
// Usage: node check_opcua_identity.js PORT [anonymous-read|anonymous-only]. The users file holds
// operator/op-pass (read-write) and viewer/view-pass (read-only). Exits non-zero with a message
// on the first failure.
'use strict';
const assert = require('node:assert/strict');
const { OPCUAClient, AttributeIds, DataType, StatusCodes, UserTokenType } = require('node-opcua-client');

const port = Number(process.argv[2]);
const anonymousRead = process.argv[3] === 'anonymous-read', anonymousOnly = process.argv[3] === 'anonymous-only';
const url = `opc.tcp://127.0.0.1:${port}`;
const level = 'ns=4;s=|var|virtcom.Application.MAIN.level';

// createSession's failure as a status code name ('' when it succeeded).
async function refusal(client, identity) {
  try {
    const session = await client.createSession(identity);
    await session.close();
    return '';
  } catch (e) {
    return String(e.message);
  }
}

const writeLevel = (session, v) =>
  session.write({ nodeId: level, attributeId: AttributeIds.Value, value: { value: { dataType: DataType.Int16, value: v } } });

async function anonymousReads(client) {
  const session = await client.createSession();
  assert.equal((await session.read({ nodeId: level, attributeId: AttributeIds.Value })).statusCode.value, StatusCodes.Good.value);
  assert.equal((await writeLevel(session, 9)).value, StatusCodes.BadUserAccessDenied.value, 'anonymous may not write');
  await session.close();
}

(async () => {
  const client = OPCUAClient.create({ endpointMustExist: false, connectionStrategy: { maxRetry: 0 } });
  await client.connect(url);
  const endpoints = await client.getEndpoints();
  const tokens = endpoints[0].userIdentityTokens.map((t) => t.tokenType);
  if (anonymousOnly) {
    assert.deepEqual(tokens, [UserTokenType.Anonymous], 'only the anonymous identity is announced');
    await anonymousReads(client);
    await client.disconnect();
    console.log('ok: anonymous reads only');
    return;
  }
  if (anonymousRead) {
    assert.deepEqual(tokens, [UserTokenType.Anonymous, UserTokenType.UserName], 'anonymous and UserName identities are announced');
    await anonymousReads(client);
  } else {
    assert.deepEqual(tokens, [UserTokenType.UserName], 'only UserName identities are announced');
    assert.match(await refusal(client, { type: UserTokenType.Anonymous }), /Cannot find ANONYMOUS/, 'anonymous not offered');
  }
  assert.match(await refusal(client, { type: UserTokenType.UserName, userName: 'operator', password: 'wrong' }),
    /BadUserAccessDenied/, 'wrong password refused');
  assert.match(await refusal(client, { type: UserTokenType.UserName, userName: 'nobody', password: 'op-pass' }),
    /BadUserAccessDenied/, 'unknown user refused');

  const operator = await client.createSession({ type: UserTokenType.UserName, userName: 'operator', password: 'op-pass' });
  assert.equal((await writeLevel(operator, 5)).value, StatusCodes.Good.value, 'the read-write user writes');
  const operatorAccess = await operator.read({ nodeId: level, attributeId: AttributeIds.UserAccessLevel });
  assert.equal(operatorAccess.value.value & 2, 2, 'UserAccessLevel has CurrentWrite for the read-write user');
  await operator.close();

  const viewer = await client.createSession({ type: UserTokenType.UserName, userName: 'viewer', password: 'view-pass' });
  const dv = await viewer.read({ nodeId: level, attributeId: AttributeIds.Value });
  assert.equal(dv.statusCode.value, StatusCodes.Good.value, 'the read-only user reads');
  assert.equal(dv.value.value, 5, 'the operator\'s write');
  assert.equal((await writeLevel(viewer, 8)).value, StatusCodes.BadUserAccessDenied.value, 'the read-only user may not write');
  const viewerAccess = await viewer.read({ nodeId: level, attributeId: AttributeIds.UserAccessLevel });
  assert.equal(viewerAccess.value.value & 2, 0, 'UserAccessLevel has no CurrentWrite for the read-only user');
  const accessLevel = await viewer.read({ nodeId: level, attributeId: AttributeIds.AccessLevel });
  assert.equal(accessLevel.value.value & 2, 2, 'AccessLevel keeps CurrentWrite');
  await viewer.close();
  await client.disconnect();
  console.log('ok: identities');
})().catch((e) => {
  console.error('FAIL', e);
  process.exit(1);
});
