// The report's 3D viewer (docs/report.md), bundled with three.js at build time (viewer.cmake).
// A dense cylinder follows the centreline; its vertices sit at the coarse map cells and are
// pushed out by the displacement; the report's texture picture is its texture. Orbit and
// fly-through cameras; a click reads station, clock and radius (raycast).
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

const data = JSON.parse(document.getElementById('viewer-data').textContent);
const canvas = document.getElementById('viewer-canvas');
const readout = document.getElementById('viewer-readout');
const slider = document.getElementById('viewer-station');
const sliderText = document.getElementById('viewer-station-text');
const textureImage = document.querySelector('#maps .mapview img');
const nr = data.rows, nc = data.clocks, R = data.radius_mm;
const tex = data.texture;
const s0 = data.stations_mm[0], s1 = data.stations_mm[nr - 1];

const displacement = (() => {  // int16 0.01 mm, −32768 none → Float32 mm, NaN none
  const bytes = Uint8Array.from(atob(data.displacement_b64), (c) => c.charCodeAt(0));
  const raw = new Int16Array(bytes.buffer);
  return Float32Array.from(raw, (v) => (v === -32768 ? NaN : v / 100));
})();

const vec = (i, k) => new THREE.Vector3(data.frames[9 * i + 3 * k], data.frames[9 * i + 3 * k + 1],
                                       data.frames[9 * i + 3 * k + 2]);
const frames = data.stations_mm.map((_, i) => ({ origin: vec(i, 0), crown: vec(i, 1), right: vec(i, 2) }));

// The frame at a station, linear between the rows' frames.
function frameAt(station) {
  const t = Math.min(Math.max((station - s0) / Math.max(s1 - s0, 1e-9), 0), 1) * (nr - 1);
  const i = Math.min(Math.floor(t), Math.max(nr - 2, 0)), w = t - i, j = Math.min(i + 1, nr - 1);
  const mix = (a, b) => a.clone().lerp(b, w);
  const f = { origin: mix(frames[i].origin, frames[j].origin), crown: mix(frames[i].crown, frames[j].crown).normalize() };
  f.right = mix(frames[i].right, frames[j].right).normalize();
  f.tangent = frames[j].origin.clone().sub(frames[i].origin).normalize();
  if (nr < 2) f.tangent = f.right.clone().cross(f.crown);
  return f;
}

function buildGeometry(relief) {
  const positions = new Float32Array(nr * (nc + 1) * 3), uvs = new Float32Array(nr * (nc + 1) * 2);
  for (let i = 0; i < nr; ++i) {
    const f = frames[i];
    const u = (data.stations_mm[i] - tex.station0_mm) / (tex.station1_mm - tex.station0_mm);
    for (let j = 0; j <= nc; ++j) {
      const theta = data.clocks_rad[j % nc] + (j === nc ? 2 * Math.PI : 0);
      const d = displacement[i * nc + (j % nc)];
      const r = R + relief * (Number.isNaN(d) ? 0 : d);
      const p = f.origin.clone().addScaledVector(f.crown, r * Math.cos(theta)).addScaledVector(f.right, r * Math.sin(theta));
      const k = i * (nc + 1) + j;
      positions.set([p.x, p.y, p.z], 3 * k);
      uvs.set([u, theta / (2 * Math.PI) / tex.turn_fraction], 2 * k);
    }
  }
  const index = [];
  for (let i = 0; i + 1 < nr; ++i) {
    for (let j = 0; j < nc; ++j) {
      const a = i * (nc + 1) + j, b = a + 1, c = a + nc + 1, d = c + 1;
      index.push(a, c, b, b, c, d);  // normals toward the axis: the inner wall is the front
    }
  }
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.BufferAttribute(positions, 3));
  g.setAttribute('uv', new THREE.BufferAttribute(uvs, 2));
  g.setIndex(index);
  g.computeVertexNormals();
  return g;
}

// Displacement (mm) at a station and clock angle, bilinear between the vertices.
function displacementAt(station, theta) {
  let i = 0;
  while (i + 2 < nr && data.stations_mm[i + 1] < station) ++i;
  const wi = nr < 2 ? 0 : Math.min(Math.max((station - data.stations_mm[i]) / (data.stations_mm[i + 1] - data.stations_mm[i]), 0), 1);
  const c = (theta / (2 * Math.PI)) * nc - 0.5;
  const j = Math.floor(c), wj = c - j;
  const at = (ii, jj) => displacement[Math.min(ii, nr - 1) * nc + ((jj % nc) + nc) % nc];
  const row = (ii) => at(ii, j) * (1 - wj) + at(ii, j + 1) * wj;
  return row(i) * (1 - wi) + row(i + 1) * wi;
}

