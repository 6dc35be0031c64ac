// An external PLC nobody here wrote, for the client bridge (`plc: opcua:`): an npm node-opcua
// server whose variables are those of examples/ads-cell's MAIN (Clamp and Press handshakes,
// step, cycles, cycleDone, maxForce), under the CODESYS-form string node ids of that namespace,
// driven by the same state machine as plc/main.st, scanned every 10 ms.
// Usage: node bridge_plc_server.js [NAMESPACE_INDEX]. Prints
// "node-opcua: serving opc.tcp://127.0.0.1:PORT" on stderr once it listens (a free port); stops
// cleanly on SIGTERM (exit 0) and then prints the writes it was sent per variable.
'use strict';
const fs = require('node:fs');
const net = require('node:net');
const os = require('node:os');
const path = require('node:path');
const { OPCUAServer } = require('node-opcua-server');
const { OPCUACertificateManager } = require('node-opcua-certificate-manager');
const { DataType, Variant, StatusCodes, MessageSecurityMode, SecurityPolicy } = require('node-opcua-client');

// The PLC's namespace gets this index: CODESYS has its application at ns=4.
const namespaceIndex = Number(process.argv[2] || 4);
const prefix = '|var|virtcom.Application.MAIN.';

const handshake = { programNumber: DataType.Int16, execute: DataType.Boolean, done: DataType.Boolean, error: DataType.Int16, busy: DataType.Boolean };
const variables = {
  Clamp: handshake,
  Press: { ...handshake, actualForce: DataType.Double, position: DataType.Double },
  step: DataType.Int16, cycles: DataType.Int16, cycleDone: DataType.Boolean, maxForce: DataType.Double,
};

// MAIN's variables as one object, as the PLC's image.
const MAIN = { step: 0, cycles: 0, cycleDone: false, maxForce: 0 };
for (const device of ['Clamp', 'Press']) {
  MAIN[device] = {};
  for (const [name, type] of Object.entries(variables[device])) MAIN[device][name] = type === DataType.Boolean ? false : 0;
}
const writes = {};

// plc/main.st, one scan.
function scan() {
  const { Clamp, Press } = MAIN;
  switch (MAIN.step) {
    case 0:
      Clamp.programNumber = 1;
      Clamp.execute = true;
      if (Clamp.done) { Clamp.execute = false; MAIN.cycleDone = false; MAIN.step = 1; }
      break;
    case 1: if (!Clamp.done) { Press.programNumber = 1; Press.execute = true; MAIN.step = 2; } break;
    case 2:
      if (Press.actualForce > MAIN.maxForce) MAIN.maxForce = Press.actualForce;
      if (Press.done) { Press.execute = false; MAIN.step = 3; }
      break;
    case 3: if (!Press.done) { Clamp.programNumber = 2; Clamp.execute = true; MAIN.step = 4; } break;
    case 4: if (Clamp.done) { Clamp.execute = false; MAIN.step = 5; } break;
    case 5: if (!Clamp.done) { MAIN.cycles += 1; MAIN.cycleDone = true; MAIN.step = 0; } break;
  }
}

function freePort() {
  return new Promise((resolve, reject) => {
    const probe = net.createServer();
    probe.on('error', reject);
    probe.listen(0, '127.0.0.1', () => {
      const { port } = probe.address();
      probe.close(() => resolve(port));
    });
  });
}

function addVariables(namespace, parent, owner, fields, pathText) {
  for (const [name, type] of Object.entries(fields)) {
    const full = pathText + name;
    if (typeof type === 'object') {
      const folder = namespace.addObject({ organizedBy: parent, browseName: name, nodeId: `s=${prefix}${full}` });
      addVariables(namespace, folder, owner[name], type, full + '.');
      continue;
    }
    namespace.addVariable({
      componentOf: parent, browseName: name, nodeId: `s=${prefix}${full}`, dataType: type, minimumSamplingInterval: 10,
      accessLevel: 'CurrentRead | CurrentWrite', userAccessLevel: 'CurrentRead | CurrentWrite',
      value: {
        get: () => new Variant({ dataType: type, value: owner[name] }),
        set: (variant) => {
          owner[name] = variant.value;
          writes[full] = (writes[full] || 0) + 1;
          return StatusCodes.Good;
        },
      },
    });
  }
}

async function main() {
  const pki = fs.mkdtempSync(path.join(os.tmpdir(), 'virtcom-node-opcua-'));
  const certificates = (name) => new OPCUACertificateManager({ rootFolder: path.join(pki, name), automaticallyAcceptUnknownCertificate: true });
  const port = await freePort();
  const server = new OPCUAServer({
    port, host: '127.0.0.1', hostname: '127.0.0.1',
    securityModes: [MessageSecurityMode.None], securityPolicies: [SecurityPolicy.None], allowAnonymous: true,
    serverCertificateManager: certificates('server'), userCertificateManager: certificates('user'),
  });
  await server.initialize();
  const addressSpace = server.engine.addressSpace;
  // Namespaces up to the one asked for, so that the PLC's gets its index.
  let namespace = addressSpace.getOwnNamespace();
  while (namespace.index < namespaceIndex) namespace = addressSpace.registerNamespace(`urn:virtcom:e2e:ns${namespace.index + 1}`);
  const main = namespace.addObject({ organizedBy: addressSpace.rootFolder.objects, browseName: 'MAIN', nodeId: `s=${prefix.slice(0, -1)}` });
  addVariables(namespace, main, MAIN, variables, '');
  const timer = setInterval(scan, 10);
  await server.start();
  process.stderr.write(`node-opcua: serving opc.tcp://127.0.0.1:${port}\n`);
  process.on('SIGTERM', async () => {
    clearInterval(timer);
    await server.shutdown(0);
    fs.rmSync(pki, { recursive: true, force: true });
    process.stderr.write(`node-opcua: ${MAIN.cycles} cycle(s); writes ${JSON.stringify(writes)}\n`);
    process.exit(0);
  });
}

main().catch((e) => {
  process.stderr.write(`node-opcua: ${e.stack || e}\n`);
  process.exit(1);
});
