// host-sim serve: the simulator page. Plain DOM, no framework, no build step.
// The server's contract is the HTTP/JSON API of `host-sim serve`; every field
// is read defensively so an older or newer server still shows what it can.
'use strict';

const $ = (id) => document.getElementById(id);
const LIST_MAX = 40;            // longer lists start collapsed
const SVGNS = 'http://www.w3.org/2000/svg';

// Element builder: h('div', {class: 'x', onclick: f}, child, 'text', ...).
function h(tag, attrs, ...kids) {
  const el = tag.startsWith('svg:') ? document.createElementNS(SVGNS, tag.slice(4)) : document.createElement(tag);
  for (const [k, v] of Object.entries(attrs || {})) {
    if (v == null || v === false) continue;
    if (k.startsWith('on')) el.addEventListener(k.slice(2), v);
    else if (k === 'text') el.textContent = v;
    else el.setAttribute(k, v === true ? '' : v);
  }
  for (const c of kids.flat()) if (c != null) el.append(c.nodeType ? c : String(c));
  return el;
}
const svg = (tag, attrs, ...kids) => h('svg:' + tag, attrs, ...kids);

let model = null;     // GET /api/model
let st = null;        // last state
const ui = { inputs: [], outputs: [], timers: [], sups: [], events: {}, commands: {}, analog: [], nets: [], diag: [] };
let busy = false;     // a POST in flight (the run loop waits for it)
let renders = 0;      // states rendered (body data-renders: tests wait on it)

// What an unexpected event leads to under the project's policy.
function unexpectedGoes() {
  const u = (model.project || {}).unexpected;
  return u === 'fault' ? '→ fault' : `→ ${u || 'unexpected'}`;
}

function fmtTime(ms) { return (ms / 1000).toFixed(3) + ' s'; }
function fmtRate(n) { return n >= 1e6 ? (n / 1e6).toFixed(2) + ' M' : n >= 1e3 ? (n / 1e3).toFixed(1) + ' k' : n.toFixed(0) + ' '; }
function say(text, err) { const s = $('status'); s.textContent = text || ''; s.className = err ? 'err' : ''; }

async function api(path, body) {
  const opt = body === undefined ? {} : { method: 'POST', headers: { 'Content-Type': 'application/json' }, body: JSON.stringify(body) };
  const r = await fetch('api/' + path, opt);
  let j = null;
  try { j = await r.json(); } catch (e) { j = null; }
  if (!r.ok || !j) throw new Error((j && j.error) || (r.status + ' ' + r.statusText + ' on ' + path));
  return j;
}

// A POST that updates the page with the state it returns.
async function act(path, body) {
  busy = true;
  try {
    const s = await api(path, body);
    say('');
    render(s);
    return s;
  } catch (e) {
    say(e.message, true);
    throw e;
  } finally { busy = false; }
}

// A list container that hides its entries past LIST_MAX behind a toggle.
function collapsible(box, n) {
  if (n <= LIST_MAX) return;
  box.classList.add('collapsed');
  const t = h('button', { class: 'more', onclick: () => { box.classList.toggle('collapsed'); t.textContent = box.classList.contains('collapsed') ? `show all ${n}` : 'show fewer'; } }, `show all ${n}`);
  box.after(t);
}

// ---------- static structure, from the model ----------

