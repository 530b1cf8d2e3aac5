// The honeycomb editor's page: shows M, M', the walls and the node axes, sends drags to the
// server over a WebSocket and redraws every iterate it streams back.
import * as THREE from 'three';
import { OrbitControls } from '/vendor/OrbitControls.js';

const $ = (id) => document.getElementById(id);
const canvas = $('view');
const renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(window.devicePixelRatio);
const scene = new THREE.Scene();
scene.background = new THREE.Color(0xf4f4f1);
const camera = new THREE.PerspectiveCamera(40, 1, 0.01, 1e6);
const controls = new OrbitControls(camera, canvas);
scene.add(new THREE.HemisphereLight(0xffffff, 0x888877, 2.0));
const sun = new THREE.DirectionalLight(0xffffff, 1.2);
sun.position.set(1, 2, 3);
scene.add(sun);

// The page's state, also read by the end-to-end test.
const app = (window.honeycomb = {
  mesh: null, meshes: 0, lastState: null, states: 0, errors: [], warnings: [], connected: false, drags: 0,
  page: null, screenOf, axisTipNearCentre, download,
});

let objects = null; // the three.js objects of the current mesh
let stroke = 0;
let drag = null;

// --- connection -----------------------------------------------------------------------------
const socket = new WebSocket(`ws://${location.host}/ws`);
socket.onopen = () => { app.connected = true; };
socket.onclose = () => { app.connected = false; showError('connection to the server lost'); };
socket.onmessage = (event) => {
  const m = JSON.parse(event.data);
  if (m.type === 'hello') app.page = m.page;
  else if (m.type === 'mesh') buildMesh(m);
  else if (m.type === 'state') applyState(m);
  else if (m.type === 'error') showError(m.message);
  else if (m.type === 'warning') showWarning(m.message);
  else if (m.type === 'saved') setStatus(`saved to ${m.dir}`);
};
function send(message) {
  if (socket.readyState === WebSocket.OPEN) socket.send(JSON.stringify(message));
}
app.send = send;

function showError(message) {
  app.errors.push(message);
  if (drag) drag.sliding = false;
  const box = $('error');
  box.textContent = message;
  box.hidden = false;
  clearTimeout(showError.timer);
  showError.timer = setTimeout(() => { box.hidden = true; }, 8000);
}
// A warning stays until the next gesture: it is about the last one.
function showWarning(message) {
  app.warnings.push(message);
  const box = $('warning');
  box.textContent = message;
  box.hidden = false;
}
function setStatus(text) { $('status').textContent = text; }