const renderer = new THREE.WebGLRenderer({ canvas, antialias: true });
renderer.setPixelRatio(window.devicePixelRatio || 1);
const scene = new THREE.Scene();
scene.background = new THREE.Color(0x1b1f24);
const camera = new THREE.PerspectiveCamera(45, 16 / 9, 1, 1e6);
const headlight = new THREE.PointLight(0xffffff, 2.2, 0, 0);
camera.add(headlight);
scene.add(camera, new THREE.AmbientLight(0xffffff, 0.9));
const texture = new THREE.Texture(textureImage);
texture.flipY = false;
texture.colorSpace = THREE.SRGBColorSpace;
texture.anisotropy = 4;
const material = new THREE.MeshLambertMaterial({ map: texture });  // cheap to compile in software GL
const mesh = new THREE.Mesh(buildGeometry(1), material);
scene.add(mesh);
const marker = new THREE.Mesh(new THREE.SphereGeometry(R * 0.02), new THREE.MeshBasicMaterial({ color: 0x00e0ff }));
marker.visible = false;
scene.add(marker);
const controls = new OrbitControls(camera, canvas);
let mode = 'orbit', station = 0.5 * (s0 + s1), roll = 0;

function render() { renderer.render(scene, camera); }

function resize() {
  const w = canvas.clientWidth, h = canvas.clientHeight;
  renderer.setSize(w, h, false);
  camera.aspect = w / h;
  camera.updateProjectionMatrix();
  render();
}

function placeCamera() {
  const f = frameAt(station);
  if (mode === 'fly') {
    const up = f.crown.clone().multiplyScalar(Math.cos(roll)).addScaledVector(f.right, Math.sin(roll));
    camera.position.copy(f.origin);
    camera.up.copy(up);
    camera.lookAt(f.origin.clone().addScaledVector(f.tangent, 4 * R));
  } else {
    // From the 3 o'clock side, a little above, so station grows to the right and the inner
    // wall of the far (9 o'clock) half faces the camera; the near half is culled.
    const hfov = 2 * Math.atan(Math.tan(THREE.MathUtils.degToRad(camera.fov / 2)) * camera.aspect);
    const distance = Math.max(0.55 * (s1 - s0) / Math.tan(hfov / 2), 2.6 * R);
    camera.up.copy(f.crown);
    camera.position.copy(f.origin).addScaledVector(f.right, distance).addScaledVector(f.crown, 0.2 * distance);
    controls.target.copy(f.origin);
    controls.update();
  }
  controls.enabled = mode === 'orbit';
  slider.value = String(Math.round(1000 * (station - s0) / Math.max(s1 - s0, 1e-9)));
  sliderText.textContent = (station / 1000).toFixed(3) + ' m';
  render();
}

function pick(event) {
  const r = canvas.getBoundingClientRect();
  const ndc = new THREE.Vector2(((event.clientX - r.left) / r.width) * 2 - 1, -((event.clientY - r.top) / r.height) * 2 + 1);
  const ray = new THREE.Raycaster();
  ray.setFromCamera(ndc, camera);
  const hit = ray.intersectObject(mesh)[0];
  if (!hit) { readout.textContent = 'No wall under the cursor.'; return; }
  const s = tex.station0_mm + hit.uv.x * (tex.station1_mm - tex.station0_mm);
  const theta = 2 * Math.PI * ((hit.uv.y * tex.turn_fraction) % 1);
  const d = displacementAt(s, theta);
  const clock = (theta / (2 * Math.PI)) * 12;
  readout.dataset.stationMm = s.toFixed(2);
  readout.dataset.clockH = clock.toFixed(3);
  readout.dataset.radiusMm = Number.isNaN(d) ? '' : (R + d).toFixed(3);
  readout.textContent = 'station ' + (s / 1000).toFixed(3) + ' m, clock ' + (clock < 0.05 ? 12 : clock).toFixed(2) +
    ' h, radius ' + (Number.isNaN(d) ? 'no data' : (R + d).toFixed(2) + ' mm (displacement ' + (d >= 0 ? '+' : '') + d.toFixed(2) + ' mm)');
  marker.position.copy(hit.point);
  marker.visible = true;
  render();
}

let down = null;
canvas.addEventListener('pointerdown', (e) => { down = { x: e.clientX, y: e.clientY }; });
canvas.addEventListener('pointerup', (e) => {
  if (down && Math.hypot(e.clientX - down.x, e.clientY - down.y) < 4) pick(e);
  down = null;
});
controls.addEventListener('change', render);
slider.addEventListener('input', () => { station = s0 + (Number(slider.value) / 1000) * (s1 - s0); placeCamera(); });
for (const radio of document.querySelectorAll('input[name=viewer-mode]'))
  radio.addEventListener('change', () => { mode = radio.value; placeCamera(); });
document.getElementById('viewer-relief').addEventListener('change', (e) => {
  mesh.geometry.dispose();
  mesh.geometry = buildGeometry(Number(e.target.value));
  render();
});
window.addEventListener('keydown', (e) => {
  if (mode !== 'fly' || !['ArrowUp', 'ArrowDown', 'ArrowLeft', 'ArrowRight'].includes(e.key)) return;
  e.preventDefault();
  if (e.key === 'ArrowUp' || e.key === 'ArrowDown') {
    const step = Math.max((s1 - s0) / 200, 1);
    station = Math.min(Math.max(station + (e.key === 'ArrowUp' ? step : -step), s0), s1);
  } else {
    roll += (e.key === 'ArrowRight' ? 1 : -1) * Math.PI / 12;
  }
  placeCamera();
});
window.addEventListener('resize', resize);

textureImage.decode().catch(() => {}).then(() => {
  texture.needsUpdate = true;
  resize();
  placeCamera();
  window.sewer3dViewer = { ready: true, vertices: nr * (nc + 1) };
});
