// fuzzymotiv lab: the page's script. Plain JavaScript and SVG; talks to its own server only.
'use strict';

// The paper's four motivations and their letters; a config may add others (docs/guide/motivations.md).
const NAMES = ['curiosity', 'homing', 'orientation', 'energy'];
const LETTERS = { curiosity: 'C', homing: 'H', orientation: 'O', energy: 'E' };
// Default values of "What would F be?" per input.
const EXPLAIN_DEFAULTS = { a: 0.9, g: 0.5, l: 0, b: 0.8 };
const SVGNS = 'http://www.w3.org/2000/svg';
const COLORS = { best: '#c33', mean: '#36c', a: '#2a6', g: '#c80', l: '#86c', b: '#088',
  goal: '#d3a', urgency: '#a50', waypoints: '#567', safety: '#6a0' };
const MORE_COLORS = ['#e70', '#09c', '#a3a', '#5a5', '#c66'];
const lab = {
  x: [0.8, 0.1, 0.0, 0.1], motivations: [], info: null, rooms: [], chosen: new Set(['H', 'T', 'L', 'square', 'rectangle']),
  run: null, source: null, gens: [], times: {}, draw: emptyDrawing(),
};
window.labTimes = lab.times;
// A room being drawn: corners on the 10 cm grid; goal and waypoints as {x, y, radius} (mm).
function emptyDrawing() {
  return { outline: [], obstacles: [], home: null, current: -1, goal: null, waypoints: [] };
}

const $ = (id) => document.getElementById(id);
function el(tag, attrs, parent) {
  const e = document.createElementNS(SVGNS, tag);
  for (const k in attrs || {}) e.setAttribute(k, attrs[k]);
  if (parent) parent.appendChild(e);
  return e;
}
function html(tag, text, parent) {
  const e = document.createElement(tag);
  if (text !== undefined) e.textContent = text;
  if (parent) parent.appendChild(e);
  return e;
}
const TOKEN_GONE = 'The lab no longer accepts this page: it was restarted, and each start makes a new access token ' +
  'unless started with --token. Open the address `fuzzymotiv lab` printed (…/?token=…) to go on.';
function showError(msg) {
  if (lab.locked && msg !== TOKEN_GONE) return;
  const bar = $('error-bar');
  bar.textContent = msg;
  bar.hidden = !msg;
}
async function api(method, url, body) {
  const opts = { method, headers: {} };
  if (body !== undefined) { opts.body = JSON.stringify(body); opts.headers['content-type'] = 'application/json'; }
  const r = await fetch(url, opts);
  if (r.status === 401) {
    lab.locked = true;
    const e = new Error(TOKEN_GONE);
    showError(TOKEN_GONE);
    e.status = 401;
    throw e;
  }
  const data = await r.json().catch(() => ({}));
  if (!r.ok) { const e = new Error(data.error || r.statusText); e.data = data; e.status = r.status; throw e; }
  return data;
}

// ---- 1. Motivations -------------------------------------------------------------------------
// The sliders of `list` ({name, weight, term, spec}, one per motivation of the loaded config).
function setMotivations(list) {
  lab.motivations = list.map((m) => ({ ...m }));
  lab.x = list.map((m) => m.weight);
  buildSliders();
  buildExplainInputs();
}
function sliderLabel(m) {
  const name = m.name[0].toUpperCase() + m.name.slice(1);
  return LETTERS[m.name] ? `${name} ${LETTERS[m.name]}` : `${name} (${m.term})`;
}
function buildSliders() {
  const box = $('sliders');
  box.replaceChildren();
  lab.motivations.forEach((m, i) => {
    const row = html('div', undefined, box);
    row.className = 'slider';
    const label = html('label', sliderLabel(m), row);
    label.htmlFor = `slider-${m.name}`;
    const input = html('input', undefined, row);
    Object.assign(input, { type: 'range', min: 0, max: 1, step: 0.01, id: `slider-${m.name}` });
    input.setAttribute('aria-label', sliderLabel(m));
    const out = html('output', '', row);
    out.id = `value-${m.name}`;
    input.addEventListener('input', () => setWeight(i, Number(input.value)));
  });
  const n = lab.motivations.length;
  $('sliders-hint').textContent = `The ${n} weights X = (${lab.motivations.map((m) => LETTERS[m.name] || m.name).join(', ')}) ` +
    'always sum to 1: moving one slider shares the rest among the others.';
  $('membership-title').textContent = `Membership functions of ${inputNames().join(', ')}`;
  showWeights();
}
// The TSK's input names: the term each motivation weighs, or its name where two weigh one term.
function inputNames() {
  return lab.motivations.map((m) => (lab.motivations.filter((o) => o.term === m.term).length > 1 ? m.name : m.term));
}
function setWeight(i, v) {
  const rest = lab.x.reduce((s, w, k) => (k === i ? s : s + w), 0);
  const left = 1 - v, others = Math.max(1, lab.x.length - 1);
  lab.x = lab.x.map((w, k) => (k === i ? v : rest > 1e-9 ? (w / rest) * left : left / others));
  lab.x = lab.x.map((w) => Math.round(w * 1000) / 1000);
  const drift = 1 - lab.x.reduce((s, w) => s + w, 0);
  const fix = lab.x.findIndex((w, k) => k !== i && w + drift >= 0);
  if (fix >= 0) lab.x[fix] = Math.round((lab.x[fix] + drift) * 1000) / 1000;
  showWeights();
}
function showWeights() {
  lab.motivations.forEach((m, i) => {
    $(`slider-${m.name}`).value = lab.x[i];
    $(`value-${m.name}`).textContent = lab.x[i].toFixed(2);
  });
}
// The motivations as a config's [motivations] writes them, with the sliders' weights.
function motivationsSpec() {
  const out = {};
  lab.motivations.forEach((m, i) => {
    out[m.name] = typeof m.spec === 'number' ? lab.x[i] : { ...m.spec, weight: lab.x[i] };
  });
  return out;
}
function buildExplainInputs() {
  const box = $('explain-inputs');
  box.querySelectorAll('label').forEach((l) => l.remove());
  const button = $('explain-button');
  inputNames().forEach((name) => {
    const label = html('label', `${name} `);
    const input = html('input', undefined, label);
    Object.assign(input, { type: 'number', min: 0, max: 1, step: 0.05, id: `explain-${name}`,
      value: EXPLAIN_DEFAULTS[name] ?? 0.5 });
    box.insertBefore(label, button);
  });
}
async function loadConfig(file) {
  try {
    const r = await api('POST', '/api/config', { toml: await file.text() });
    setMotivations(r.motivations);
    $('config-message').className = 'ok';
    $('config-message').textContent = `${file.name}: ${r.motivations.length} motivations loaded (its other settings are the lab's to set below).`;
  } catch (e) {
    $('config-message').className = 'error';
    $('config-message').textContent = e.message;
  }
}
function drawMembership(peaks) {
  const svg = $('membership');
  svg.replaceChildren();
  const X = (v) => 20 + v * 280, Y = (m) => 90 - m * 70;
  el('line', { x1: X(0), y1: Y(0), x2: X(1), y2: Y(0), stroke: '#999' }, svg);
  peaks.forEach((p, k) => {
    const lo = k > 0 ? peaks[k - 1] : p, hi = k < peaks.length - 1 ? peaks[k + 1] : p;
    const pts = [[lo, k > 0 ? 0 : 1], [p, 1], [hi, k < peaks.length - 1 ? 0 : 1]];
    el('polyline', { points: pts.map(([v, m]) => `${X(v)},${Y(m)}`).join(' '), fill: 'none',
      stroke: ['#c33', '#c80', '#2a6', '#36c', '#86c'][k % 5], 'stroke-width': 2 }, svg);
    el('text', { x: X(p), y: 105, 'font-size': 10, 'text-anchor': 'middle' }, svg).textContent = p;
  });
}
// The fitness combinations of the run form (`[fitness] combine`), as the page names them.
const COMBINE = { tsk: 'the TSK rule base', 'weighted-sum': 'a weighted sum (F = Σ Xᵢ·Yᵢ)',
  'weighted-squares': 'weighted squares (F = Σ Xᵢ·Yᵢ²)' };