// --- geometry -------------------------------------------------------------------------------
function buildMesh(m) {
  if (objects) for (const o of Object.values(objects)) if (o.isObject3D) { scene.remove(o); o.geometry.dispose(); }
  app.mesh = m;
  app.meshes += 1;
  $('source').textContent = m.source;
  $('variant-row').hidden = !m.variant;
  $('variant-name').textContent = m.variant ? m.variant.name : 'variant';
  $('variant').textContent = '-';
  $('variant-unit').textContent = m.variant ? variantUnit[m.variant.name.split(' ')[0]] : '';
  $('thickness_now').textContent = m.thickness.toPrecision(3);
  $('remake').hidden = m.remake.cells === null && !m.remake.thickness;
  $('cells-row').hidden = m.remake.cells === null;
  $('thickness-row').hidden = !m.remake.thickness;
  if (m.remake.cells !== null) $('cells').value = m.remake.cells;
  $('thickness').value = Number(m.thickness.toPrecision(3));
  $('sphere-caption').textContent = `Spherical image (seen along the mean axis): ${nvText(m.vertices)} `
    + `dots, one per node axis as a unit vector; ${nvText(m.faces.length)} polygons, one per cell, `
    + `joining its nodes' axes. Small polygons: nearly parallel axes.`;
  const nv = m.vertices;
  const surface = new THREE.BufferGeometry();
  surface.setAttribute('position', new THREE.Float32BufferAttribute(m.surface.vertices, 3));
  surface.setIndex(m.surface.triangles);
  surface.computeVertexNormals();
  const surfaceMesh = new THREE.Mesh(surface, new THREE.MeshLambertMaterial({
    color: 0xb9c4cc, transparent: true, opacity: 0.35, side: THREE.DoubleSide, depthWrite: false,
  }));

  // Walls: one quad (two triangles) per edge, corners v_a v_b v'_b v'_a, a colour per wall.
  const walls = new THREE.BufferGeometry();
  walls.setAttribute('position', new THREE.BufferAttribute(new Float32Array(m.edges.length * 4 * 3), 3));
  walls.setAttribute('color', new THREE.BufferAttribute(new Float32Array(m.edges.length * 4 * 3), 3));
  const index = [];
  m.edges.forEach((_, e) => { const k = 4 * e; index.push(k, k + 1, k + 2, k, k + 2, k + 3); });
  walls.setIndex(index);
  const wallMesh = new THREE.Mesh(walls, new THREE.MeshLambertMaterial({
    vertexColors: true, side: THREE.DoubleSide, transparent: true, opacity: 0.85,
  }));

  const lines = (count, color) => {
    const g = new THREE.BufferGeometry();
    g.setAttribute('position', new THREE.BufferAttribute(new Float32Array(count * 2 * 3), 3));
    return new THREE.LineSegments(g, new THREE.LineBasicMaterial({ color }));
  };
  const base = lines(m.edges.length, 0x1b3a5c);
  const offset = lines(m.edges.length, 0x5c3a1b);
  const axes = lines(nv, 0x2a7a2a);
  const points = (color, size) => {
    const g = new THREE.BufferGeometry();
    g.setAttribute('position', new THREE.BufferAttribute(new Float32Array(nv * 3), 3));
    return new THREE.Points(g, new THREE.PointsMaterial({ color, size, sizeAttenuation: false }));
  };
  const handles = points(0x1b3a5c, 4);
  const tips = points(0x2a7a2a, 5);
  const picked = points(0xff2020, 10);
  picked.geometry.setDrawRange(0, 0);
  // Quads: the diagonal that splits each cell, from a quad's last corner to its first.
  const quads = (m.variant && m.variant.quads) || [];
  const diagonals = lines(quads.length, 0x9a2a8a);
  objects = { surfaceMesh, wallMesh, base, offset, axes, handles, tips, picked, diagonals };
  for (const o of Object.values(objects)) scene.add(o);
  objects.framed = false;
  sphereImage.build(m.faces, nv);
  redraw();
}

// The unit of each variant's row, by the first word of its name, until its first measure.
const variantUnit = { quads: 'delta_face max / avg', parallel: 'deg, beta max / avg', shading: 'light share' };

// What an edit left of the variant: the row's value and its unit, which says what it is.
function variantCells(w, f) {
  if (w.variant === 'quads') {
    return [`${f(w.delta_face_max)} / ${f(w.delta_face_avg)}`, `delta_face max / avg, ${w.quads} quads`];
  }
  if (w.variant === 'parallel') return [`${f(w.beta_max_deg)} / ${f(w.beta_avg_deg)}`, variantUnit.parallel];
  const share = (c) => `${c.before.toFixed(3)} -> ${c.after.toFixed(3)}`;
  const path = w.sun_path_mean ? `; the day's mean ${share(w.sun_path_mean)}` : '';
  return [share(w.light), `light share, along S's normals -> these walls (half asked)${path}`];
}

