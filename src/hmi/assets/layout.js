// The layout view: a top view of the cell drawn from /api/model (places in cell millimetres,
// y up, so the SVG's y is negated) and updated from the live state. Every device is a
// <g class="device" data-name=... data-state=idle|busy|error|fault>; the cell file's static
// shapes (`hmi: shapes:`) are <g class="shape" data-kind=...> under them, and each `group` a
// <g class="group" data-group=...> frame around its devices.
const SVG = 'http://www.w3.org/2000/svg';

function el(parent, name, attrs = {}, text) {
  const e = document.createElementNS(SVG, name);
  for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, v);
  if (text !== undefined) e.textContent = text;
  parent.appendChild(e);
  return e;
}

const portTag = (device, port) => device.ports.find(p => p.name === port)?.tag;

// The smallest box {x, y, w, h} (mm, y up) holding every box of `boxes`.
function bounds(boxes) {
  let minX = Infinity, minY = Infinity, maxX = -Infinity, maxY = -Infinity;
  for (const b of boxes) {
    minX = Math.min(minX, b.x); maxX = Math.max(maxX, b.x + b.w);
    minY = Math.min(minY, b.y); maxY = Math.max(maxY, b.y + b.h);
  }
  return { x: minX, y: minY, w: maxX - minX, h: maxY - minY };
}

function shapeBox(s) {
  if (s.kind === 'rect') return { x: s.x, y: s.y, w: s.w, h: s.h };
  if (s.kind === 'circle') return { x: s.x - s.r, y: s.y - s.r, w: 2 * s.r, h: 2 * s.r };
  if (s.kind === 'line') return { x: Math.min(s.x, s.x2), y: Math.min(s.y, s.y2), w: Math.abs(s.x2 - s.x), h: Math.abs(s.y2 - s.y) };
  return { x: s.x, y: s.y, w: 0, h: 0 };
}

// A static shape of the cell file; its colour (checked by the loader) strokes it, fills text.
function drawShape(svg, s) {
  const g = el(svg, 'g', { class: 'shape', 'data-kind': s.kind });
  if (s.colour) g.style.setProperty('--shape-colour', s.colour);
  if (s.kind === 'rect') el(g, 'rect', { x: s.x, y: -(s.y + s.h), width: s.w, height: s.h });
  else if (s.kind === 'circle') el(g, 'circle', { cx: s.x, cy: -s.y, r: s.r });
  else if (s.kind === 'line') el(g, 'line', { x1: s.x, y1: -s.y, x2: s.x2, y2: -s.y2 });
  if (s.label) {
    const at = s.kind === 'rect' ? { x: s.x + 20, y: -s.y - 20 } : s.kind === 'circle' ? { x: s.x + s.r + 20, y: -s.y } : { x: s.x, y: -s.y };
    el(g, 'text', { class: s.kind === 'text' ? 'caption' : 'shape-label', ...at }, s.label);
  }
}

export class Layout {
  constructor(svg, model) {
    this.views = [];
    this.zoneShapes = new Map();  // zone index -> [SVG elements]
    const shapes = model.shapes ?? [];
    const box = bounds([...model.devices.map(d => d.place), ...shapes.map(shapeBox)]);
    const pad = 100;
    svg.setAttribute('viewBox', `${box.x - pad} ${-(box.y + box.h) - pad} ${box.w + 2 * pad} ${box.h + 2 * pad}`);
    for (const s of shapes) drawShape(svg, s);
    this.drawGroups(svg, model.devices);
    model.devices.forEach((d, i) => this.views.push(this.drawDevice(svg, d, model, i)));
  }

  drawGroups(svg, devices) {
    const groups = new Map();
    for (const d of devices) if (d.layoutGroup) groups.set(d.layoutGroup, [...(groups.get(d.layoutGroup) ?? []), d.place]);
    const margin = 60;
    for (const [name, places] of groups) {
      const b = bounds(places);
      const g = el(svg, 'g', { class: 'group', 'data-group': name });
      el(g, 'rect', { x: b.x - margin, y: -(b.y + b.h) - margin, width: b.w + 2 * margin, height: b.h + 2 * margin, rx: 30 });
      el(g, 'text', { x: b.x - margin + 20, y: -(b.y + b.h) - margin - 20 }, name);
    }
  }