// F under the run form's combination; the firing rules are the TSK's (a baseline has none).
async function explainF() {
  const y = {};
  inputNames().forEach((k) => { y[k] = Number($(`explain-${k}`).value); });
  const body = { motivations: motivationsSpec(), fitness: y };
  if ($('combine').value !== 'tsk') body.combine = $('combine').value;
  try {
    const r = await api('POST', '/api/explain', body);
    const out = $('explain-out');
    out.replaceChildren();
    const rules = `${r.rules.length} firing rule(s) (Σw = ${r.weight_sum.toFixed(4)})`;
    html('p', r.combine === 'tsk' ? `F = ${r.fitness.toFixed(6)} from ${rules}`
      : `F = ${r.combined.toFixed(6)} under ${COMBINE[r.combine]}, the fitness combination chosen in 3. ` +
        `The TSK would give F = ${r.fitness.toFixed(6)} from ${rules}:`, out).id = 'explain-f';
    const t = html('table', undefined, out);
    const head = html('tr', undefined, t);
    ['rule', ...r.inputs.map((k) => `${k} is`), 'w', 'f'].forEach((h) => html('th', h, head));
    r.rules.slice(0, 16).forEach((rule) => {
      const tr = html('tr', undefined, t);
      [rule.number, ...rule.label_names, rule.weight.toFixed(4), rule.output.toFixed(4)].forEach((v) => html('td', String(v), tr));
    });
    showError('');
  } catch (e) { showError(e.message); }
}