function applyState(s) {
  if (!objects) return;
  app.lastState = s;
  app.states += 1;
  app.lastStateAt = performance.now();
  const m = app.mesh;
  const set = (attr, values) => { attr.array.set(values); attr.needsUpdate = true; };
  const B = s.base, O = s.offset;
  const wallPos = objects.wallMesh.geometry.attributes.position;
  const wallCol = objects.wallMesh.geometry.attributes.color;
  const basePos = objects.base.geometry.attributes.position;
  const offPos = objects.offset.geometry.attributes.position;
  const by = document.querySelector('input[name=colour]:checked').value;
  const colour = new THREE.Color();
  m.edges.forEach(([a, b], e) => {
    const corners = [[B, a], [B, b], [O, b], [O, a]];
    corners.forEach(([P, v], k) => wallPos.array.set([P[3 * v], P[3 * v + 1], P[3 * v + 2]], 12 * e + 3 * k));
    basePos.array.set([B[3 * a], B[3 * a + 1], B[3 * a + 2], B[3 * b], B[3 * b + 1], B[3 * b + 2]], 6 * e);
    offPos.array.set([O[3 * a], O[3 * a + 1], O[3 * a + 2], O[3 * b], O[3 * b + 1], O[3 * b + 2]], 6 * e);
    if (by === 'axis') {
      lean(Math.max(s.axis[a], s.axis[b]), colour);
    } else {
      const value = by === 'omega' ? Math.max(s.omega[a], s.omega[b]) : s.delta[e];
      heat(value, by === 'omega' ? 0.05 : 1e-3, colour);
    }
    for (let k = 0; k < 4; k++) wallCol.array.set([colour.r, colour.g, colour.b], 12 * e + 3 * k);
  });
  wallPos.needsUpdate = wallCol.needsUpdate = basePos.needsUpdate = offPos.needsUpdate = true;
  objects.wallMesh.geometry.computeVertexNormals();
  const axisPos = objects.axes.geometry.attributes.position;
  for (let v = 0; v < m.vertices; v++) {
    axisPos.array.set([B[3 * v], B[3 * v + 1], B[3 * v + 2], O[3 * v], O[3 * v + 1], O[3 * v + 2]], 6 * v);
  }
  axisPos.needsUpdate = true;
  const quads = (m.variant && m.variant.quads) || [];
  const diagonalPos = objects.diagonals.geometry.attributes.position;
  quads.forEach((q, k) => {
    const [a, d] = [q[3], q[0]];
    diagonalPos.array.set([B[3 * a], B[3 * a + 1], B[3 * a + 2], B[3 * d], B[3 * d + 1], B[3 * d + 2]], 6 * k);
  });
  diagonalPos.needsUpdate = true;
  if (quads.length) objects.diagonals.geometry.computeBoundingSphere();
  set(objects.handles.geometry.attributes.position, B);
  set(objects.tips.geometry.attributes.position, O);
  for (const o of ['base', 'offset', 'axes', 'handles', 'tips']) objects[o].geometry.computeBoundingSphere();
  objects.wallMesh.geometry.computeBoundingSphere();
  if (!objects.framed) frame();
  if (drag) markPicked(drag);
  slid(s);

  const f = (x, d = 3) => (x < 1e-3 && x > 0 ? x.toExponential(2) : x.toFixed(d));
  const ms = s.measures;
  $('iteration').textContent = s.iteration;
  $('omega_max').textContent = f(ms.omega_max_deg, 4);
  $('omega_avg').textContent = f(ms.omega_avg_deg, 4);
  $('delta_max').textContent = f(ms.delta_max);
  $('delta_avg').textContent = f(ms.delta_avg);
  $('closeness_max').textContent = f(ms.closeness_max);
  $('closeness_avg').textContent = f(ms.closeness_avg);
  $('axis_mean').textContent = ms.axis_normal_mean_deg.toFixed(2);
  $('axis_max').textContent = ms.axis_normal_max_deg.toFixed(2);
  $('edge_length').textContent = ms.mean_edge_length.toPrecision(3);
  $('step_ms').textContent = s.step_ms.toFixed(1);
  $('edit_ms').textContent = s.edit_ms.toFixed(1);
  // A variant is measured once an edit's solve has ended; in between the last figure stays.
  if (s.variant) [$('variant').textContent, $('variant-unit').textContent] = variantCells(s.variant, f);
  setStatus(s.done ? 'ready' : 'solving...');
  // Each page undoes only its own gestures: a new page has none, whatever the others did.
  $('undo').disabled = s.undo_page === null || s.undo_page !== app.page;
  $('redo').disabled = s.redo_page === null || s.redo_page !== app.page;
  sphereImage.update(B, O);
  redraw();
}