  drawDevice(svg, d, model, index) {
    const p = d.place;
    const g = el(svg, 'g', { class: `device ${d.type}`, 'data-name': d.name, 'data-state': 'idle' });
    el(g, 'rect', { class: 'body', x: p.x, y: -(p.y + p.h), width: p.w, height: p.h, rx: 20 });
    el(g, 'text', { x: p.x + 20, y: -(p.y + p.h) + 70 }, d.label ?? d.name);
    const view = { device: d, index, g, op: el(g, 'text', { class: 'op', x: p.x + 20, y: -(p.y + p.h) + 130 }, ''), update: () => {} };
    const draw = { robot: this.drawRobot, axis: this.drawAxis, press: this.drawPress, conveyor: this.drawConveyor, sensor: this.drawSensor }[d.type];
    if (draw) draw.call(this, g, d, view, model);
    return view;
  }

  drawRobot(g, d, view, model) {
    const p = d.place, geo = d.geometry;
    el(g, 'circle', { cx: p.originX, cy: -p.originY, r: 60, fill: '#345' });
    for (const loc of geo.locations) {
      const x = p.originX + loc.x, y = -(p.originY + loc.y);
      if (loc.zone !== null) {
        const zone = model.zones.indexOf(loc.zone);
        const shape = el(g, 'circle', { class: 'zone', cx: x, cy: y, r: 140, 'data-zone': loc.zone });
        if (!this.zoneShapes.has(zone)) this.zoneShapes.set(zone, []);
        this.zoneShapes.get(zone).push(shape);
      }
      const l = el(g, 'g', { class: 'location' });
      el(l, 'rect', { x: x - 20, y: y - 20, width: 40, height: 40 });
      el(l, 'text', { x: x + 30, y: y + 12 }, loc.name);
    }
    const tx = portTag(d, 'actualX'), ty = portTag(d, 'actualY'), tt = portTag(d, 'toolAttached');
    const tcp = el(g, 'circle', { class: 'tcp', r: 45, 'data-device': d.name, cx: p.originX, cy: -p.originY });
    const tool = el(g, 'text', { class: 'tool' }, '');
    view.update = (values) => {
      const x = p.originX + (values[tx] ?? 0), y = -(p.originY + (values[ty] ?? 0));
      tcp.setAttribute('cx', x.toFixed(1));
      tcp.setAttribute('cy', y.toFixed(1));
      tool.setAttribute('x', x + 55);
      tool.setAttribute('y', y - 30);
      const index = values[tt] ?? 0;
      tool.textContent = index > 0 ? geo.tools[index - 1] ?? '' : '';
    };
  }

  drawAxis(g, d, view) {
    const p = d.place, geo = d.geometry, y = -(p.y + p.h / 2) + 60;
    const x0 = p.x + 60, x1 = p.x + p.w - 60;
    el(g, 'line', { class: 'rail', x1: x0, y1: y, x2: x1, y2: y });
    const slider = el(g, 'rect', { class: 'slider', y: y - 50, width: 80, height: 100, x: x0 - 40 });
    const tag = portTag(d, 'actualPosition');
    const span = Math.max(geo.maxPosition - geo.minPosition, 1e-9);
    view.update = (values) => {
      const f = Math.min(Math.max(((values[tag] ?? 0) - geo.minPosition) / span, 0), 1);
      slider.setAttribute('x', (x0 + f * (x1 - x0) - 40).toFixed(1));
    };
  }

  drawPress(g, d, view) {
    const p = d.place, stroke = d.geometry.stroke || 100;
    const top = -(p.y + p.h) + 160, travel = p.h - 240;
    const ram = el(g, 'rect', { class: 'ram', x: p.x + p.w / 2 - 60, y: top, width: 120, height: 20 });
    const tag = portTag(d, 'position');
    view.update = (values) => {
      const f = Math.min(Math.max((values[tag] ?? 0) / stroke, 0), 1);
      ram.setAttribute('height', (20 + f * travel).toFixed(1));
    };
  }