// ---- 2. Rooms -------------------------------------------------------------------------------
function roomSvg(room, svg, pad) {
  const xs = room.outline.map((p) => p.x), ys = room.outline.map((p) => p.y);
  const [x0, x1, y0, y1] = [Math.min(...xs), Math.max(...xs), Math.min(...ys), Math.max(...ys)];
  pad = pad || 40;
  svg.setAttribute('viewBox', `${x0 - pad} ${-(y1 + pad)} ${x1 - x0 + 2 * pad} ${y1 - y0 + 2 * pad}`);
  const pts = (poly) => poly.map((p) => `${p.x},${-p.y}`).join(' ');
  el('polygon', { points: pts(room.outline), fill: '#f6f6f0', stroke: '#333', 'stroke-width': 8 }, svg);
  room.obstacles.forEach((o) => el('polygon', { points: pts(o), fill: '#999', stroke: '#333', 'stroke-width': 4 }, svg));
  const z = room.home_zone;
  el('circle', { cx: z.centre.x, cy: -z.centre.y, r: z.radius, fill: 'none', stroke: '#2a6', 'stroke-dasharray': '12 8', 'stroke-width': 4 }, svg);
  el('circle', { cx: room.home.x, cy: -room.home.y, r: 28, fill: '#2a6' }, svg);
  const m = room.mission || {};
  drawMission(svg, m.goal && { x: m.goal.centre.x, y: m.goal.centre.y, radius: m.goal.radius },
    (m.waypoints || []).map((w) => ({ x: w.centre.x, y: w.centre.y, radius: w.radius })), (y) => -y);
  return svg;
}
// A mission on `svg`: the goal a gold disc with a flag, the waypoints numbered in their order.
function drawMission(svg, goal, waypoints, Y, bad) {
  const wrong = (field) => bad && bad.field && (bad.field === field || bad.field.startsWith(`${field}.`));
  if (waypoints.length > 1) {
    el('polyline', { points: waypoints.map((w) => `${w.x},${Y(w.y)}`).join(' '), fill: 'none', stroke: '#567',
      'stroke-width': 4, 'stroke-dasharray': '10 8' }, svg);
  }
  waypoints.forEach((w, k) => {
    const field = `waypoints[${k}]`;
    const c = el('circle', { cx: w.x, cy: Y(w.y), r: w.radius, fill: '#cde', 'fill-opacity': 0.7,
      stroke: wrong(field) ? '#d00' : '#567', 'stroke-width': wrong(field) ? 12 : 4 }, svg);
    c.setAttribute('class', 'waypoint');
    const t = el('text', { x: w.x, y: Y(w.y) + 14, 'font-size': 40, 'text-anchor': 'middle', 'font-weight': 'bold', fill: '#234' }, svg);
    t.textContent = String(k + 1);
  });
  if (goal) {
    const c = el('circle', { cx: goal.x, cy: Y(goal.y), r: goal.radius, fill: '#fd6', 'fill-opacity': 0.75,
      stroke: wrong('goal') ? '#d00' : '#b80', 'stroke-width': wrong('goal') ? 12 : 6 }, svg);
    c.setAttribute('class', 'goal');
    el('line', { x1: goal.x, y1: Y(goal.y), x2: goal.x, y2: Y(goal.y) - 70, stroke: '#333', 'stroke-width': 5 }, svg);
    el('polygon', { points: `${goal.x},${Y(goal.y) - 70} ${goal.x + 45},${Y(goal.y) - 57} ${goal.x},${Y(goal.y) - 44}`, fill: '#c33' }, svg);
  }
}
async function loadRooms() {
  lab.rooms = await api('GET', '/api/rooms');
  const box = $('room-choices');
  box.replaceChildren();
  lab.rooms.forEach((r) => {
    const d = html('div', undefined, box);
    d.className = 'thumb';
    roomSvg(r.room, el('svg', { role: 'img', 'aria-label': `room ${r.room.name}` }, d));
    const label = html('label', undefined, d);
    const cb = html('input', undefined, label);
    Object.assign(cb, { type: 'checkbox', checked: lab.chosen.has(r.entry), id: `room-${r.entry}` });
    cb.addEventListener('change', () => { if (cb.checked) lab.chosen.add(r.entry); else lab.chosen.delete(r.entry); });
    const m = r.room.mission || {};
    const mission = [m.goal ? 'goal' : '', m.waypoints && m.waypoints.length ? `${m.waypoints.length} waypoints` : ''].filter(Boolean).join(', ');
    const from = r.config ? ' (config)' : r.builtin ? '' : ' (drawn)';
    label.appendChild(document.createTextNode(` ${r.room.name}${from}${mission ? ` (${mission})` : ''}`));
    const edit = html('button', 'Edit', d);
    edit.type = 'button';
    edit.className = 'small';
    edit.title = `Copy ${r.room.name} into the editor to give it a goal and waypoints`;
    edit.addEventListener('click', () => editRoom(r));
  });
}
// The room point (mm) under the pointer: on the 10 cm grid, or to 1 cm with `fine`.
function editorPoint(ev, fine) {
  const svg = $('room-editor');
  const pt = svg.createSVGPoint();
  pt.x = ev.clientX; pt.y = ev.clientY;
  const p = pt.matrixTransform(svg.getScreenCTM().inverse());
  const g = fine ? 10 : 100;
  return [Math.round(p.x / g) * g, Math.round((1200 - p.y) / g) * g];
}
function drawEditor(bad) {
  const svg = $('room-editor'), d = lab.draw;
  svg.replaceChildren();
  for (let v = 0; v <= 1200; v += 100) {
    el('line', { x1: v, y1: 0, x2: v, y2: 1200, stroke: '#eee', 'stroke-width': 3 }, svg);
    el('line', { x1: 0, y1: v, x2: 1200, y2: v, stroke: '#eee', 'stroke-width': 3 }, svg);
  }
  const pts = (poly) => poly.map(([x, y]) => `${x},${1200 - y}`).join(' ');
  const polys = [['outline', d.outline, '#333', '#f6f6f0'], ...d.obstacles.map((o, k) => [`obstacles[${k}].outline`, o, '#333', '#999'])];
  polys.forEach(([field, poly, stroke, fill]) => {
    const wrong = bad && bad.field && bad.field.startsWith(field);
    el('polygon', { points: pts(poly), fill, 'fill-opacity': 0.6, stroke: wrong ? '#d00' : stroke, 'stroke-width': wrong ? 12 : 6 }, svg);
    poly.forEach(([x, y], k) => el('circle', { cx: x, cy: 1200 - y, r: 14, fill: wrong ? '#d00' : '#333' }, svg));
    if (wrong && poly.length) {
      const [x, y] = poly[poly.length - 1];
      const t = el('text', { x: x + 20, y: 1200 - y - 20, 'font-size': 44, fill: '#d00' }, svg);
      t.textContent = bad.error.split(': ').slice(-1)[0].slice(0, 60);
    }
  });
  if (d.home) el('circle', { cx: d.home[0], cy: 1200 - d.home[1], r: 30, fill: '#2a6' }, svg);
  drawMission(svg, d.goal, d.waypoints, (y) => 1200 - y, bad);
  if (bad && bad.field && /^(goal|waypoints)/.test(bad.field)) {
    const z = bad.field.startsWith('goal') ? d.goal : d.waypoints[Number((bad.field.match(/\d+/) || [0])[0])];
    if (z) {
      const t = el('text', { x: z.x + z.radius + 10, y: 1200 - z.y, 'font-size': 40, fill: '#d00' }, svg);
      t.textContent = bad.error.split(': ').slice(-1)[0].slice(0, 60);
    }
  }
}
function drawnRoom() {
  const d = lab.draw;
  const room = { name: $('room-name').value, outline: d.outline,
    home: d.home ? { x: d.home[0], y: d.home[1], heading_deg: Number($('home-heading').value) } : { x: 0, y: 0, heading_deg: 0 } };
  if (d.obstacles.length) room.obstacles = d.obstacles.filter((o) => o.length).map((o) => ({ outline: o }));
  if (d.homeZone) room.home_zone = { ...d.homeZone };
  if (d.goal) room.goal = { ...d.goal };
  if (d.waypoints.length) room.waypoints = d.waypoints.map((w) => ({ ...w }));
  return room;
}
async function checkRoom(save, body) {
  const msg = $('room-message');
  try {
    const r = await api('POST', '/api/rooms', body || { room: drawnRoom(), save });
    msg.className = 'ok';
    msg.textContent = save ? `Saved as ${r.entry}: it is now in the room list.` : `Room ${r.room.name} is valid.`;
    drawEditor();
    if (save) { lab.chosen.add(r.entry); await loadRooms(); }
  } catch (e) {
    msg.className = 'error';
    msg.textContent = e.message;
    drawEditor(e.data);
  }
}
// Goal and waypoints: press to place the centre, drag to size (a click keeps 60 mm).
function setupMissionDrawing(svg) {
  let zone = null;
  svg.addEventListener('pointerdown', (ev) => {
    const mode = $('draw-mode').value, d = lab.draw;
    if (mode !== 'goal' && mode !== 'waypoint') return;
    const [x, y] = editorPoint(ev, true);
    zone = { x, y, radius: 60 };
    if (mode === 'goal') d.goal = zone; else d.waypoints.push(zone);
    svg.setPointerCapture?.(ev.pointerId);
    drawEditor();
  });
  svg.addEventListener('pointermove', (ev) => {
    if (!zone) return;
    const [x, y] = editorPoint(ev, true);
    const r = Math.round(Math.hypot(x - zone.x, y - zone.y) / 10) * 10;
    if (r >= 20) { zone.radius = r; drawEditor(); }
  });
  const end = () => { zone = null; };
  svg.addEventListener('pointerup', end);
  svg.addEventListener('pointercancel', end);
}
// A listed room copied into the editor (a built-in one under a new name), to give it a mission.
function editRoom(view) {
  const r = view.room, pt = (p) => [p.x, p.y], zone = (z) => ({ x: z.centre.x, y: z.centre.y, radius: z.radius });
  const m = r.mission || {};
  lab.draw = { outline: r.outline.map(pt), obstacles: r.obstacles.map((o) => o.map(pt)), current: -1,
    home: [r.home.x, r.home.y], homeZone: zone(r.home_zone), goal: m.goal ? zone(m.goal) : null, waypoints: (m.waypoints || []).map(zone) };
  $('home-heading').value = Math.round((r.home.heading * 180) / Math.PI);
  $('room-name').value = view.builtin ? `${r.name}-mission` : `${r.name}-2`;
  $('room-editor-box').open = true;
  $('draw-mode').value = 'goal';
  $('room-message').textContent = `Editing a copy of ${r.name}: save it under a new name.`;
  drawEditor();
  $('room-editor').scrollIntoView({ block: 'center' });
}
function setupEditor() {
  const svg = $('room-editor');
  setupMissionDrawing(svg);
  svg.addEventListener('click', (ev) => {
    const p = editorPoint(ev), d = lab.draw, mode = $('draw-mode').value;
    if (mode === 'goal' || mode === 'waypoint') return;
    if (mode === 'home') d.home = p;
    else if (mode === 'obstacle') {
      if (d.current < 0) { d.obstacles.push([]); d.current = d.obstacles.length - 1; }
      d.obstacles[d.current].push(p);
    } else d.outline.push(p);
    drawEditor();
  });
  $('new-obstacle').addEventListener('click', () => { lab.draw.obstacles.push([]); lab.draw.current = lab.draw.obstacles.length - 1; $('draw-mode').value = 'obstacle'; });
  $('undo-vertex').addEventListener('click', () => {
    const d = lab.draw, mode = $('draw-mode').value;
    if (mode === 'obstacle' && d.current >= 0) d.obstacles[d.current].pop(); else if (mode === 'outline') d.outline.pop();
    else if (mode === 'goal') d.goal = null; else if (mode === 'waypoint') d.waypoints.pop(); else d.home = null;
    drawEditor();
  });
  $('clear-room').addEventListener('click', () => { lab.draw = emptyDrawing(); drawEditor(); });
  $('check-room').addEventListener('click', () => checkRoom(false));
  $('save-room').addEventListener('click', () => checkRoom(true));
  $('room-file').addEventListener('change', async (ev) => {
    const f = ev.target.files[0];
    if (!f) return;
    if (f.size > (lab.info ? lab.info.limits.body_bytes : 65536)) { $('room-message').textContent = 'The file is larger than the lab accepts.'; return; }
    await checkRoom(true, { toml: await f.text(), save: true });
  });
  drawEditor();
}