// Blue (0) over green and yellow to red (at `scale` and above), on a log scale from scale/1e4.
// An axis's angle to S's normal: blue (along it) over green to red (45 degrees and more).
function lean(degrees, out) {
  const t = Math.min(1, Math.max(0, degrees / 45));
  out.setHSL((1 - t) * 0.66, 0.75, 0.5);
}

function heat(value, scale, out) {
  const t = Math.min(1, Math.max(0, Math.log10(Math.max(value, 1e-30) / scale) / 4 + 1));
  out.setHSL((1 - t) * 0.66, 0.75, 0.5);
}

function nvText(n) { return n.toLocaleString('en'); }

// The legend of the wall colours: the same scales as heat() and lean().
const scales = {
  omega: { title: 'walls: omega, the largest error from 120 deg of a node angle at the wall (deg, log scale)',
    ticks: ['5e-6', '5e-5', '5e-4', '0.005', '0.05+'] },
  delta: { title: 'walls: delta, a wall\'s diagonals apart, in edge lengths (planarity; log scale)',
    ticks: ['1e-7', '1e-6', '1e-5', '1e-4', '0.001+'] },
  axis: { title: 'walls: the larger angle of its node axes to S\'s normal (deg)',
    ticks: ['0', '11', '22', '34', '45+'] },
};
function legend() {
  const by = document.querySelector('input[name=colour]:checked').value;
  const stops = [0, 0.25, 0.5, 0.75, 1].map((t) => `hsl(${Math.round((1 - t) * 0.66 * 360)}, 75%, 50%)`);
  $('legend-title').textContent = scales[by].title;
  $('legend-bar').style.background = `linear-gradient(to right, ${stops.join(', ')})`;
  $('legend-ticks').replaceChildren(...scales[by].ticks.map((t) => {
    const span = document.createElement('span');
    span.textContent = t;
    return span;
  }));
}
legend();

function frame() {
  const sphere = objects.wallMesh.geometry.boundingSphere;
  controls.target.copy(sphere.center);
  camera.position.copy(sphere.center).add(new THREE.Vector3(0.4, -1.2, 1.0).normalize().multiplyScalar(3.4 * sphere.radius));
  camera.up.set(0, 0, 1);
  camera.near = sphere.radius / 100;
  camera.far = sphere.radius * 100;
  camera.updateProjectionMatrix();
  controls.update();
  objects.framed = true;
}

// --- picking and dragging -------------------------------------------------------------------
const raycaster = new THREE.Raycaster();
function pointer(event) {
  const r = canvas.getBoundingClientRect();
  return new THREE.Vector2(((event.clientX - r.left) / r.width) * 2 - 1, -((event.clientY - r.top) / r.height) * 2 + 1);
}
function mode() { return document.querySelector('input[name=mode]:checked').value; }
function point(flat, v) { return new THREE.Vector3(flat[3 * v], flat[3 * v + 1], flat[3 * v + 2]); }

// The vertex (or axis tip) under the pointer: the nearest in screen space within 12 pixels.
function pick(event, tips) {
  if (!app.lastState) return null;
  let best = null, bestD = 12;
  for (let v = 0; v < app.mesh.vertices; v++) {
    const p = screenOf(v, tips);
    const d = Math.hypot(p.x - event.clientX, p.y - event.clientY);
    if (d < bestD) { bestD = d; best = v; }
  }
  return best;
}