function build() {
  const p = model.project || {}, plant = model.plant || {};
  document.title = `host-sim — ${p.name || 'project'}`;
  $('project').textContent = p.name || '?';
  $('project-info').textContent = [p.file, `${p.scan_period_ms} ms scan`, `${p.backend} backend`, `unexpected → ${p.unexpected}`].filter(Boolean).join(' · ');
  const physical = plant.kind === 'boiler' || plant.kind === 'cell';
  $('inputs-hint').textContent = physical ? 'driven by the plant' : 'click to toggle';

  const ib = $('inputs');
  ui.inputs = (model.inputs || []).map((inp) => {
    const b = h('button', { class: 'io input', 'data-name': inp.name, id: 'input-' + inp.name, 'data-testid': 'input-' + inp.name, disabled: physical,
      title: `${inp.name}${inp.debounce_scans ? `, debounced ${inp.debounce_scans} scans` : ''}${inp.reset ? ' — the reset input' : ''}`,
      onclick: () => act('input', { name: inp.name, value: !(st && st.inputs[ui.inputs.indexOf(b)]) }).catch(() => {}) },
      h('span', { class: 'dot' }), h('span', { class: 'nm' }, inp.name), inp.reset ? h('span', { class: 'tag reset' }, 'reset') : null,
      inp.debounce_scans ? h('span', { class: 'tag' }, 'db' + inp.debounce_scans) : null);
    ib.append(b);
    return b;
  });
  collapsible(ib, ui.inputs.length);

  const ob = $('outputs');
  ui.outputs = (model.outputs || []).map((o) => {
    const d = h('div', { class: 'io output', 'data-name': o.name, id: 'output-' + o.name, 'data-testid': 'output-' + o.name, 'data-level': '0', title: `${o.name}: driven by ${o.drive}; safe level ${o.safe ? 1 : 0}` },
      h('span', { class: 'lamp' }), h('span', { class: 'nm' }, o.name), o.safe ? h('span', { class: 'tag' }, 'safe 1') : null);
    ob.append(d);
    return d;
  });
  collapsible(ob, ui.outputs.length);

  const tb = $('timers');
  $('timers-panel').hidden = !(model.timers || []).length;
  ui.timers = (model.timers || []).map((t) => {
    const bar = h('div', { class: 'fill' }), val = h('span', { class: 'val' });
    tb.append(h('div', { class: 'timer', id: 'timer-' + t.name }, h('span', { class: 'nm' }, t.name), h('div', { class: 'bar' }, bar), val));
    return { bar, val, preset: t.preset_ms, row: tb.lastChild };
  });

  buildPlant(plant, physical);

  const sb = $('supervisors');
  ui.sups = (model.supervisors || []).map((s) => {
    const v = h('b', { class: 'state', id: 'state-' + s.name, 'data-testid': 'state-' + s.name });
    sb.append(h('div', { class: 'sup', 'data-name': s.name }, h('span', { class: 'nm' }, s.name), h('span', { class: 'dim' }, s.kind === 'net' ? 'net' : `${s.kind}, ${s.states} states`), v));
    return v;
  });
  collapsible(sb, ui.sups.length);

  const eb = $('events');
  for (const e of (model.events || []).filter((e) => !e.controllable)) {
    const why = h('span', { class: 'why' }), fx = h('span', { class: 'fx' }, unexpectedGoes());
    const b = h('button', { class: 'ev', 'data-name': `${e.name} ${e.trigger}`, id: 'event-' + e.name, 'data-testid': 'event-' + e.name, disabled: !e.clickable,
      title: `${e.name}: ${e.trigger} (${e.origin})${e.clickable ? '' : ' — not clickable'}`,
      onclick: () => act('event', { name: e.name }).catch(() => {}) },
      h('span', { class: 'nm' }, e.name), h('span', { class: 'trig' }, e.trigger), fx, why);
    eb.append(b);
    ui.events[e.name] = { b, why, fx, resets: !!p.reset && e.trigger === 'rising ' + p.reset };
  }
  if (!eb.children.length) eb.append(h('div', { class: 'dim' }, 'none'));
  collapsible(eb, eb.children.length);

  const cb = $('commands');
  for (const e of (model.events || []).filter((e) => e.controllable)) {
    const why = h('div', { class: 'why' }), req = h('span', { class: 'req' });
    const row = h('div', { class: 'cmd', 'data-name': `${e.name} ${e.request || ''}`, id: 'command-' + e.name, 'data-testid': 'command-' + e.name, 'data-enabled': '0' },
      h('span', { class: 'dot' }), h('span', { class: 'nm' }, e.name), req, h('span', { class: 'trig' }, e.request ? 'on ' + e.request : ''), why);
    cb.append(row);
    ui.commands[e.name] = { row, why, req };
  }
  if (!cb.children.length) cb.append(h('div', { class: 'dim' }, 'none'));
  collapsible(cb, cb.children.length);

  (model.supervisors || []).forEach((s, i) => {
    if (!s.diagram || !(s.diagram.states || []).length) return;
    const d = automatonDiagram(s.diagram);
    const box = diagramPanel('diagram-' + s.name, s.name, 'state diagram: solid = controllable, dashed = uncontrollable, ↺ self-loops', d.svg, s.diagram.states.length <= 16);
    const entry = { sup: i, box, ...d };
    ui.diag.push(entry);
    box.parentNode.addEventListener('toggle', () => scrollToNode(entry, entry.cur));
  });
  (model.nets || []).forEach((n) => {
    const d = netDiagram(n);
    ui.nets.push(d);
    diagramPanel('net-' + n.name, n.name, 'Petri net: tokens per place, control places red, enabled transitions green', d.svg, d.tokens.length + d.trans.length <= 60);
  });
}

// A diagram in a panel that folds (large ones start folded) and scrolls.
function diagramPanel(id, name, hint, el, open) {
  const box = h('div', { class: 'dscroll' }, el);
  $('diagrams').append(h('details', { class: 'panel diagram', 'data-name': name, id, open }, h('summary', {}, h('h2', {}, `${name} `, h('span', { class: 'hint' }, hint))), box));
  fitWidth(el);
  return box;
}

function buildPlant(plant, physical) {
  const pb = $('plant');
  pb.append(h('div', { class: 'dim plant-text', title: 'plant: ' + (plant.kind || '?') }, plant.text || plant.kind || ''));
  ui.components = (plant.components || []).map((c) => {
    const v = h('b', { class: 'state' });
    pb.append(h('div', { class: 'sup' }, h('span', { class: 'nm' }, c), v));
    return v;
  });
  if ((plant.actions || []).length) {
    const ab = h('div', { class: 'actions' });
    for (const a of plant.actions) ab.append(h('button', { id: 'action-' + a.name, 'data-testid': 'action-' + a.name, onclick: () => act('action', { name: a.name }).catch(() => {}) }, a.label || a.name));
    pb.append(ab);
  }
  ui.analog = (plant.analog || []).map((a) => {
    const fill = h('div', { class: 'fill' }), val = h('b', { class: 'val' });
    pb.append(h('div', { class: 'analog', id: 'analog-' + a.name }, h('span', { class: 'nm' }, a.label || a.name), h('div', { class: 'bar' }, fill), val));
    return { fill, val, a };
  });
  if (!physical && !(plant.components || []).length && !(plant.actions || []).length && !(plant.analog || []).length) pb.firstChild.classList.add('only');
}

