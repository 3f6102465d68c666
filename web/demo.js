// The demo page: a file written by `jade bake` (?file=URL, default the committed blue-jewel
// bunny) drawn with JadeTranslucentMaterial, OrbitControls, and the test's light rigs
// (test/scenes.json: front, back, point) and materials to switch between. docs/web.md.
import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import { loadJadeGltf } from './src/index.js';
import { makeLight } from './src/lights.js';

const status = document.getElementById('status');
const file = new URLSearchParams(location.search).get('file') ?? 'assets/bunny_blue_jewel.glb';

const renderer = new THREE.WebGLRenderer({ antialias: true });
renderer.setPixelRatio(window.devicePixelRatio);
renderer.setSize(window.innerWidth, window.innerHeight);
renderer.outputColorSpace = THREE.SRGBColorSpace;  // Jade's PNG: linear, clipped, sRGB-encoded
renderer.toneMapping = THREE.NoToneMapping;
document.body.appendChild(renderer.domElement);

const scene = new THREE.Scene();
const camera = new THREE.PerspectiveCamera(30, window.innerWidth / window.innerHeight, 0.01, 100);
const controls = new OrbitControls(camera, renderer.domElement);
const rigs = {};
let lights = new THREE.Group(), meshes = [], rig = 'back', material = 'jade';
scene.add(lights);

function draw() { renderer.render(scene, camera); }

// The rig's lights are given for a camera on +z (jade render's presets): they turn with the
// camera, as jade render's presets are placed in the camera's frame.
function syncLights() {
  lights.quaternion.copy(camera.quaternion);
  lights.updateMatrixWorld(true);
}

function setRig(name) {
  rig = name;
  scene.remove(lights);
  lights = new THREE.Group();
  for (const l of rigs[name]) {
    const light = makeLight(l);
    lights.add(light);
    if (light.isDirectionalLight) lights.add(light.target);  // its target turns with the rig too
  }
  scene.add(lights);
  syncLights();
  update();
}

function setMaterial(name) {
  material = name;
  for (const mesh of meshes) mesh.material = mesh.userData.jade[`${name}Material`];
  update();
}

function update() {
  for (const b of document.querySelectorAll('[data-rig]')) b.classList.toggle('on', b.dataset.rig === rig);
  for (const b of document.querySelectorAll('[data-material]')) b.classList.toggle('on', b.dataset.material === material);
  draw();
}

async function main() {
  const [gltf, config] = await Promise.all([loadJadeGltf(file), fetch('test/scenes.json').then((r) => r.json())]);
  Object.assign(rigs, config.scenes);
  gltf.scene.traverse((o) => { if (o.isMesh && o.userData.jade) meshes.push(o); });
  if (meshes.length === 0) throw new Error(`${file}: no primitive baked by jade bake (JADE_materials_translucency)`);
  for (const mesh of meshes) {
    const jade = mesh.userData.jade;
    jade.jadeMaterial = mesh.material;
    jade.standardMaterial = new THREE.MeshStandardMaterial({
      color: new THREE.Color().setRGB(...jade.extension.albedo), roughness: jade.extension.roughness, metalness: 0 });
  }
  scene.add(gltf.scene);
  camera.position.set(...config.camera.eye);
  controls.target.set(...config.camera.target);
  controls.update();
  controls.addEventListener('change', () => { syncLights(); draw(); });
  for (const b of document.querySelectorAll('[data-rig]')) b.onclick = () => setRig(b.dataset.rig);
  for (const b of document.querySelectorAll('[data-material]')) b.onclick = () => setMaterial(b.dataset.material);
  window.addEventListener('resize', () => {
    camera.aspect = window.innerWidth / window.innerHeight;
    camera.updateProjectionMatrix();
    renderer.setSize(window.innerWidth, window.innerHeight);
    draw();
  });
  setRig(rig);
  const x = meshes[0].userData.jade.extension;
  status.textContent = `${file.split('/').pop()}: material ${x.name}, ` +
    `${meshes.reduce((n, m) => n + m.geometry.attributes.position.count, 0)} vertices. Drag to orbit.`;
  window.jadeDemoReady = true;
}

main().catch((error) => {
  status.textContent = `error: ${error.message}`;
  console.error(error);
});