// Page coordinates of a vertex of M (or of M' with `tips`).
function screenOf(v, tips = false) {
  const s = app.lastState;
  const p = point(tips ? s.offset : s.base, v).project(camera);
  const r = canvas.getBoundingClientRect();
  return { x: r.left + (p.x + 1) / 2 * r.width, y: r.top + (1 - p.y) / 2 * r.height };
}

// For the test: the axis tip of the vertex closest to the middle of M.
function axisTipNearCentre() {
  const s = app.lastState, n = app.mesh.vertices;
  const c = new THREE.Vector3();
  for (let v = 0; v < n; v++) c.add(point(s.base, v));
  c.divideScalar(n);
  let best = 0;
  for (let v = 1; v < n; v++) if (point(s.base, v).distanceTo(c) < point(s.base, best).distanceTo(c)) best = v;
  return { vertex: best, ...screenOf(best, true) };
}

function markPicked(d) {
  const g = objects.picked.geometry;
  g.attributes.position.array.set(point(d.tips ? app.lastState.offset : app.lastState.base, d.vertex).toArray(), 0);
  g.attributes.position.needsUpdate = true;
  g.setDrawRange(0, 1);
  g.computeBoundingSphere();
  redraw();
}

canvas.addEventListener('pointerdown', (event) => {
  if (!app.lastState || event.button !== 0) return;
  const m = mode();
  const tips = m === 'axis';
  const vertex = pick(event, tips);
  if (vertex === null) return;
  $('warning').hidden = true;
  controls.enabled = false;
  canvas.setPointerCapture(event.pointerId);
  stroke += 1;
  const s = app.lastState;
  const anchor = point(tips ? s.offset : s.base, vertex);
  // The drag plane: through the picked point, facing the camera.
  const normal = camera.getWorldDirection(new THREE.Vector3());
  drag = {
    vertex, tips, mode: m, stroke, anchor,
    plane: new THREE.Plane().setFromNormalAndCoplanarPoint(normal, anchor),
    base: point(s.base, vertex), axis: point(s.offset, vertex).sub(point(s.base, vertex)).normalize(),
    slid: 0, wanted: 0, sliding: false, pending: null,
  };
  markPicked(drag);
  app.drags += 1;
});

canvas.addEventListener('pointermove', (event) => {
  if (!drag) return;
  raycaster.setFromCamera(pointer(event), camera);
  const hit = new THREE.Vector3();
  if (drag.mode === 'vertex') {
    const onSurface = raycaster.intersectObject(objects.surfaceMesh)[0];
    const target = onSurface ? onSurface.point : raycaster.ray.intersectPlane(drag.plane, hit);
    if (target) queue({ type: 'drag_vertex', vertex: drag.vertex, target: target.toArray(), radius: radius(), stroke: drag.stroke });
  } else if (drag.mode === 'axis') {
    if (!raycaster.ray.intersectPlane(drag.plane, hit)) return;
    // The axis turns as if it were a lever thirty edges long: an axis is short on screen, and
    // a turn of a few degrees is what a designer usually wants (a few pixels per degree
    // with the whole model in view).
    const lever = 30 * app.lastState.measures.mean_edge_length;
    const shift = hit.sub(drag.anchor);
    shift.addScaledVector(drag.axis, -shift.dot(drag.axis));
    const direction = drag.axis.clone().multiplyScalar(lever).add(shift);
    queue({ type: 'drag_axis', vertex: drag.vertex, direction: direction.toArray(), radius: radius(), stroke: drag.stroke });
  } else {
    // Slide: the point of the axis line closest to the pointer's ray.
    const along = new THREE.Vector3();
    raycaster.ray.distanceSqToSegment(
      drag.base.clone().addScaledVector(drag.axis, -1e3), drag.base.clone().addScaledVector(drag.axis, 1e3), null, along);
    const t = along.sub(drag.base).dot(drag.axis);
    drag.wanted = t;
    slide();
  }
});

