// The HMI page: reads /api/model once, follows /api/stream (server-sent events, one JSON frame of
// changes at a time; schema in docs/hmi.md) and sends controls, writes and faults as POSTs. With a
// history database the History panel (history.js) shows recorded runs; under `virtcom history
// --http` (model.replay) it is all the page shows: no stream, no controls.
import { Layout } from './layout.js';
import { Gantt } from './gantt.js';
import { Trend } from './trend.js';
import { StationPanel, SfcPanel, RulePanel } from './panels.js';
import { HistoryView } from './history.js';

const $ = (id) => document.getElementById(id);
const seconds = (ns) => `${(ns / 1e9).toFixed(3)} s`;

const state = {
  model: null,
  values: [],                 // signal value by tag
  activities: new Map(),      // index -> [index, device, label, start, end, error, energy]
  current: new Map(),         // trace device index -> running activity
  injected: [],
  forced: [],
  watch: JSON.parse(localStorage.getItem('virtcom.watch') || '[]'),
  vars: new Map(),            // watched name -> {value, forced}
  belts: new Map(),           // device index -> [[position mm, kind], ...] on its belt
  nowNs: 0,
  dirty: true,
};
let layout, gantt, trend, stream, stationPanel, sfcPanel, rulePanel, history;
const live = () => !history?.active;  // the Gantt chart and trends follow the live run

async function post(path, body) {
  const headers = { 'Content-Type': 'application/json' };
  const token = $('token').value;
  if (token) headers.Authorization = `Bearer ${token}`;
  const response = await fetch(path, { method: 'POST', headers, body: JSON.stringify(body) });
  const reply = await response.json().catch(() => ({}));
  $('message').textContent = response.ok ? '' : reply.error ?? `HTTP ${response.status}`;
  return response.ok;
}

function deviceState(device) {
  const error = device.ports.find(p => p.name === 'error');
  const running = state.current.get(device.trace);
  const index = state.model.devices.indexOf(device);
  const op = running ? state.model.labels[running[2]] ?? '' : '';
  if (error && state.values[error.tag]) return { state: 'error', op: `error ${state.values[error.tag]}` };
  if (state.injected[index]) return { state: 'fault', op: op || `fault ${state.injected[index]} armed` };
  return { state: running ? 'busy' : 'idle', op };
}

// A reset started the run again: what the page shows of the previous run goes.
function startOver() {
  state.activities.clear();
  state.current.clear();
  state.belts.clear();
  $('events').replaceChildren();
  trend.clear();
  rulePanel.clear();
  stationPanel.clear();
  $('message').textContent = 'reset: the run started again';
}

function applyFrame(f) {
  if (f.reset !== undefined) startOver();
  state.nowNs = f.t;
  const badge = $('run-state');
  badge.textContent = f.ended !== undefined ? 'ended' : f.paused ? 'paused' : 'running';
  badge.className = `badge ${f.ended !== undefined ? 'ended' : f.paused ? 'paused' : ''}`;
  if (f.ended !== undefined) $('message').textContent = f.ended;
  if (document.activeElement !== $('speed')) $('speed').value = f.speed;
  for (const [tag, value] of f.signals ?? []) {
    state.values[tag] = value;
    if (live()) trend.push(state.model.signals[tag].name, f.t, value);
  }
  for (const a of f.activities ?? []) {
    state.activities.set(a[0], a);
    if (a[4] < 0) state.current.set(a[1], a);
    else if (state.current.get(a[1])?.[0] === a[0]) state.current.delete(a[1]);
  }
  if (f.stations) stationPanel.update(f.stations);
  for (const e of f.faults ?? []) addEvent(`${seconds(e.t)} ${e.source}: ${e.message}`, 'fault');
  for (const c of f.collisions ?? []) {
    const names = state.model.devices;
    addEvent(`${seconds(c.t)} collision in ${state.model.labels[c.zone]}: ${names[c.a]?.name} and ${names[c.b]?.name}`, 'collision');
    layout.flashZone(state.model.zones.indexOf(state.model.labels[c.zone]));
  }
  if (f.kpi) {
    $('kpi-cycles').textContent = f.kpi.cycles;
    $('kpi-cycle').textContent = seconds(f.kpi.cycleNs);
    $('kpi-last').textContent = f.kpi.lastCycleNs ? seconds(f.kpi.lastCycleNs) : '–';
    $('kpi-ops').textContent = f.kpi.operations;
    $('kpi-energy').textContent = `${f.kpi.energyJ.toFixed(0)} J`;
    if (f.kpi.shift) {  // virtcom monitor with a production plan: parts against the plan so far
      const s = f.kpi.shift;
      $('kpi-shift-name').hidden = $('kpi-shift').hidden = false;
      $('kpi-shift-name').textContent = s.name ? `shift ${s.name}: parts / plan now` : 'shift: none now';
      $('kpi-shift').textContent = s.name ? `${s.parts} / ${s.planNow.toFixed(1)}` : '–';
    }
  }
  if (f.injected) state.injected = f.injected;
  if (f.forced) state.forced = f.forced;
  for (const v of f.vars ?? []) {
    state.vars.set(v.name, v);
    if (live()) trend.push(v.name, f.t, v.value);
  }
  if (f.steps) sfcPanel.update(f.steps);
  if (f.rules) rulePanel.update(f.rules);
  for (const b of f.belts ?? []) state.belts.set(b.device, b.parts);
  state.dirty = true;
}