  // The belt with its sensors, the parts it carries (drawn where the stream's `belts` put them,
  // coloured by kind) and its bins (one per pusher, beside it, and the end bin with discharge)
  // with their part counts (the `<bin>_<kind>` ports).
  drawConveyor(g, d, view) {
    const p = d.place, geo = d.geometry, y = -(p.y + p.h / 2) + 40;
    const belt = el(g, 'rect', { class: 'belt', x: p.x + 40, y: y - 40, width: p.w - 80, height: 80 });
    const length = Math.max(geo.length || 1, 1e-9);
    const at = (mm) => p.x + 40 + (mm / length) * (p.w - 80);
    const sensors = geo.sensors.map(s => ({
      tag: portTag(d, s.name),
      shape: el(g, 'circle', { class: 'sensor', r: 25, cx: at(s.position), cy: y + 80 }),
    }));
    const kinds = geo.kinds ?? ['parts'];
    const bin = (name, x) => {
      // The count inside the bin (a belt's bins stand close together), its name as the tooltip.
      const b = el(g, 'g', { class: 'bin', 'data-bin': name });
      el(b, 'title', {}, name);
      el(b, 'rect', { x: x - 60, y: y - 200, width: 120, height: 100 });
      const count = el(b, 'text', { class: 'bin-count', x: x - 45, y: y - 130 }, '');
      return { name, count, tags: kinds.map(k => portTag(d, `${name}_${k}`)) };
    };
    const bins = (geo.pushers ?? []).map(s => bin(s.name, at(s.position)));
    if (geo.discharge) bins.push(bin('end', p.x + p.w - 60));
    const parts = el(g, 'g', { class: 'parts' });
    const partWidth = Math.max(((geo.partLength ?? 100) / length) * (p.w - 80), 6);
    const moving = portTag(d, 'moving');
    const index = view.index;
    view.update = (values, belts) => {
      belt.classList.toggle('moving', !!values[moving]);
      for (const s of sensors) s.shape.classList.toggle('on', !!values[s.tag]);
      for (const b of bins) {
        const total = b.tags.reduce((sum, tag) => sum + (values[tag] ?? 0), 0);
        b.count.textContent = total;
        b.count.dataset.count = total;
      }
      const onBelt = belts?.get(index) ?? [];
      while (parts.childNodes.length > onBelt.length) parts.lastChild.remove();
      while (parts.childNodes.length < onBelt.length) el(parts, 'rect', { class: 'part', y: y - 30, height: 60, width: partWidth });
      onBelt.forEach(([mm, kind], i) => {
        const r = parts.childNodes[i];
        r.setAttribute('x', at(mm).toFixed(1));
        r.dataset.kind = kinds[kind] ?? kind;
        r.style.fill = `hsl(${(kind * 67) % 360} 60% 45%)`;
      });
    };
  }

  drawSensor(g, d, view) {
    const p = d.place;
    const lamp = el(g, 'circle', { class: 'sensor', r: 60, cx: p.x + p.w / 2, cy: -(p.y + p.h / 2) + 40 });
    const tag = portTag(d, 'value');
    view.update = (values) => lamp.classList.toggle('on', !!values[tag]);
  }

  // values: signal values by tag; state(device) -> {state, op}; belts: device index -> the
  // parts on its belt ([position mm, kind], ...).
  update(values, state, belts) {
    for (const v of this.views) {
      const s = state(v.device);
      v.g.dataset.state = s.state;
      v.op.textContent = s.op;
      v.update(values, belts);
    }
  }

  flashZone(zone) {
    for (const shape of this.zoneShapes.get(zone) ?? []) {
      shape.classList.remove('flash');
      void shape.getBBox();  // restart the animation
      shape.classList.add('flash');
    }
  }
}