// ---- 3. Evolve ------------------------------------------------------------------------------
// The built-in robots (/api/robots), each with its body radius and sensor layout (mm, degrees).
async function loadRobots() {
  lab.robots = await api('GET', '/api/robots');
  // Every preview on one scale: the largest robot with its longest ray fills the picture.
  lab.robotReach = Math.max(...lab.robots.map((r) => Math.max(r.radius, ...r.layout.map((m) => Math.hypot(m.x, m.y) + m.range))));
  const select = $('robot');
  select.replaceChildren();
  lab.robots.forEach((r) => {
    const o = html('option', `${r.name} (${r.sensors} sensors, ${2 * r.radius} mm)`, select);
    o.title = r.title;
    o.value = r.name;
  });
  select.addEventListener('change', () => { showRobot(); clearRefusal(); });
  showRobot();
}
// Another robot picked after a refused run: the refusal was the other robot's.
function clearRefusal() {
  const status = $('run-status');
  if (status.className !== 'error') return;
  status.className = '';
  status.textContent = `Not started. ${robotNamed($('robot').value).title} picked: press Evolve to start a run.`;
  showError('');
}
function robotNamed(name) {
  return (lab.robots || []).find((r) => r.name === name);
}
// The picked robot: its body and sensors to scale (a 10 cm bar beside it), and what it is.
function showRobot() {
  const r = robotNamed($('robot').value), svg = $('robot-preview');
  svg.replaceChildren();
  if (!r) return;
  const reach = lab.robotReach * 1.05;
  svg.setAttribute('viewBox', `${-reach} ${-reach} ${2 * reach} ${2 * reach}`);
  drawRobot(svg, r, [0, 0, Math.PI / 2], (y) => -y);
  el('line', { x1: -reach * 0.95, y1: reach * 0.9, x2: -reach * 0.95 + 100, y2: reach * 0.9, stroke: '#333',
    'stroke-width': 2, 'vector-effect': 'non-scaling-stroke', class: 'scale-bar' }, svg);
  el('text', { x: -reach * 0.95, y: reach * 0.8, 'font-size': reach * 0.13 }, svg).textContent = '10 cm';
  $('robot-about').textContent = `${r.title}: a ${2 * r.radius} mm disc with ${r.sensors} sensors reading 0 to ` +
    `${r.reading_max} (the network's ${r.sensors} inputs); drawn at the end of each path below.`;
}
// Robot `r` at `pose` [x, y, heading] (mm, mm, rad) on `svg`, to scale: each sensor a ray from
// its mount in the direction it faces, as long as its reach, the body's disc and its heading.
function drawRobot(svg, r, pose, Y) {
  const [x, y, h] = pose, c = Math.cos(h), s = Math.sin(h);
  const thin = { 'vector-effect': 'non-scaling-stroke' };
  const g = el('g', { class: 'robot', 'data-robot': r.name }, svg);
  r.layout.forEach((m) => {
    const mx = x + c * m.x - s * m.y, my = y + s * m.x + c * m.y, d = h + (m.facing_deg * Math.PI) / 180;
    el('line', { x1: mx, y1: Y(my), x2: mx + m.range * Math.cos(d), y2: Y(my + m.range * Math.sin(d)),
      stroke: '#d62728', 'stroke-width': 1.5, class: 'sensor-ray', ...thin }, g);
  });
  el('circle', { cx: x, cy: Y(y), r: r.radius, fill: '#1f77b4', 'fill-opacity': 0.35, stroke: '#1f4e79',
    'stroke-width': 1.5, class: 'robot-body', ...thin }, g);
  el('line', { x1: x, y1: Y(y), x2: x + r.radius * c, y2: Y(y + r.radius * s), stroke: '#1f4e79',
    'stroke-width': 2, class: 'robot-heading', ...thin }, g);
}
// Round tick values over [lo, hi]: every multiple of a 1, 2 or 5 × 10^k step, about `target`
// intervals (the figures' Ticks::nice); `integer` keeps the step at least 1.
function niceTicks(lo, hi, target, integer) {
  if (!(hi > lo)) return { step: 1, values: [lo] };
  const raw = (hi - lo) / target, mag = Math.pow(10, Math.floor(Math.log10(raw)));
  let step = [1, 2, 5, 10].map((m) => m * mag).find((v) => v >= raw * (1 - 1e-9));
  if (integer) step = Math.max(1, step);
  const values = [];
  for (let k = Math.ceil(lo / step - 1e-9); k <= Math.floor(hi / step + 1e-9); k++) values.push(k * step);
  return { step, values };
}
function tickLabel(v, step) {
  return v.toFixed(Math.max(0, -Math.floor(Math.log10(step))));
}
// A chart of `series` per generation: y from 0 to yMax, ticks and labels on both axes; a series
// at 0 throughout lies on the x axis, so it is dashed and its legend says "= 0".
function chart(svg, series, yMax) {
  svg.replaceChildren();
  const n = Math.max(2, ...series.map((s) => s.values.length));
  const legend = legendLayout(series, 42, 392);
  const [x0, x1, y0, y1] = [38, 392, 170, 22 + 12 * (legend.rows - 1)];
  const X = (i) => x0 + (i / (n - 1)) * (x1 - x0), Y = (v) => y0 - (v / yMax) * (y0 - y1);
  const yt = niceTicks(0, yMax, 5, false);
  yt.values.forEach((v) => {
    el('line', { x1: x0, y1: Y(v), x2: x1, y2: Y(v), stroke: '#eee' }, svg);
    el('line', { x1: x0 - 4, y1: Y(v), x2: x0, y2: Y(v), stroke: '#666' }, svg);
    el('text', { x: x0 - 6, y: Y(v) + 3, 'font-size': 9, 'text-anchor': 'end', class: 'y-tick' }, svg).textContent = tickLabel(v, yt.step);
  });
  const xt = niceTicks(0, n - 1, 6, true);
  xt.values.forEach((g) => {
    el('line', { x1: X(g), y1: y0, x2: X(g), y2: y0 + 4, stroke: '#666' }, svg);
    el('text', { x: X(g), y: y0 + 13, 'font-size': 9, 'text-anchor': 'middle', class: 'x-tick' }, svg).textContent = String(g);
  });
  el('line', { x1: x0, y1: y0, x2: x1, y2: y0, stroke: '#666' }, svg);
  el('line', { x1: x0, y1: y1, x2: x0, y2: y0, stroke: '#666' }, svg);
  el('text', { x: (x0 + x1) / 2, y: 197, 'font-size': 9, 'text-anchor': 'middle' }, svg).textContent = 'generation';
  series.forEach((s, k) => {
    const zero = legend.zero[k], [lx, ly] = legend.at[k];
    const dash = zero ? { 'stroke-dasharray': '6 4', 'stroke-width': 3 } : { 'stroke-width': 2 };
    const line = el('polyline', { points: s.values.map((v, i) => `${X(i)},${Y(v)}`).join(' '), fill: 'none', stroke: s.color, ...dash }, svg);
    line.id = `${svg.id}-${s.name}`;
    line.setAttribute('data-points', String(s.values.length));
    el('line', { x1: lx, y1: ly - 3, x2: lx + 14, y2: ly - 3, stroke: s.color, ...dash }, svg);
    const label = el('text', { x: lx + 17, y: ly, 'font-size': 10, fill: s.color, class: 'legend' }, svg);
    label.textContent = legend.text[k];
  });
}
// Where each series' legend goes: left to right from `from`, a new row where `to` is passed.
function legendLayout(series, from, to) {
  const zero = series.map((s) => s.values.length > 0 && s.values.every((v) => v === 0));
  const text = series.map((s, k) => (zero[k] ? `${s.name} = 0 throughout` : s.name));
  let lx = from, row = 0;
  const at = text.map((t) => {
    const w = 30 + t.length * 6;
    if (lx > from && lx + w - 12 > to) { lx = from; row += 1; }
    const p = [lx, 12 + 12 * row];
    lx += w;
    return p;
  });
  return { zero, text, at, rows: row + 1 };
}
// The terms a run shows: a, g, l, b, then the mission and user terms it measures.
function termNames(gens) {
  const more = [];
  gens.forEach((g) => Object.keys(g.terms || {}).forEach((k) => { if (!more.includes(k)) more.push(k); }));
  return ['a', 'g', 'l', 'b', ...more];
}
function drawCharts(gens, fit, terms) {
  const best = gens.map((g) => g.best), mean = gens.map((g) => g.mean);
  chart(fit, [{ name: 'best', values: best, color: COLORS.best }, { name: 'mean', values: mean, color: COLORS.mean }],
    1);
  const names = termNames(gens);
  const value = (g, k) => (k in g && typeof g[k] === 'number' ? g[k] : (g.terms || {})[k] ?? 0);
  chart(terms, names.map((k, i) => ({ name: k, values: gens.map((g) => value(g, k)),
    color: COLORS[k] || MORE_COLORS[i % MORE_COLORS.length] })), 1);
  const caption = terms.closest('figure')?.querySelector('figcaption');
  if (caption) caption.textContent = `Mean terms ${names.join(', ')} per generation`;
}
function drawPaths(box, paths) {
  box.replaceChildren();
  if (!paths) return;
  paths.rooms.forEach((p) => {
    const room = lab.rooms.find((r) => r.room.name === p.room);
    const d = html('div', undefined, box);
    d.className = 'thumb';
    const svg = el('svg', { role: 'img', 'aria-label': `path in ${p.room}` }, d);
    if (room) roomSvg(room.room, svg);
    const line = el('polyline', { points: p.points.map(([x, y]) => `${x},${-y}`).join(' '), fill: 'none', stroke: '#c33', 'stroke-width': 6 }, svg);
    line.setAttribute('class', 'robot-path');
    const robot = robotNamed(paths.robot);
    if (robot && p.pose) drawRobot(svg, robot, p.pose, (y) => -y);
    const goal = room && room.room.mission && room.room.mission.goal;
    const reached = !goal ? '' : p.goal_step != null ? `, goal at step ${p.goal_step}` : ', goal not reached';
    html('div', `${p.room}${p.f !== undefined ? `, F = ${p.f.toFixed(3)}` : ''}${reached}`, d);
  });
}
function gaPreset() {
  const v = $('ga-preset').value, sizes = { quick: [30, 30], medium: [80, 80], paper: [200, 200] }[v];
  if (sizes) { $('population').value = sizes[0]; $('generations').value = sizes[1]; }
}
// A run's settings; room recognition needs two rooms, so one room runs without it. Steps left
// empty are the config default; the TSK (the default combination) is not sent.
function settings() {
  const rooms = lab.rooms.filter((r) => lab.chosen.has(r.entry)).map((r) => r.entry);
  const out = { name: $('run-name').value, seed: Number($('seed').value),
    motivations: motivationsSpec(),
    population: Number($('population').value), generations: Number($('generations').value),
    motion: $('motion').value, rooms, recognition: $('recognition').checked && rooms.length >= 2 };
  if ($('robot').value) out.robot = $('robot').value;
  if ($('steps').value !== '') out.steps = Number($('steps').value);
  if ($('combine').value !== 'tsk') out.combine = $('combine').value;
  return out;
}
// The page opened by `fuzzymotiv lab --config FILE`: the config's rooms chosen, the settings the
// form has filled in, and the keys the lab cannot set named (its motivations are the sliders).
function applyStart(start) {
  const s = start.settings;
  lab.chosen = new Set(s.rooms);
  $('run-name').value = s.name;
  $('seed').value = s.seed;
  $('population').value = s.population;
  $('generations').value = s.generations;
  const preset = Object.entries(lab.info.presets.ga).find(([, [p, g]]) => p === s.population && g === s.generations);
  $('ga-preset').value = preset ? preset[0] : 'custom';
  if (s.motion) $('motion').value = s.motion;
  if (s.steps) $('steps').value = s.steps;
  $('recognition').checked = s.recognition !== false;
  if (s.combine) $('combine').value = s.combine;
  if (s.robot && robotNamed(s.robot)) { $('robot').value = s.robot; showRobot(); }
  const msg = $('start-config');
  msg.hidden = false;
  msg.className = 'ok';
  msg.textContent = `Started on ${start.config}: its ${start.motivations.length} motivations (1), its ` +
    `${s.rooms.length} room${s.rooms.length === 1 ? '' : 's'} chosen (2), and its robot, name, seed, GA size, steps, motion model, ` +
    'room recognition and fitness combination (3). ' + (start.not_set.length
    ? `The lab cannot set ${start.not_set.join(', ')}: its runs take the defaults there; for those, run ` +
      `\`fuzzymotiv run ${start.config}\`.`
    : 'The lab sets all of its settings.');
}
async function evolve() {
  try {
    lab.times.evolve = performance.now();
    delete lab.times.firstGeneration; delete lab.times.finished;
    const r = await api('POST', '/api/runs', settings());
    follow(r.id);
    showError('');
  } catch (e) {
    // Refused (a room too small for the robot, a bad value): said beside Evolve too.
    const status = $('run-status');
    status.className = 'error';
    status.textContent = `Not started: ${e.message}` + (/closer than robot\.radius/.test(e.message)
      ? '. Rooms scaled for a larger robot: load rooms/thymio2/*.toml of the repository with "Load room file" in 2.' : '');
    showError(e.message);
  }
}
function follow(id) {
  if (lab.source) lab.source.close();
  lab.run = id; lab.gens = [];
  $('result').hidden = true;
  $('stop').disabled = false;
  $('run-status').className = '';
  $('run-status').textContent = `Run ${id}: waiting…`;
  refreshRuns();
  drawCharts([], $('fitness-chart'), $('terms-chart'));
  $('paths').replaceChildren();
  const src = new EventSource(`/api/runs/${encodeURIComponent(id)}/events`);
  lab.source = src;
  src.addEventListener('generation', (ev) => {
    const g = JSON.parse(ev.data);
    lab.gens.push(g);
    drawCharts(lab.gens, $('fitness-chart'), $('terms-chart'));
    if (lab.times.firstGeneration === undefined) lab.times.firstGeneration = performance.now();
    $('run-status').textContent = `Run ${id}: generation ${g.generation + 1}, best F ${g.best.toFixed(3)}`;
  });
  src.addEventListener('paths', (ev) => {
    const p = JSON.parse(ev.data);
    $('paths-title').textContent = `Paths of the best robot (generation ${p.generation + 1}${p.final ? ', final' : ''})`;
    drawPaths($('paths'), p);
  });
  src.addEventListener('end', (ev) => {
    src.close();
    const end = JSON.parse(ev.data);
    lab.times.finished = performance.now();
    $('stop').disabled = true;
    $('run-status').textContent = `Run ${id}: ${end.status}${end.error ? ` (${end.error})` : ''}`;
    if (end.status === 'finished') showResult(id, end.result);
    refreshRuns();
  });
}
// The per-room table; with `paths` (the final paths), a column of when each room's goal was
// reached by the best robot, for runs in rooms with goals.
function table(rows, parent, paths) {
  const cols = ['room', 'exploration_pct', 'homing_pct', 'battery_pct', 'recognition_pct', 'average_fitness'];
  const heads = ['room', '% exploration', '% homing', '% battery', '% recognition', 'mean F'];
  const goalOf = (name) => { const r = lab.rooms.find((v) => v.room.name === name); return r && r.room.mission && r.room.mission.goal; };
  const withGoal = paths && paths.rooms.some((p) => goalOf(p.room));
  if (withGoal) heads.push('goal reached (step)');
  const t = html('table', undefined, parent);
  const tr = html('tr', undefined, t);
  heads.forEach((h) => html('th', h, tr));
  rows.forEach((r) => {
    const row = html('tr', undefined, t);
    cols.forEach((c) => html('td', typeof r[c] === 'number' ? r[c].toFixed(c === 'average_fitness' ? 3 : 1) : (r[c] ?? '—'), row));
    if (withGoal) {
      const p = paths.rooms.find((q) => q.room === r.room);
      html('td', !goalOf(r.room) || !p ? '—' : p.goal_step != null ? `yes (${p.goal_step})` : 'no', row);
    }
  });
  return t;
}
function showResult(id, result) {
  $('result').hidden = false;
  const box = $('result-table');
  box.replaceChildren();
  table(result.rows, box, result.paths);
  if (result.combine) html('p', `F combined by ${COMBINE[result.combine]}.`, box).id = 'result-combine';
  html('p', `Wall time ${result.wall_seconds.toFixed(1)} s.`, box);
  $('save-name').value = id;
  $('download-config').href = `/api/runs/${encodeURIComponent(id)}/config.toml`;
  $('open-report').href = `/runs/${encodeURIComponent(id)}/report.html`;
  $('save-message').textContent = '';
}
async function saveRun() {
  try {
    const r = await api('POST', `/api/runs/${encodeURIComponent(lab.run)}/save`, { name: $('save-name').value });
    $('save-message').className = 'ok';
    $('save-message').textContent = `Saved: ${r.saved}`;
  } catch (e) { $('save-message').className = 'error'; $('save-message').textContent = e.message; }
}

