// Load test of every server of one running cell (docs/performance.md, "Many clients at once"):
// `virtcom serve` of the gearbox cell with --ads, --modbus, --opcua and --http, then for a fixed
// time 100 ADS clients (npm ads-client), 100 Modbus TCP clients (raw MBAP, FC 4), 20 HMI streams
// (server-sent events) and 20 OPC UA sessions (node-opcua-client), each its own TCP connection.
// Every ADS and OPC UA client also writes MAIN.sequence := 3 (its value already) once a second:
// the write audit's count at the end must equal the writes acknowledged (nothing lost).
// Measures requests served, errors and refusals per protocol, and from the stream frames how far
// virtual time fell behind the wall clock (the pacing lag: a scan that ran late shows as lag), and
// the served run's own count of late ticks (its JSON report).
// Run by hand, never by ctest (it measures time):
//   npm ci --prefix tests/e2e/ads && npm ci --prefix tests/e2e/opcua
//   node bench/load/load_test.js build/release/src/cli/virtcom [SECONDS=30]
'use strict';
const path = require('node:path');
const net = require('node:net');
const http = require('node:http');
const fs = require('node:fs');
const os = require('node:os');
const { spawn } = require('node:child_process');

const root = path.resolve(__dirname, '../..');
const { Client: AdsClient } = require(path.join(root, 'tests/e2e/ads/node_modules/ads-client'));
const ua = require(path.join(root, 'tests/e2e/opcua/node_modules/node-opcua-client'));

const exe = path.resolve(process.argv[2] || 'build/release/src/cli/virtcom');
const seconds = Number(process.argv[3] || 30);
const counts = { ADS: 100, Modbus: 100, HMI: 20, 'OPC UA': 20 };
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));
const stats = {};
for (const p of Object.keys(counts)) stats[p] = { connected: 0, requests: 0, writes: 0, errors: 0, refused: 0 };

// The served run's JSON report, written when it is stopped: its ticks and late ticks.
const reportFile = path.join(os.tmpdir(), `virtcom-load-${process.pid}.json`);

function startCell() {
  const args = ['serve', path.join(root, 'examples/gearbox-cell/cell.yaml'), '--ads', '127.0.0.1:0', '--modbus', '127.0.0.1:0',
    '--opcua', '127.0.0.1:0', '--opcua-anonymous', 'write', '--http', '127.0.0.1:0', '--quiet', '--json', reportFile];
  const child = spawn(exe, args, { stdio: ['ignore', 'ignore', 'pipe'] });
  let err = '';
  const ports = new Promise((resolve, reject) => {
    child.stderr.on('data', (d) => {
      err += d;
      const ads = /ads: serving on 127\.0\.0\.1:(\d+)/.exec(err), mb = /modbus: serving on 127\.0\.0\.1:(\d+)/.exec(err);
      const opc = /opcua: serving opc\.tcp:\/\/127\.0\.0\.1:(\d+)/.exec(err), hmi = /hmi: serving http:\/\/127\.0\.0\.1:(\d+)/.exec(err);
      if (ads && mb && opc && hmi) resolve({ ads: +ads[1], modbus: +mb[1], opcua: +opc[1], http: +hmi[1] });
    });
    child.on('exit', (code) => reject(new Error(`serve exited with ${code}:\n${err}`)));
  });
  return { child, ports, stderr: () => err };
}

async function adsClient(port, until) {
  const s = stats.ADS;
  const c = new AdsClient({ targetAmsNetId: '127.0.0.1.1.1', targetAdsPort: 851, routerAddress: '127.0.0.1', routerTcpPort: port });
  try { await c.connect(); s.connected++; } catch { s.refused++; return; }
  let nextWrite = Date.now();
  while (Date.now() < until) {
    try {
      await c.readValue('MAIN.jobsFinished');
      s.requests++;
      if (Date.now() >= nextWrite) {
        await c.writeValue('MAIN.sequence', 3);
        s.writes++;
        nextWrite += 1000;
      }
    } catch { s.errors++; await sleep(10); }
  }
  await c.disconnect().catch(() => {});
}

// Read input registers 0..9 (FC 4: the devices' status, which the gearbox cell's map fills past
// 20; it has only 7 holding registers, so FC 3 of ten was refused with exception 02) in a loop
// over one connection. An exception response counts as an error.
function modbusClient(port, until) {
  const s = stats.Modbus;
  return new Promise((resolve) => {
    const sock = net.connect(port, '127.0.0.1');
    let id = 0, buffer = Buffer.alloc(0), open = false;
    const ask = () => {
      if (Date.now() >= until) { sock.end(); return; }
      id = (id + 1) & 0xffff;
      sock.write(Buffer.from([id >> 8, id & 0xff, 0, 0, 0, 6, 1, 4, 0, 0, 0, 10]));
    };
    sock.on('connect', () => { open = true; s.connected++; ask(); });
    sock.on('data', (d) => {
      buffer = Buffer.concat([buffer, d]);
      while (buffer.length >= 6 && buffer.length >= 6 + buffer.readUInt16BE(4)) {
        const n = 6 + buffer.readUInt16BE(4);
        if (buffer[7] & 0x80) s.errors++; else s.requests++;
        buffer = buffer.subarray(n);
        ask();
      }
    });
    sock.on('error', () => { if (!open) s.refused++; else s.errors++; });
    sock.on('close', () => { if (open && Date.now() < until - 500) s.errors++; resolve(); });
  });
}

