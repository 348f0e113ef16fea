// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// The report page: reads the element `viewer-data` written by write_html_report(), draws the
// mesh with its border and non-manifold edges and the markers, and fills the side panel (the
// before/after table, the tolerance, the gap histogram, the marker switches, and the open
// problems: the holes and the ambiguous sites, a click flying the camera there).
// Sets `data-ready="true"` on <body> once the first frame is drawn.

const marker_kinds = [
  { key: 'welded_vertices', label: 'welded vertices', color: 0x33cc66 },
  { key: 't_junction_splits', label: 'T-junction splits', color: 0x33ccff },
  { key: 'refused_welds', label: 'refused welds', color: 0xff8800 },
  { key: 'refused_splits', label: 'refused splits', color: 0xcc66ff },
  { key: 'ambiguous_sites', label: 'ambiguous sites (below the tolerance)', color: 0xffee00 },
];

function decode_base64(text, ArrayType) {
  const binary = atob(text);
  const bytes = new Uint8Array(binary.length);
  for (let i = 0; i < binary.length; ++i) bytes[i] = binary.charCodeAt(i);
  return new ArrayType(bytes.buffer);
}

function element(tag, attributes, text) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attributes || {})) e.setAttribute(k, v);
  if (text !== undefined) e.textContent = text;
  return e;
}

function plural(n, noun) {
  return `${n.toLocaleString()} ${noun}${n === 1 ? '' : 's'}`;
}

function format_length(x) {
  if (x === null || x === undefined) return '-';
  if (x === 0) return '0';
  return Number(x).toPrecision(3);
}

const data = JSON.parse(document.getElementById('viewer-data').textContent);
// The view draws a point p of the soup at (p - origin) * 2^view_exponent (a unit that keeps the
// digits of float coordinates at any scale); lengths shown in the panel are in the soup's unit.
const view_exponent = data.view_exponent || 0;
function times_power_of_two(x, e) {
  const half = Math.trunc(e / 2);
  return x * 2 ** half * 2 ** (e - half);
}
const to_view_length = (x) => times_power_of_two(x, view_exponent);
const to_soup_coordinate = (x, axis) => times_power_of_two(x, -view_exponent) + data.origin[axis];
const canvas = document.getElementById('view');
const panel = document.getElementById('panel');

// The scene.
const renderer = new THREE.WebGLRenderer({ canvas, antialias: false });
renderer.setPixelRatio(1);
const scene = new THREE.Scene();
scene.background = new THREE.Color(0x22262b);
const camera = new THREE.PerspectiveCamera(40, 1, 0.01, 1000);
scene.add(new THREE.AmbientLight(0xffffff, 0.55));
const headlight = new THREE.DirectionalLight(0xffffff, 1.6);
camera.add(headlight);
scene.add(camera);

const positions = decode_base64(data.positions, Float32Array);
const mesh_geometry = new THREE.BufferGeometry();
const position_attribute = new THREE.BufferAttribute(positions, 3);
mesh_geometry.setAttribute('position', position_attribute);
mesh_geometry.setIndex(new THREE.BufferAttribute(decode_base64(data.triangles, Uint32Array), 1));
mesh_geometry.computeBoundingSphere();
const mesh = new THREE.Mesh(mesh_geometry, new THREE.MeshPhongMaterial({
  color: 0xa9bccf, flatShading: true, side: THREE.DoubleSide,
  polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1,
}));
scene.add(mesh);

function edge_lines(base64, color) {
  const indices = decode_base64(base64, Uint32Array);
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', position_attribute);
  geometry.setIndex(new THREE.BufferAttribute(indices, 1));
  const lines = new THREE.LineSegments(geometry, new THREE.LineBasicMaterial({ color }));
  scene.add(lines);
  return lines;
}
edge_lines(data.border_edges, 0xff0000);
edge_lines(data.non_manifold_edges, 0xff00ff);

const marker_objects = {};
for (const kind of marker_kinds) {
  const points = data.markers[kind.key] || [];
  if (points.length === 0) continue;
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array(points.flat()), 3));
  const object = new THREE.Points(geometry, new THREE.PointsMaterial({ color: kind.color, size: 7, sizeAttenuation: false, depthTest: false }));
  object.renderOrder = 2;
  scene.add(object);
  marker_objects[kind.key] = object;
}