// ---- 4. Runs and comparison -----------------------------------------------------------------
async function refreshRuns() {
  let runs;
  try { runs = await api('GET', '/api/runs'); } catch (e) { return; }
  const mine = runs.find((r) => r.id === lab.run);
  if (mine && mine.status === 'queued' && lab.gens.length === 0) {
    const ahead = mine.queue_position - 1 + (runs.some((r) => r.status === 'running') ? 1 : 0);
    $('run-status').textContent = `Run ${mine.id}: waiting, place ${mine.queue_position} in the queue ` +
      `(${ahead} run${ahead === 1 ? '' : 's'} before it)…`;
  }
  const body = $('run-list').querySelector('tbody');
  body.replaceChildren();
  runs.slice().reverse().forEach((r) => {
    const tr = html('tr', undefined, body);
    const names = r.about.motivation_names || NAMES;
    const m = Array.isArray(r.about.motivations) ? r.about.motivations : NAMES.map((k) => r.about.motivations[k]);
    const paper = names.length === 4 && names.every((n, k) => n === NAMES[k]);
    html('td', r.id, tr);
    const combine = r.about.combine && r.about.combine !== 'tsk' ? ` by ${r.about.combine}` : '';
    html('td', (paper ? `(${m.map((v) => Number(v).toFixed(2)).join(', ')})`
      : names.map((n, k) => `${LETTERS[n] || n} ${Number(m[k]).toFixed(2)}`).join(', ')) + combine +
      (r.about.notes && r.about.notes.length ? ` (${r.about.notes.join('; ')})` : ''), tr);
    html('td', `${r.about.population} × ${r.about.generations}${r.about.robot ? `, ${r.about.robot}` : ''}`, tr);
    html('td', r.status + (r.queue_position ? ` (queue ${r.queue_position})` : ''), tr);
    const td = html('td', undefined, tr);
    if (r.status === 'running' || r.status === 'queued') {
      const b = html('button', 'Stop', td);
      b.addEventListener('click', () => api('POST', `/api/runs/${encodeURIComponent(r.id)}/cancel`).then(refreshRuns));
    } else if (r.status === 'finished') {
      const b = html('button', 'Show', td);
      b.addEventListener('click', () => follow(r.id));
    }
  });
  const done = runs.filter((r) => r.status === 'finished').map((r) => r.id);
  ['compare-a', 'compare-b'].forEach((sel, k) => {
    const s = $(sel), keep = s.value;
    s.replaceChildren();
    done.forEach((id) => { const o = html('option', id, s); o.value = id; });
    s.value = done.includes(keep) ? keep : done[Math.max(0, done.length - 1 - k)] || '';
  });
}
async function compare() {
  const out = $('compare-out');
  try {
    const a = $('compare-a').value, b = $('compare-b').value;
    const r = await api('GET', `/api/compare?a=${encodeURIComponent(a)}&b=${encodeURIComponent(b)}`);
    out.replaceChildren();
    const grid = html('div', undefined, out);
    grid.className = 'compare';
    [r.a, r.b].forEach((side, k) => {
      const col = html('div', undefined, grid);
      html('h3', `${k ? 'B' : 'A'}: ${side.id}`, col);
      const svg = el('svg', { viewBox: '0 0 400 200', role: 'img', 'aria-label': `fitness of ${side.id}` }, col);
      svg.id = `compare-fit-${k}`;
      const t = el('svg', { viewBox: '0 0 400 200' });
      drawCharts(side.generations, svg, t);
      table(side.result.rows, col);
      const paths = html('div', undefined, col);
      paths.className = 'thumbs';
      drawPaths(paths, side.paths);
    });
    html('h3', 'Differences A − B over the test runs (as fuzzymotiv compare)', out);
    if (r.tests.length) {
      const t = html('table', undefined, out);
      t.id = 'differences';
      const head = html('tr', undefined, t);
      ['measure', 'room', 'n A', 'n B', 'A', 'B', 'A − B', '95 % interval', 'p (Holm)', 'verdict'].forEach((h) => html('th', h, head));
      const names = { exploration_pct: '% exploration', homing_pct: '% homing', battery_pct: '% battery', recognition_pct: '% recognition' };
      r.tests.forEach((c) => {
        const tr = html('tr', undefined, t);
        const f = (v) => (typeof v === 'number' ? v.toFixed(1) : '—');
        [names[c.metric] || c.metric, c.room, c.n_a, c.n_b, f(c.mean_a), f(c.mean_b), f(c.difference), `[${f(c.ci_low)}, ${f(c.ci_high)}]`,
          c.p_holm.toFixed(3), c.verdict].forEach((v) => html('td', String(v), tr));
      });
    }
    html('p', r.note, out).className = 'hint';
    showError('');
  } catch (e) { showError(e.message); }
}