// ---------- diagrams ----------

// Layers by breadth-first search from `roots` (then from any node still
// unplaced), ordered inside a layer by two barycentre sweeps.
function layered(n, edges, roots) {
  const out = Array.from({ length: n }, () => []), inc = Array.from({ length: n }, () => []);
  for (const [a, b] of edges) if (a !== b) { out[a].push(b); inc[b].push(a); }
  const layer = new Array(n).fill(-1);
  let queue = roots.filter((r) => r >= 0 && r < n);
  const seeds = [...queue, ...Array.from({ length: n }, (_, i) => i)];
  let base = 0;
  for (const s of seeds) {
    if (layer[s] >= 0) continue;
    const q = [s]; layer[s] = base;
    for (const r of queue) if (layer[r] < 0) { layer[r] = base; q.push(r); }
    queue = [];
    while (q.length) { const x = q.shift(); for (const y of out[x]) if (layer[y] < 0) { layer[y] = layer[x] + 1; q.push(y); } }
    base = Math.max(...layer) + 1;
  }
  const cols = [];
  layer.forEach((l, i) => (cols[l] = cols[l] || []).push(i));
  const pos = new Array(n).fill(0);
  const place = () => cols.forEach((c) => c.forEach((x, k) => (pos[x] = k - (c.length - 1) / 2)));
  place();
  for (let sweep = 0; sweep < 2; sweep++) {
    for (const c of cols.slice(1)) {
      const bc = (x) => { const ps = inc[x].filter((y) => layer[y] < layer[x]); return ps.length ? ps.reduce((s, y) => s + pos[y], 0) / ps.length : pos[x]; };
      c.sort((a, b) => bc(a) - bc(b));
      place();
    }
  }
  return { layer, pos, cols };
}

function textWidth(s, px) { return s.length * px * 0.6; }

// Where the ray from a box's centre towards (tx, ty) leaves the box.
function clip(cx, cy, hw, hh, tx, ty) {
  const dx = tx - cx, dy = ty - cy;
  if (!dx && !dy) return [cx, cy];
  const t = Math.min(dx ? hw / Math.abs(dx) : Infinity, dy ? hh / Math.abs(dy) : Infinity);
  return [cx + dx * t, cy + dy * t];
}

// Edge between two boxes: straight for forward neighbours, else bent to
// its left so a pair of opposite edges and back edges separate.
function edgePath(g, a, b, straight, label, cls, weight, arrow) {
  const dx = b.x - a.x, dy = b.y - a.y, len = Math.hypot(dx, dy) || 1;
  const bend = straight ? 0 : Math.max(22, len * 0.22);
  const cx = (a.x + b.x) / 2 - (dy / len) * bend, cy = (a.y + b.y) / 2 + (dx / len) * bend;
  const [x0, y0] = clip(a.x, a.y, a.hw + 2, a.hh + 2, cx, cy);
  const [x1, y1] = clip(b.x, b.y, b.hw + 4, b.hh + 4, cx, cy);
  g.append(svg('path', { d: `M${x0.toFixed(1)},${y0.toFixed(1)} Q${cx.toFixed(1)},${cy.toFixed(1)} ${x1.toFixed(1)},${y1.toFixed(1)}`, class: 'edge ' + cls, 'marker-end': arrow }));
  if (label) {
    const lx = 0.25 * x0 + 0.5 * cx + 0.25 * x1, ly = 0.25 * y0 + 0.5 * cy + 0.25 * y1;
    const t = svg('text', { x: lx.toFixed(1), y: (ly - 3).toFixed(1), class: 'elabel' + (weight ? ' weight' : ''), 'text-anchor': 'middle' }, label.text);
    if (label.title) t.append(svg('title', {}, label.title));
    g.append(t);
  }
}

// Each diagram has its own arrowhead: a marker in a hidden diagram would
// not draw in the others.
let arrows = 0;
function arrowDefs() {
  const id = 'arrow' + ++arrows;
  return svg('defs', {}, svg('marker', { id, viewBox: '0 0 10 10', refX: '9', refY: '5', markerWidth: '7', markerHeight: '7', orient: 'auto-start-reverse' },
    svg('path', { d: 'M0,1 L10,5 L0,9 z', class: 'arrowhead' })));
}