// Drawing on demand: one frame per change.
let frame_requested = false;
function draw() {
  frame_requested = false;
  renderer.render(scene, camera);
  if (document.body.dataset.ready !== 'true') {
    requestAnimationFrame(() => { document.body.dataset.ready = 'true'; });
  }
}
function request_draw() {
  if (frame_requested) return;
  frame_requested = true;
  requestAnimationFrame(draw);
}
function resize() {
  const width = canvas.clientWidth, height = canvas.clientHeight;
  renderer.setSize(width, height, false);
  camera.aspect = width / Math.max(height, 1);
  camera.updateProjectionMatrix();
  request_draw();
}

const controls = new Orbit_controls(camera, canvas, request_draw);
const sphere = mesh_geometry.boundingSphere;
const whole_distance = (sphere && sphere.radius > 0 ? sphere.radius : 1) / Math.sin((camera.fov * Math.PI) / 360);

// Flies the camera to look at `center` (relative coordinates) from `distance`.
let flight = null;
function fly_to(center, distance) {
  const start_target = controls.target.clone();
  const start_distance = controls.distance;
  const goal = new THREE.Vector3(center[0], center[1], center[2]);
  const start = performance.now();
  if (flight) cancelAnimationFrame(flight);
  const step = (now) => {
    const s = Math.min(1, (now - start) / 700);
    const t = s * s * (3 - 2 * s);
    controls.target.lerpVectors(start_target, goal, t);
    controls.distance = Math.exp(Math.log(start_distance) * (1 - t) + Math.log(distance) * t);
    controls.update();
    flight = s < 1 ? requestAnimationFrame(step) : null;
  };
  flight = requestAnimationFrame(step);
}

// The panel.
panel.append(element('h1', {}, data.title));
if (data.decimated) {
  panel.append(element('p', { class: 'note' }, `Shown simplified: ${data.displayed_triangles.toLocaleString()} of ` +
    `${data.soup_triangles.toLocaleString()} triangles (above ${data.display_triangle_limit.toLocaleString()}); ` +
    'border and non-manifold areas at full resolution.'));
}
for (const note of data.notes) panel.append(element('p', { class: 'note' }, note));

panel.append(element('h2', {}, 'Before and after'));
const table = element('table', { id: 'before-after' });
const head = element('tr');
for (const h of data.table_header) head.append(element('th', {}, h));
table.append(head);
for (const row of data.table) {
  const tr = element('tr');
  for (const cell of row) tr.append(element('td', {}, cell));
  table.append(tr);
}
panel.append(table);
panel.append(element('p', { id: 'tolerance' }, `Tolerance: ${format_length(data.tolerance)}`));

// The gap histogram: log-scaled lengths, bars below the tolerance (closed) in green.
function draw_histogram(bins, tolerance) {
  const width = 320, height = 130, left = 34, bottom = 22;
  const svg = document.createElementNS('http:\/\/www.w3.org/2000/svg', 'svg');
  svg.setAttribute('width', width); svg.setAttribute('height', height); svg.setAttribute('id', 'gap-histogram');
  const add = (tag, attributes, text) => {
    const e = document.createElementNS(svg.namespaceURI, tag);
    for (const [k, v] of Object.entries(attributes)) e.setAttribute(k, v);
    if (text !== undefined) e.textContent = text;
    svg.append(e);
  };
  const lo = Math.log10(bins[0].lower), hi = Math.log10(bins[bins.length - 1].upper);
  const x = (value) => left + ((Math.log10(value) - lo) / (hi - lo)) * (width - left - 6);
  const top_count = Math.max(...bins.map((b) => b.count));
  const y = (count) => (height - bottom) - (Math.log10(1 + count) / Math.log10(1 + top_count)) * (height - bottom - 8);
  for (const b of bins) {
    if (b.count === 0) continue;
    const closed = tolerance > 0 && b.upper <= tolerance * 1.0000001;
    add('rect', { x: x(b.lower) + 0.5, y: y(b.count), width: Math.max(1, x(b.upper) - x(b.lower) - 1),
      height: (height - bottom) - y(b.count), fill: closed ? '#33cc66' : '#7f9fbf' }, undefined);
  }
  add('line', { x1: left, y1: height - bottom, x2: width - 6, y2: height - bottom, stroke: '#ccc' });
  if (Math.floor(hi) - Math.ceil(lo) >= 1) {
    for (let d = Math.ceil(lo); d <= Math.floor(hi); ++d) {
      const anchor = x(10 ** d) > width - 20 ? 'end' : 'middle';
      add('text', { x: x(10 ** d), y: height - 6, fill: '#ccc', 'font-size': 10, 'text-anchor': anchor }, `1e${d}`);
    }
  } else {
    add('text', { x: left, y: height - 6, fill: '#ccc', 'font-size': 10 }, format_length(bins[0].lower));
    add('text', { x: width - 6, y: height - 6, fill: '#ccc', 'font-size': 10, 'text-anchor': 'end' },
      format_length(bins[bins.length - 1].upper));
  }
  add('text', { x: 2, y: 12, fill: '#ccc', 'font-size': 10 }, `${top_count}`);
  if (tolerance > 0 && Math.log10(tolerance) >= lo - 1 && Math.log10(tolerance) <= hi + 1) {
    const tx = Math.min(width - 6, Math.max(left, x(tolerance)));
    add('line', { x1: tx, y1: 4, x2: tx, y2: height - bottom, stroke: '#ffcc00', 'stroke-width': 2, id: 'tolerance-line' });
    add('text', { x: Math.min(tx + 3, width - 60), y: 12, fill: '#ffcc00', 'font-size': 10 }, 'tolerance');
  }
  return svg;
}
panel.append(element('h2', {}, 'Gaps of the input'));
if (data.gap_histogram.length > 0) {
  panel.append(draw_histogram(data.gap_histogram, data.tolerance));
  panel.append(element('p', { class: 'note' }, 'Per border vertex of the input, the distance to the nearest other part ' +
    'of the border (log scale); green bars lie below the tolerance.'));
} else {
  panel.append(element('p', { class: 'note' }, data.gap_note));
}