// ---- 5. Studies -----------------------------------------------------------------------------
// The study files of the lab's study folder, picked into the text box; the lab's studies
// polled while one runs; an analysed study's pooled claims and forest plot.
async function loadStudyFiles() {
  const r = await api('GET', '/api/studies');
  lab.studyFiles = r.files;
  const sel = $('study-file');
  r.files.forEach((f) => { const o = html('option', f.file, sel); o.value = f.file; });
  showStudy(r.studies[0]);
}
function pickStudyFile() {
  const f = (lab.studyFiles || []).find((x) => x.file === $('study-file').value);
  if (f) $('study-text').value = f.toml;
}
async function startStudy() {
  const msg = $('study-message');
  msg.className = ''; msg.textContent = '';
  const file = $('study-file').value || undefined;
  try {
    const s = await api('POST', '/api/studies', { toml: $('study-text').value, file });
    lab.study = s.id;
    showStudy(s);
    pollStudy();
  } catch (e) { msg.className = 'error'; msg.textContent = e.message; }
}
async function pollStudy() {
  let r;
  try { r = await api('GET', '/api/studies'); } catch (e) { return; }
  const s = r.studies.find((x) => x.id === lab.study);
  showStudy(s);
  if (s && s.status === 'running') setTimeout(pollStudy, 500);
}
function showStudy(s) {
  if (!s) return;
  lab.study = s.id;
  const running = s.status === 'running';
  $('study-stop').disabled = !running;
  $('study-start').disabled = running;
  const state = { running: 'running', finished: 'analysed', stopped: 'stopped (start it again to resume in a new folder)', failed: 'failed' }[s.status] || s.status;
  $('study-status').textContent = `Study ${s.name} (${s.id}): ${s.done} of ${s.total} runs, ${state}.`;
  if (s.error) { $('study-message').className = 'error'; $('study-message').textContent = s.error; }
  else if (s.notes && s.notes.length) { $('study-message').className = 'note'; $('study-message').textContent = s.notes.join('\n'); }
  $('study-result').hidden = !s.claims;
  if (!s.claims) return;
  const body = $('study-claims').querySelector('tbody');
  body.replaceChildren();
  const f = (v) => (typeof v === 'number' && Number.isFinite(v) ? v.toPrecision(3) : '—');
  s.claims.forEach((c) => {
    const tr = html('tr', undefined, body);
    [c.id, c.sentence, f(c.effect), `[${f(c.ci_low)}, ${f(c.ci_high)}]`, f(c.p_adjusted), f(c.mdd), c.verdict]
      .forEach((v) => html('td', String(v), tr));
    tr.className = `verdict-${String(c.verdict).replace(/ /g, '-')}`;
  });
  $('study-title').textContent = `Claims of ${s.name} (pooled over its seeds)`;
  $('study-forest').src = `/api/studies/${encodeURIComponent(s.id)}/forest.svg`;
}
function setupStudies() {
  $('study-file').addEventListener('change', pickStudyFile);
  $('study-upload').addEventListener('change', async (ev) => {
    const f = ev.target.files[0];
    if (!f) return;
    $('study-text').value = await f.text();
    $('study-file').value = '';
  });
  $('study-text').addEventListener('input', () => { $('study-file').value = ''; });
  $('study-start').addEventListener('click', startStudy);
  $('study-stop').addEventListener('click', () => lab.study && api('POST', `/api/studies/${encodeURIComponent(lab.study)}/cancel`).then(pollStudy).catch((e) => showError(e.message)));
  return loadStudyFiles();
}