function addEvent(text, kind) {
  const li = document.createElement('li');
  li.className = kind;
  li.textContent = text;
  $('events').prepend(li);
}

function render() {
  if (state.dirty && state.model) {
    state.dirty = false;
    $('vtime').textContent = seconds(state.nowNs);
    $('vtime').dataset.ns = state.nowNs;
    layout.update(state.values, deviceState, state.belts);
    if (live()) {
      gantt.render(state.activities, state.nowNs);
      trend.render(state.nowNs);
    }
    stationPanel.render(state.nowNs, deviceState);
    renderWatch();
  }
  history?.render();
  requestAnimationFrame(render);
}

function renderWatch() {
  for (const row of $('watch').tBodies[0].rows) {
    const v = state.vars.get(row.dataset.name);
    row.querySelector('.value').textContent = v ? v.value : '';
    row.classList.toggle('forced', !!v?.forced);
  }
}

function openStream() {
  if (stream) stream.close();
  stream = new EventSource(`/api/stream?watch=${encodeURIComponent(state.watch.join(','))}`);
  stream.onmessage = (event) => applyFrame(JSON.parse(event.data));
  stream.onerror = () => { $('run-state').textContent = 'reconnecting'; };
}

function addWatchRow(name) {
  const row = $('watch').tBodies[0].insertRow();
  row.dataset.name = name;
  row.innerHTML = '<td class="name"></td><td class="value"></td><td><input class="new-value"></td>' +
                  '<td><button class="write">Write</button><button class="force">Force</button><button class="release">Release</button>' +
                  '<button class="unwatch" title="stop watching">×</button></td>';
  row.querySelector('.name').textContent = name;
  const value = () => row.querySelector('.new-value').value;
  row.querySelector('.write').onclick = () => post('/api/write', { name, value: value(), force: false });
  row.querySelector('.force').onclick = () => post('/api/write', { name, value: value(), force: true });
  row.querySelector('.release').onclick = () => post('/api/release', { name });
  row.querySelector('.unwatch').onclick = () => {
    state.watch = state.watch.filter(n => n !== name);
    row.remove();
    saveWatch();
  };
}

// A trended name: a bus signal, or a PLC variable (then watched, so the stream sends its values).
function addTrend(name) {
  if (!live()) {  // the history has the recorded signals by name
    trend.add(name);
    history.reload();
    return;
  }
  const tag = state.model.signals.findIndex(s => s.name === name);
  if (tag < 0 && !state.watch.includes(name)) watch(name);
  trend.add(name);
  const value = tag >= 0 ? state.values[tag] : state.vars.get(name)?.value;  // from here on, changes come with frames
  if (value !== undefined) trend.push(name, state.nowNs, value);
}