function fitSvg(nodes, extra) {
  let x0 = Infinity, y0 = Infinity, x1 = -Infinity, y1 = -Infinity;
  for (const n of nodes) { x0 = Math.min(x0, n.x - n.hw); x1 = Math.max(x1, n.x + n.hw); y0 = Math.min(y0, n.y - n.hh); y1 = Math.max(y1, n.y + n.hh); }
  const m = extra;
  const w = x1 - x0 + 2 * m, hgt = y1 - y0 + 2 * m;
  return svg('svg', { viewBox: `${(x0 - m).toFixed(0)} ${(y0 - m).toFixed(0)} ${w.toFixed(0)} ${hgt.toFixed(0)}`, width: w.toFixed(0), height: hgt.toFixed(0), class: 'dsvg' });
}

// A diagram up to a third wider than its panel is scaled down to fit;
// a larger one keeps its size and the panel scrolls.
function fitWidth(el) {
  const avail = el.parentNode.clientWidth - 20, w = Number(el.getAttribute('width'));
  if (avail > 0 && w > avail && w < avail * 1.35) { el.setAttribute('width', avail); el.setAttribute('height', (Number(el.getAttribute('height')) * avail / w).toFixed(0)); }
}

// Scrolls a large diagram's panel so that state `i` is in view.
function scrollToNode(d, i) {
  const box = d.box, nd = d.nodes[i], vb = d.svg.viewBox.baseVal;
  if (!box || !nd || !vb || box.scrollHeight <= box.clientHeight + 2 && box.scrollWidth <= box.clientWidth + 2) return;
  const k = Number(d.svg.getAttribute('width')) / vb.width;
  box.scrollTo({ left: (nd.x - vb.x) * k - box.clientWidth / 2, top: (nd.y - vb.y) * k - box.clientHeight / 2 });
}

function automatonDiagram(dg) {
  const states = dg.states, edges = dg.edges || [];
  const n = states.length;
  const loops = states.map(() => []);
  for (const e of edges) if (e.from === e.to && loops[e.from]) loops[e.from].push(...e.events);
  const init = states.findIndex((s) => s.initial);
  const L = layered(n, edges.filter((e) => e.from !== e.to).map((e) => [e.from, e.to]), [init < 0 ? 0 : init]);
  // Box sizes: the name, then the self-loops wrapped at ~22 characters.
  const nodes = states.map((s, i) => {
    const lines = [];
    let cur = '';
    for (const ev of loops[i]) { if (cur && (cur + ' ' + ev).length > 16) { lines.push(cur); cur = ''; } cur = cur ? cur + ' ' + ev : ev; }
    if (cur) lines.push(cur);
    const w = Math.max(textWidth(s.name, 13) + 18, ...lines.map((l) => textWidth('↺ ' + l, 10) + 12), 36);
    return { i, lines, hw: w / 2, hh: (24 + lines.length * 12) / 2 };
  });
  const colW = L.cols.map((c) => Math.max(...c.map((i) => nodes[i].hw * 2)));
  let x = 0;
  const colX = colW.map((w) => { const cx = x + w / 2; x += w + 64; return cx; });
  const rowH = Math.max(...nodes.map((nd) => nd.hh * 2)) + 46;
  nodes.forEach((nd) => { nd.x = colX[L.layer[nd.i]]; nd.y = L.pos[nd.i] * rowH; });
  const root = fitSvg(nodes, 34);
  root.append(arrowDefs());
  const arrow = `url(#arrow${arrows})`;
  const ge = svg('g', {}), gn = svg('g', {});
  const has = new Set(edges.map((e) => e.from + ',' + e.to));
  for (const e of edges) {
    if (e.from === e.to || !nodes[e.from] || !nodes[e.to]) continue;
    const a = nodes[e.from], b = nodes[e.to];
    const straight = L.layer[e.to] === L.layer[e.from] + 1 && !has.has(e.to + ',' + e.from) && Math.abs(L.pos[e.to] - L.pos[e.from]) < 1.5;
    const full = e.events.join(', ');
    edgePath(ge, a, b, straight, { text: full.length > 26 ? full.slice(0, 24) + '…' : full, title: full }, e.controllable ? 'ctl' : 'unc', false, arrow);
  }
  const groups = nodes.map((nd) => {
    const s = states[nd.i];
    const g = svg('g', { class: 'node' + (s.marked ? ' marked' : '') + (s.initial ? ' initial' : ''), transform: `translate(${nd.x.toFixed(1)},${nd.y.toFixed(1)})` },
      svg('title', {}, `state ${s.name}${s.initial ? ', initial' : ''}${s.marked ? ', marked' : ''}${nd.lines.length ? '\nself-loops: ' + loops[nd.i].join(', ') : ''}`),
      svg('rect', { x: -nd.hw, y: -nd.hh, width: nd.hw * 2, height: nd.hh * 2, rx: 7 }));
    if (s.marked) g.append(svg('rect', { class: 'inner', x: -nd.hw + 3, y: -nd.hh + 3, width: nd.hw * 2 - 6, height: nd.hh * 2 - 6, rx: 5 }));
    g.append(svg('text', { y: -nd.hh + 16, 'text-anchor': 'middle', class: 'sname' }, s.name));
    nd.lines.forEach((l, k) => g.append(svg('text', { y: -nd.hh + 29 + 12 * k, 'text-anchor': 'middle', class: 'loops' }, (k ? '' : '↺ ') + l)));
    if (s.initial) g.append(svg('path', { d: `M${-nd.hw - 22},0 L${-nd.hw - 3},0`, class: 'edge unc initarrow', 'marker-end': arrow }));
    gn.append(g);
    return g;
  });
  root.append(ge, gn);
  return { svg: root, groups, nodes, cur: -1 };
}