// ---- start ----------------------------------------------------------------------------------
async function start() {
  lab.info = await api('GET', '/api/info');
  const presets = lab.info.presets.motivations, start = lab.info.start;
  setMotivations(start ? start.motivations : presets['high curiosity']);
  await loadRobots();
  if (start) applyStart(start);
  drawMembership(lab.info.peaks);
  [['preset-high', 'high curiosity'], ['preset-low', 'low curiosity'], ['preset-fetch', 'fetch']].forEach(([id, name]) =>
    $(id).addEventListener('click', () => setMotivations(presets[name])));
  $('config-file').addEventListener('change', (ev) => { const f = ev.target.files[0]; if (f) loadConfig(f); });
  $('explain-button').addEventListener('click', explainF);
  $('combine').addEventListener('change', () => { if ($('explain-out').childElementCount) explainF(); });
  $('ga-preset').addEventListener('change', gaPreset);
  ['population', 'generations'].forEach((id) => $(id).addEventListener('input', () => { $('ga-preset').value = 'custom'; }));
  $('evolve').addEventListener('click', evolve);
  $('stop').addEventListener('click', () => lab.run && api('POST', `/api/runs/${encodeURIComponent(lab.run)}/cancel`).catch((e) => showError(e.message)));
  $('save-run').addEventListener('click', saveRun);
  $('compare-button').addEventListener('click', compare);
  setupEditor();
  await loadRooms();
  drawCharts([], $('fitness-chart'), $('terms-chart'));
  await refreshRuns();
  setInterval(refreshRuns, 2000);
  await setupStudies();
}
document.addEventListener('DOMContentLoaded', () => start().catch((e) => showError(e.message)));