// A slide is sent as a step from where the vertex stands, one at a time: the server may stop
// it short (off S, or at M'), and steps counted from the pointer alone would then carry the
// vertex back before the pointer came back.
function slide() {
  if (drag.sliding || drag.wanted === drag.slid) return;
  drag.sliding = true;
  drag.sent = drag.wanted;
  send({ type: 'slide', vertex: drag.vertex, distance: drag.wanted - drag.slid, stroke: drag.stroke });
}
function slid(s) {
  if (!drag || drag.mode !== 'slide' || !drag.sliding || s.stroke !== drag.stroke) return;
  drag.slid = point(s.base, drag.vertex).sub(drag.base).dot(drag.axis);
  drag.sliding = false;
  // Nothing more unless the pointer moved on: a stopped slide is not asked again.
  if (drag.wanted !== drag.sent) slide();
  else drag.wanted = drag.slid;
}

// One drag message per frame at most: the server replaces a stale one anyway.
function queue(message) {
  if (!drag.pending) requestAnimationFrame(() => { if (drag && drag.pending) { send(drag.pending); drag.pending = null; } });
  drag.pending = message;
}

function endDrag() {
  if (!drag) return;
  if (drag.pending) send(drag.pending);
  drag = null;
  controls.enabled = true;
  objects.picked.geometry.setDrawRange(0, 0);
  redraw();
}
canvas.addEventListener('pointerup', endDrag);
canvas.addEventListener('pointercancel', endDrag);

function radius() { return Number($('radius').value); }
$('radius').addEventListener('input', () => { $('radius-value').textContent = radius(); });
$('undo').onclick = () => send({ type: 'undo' });
$('redo').onclick = () => send({ type: 'redo' });
$('cancel').onclick = () => send({ type: 'cancel' });
$('save').onclick = () => send({ type: 'save', name: $('save-name').value });
$('load').onclick = () => send({ type: 'load', name: $('save-name').value });
for (const r of document.querySelectorAll('input[name=colour]')) {
  r.onchange = () => { legend(); if (app.lastState) applyState(app.lastState); };
}
$('remake-go').onclick = () => {
  const m = app.mesh, message = { type: 'remake' };
  if (m.remake.cells !== null && Number($('cells').value) !== m.remake.cells) message.cells = Number($('cells').value);
  if (m.remake.thickness && Number($('thickness').value) !== Number(m.thickness.toPrecision(3))) {
    message.thickness = Number($('thickness').value);
  }
  setStatus('making again...');
  send(message);
};
// A download is made by the server from the current state; a refusal (not a honeycomb) is
// shown as an error instead of being saved as the file.
async function download(file) {
  const r = await fetch(`/download/${file}?units=${$('units').value}`);
  if (!r.ok) {
    showError(`download ${file}: ${await r.text()}`);
    return { ok: false, status: r.status };
  }
  const blob = await r.blob();
  const a = document.createElement('a');
  a.href = URL.createObjectURL(blob);
  a.download = file;
  a.click();
  setTimeout(() => URL.revokeObjectURL(a.href), 10000);
  return { ok: true, status: r.status, bytes: blob.size, type: r.headers.get('content-type') };
}
for (const b of document.querySelectorAll('#downloads button')) b.onclick = () => download(b.dataset.file);
window.addEventListener('keydown', (e) => {
  if (!(e.ctrlKey || e.metaKey) || e.target.tagName === 'INPUT' && e.target.type !== 'radio') return;
  if (e.key === 'z') send({ type: 'undo' });
  if (e.key === 'y') send({ type: 'redo' });
});