function netDiagram(net) {
  const P = (net.places || []).length, T = (net.transitions || []).length;
  const arcs = net.arcs || [];
  const edges = arcs.map((a) => (a.to_transition ? [a.place, P + a.transition] : [P + a.transition, a.place]));
  const roots = (net.places || []).map((p, i) => (p.initial > 0 && !p.control ? i : -1)).filter((i) => i >= 0);
  const L = layered(P + T, edges, roots);
  const nodes = Array.from({ length: P + T }, (_, i) => (i < P ? { i, hw: 16, hh: 16 } : { i, hw: 4, hh: 15 }));
  nodes.forEach((nd) => { nd.x = L.layer[nd.i] * 78; nd.y = L.pos[nd.i] * 70; });
  const root = fitSvg(nodes, 30);
  root.append(arrowDefs());
  const arrow = `url(#arrow${arrows})`;
  const ge = svg('g', {}), gn = svg('g', {});
  const has = new Set(edges.map(([a, b]) => a + ',' + b));
  arcs.forEach((a, k) => {
    const [f, t] = edges[k];
    if (!nodes[f] || !nodes[t]) return;
    const straight = L.layer[t] === L.layer[f] + 1 && !has.has(t + ',' + f) && Math.abs(L.pos[t] - L.pos[f]) < 1.5;
    const cp = net.places[a.place] && net.places[a.place].control;
    edgePath(ge, nodes[f], nodes[t], straight, a.weight > 1 ? { text: String(a.weight) } : null, cp ? 'ctl controlarc' : 'ctl', a.weight > 1, arrow);
  });
  const tokens = [], trans = [];
  (net.places || []).forEach((p, i) => {
    const nd = nodes[i], tok = svg('text', { y: 5, 'text-anchor': 'middle', class: 'tokens' }, String(p.initial));
    const g = svg('g', { class: 'place' + (p.control ? ' control' : ''), transform: `translate(${nd.x},${nd.y})` },
      svg('title', {}, `place ${p.name}${p.control ? ' (control place of the synthesised supervisor)' : ''}, initially ${p.initial}`),
      svg('circle', { r: 16 }), tok, svg('text', { y: 29, 'text-anchor': 'middle', class: 'pname' }, p.name));
    gn.append(g);
    tokens.push({ tok, g });
  });
  (net.transitions || []).forEach((t, j) => {
    const nd = nodes[P + j];
    const g = svg('g', { class: 'trans' + (t.controllable ? ' c' : ' u'), transform: `translate(${nd.x},${nd.y})` },
      svg('title', {}, `transition ${t.name}${t.controllable ? ' (controllable)' : ' (uncontrollable)'}`),
      svg('rect', { x: -4, y: -15, width: 8, height: 30 }), svg('text', { y: -19, 'text-anchor': 'middle', class: 'tname' }, t.name));
    gn.append(g);
    trans.push(g);
  });
  root.append(ge, gn);
  return { svg: root, tokens, trans, arcs, P };
}

// ---------- rendering a state ----------

function setLevel(el, on) {
  el.classList.toggle('on', !!on);
  el.dataset.level = on ? '1' : '0';
}