panel.append(element('h2', {}, 'Markers'));
for (const kind of marker_kinds) {
  const count = data.marker_counts[kind.key];
  const shown = (data.markers[kind.key] || []).length;
  const label = element('label', { class: 'marker-kind' });
  const box = element('input', { type: 'checkbox', 'data-kind': kind.key });
  box.checked = shown > 0;
  box.disabled = shown === 0;
  box.addEventListener('change', () => { marker_objects[kind.key].visible = box.checked; request_draw(); });
  const swatch = element('span', { class: 'swatch', style: `background:#${kind.color.toString(16).padStart(6, '0')}` });
  let where = '';
  if (count && shown === 0) where = ' (positions not recorded)';
  else if (shown !== count) where = ` at ${shown} places`;
  label.append(box, swatch, `${kind.label}: ${count === null ? '-' : count}${where}`);
  panel.append(label);
}

// The open problems: the holes (longest first), then the ambiguous sites; a click flies there.
function open_problems() {
  const listed_sites = 500;
  const holes = data.holes.map((h) => ({
    kind: 'hole', center: h.center, radius: h.radius,
    text: `hole: ${h.edges} border edges, length ${format_length(h.length)}, size ${format_length(h.size)}`,
  }));
  const sites = (data.markers.ambiguous_sites || []).slice(0, listed_sites).map((p) => ({
    kind: 'ambiguous', center: p, radius: data.tolerance ? to_view_length(data.tolerance) : whole_distance / 1000,
    text: `ambiguous site at ${p.map((c, i) => format_length(to_soup_coordinate(c, i))).join(', ')}`,
  }));
  panel.append(element('h2', {}, 'Open problems'));
  const site_count = data.marker_counts.ambiguous_sites;
  panel.append(element('p', { class: 'note', id: 'open-problem-counts' },
    `${data.holes_total === 0 ? 'No border edge: the mesh is closed' : plural(data.holes_total, 'hole')}; ` +
    `${site_count ? plural(site_count, 'ambiguous site') : 'no ambiguous site'}` +
    (site_count && sites.length === 0 ? ' (positions not recorded)' : '') + '.'));
  if (holes.length + sites.length === 0) return;
  const list = element('ol', { class: 'problems', id: 'open-problems' });
  for (const item of holes.concat(sites)) {
    const li = element('li', { 'data-kind': item.kind }, item.text);
    if (item.kind === 'ambiguous') li.style.color = '#ffee00';
    li.addEventListener('click', () => fly_to(item.center, Math.max(item.radius * 4, whole_distance / 200)));
    list.append(li);
  }
  panel.append(list);
  const unlisted = (data.holes_total - holes.length) + Math.max(0, (data.markers.ambiguous_sites || []).length - sites.length);
  if (unlisted > 0) panel.append(element('p', { class: 'note' }, `${unlisted} more not listed`));
}
open_problems();

window.addEventListener('resize', resize);
controls.look_at(sphere ? sphere.center : new THREE.Vector3(), whole_distance * 1.1);
resize();