// --- spherical image inset: node axes on the unit sphere, a polygon per cell -----------------
const sphereImage = (() => {
  const canvas2 = $('sphere');
  const r2 = new THREE.WebGLRenderer({ canvas: canvas2, antialias: true });
  r2.setPixelRatio(window.devicePixelRatio);
  const s2 = new THREE.Scene();
  s2.background = new THREE.Color(0xffffff);
  const cam = new THREE.PerspectiveCamera(30, 1, 0.1, 100);
  cam.position.set(0, 0, 4.2);
  s2.add(new THREE.Mesh(new THREE.SphereGeometry(0.995, 32, 16), new THREE.MeshBasicMaterial({ color: 0xe8ecef, wireframe: true })));
  let cells = null, dots = null, faces = [];
  return {
    build(f, nv) {
      faces = f;
      if (cells) { s2.remove(cells); s2.remove(dots); }
      const count = f.reduce((n, face) => n + face.length, 0);
      const g = new THREE.BufferGeometry();
      g.setAttribute('position', new THREE.BufferAttribute(new Float32Array(count * 2 * 3), 3));
      cells = new THREE.LineSegments(g, new THREE.LineBasicMaterial({ color: 0x1b3a5c }));
      const d = new THREE.BufferGeometry();
      d.setAttribute('position', new THREE.BufferAttribute(new Float32Array(nv * 3), 3));
      dots = new THREE.Points(d, new THREE.PointsMaterial({ color: 0x2a7a2a, size: 2, sizeAttenuation: false }));
      s2.add(cells, dots);
    },
    update(B, O) {
      const n = O.length / 3;
      const axis = (v) => new THREE.Vector3(O[3 * v] - B[3 * v], O[3 * v + 1] - B[3 * v + 1], O[3 * v + 2] - B[3 * v + 2]).normalize();
      const mean = new THREE.Vector3();
      const axes = [];
      for (let v = 0; v < n; v++) { axes.push(axis(v)); mean.add(axes[v]); }
      // Look at the image from the mean axis, close enough that it fills the inset.
      mean.normalize();
      const spread = axes.reduce((m, a) => Math.max(m, a.distanceTo(mean)), 0.02);
      cam.position.copy(mean).multiplyScalar(Math.min(4.2, Math.max(1.15, 1 + 1.3 * spread / 0.268)));
      cam.up.set(0, 0, 1);
      if (Math.abs(mean.z) > 0.99) cam.up.set(0, 1, 0);
      cam.lookAt(0, 0, 0);
      const d = dots.geometry.attributes.position;
      axes.forEach((a, v) => d.array.set(a.toArray(), 3 * v));
      d.needsUpdate = true;
      const c = cells.geometry.attributes.position;
      let k = 0;
      for (const face of faces) {
        for (let i = 0; i < face.length; i++) {
          c.array.set(axes[face[i]].toArray(), k); k += 3;
          c.array.set(axes[face[(i + 1) % face.length]].toArray(), k); k += 3;
        }
      }
      c.needsUpdate = true;
      dots.geometry.computeBoundingSphere();
      cells.geometry.computeBoundingSphere();
    },
    render() {
      const w = canvas2.clientWidth, h = canvas2.clientHeight;
      if (canvas2.width !== Math.floor(w * window.devicePixelRatio)) r2.setSize(w, h, false);
      r2.render(s2, cam);
    },
  };
})();

// --- render loop ----------------------------------------------------------------------------
function resize() {
  const w = canvas.clientWidth, h = canvas.clientHeight;
  if (canvas.width !== Math.floor(w * window.devicePixelRatio) || canvas.height !== Math.floor(h * window.devicePixelRatio)) {
    renderer.setSize(w, h, false);
    camera.aspect = w / h;
    camera.updateProjectionMatrix();
  }
}
// Draw only when something changed (a state, the camera, the window): an idle page costs
// nothing, and a software-rendered one (headless tests) keeps its main thread free.
let dirty = true;
function redraw() { dirty = true; }
controls.addEventListener('change', redraw);
window.addEventListener('resize', redraw);
renderer.setAnimationLoop(() => {
  resize();
  controls.update();
  if (!dirty) return;
  dirty = false;
  renderer.render(scene, camera);
  sphereImage.render();
});