function render(s) {
  st = s;
  $('scan').textContent = s.scan;
  $('time').textContent = fmtTime(s.time_ms || 0);
  (s.inputs || []).forEach((v, i) => ui.inputs[i] && setLevel(ui.inputs[i], v));
  (s.outputs || []).forEach((v, i) => ui.outputs[i] && setLevel(ui.outputs[i], v));
  (s.timers || []).forEach((t, i) => {
    const u = ui.timers[i];
    if (!u) return;
    const frac = u.preset ? Math.max(0, Math.min(1, t.remaining_ms / u.preset)) : 0;
    u.bar.style.width = (t.running ? frac * 100 : 0) + '%';
    u.row.classList.toggle('running', !!t.running);
    u.val.textContent = t.running ? fmtTime(t.remaining_ms) : 'stopped';
  });
  (s.supervisors || []).forEach((x, i) => { if (ui.sups[i]) ui.sups[i].textContent = x.name; });
  for (const d of ui.diag) {
    const x = (s.supervisors || [])[d.sup];
    const cur = x ? x.state : -1;
    if (cur === d.cur) continue;
    if (d.groups[d.cur]) d.groups[d.cur].classList.remove('cur');
    if (d.groups[cur]) { d.groups[cur].classList.add('cur'); scrollToNode(d, cur); }
    d.cur = cur;
  }
  ui.nets.forEach((d, k) => {
    const m = (s.markings || [])[k] || [];
    d.tokens.forEach((t, i) => { const v = m[i] || 0; t.tok.textContent = v; t.g.classList.toggle('marked', v > 0); });
    d.trans.forEach((g, j) => g.classList.toggle('enabled', d.arcs.every((a) => !a.to_transition || a.transition !== j || (m[a.place] || 0) >= a.weight)));
  });
  const pl = s.plant || {};
  (pl.states || []).forEach((v, i) => { if (ui.components[i]) ui.components[i].textContent = v; });
  (pl.analog || []).forEach((v, i) => {
    const u = ui.analog[i];
    if (!u) return;
    const span = (u.a.max - u.a.min) || 1;
    u.fill.style.width = Math.max(0, Math.min(100, ((v - u.a.min) / span) * 100)) + '%';
    u.val.textContent = `${Number(v).toFixed(1)} ${u.a.unit || ''}`;
  });
  for (const u of s.uncontrollable || []) {
    const e = ui.events[u.event];
    if (!e) continue;
    e.b.classList.toggle('expected', !!u.expected);
    e.b.classList.toggle('unexpected', !u.expected);
    e.b.dataset.expected = u.expected ? '1' : '0';
    e.why.textContent = u.needs ? 'needs ' + u.needs : '';
    e.fx.textContent = !s.fault ? unexpectedGoes() : e.resets ? '→ leaves fault mode' : 'ignored in fault mode';
  }
  for (const c of s.commands || []) {
    const e = ui.commands[c.event];
    if (!e) continue;
    e.row.dataset.enabled = c.enabled ? '1' : '0';
    e.row.classList.toggle('enabled', !!c.enabled);
    e.req.textContent = c.requested == null ? '' : c.requested ? 'requested' : 'not requested';
    e.req.className = 'req' + (c.requested ? ' yes' : '');
    e.why.textContent = (c.disabled_by || []).map((d) => `${d.supervisor}: ${d.why}`).join('; ');
  }
  renderFault(s.fault);
  renderLog(s.log || []);
  const c = s.counters || {};
  $('counters').replaceChildren(...Object.entries(c).map(([k, v]) => h('div', { class: v && k !== 'faults' ? 'warn' : '' }, h('span', {}, k.replace('_', ' ')), h('b', {}, v))));
  const drv = s.driver === 'random';
  $('driver').setAttribute('aria-pressed', String(drv));
  $('driver').textContent = drv ? 'Random driver: on' : 'Random driver: off';
  document.body.classList.toggle('faulted', !!s.fault);
  document.body.dataset.scan = String(s.scan);
  document.body.dataset.renders = String(++renders);
  if (document.body.dataset.ready !== '1') {
    document.body.dataset.ready = '1';
    document.body.dataset.readyMs = performance.now().toFixed(1);
  }
  historySoon();
}

let faultKey = null;
function renderFault(f) {
  const el = $('fault'), cause = f ? (typeof f === 'string' ? f : f.cause || 'fault') : null;
  el.hidden = !f;
  if (cause === faultKey) return;     // rebuilt only when it changes: its button stays clickable
  faultKey = cause;
  if (!f) { el.replaceChildren(); return; }
  const reset = (model.project || {}).reset;
  const physical = ['boiler', 'cell'].includes((model.plant || {}).kind);
  const action = physical && ((model.plant || {}).actions || []).find((a) => /reset/i.test(a.name));
  const safe = (model.outputs || []).filter((o) => o.safe).map((o) => o.name);
  el.replaceChildren(h('b', {}, 'FAULT MODE'), h('span', { class: 'cause', id: 'fault-cause' }, cause),
    h('span', {}, `outputs at their safe levels${safe.length ? ` (on: ${safe.join(', ')})` : ' (all off)'}`),
    reset ? h('span', {}, 'leave it with a rising edge of ', h('b', {}, reset)) : h('span', {}, 'no reset input: only a restart leaves it'),
    reset && !physical ? h('button', { id: 'fault-reset', onclick: pulseReset }, `Pulse ${reset}`) : null,
    action ? h('button', { id: 'fault-reset', onclick: () => act('action', { name: action.name }).catch(() => {}) }, action.label || action.name) : null);
}

// Press and release the reset input (held long enough for its debounce).
async function pulseReset() {
  const name = model.project.reset;
  const inp = (model.inputs || []).find((i) => i.name === name) || {};
  try {
    await act('input', { name, value: true });
    await act('step', { scans: (inp.debounce_scans || 0) + 1 });
    await act('input', { name, value: false });
    await act('step', { scans: 1 });
  } catch (e) { /* shown in the status line */ }
}

let logKey = '';
function renderLog(log) {
  const last = log[log.length - 1];
  const key = log.length + ':' + (last ? last.scan : '') + ':' + (st ? st.scan === 0 : '');
  if (key === logKey) return;
  logKey = key;
  const items = [];
  for (let i = log.length - 1; i >= 0; i--) {
    const e = log[i];
    items.push(h('div', { class: 'entry' + (e.fault ? ' f' : '') + ((e.unexpected || []).length ? ' u' : ''), 'data-scan': e.scan,
      'data-time': e.time_ms, 'data-events': (e.events || []).join(' '), 'data-unexpected': (e.unexpected || []).join(' ') },
      h('span', { class: 'sc' }, '#' + e.scan), h('span', { class: 'tm' }, fmtTime(e.time_ms)),
      h('span', { class: 'evs' }, (e.events || []).join(' '), ...(e.unexpected || []).map((u) => h('span', { class: 'unx' }, ' ' + u + '!'))),
      e.fault ? h('span', { class: 'fc' }, typeof e.fault === 'string' ? e.fault : e.fault.cause || 'fault') : null,
      e.note ? h('span', { class: 'note' }, e.note) : null));
  }
  $('log').replaceChildren(...items);
}