// One stream; the lag of virtual time behind the wall clock, per frame: each frame's wall time
// minus its virtual time (`t`), less the least of these over the stream, the frame that came
// soonest. (Measured from the stream's first frame instead, a first frame that came late under
// load made every later one look early: negative lags.)
function hmiStream(port, until, lag) {
  const s = stats.HMI;
  const offsets = [];
  let finished = false;
  const done = (resolve) => {
    if (finished) return;
    finished = true;
    const least = Math.min(...offsets);
    for (const o of offsets) lag.push(o - least);
    resolve();
  };
  return new Promise((resolve) => {
    const req = http.get({ host: '127.0.0.1', port, path: '/api/stream' }, (res) => {
      if (res.statusCode !== 200) { s.refused++; res.resume(); return resolve(); }
      s.connected++;
      let text = '';
      res.on('data', (d) => {
        text += d;
        let nl;
        while ((nl = text.indexOf('\n')) >= 0) {
          const line = text.slice(0, nl);
          text = text.slice(nl + 1);
          if (!line.startsWith('data:')) continue;
          s.requests++;
          const t = JSON.parse(line.slice(5)).t;
          offsets.push(Number(process.hrtime.bigint()) / 1e6 - t / 1e6);
        }
        if (Date.now() >= until) { req.destroy(); done(resolve); }
      });
      res.on('error', () => done(resolve));
      res.on('close', () => done(resolve));
    });
    req.on('error', () => { s.errors++; resolve(); });
  });
}

async function opcuaSession(port, until) {
  const s = stats['OPC UA'];
  const client = ua.OPCUAClient.create({ endpointMustExist: false, connectionStrategy: { maxRetry: 0 } });
  let session;
  try { await client.connect(`opc.tcp://127.0.0.1:${port}`); session = await client.createSession(); s.connected++; } catch { s.refused++; return; }
  const id = (name) => `ns=4;s=|var|virtcom.Application.${name}`;  // as TwinCAT names them (docs/opcua.md)
  let nextWrite = Date.now();
  while (Date.now() < until) {
    try {
      await session.read({ nodeId: id('MAIN.jobsFinished'), attributeId: ua.AttributeIds.Value });
      s.requests++;
      if (Date.now() >= nextWrite) {
        const r = await session.write({ nodeId: id('MAIN.sequence'), attributeId: ua.AttributeIds.Value,
          value: { value: { dataType: ua.DataType.Int16, value: 3 } } });
        if (r.value === 0) s.writes++; else s.errors++;
        nextWrite += 1000;
      }
    } catch { s.errors++; await sleep(10); }
  }
  await session.close().catch(() => {});
  await client.disconnect().catch(() => {});
}

async function main() {
  const cell = startCell();
  const ports = await cell.ports;
  const until = Date.now() + seconds * 1000;
  const lag = [];
  const all = [];
  for (let i = 0; i < counts.ADS; ++i) all.push(adsClient(ports.ads, until));
  for (let i = 0; i < counts.Modbus; ++i) all.push(modbusClient(ports.modbus, until));
  for (let i = 0; i < counts.HMI; ++i) all.push(hmiStream(ports.http, until, lag));
  for (let i = 0; i < counts['OPC UA']; ++i) all.push(opcuaSession(ports.opcua, until));
  await Promise.all(all);
  await sleep(300);  // the last writes cross their scan boundary
  cell.child.kill('SIGTERM');
  const code = await new Promise((r) => cell.child.on('exit', r));
  const err = cell.stderr();
  console.log(`${seconds} s, virtcom serve exit ${code}`);
  console.log('protocol  clients connected  requests/s   writes  errors  refused');
  for (const [p, s] of Object.entries(stats))
    console.log(`${p.padEnd(9)} ${String(counts[p]).padStart(7)} ${String(s.connected).padStart(9)} ${(s.requests / seconds).toFixed(0).padStart(11)} ${String(s.writes).padStart(8)} ${String(s.errors).padStart(7)} ${String(s.refused).padStart(8)}`);
  lag.sort((a, b) => a - b);
  const pick = (q) => (lag.length ? lag[Math.min(lag.length - 1, Math.floor(q * lag.length))].toFixed(1) : '-');
  console.log(`pacing lag (wall - virtual, beyond a stream's soonest frame, ms): median ${pick(0.5)}, p99 ${pick(0.99)}, max ${pick(1)}`);
  // The served run's own count of ticks that started late (docs/performance.md, Late ticks).
  try {
    const time = JSON.parse(fs.readFileSync(reportFile, 'utf8')).run.time;
    console.log(`late ticks of the served run: ${time.late_ticks} of ${time.ticks} (at most ${(time.max_late_s * 1000).toFixed(1)} ms late)`);
    fs.rmSync(reportFile);
  } catch (e) {
    console.log(`no JSON report of the served run: ${e.message}`);
  }
  const audit = /audit: (\d+) external writes \(ads (\d+), modbus \d+, opcua (\d+)/.exec(err);
  const acked = stats.ADS.writes + stats['OPC UA'].writes;
  console.log(audit ? `audited writes ${audit[1]} (ads ${audit[2]}, opcua ${audit[3]}), acknowledged ${acked}: ${+audit[1] === acked ? 'none lost' : 'MISMATCH'}`
                    : `no audit summary on stderr:\n${err}`);
  const refusals = err.split('\n').filter((l) => / refused /.test(l));
  console.log(`refusals logged by the server: ${refusals.length}${refusals.length ? '\n  ' + refusals.slice(0, 5).join('\n  ') : ''}`);
}

main().catch((e) => { console.error(e); process.exit(1); });