function setUpTrends() {
  trend = new Trend($('trend'), $('trend-legend'), (names) => localStorage.setItem('virtcom.trends', JSON.stringify(names)));
  for (const s of state.model.signals) $('trend-choices').appendChild(new Option(s.name));
  $('trend-form').onsubmit = (e) => {
    e.preventDefault();
    if ($('trend-name').value) addTrend($('trend-name').value.trim());
  };
  $('trend-zoom-in').onclick = () => trend.zoom(0.5);
  $('trend-zoom-out').onclick = () => trend.zoom(2);
  $('trend-all').onclick = () => trend.zoom(Infinity);
  for (const name of JSON.parse(localStorage.getItem('virtcom.trends') || '[]')) trend.add(name);
}

function saveWatch() {
  localStorage.setItem('virtcom.watch', JSON.stringify(state.watch));
  openStream();
}

function watch(name) {
  if (state.watch.includes(name)) return;
  state.watch.push(name);
  addWatchRow(name);
  saveWatch();
}

async function search() {
  const response = await fetch(`/api/vars?match=${encodeURIComponent($('var-search').value)}`);
  const { vars } = await response.json();
  const list = $('var-results');
  list.replaceChildren();
  for (const v of vars) {
    const li = document.createElement('li');
    li.textContent = `${v.name} : ${v.type} = ${v.value}${v.forced ? ' (forced)' : ''}`;
    li.dataset.name = v.name;
    li.onclick = () => watch(v.name);
    list.appendChild(li);
  }
}

// The layout at a time of a recorded run (replay): its signals' values and running activities.
function showRecordedState(s) {
  state.nowNs = s.at;
  state.values = state.model.signals.map((signal) => s.values[signal.name]);
  state.current.clear();
  for (const a of s.activities) {
    const device = state.model.devices.find((d) => d.name === s.devices[a[1]]?.name);
    const label = state.model.labels.indexOf(s.labels[a[2]]);
    if (device) state.current.set(device.trace, [a[0], device.trace, label, ...a.slice(3)]);
  }
  state.dirty = true;
}

// Replay: the panels of the live run are hidden; the history shows the newest run.
function startReplay() {
  document.body.classList.add('replay');
  $('run-state').textContent = 'history';
  $('run-state').className = 'badge ended';
  history.activate();
  requestAnimationFrame(render);
}

async function start() {
  state.model = await (await fetch('/api/model')).json();
  const m = state.model;
  document.title = `${m.name} — virtcom HMI`;
  $('cell-name').textContent = m.name;
  $('token').hidden = !m.tokenRequired;
  if (m.readOnly) for (const b of document.querySelectorAll('button:not(#trend-form button):not(#history-panel button), #speed')) b.disabled = true;  // trends and history only watch
  layout = new Layout($('layout'), m);
  gantt = new Gantt($('gantt'), m);
  stationPanel = new StationPanel($('stations').tBodies[0], m.devices, m.labels);
  sfcPanel = new SfcPanel($('sfc-panel'), $('sfc-steps').tBodies[0], m.sfcSteps ?? []);
  rulePanel = new RulePanel($('rules-panel'), $('rules').tBodies[0], m.rules ?? []);
  setUpTrends();
  if (m.history) history = new HistoryView(m, gantt, trend, showRecordedState, () => { state.dirty = true; });
  if (m.replay) return startReplay();
  for (const d of m.devices) $('fault-device').add(new Option(d.name, d.name));
  for (const button of document.querySelectorAll('[data-action]'))
    button.onclick = () => post('/api/control', { action: button.dataset.action });
  $('speed').onchange = () => post('/api/control', { action: 'speed', value: Number($('speed').value) });
  $('release-all').onclick = () => post('/api/release', {});
  $('fault-form').onsubmit = (e) => {
    e.preventDefault();
    post('/api/fault', { device: $('fault-device').value, code: Number($('fault-code').value) });
  };
  $('var-search').oninput = search;
  state.watch.forEach(addWatchRow);
  openStream();
  search();
  requestAnimationFrame(render);
}

start();