// ---------- plots ----------

let histTimer = null, histAt = 0, lastHist = null;
function historySoon() {
  if (histTimer) return;
  const wait = Math.max(0, histAt + (running ? 400 : 60) - performance.now());
  histTimer = setTimeout(async () => {
    histAt = performance.now();
    const scan = st.scan;
    try {
      drawPlot(lastHist = await api('history?points=' + Math.max(100, Math.floor($('plots').clientWidth - 130))));
      document.body.dataset.plotScan = String(scan);
    } catch (e) { /* keep the last plot */ }
    histTimer = null;
    if (st.scan !== scan) historySoon();
  }, wait);
}

function niceStep(span, n) {
  const raw = span / n, p = Math.pow(10, Math.floor(Math.log10(raw || 1)));
  return [1, 2, 5, 10].map((m) => m * p).find((s) => s >= raw) || p * 10;
}

function drawPlot(hist) {
  const cv = $('plot'), t = hist.time_ms || [];
  const lanes = [];
  (model.inputs || []).forEach((x, i) => shown(x.name) && lanes.push({ name: x.name, v: (hist.inputs || [])[i], cls: 'in' }));
  (model.outputs || []).forEach((x, i) => shown(x.name) && lanes.push({ name: x.name, v: (hist.outputs || [])[i], cls: 'out' }));
  lanes.push({ name: 'fault', v: hist.faults, cls: 'fault' });
  const analog = ((model.plant || {}).analog || []).map((a, i) => ({ a, v: (hist.analog || [])[i] || [] }));
  const LH = 13, AH = 48, GUT = 118, W = $('plots').clientWidth || 600;
  const H = lanes.length * LH + analog.length * (AH + 14) + 26;
  const dpr = window.devicePixelRatio || 1;
  cv.width = W * dpr; cv.height = H * dpr; cv.style.width = W + 'px'; cv.style.height = H + 'px';
  const g = cv.getContext('2d');
  g.setTransform(dpr, 0, 0, dpr, 0, 0);
  g.clearRect(0, 0, W, H);
  g.font = '11px ui-monospace, Menlo, Consolas, monospace';
  g.textBaseline = 'middle';
  const css = getComputedStyle(document.body);
  const col = (v) => css.getPropertyValue(v).trim() || '#333';
  const t0 = t.length ? t[0] : 0, t1 = t.length > 1 ? t[t.length - 1] : t0 + 1000, span = Math.max(1, t1 - t0);
  const X = (ms) => GUT + ((ms - t0) / span) * (W - GUT - 8);
  $('plot-hint').textContent = t.length ? `${fmtTime(t0)} … ${fmtTime(t1)}, ${t.length} samples` : 'no scans yet';
  let y = 2;
  for (const ln of lanes) {
    g.fillStyle = col('--fg-dim');
    g.fillText(ln.name, 4, y + LH / 2);
    g.strokeStyle = col('--grid'); g.beginPath(); g.moveTo(GUT, y + LH - 1.5); g.lineTo(W - 8, y + LH - 1.5); g.stroke();
    g.fillStyle = col(ln.cls === 'fault' ? '--bad' : ln.cls === 'out' ? '--on' : '--in');
    const v = ln.v || [];
    for (let k = 0; k < v.length; k++) {
      if (!v[k]) continue;
      let e = k; while (e + 1 < v.length && v[e + 1]) e++;
      const xa = X(t[k]), xb = e + 1 < t.length ? X(t[e + 1]) : X(t[e]) + 2;
      g.fillRect(xa, y + 2, Math.max(1.5, xb - xa), LH - 4);
      k = e;
    }
    y += LH;
  }
  for (const { a, v } of analog) {
    y += 14;
    const lo = a.min, hi = a.max === a.min ? a.min + 1 : a.max;
    const Y = (x) => y + AH - ((Math.max(lo, Math.min(hi, x)) - lo) / (hi - lo)) * AH;
    g.fillStyle = col('--fg-dim');
    g.fillText(`${a.label || a.name}`, 4, y + 6);
    g.fillText(v.length ? `${Number(v[v.length - 1]).toFixed(1)} ${a.unit || ''}` : '', 4, y + 20);
    g.textAlign = 'right';
    for (const tick of [lo, (lo + hi) / 2, hi]) {
      g.fillText(String(+tick.toFixed(1)), GUT - 4, Y(tick));
      g.strokeStyle = col('--grid'); g.beginPath(); g.moveTo(GUT, Y(tick)); g.lineTo(W - 8, Y(tick)); g.stroke();
    }
    g.textAlign = 'left';
    g.strokeStyle = col('--analog'); g.lineWidth = 1.5; g.beginPath();
    v.forEach((x, k) => (k ? g.lineTo(X(t[k]), Y(x)) : g.moveTo(X(t[k]), Y(x))));
    g.stroke(); g.lineWidth = 1;
    y += AH;
  }
  g.fillStyle = col('--fg-dim'); g.strokeStyle = col('--grid');
  const step = niceStep(span, 8);
  g.textAlign = 'center';
  for (let ms = Math.ceil(t0 / step) * step; ms <= t1; ms += step) {
    g.beginPath(); g.moveTo(X(ms), 2); g.lineTo(X(ms), y + 3); g.stroke();
    if (X(ms) < W - 26) g.fillText((ms / 1000).toFixed(step < 1000 ? (step < 100 ? 2 : 1) : 0) + ' s', X(ms), y + 12);
  }
  g.textAlign = 'left';
}

// ---------- controls ----------

let running = false, runAcc = 0, runLast = 0, runFrom = [0, 0];
function setRunning(on) {
  running = on;
  $('run').disabled = on; $('pause').disabled = !on;
  $('run').classList.toggle('active', on);
  if (on) { runLast = performance.now(); runAcc = 0; runFrom = [runLast, st ? st.scan : 0]; setTimeout(runTick, 0); }
}

// Real-time pacing: the scans due since the last tick at the chosen speed.
async function runTick() {
  if (!running) return;
  if (busy) { setTimeout(runTick, 10); return; }
  const now = performance.now(), period = (model.project || {}).scan_period_ms || 10;
  runAcc += ((now - runLast) * Number($('speed').value)) / period;
  runLast = now;
  const n = Math.min(Math.floor(runAcc), 200000);
  runAcc = Math.min(runAcc - n, 1);
  if (n >= 1) {
    try { await act('step', { scans: n }); } catch (e) { setRunning(false); return; }
    const secs = (performance.now() - runFrom[0]) / 1000, speed = Number($('speed').value);
    if (secs > 0.5) $('perf').textContent = `running ×${speed}: ${fmtRate((st.scan - runFrom[1]) / secs)}scans/s measured by the page (target ${fmtRate((speed * 1000) / period)}scans/s)`;
  }
  setTimeout(runTick, 40);
}

async function fastForward() {
  const n = Math.max(1, Math.min(10000000, Math.floor(Number($('ffwd-n').value) || 100000)));
  setRunning(false);
  $('ffwd').disabled = true;
  $('perf').textContent = `fast-forwarding ${n.toLocaleString('en')} scans…`;
  const t = performance.now();
  try {
    const s = await act('run', { scans: n });
    const ms = performance.now() - t;
    const ran = s.ran != null ? s.ran : n;
    const server = s.elapsed_us ? ran / (s.elapsed_us / 1e6) : NaN;
    const page = ran / (ms / 1000);
    $('perf').textContent = `ran ${ran.toLocaleString('en')} scans: server ${isNaN(server) ? '?' : fmtRate(server)}scans/s (${((s.elapsed_us || 0) / 1000).toFixed(0)} ms), page ${fmtRate(page)}scans/s (${ms.toFixed(0)} ms round trip)`;
    Object.assign($('perf').dataset, { ran: ran, serverRate: isNaN(server) ? '' : server.toFixed(0), pageRate: page.toFixed(0) });
  } catch (e) { $('perf').textContent = ''; }
  $('ffwd').disabled = false;
}

// The name filter: lists, plot lanes and diagrams keep what matches.
let filter = '';
const shown = (name) => !filter || name.toLowerCase().includes(filter);
function applyFilter() {
  filter = $('filter').value.trim().toLowerCase();
  document.body.classList.toggle('filtering', !!filter);
  for (const el of document.querySelectorAll('[data-name]')) el.hidden = !shown(el.dataset.name);
  lastHist && drawPlot(lastHist);
}

function wire() {
  $('filter').addEventListener('input', applyFilter);
  $('step').onclick = () => act('step', { scans: 1 }).catch(() => {});
  $('run').onclick = () => setRunning(true);
  $('pause').onclick = () => setRunning(false);
  $('ffwd').onclick = fastForward;
  $('restart').onclick = () => { setRunning(false); act('restart', {}).catch(() => {}); };
  $('driver').onclick = () => act('driver', { driver: st && st.driver === 'random' ? 'none' : 'random' }).catch(() => {});
  document.addEventListener('keydown', (e) => {
    if (e.target.closest('input, select, textarea') || e.ctrlKey || e.metaKey || e.altKey) return;
    if (e.key === 's') $('step').click();
    else if (e.key === 'r') setRunning(!running);
  });
  let rt = null;
  window.addEventListener('resize', () => { clearTimeout(rt); rt = setTimeout(historySoon, 150); });
}

async function main() {
  wire();
  try {
    const [m, s] = await Promise.all([api('model'), api('state')]);
    model = m;
    build();
    render(s);
  } catch (e) {
    say('cannot load the simulation: ' + e.message, true);
  }
}
main();
