// The test page: window.jadeTest draws a baked file with a fixed camera and lights, with
// JadeTranslucentMaterial or three.js's MeshPhysicalMaterial / MeshStandardMaterial, and times
// frames. Driven by render_scenes.mjs.
import * as THREE from 'three';
import { JadeTranslucentMaterial, loadJadeGltf } from '../src/index.js';
import { makeLight } from '../src/lights.js';

let renderer, meshes = [], root;

function setup(width, height) {
  if (!renderer) {
    renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
    document.body.appendChild(renderer.domElement);
  }
  renderer.setPixelRatio(1);
  renderer.setSize(width, height, false);
  // Jade's PNG: linear light clipped to [0, 1], sRGB-encoded; no tone mapping.
  renderer.outputColorSpace = THREE.SRGBColorSpace;
  renderer.toneMapping = THREE.NoToneMapping;
  renderer.setClearColor(0x000000, 1);
}

function sceneFor({ camera: c, lights, size, material }) {
  const [width, height] = size;
  setup(width, height);
  const scene = new THREE.Scene();
  scene.add(root);
  for (const mesh of meshes) {
    const jade = mesh.userData.jade;
    if (!jade[`${material}Material`]) throw new Error(`unknown material '${material}'`);
    mesh.material = jade[`${material}Material`];
  }
  for (const l of lights) scene.add(makeLight(l));
  const camera = new THREE.PerspectiveCamera(c.fov, width / height, 0.01, 100);
  camera.position.set(...c.eye);
  camera.up.set(...c.up);
  camera.lookAt(...c.target);
  return { scene, camera };
}

window.jadeTest = {
  async load(url, lightPath = 'auto', shadows = true) {
    const gltf = await loadJadeGltf(url, { lightPath, shadows });
    root = gltf.scene;
    meshes = [];
    root.traverse((o) => { if (o.isMesh && o.userData.jade) meshes.push(o); });
    if (meshes.length === 0) throw new Error(`${url}: no baked primitive with JADE_materials_translucency`);
    for (const mesh of meshes) {
      const jade = mesh.userData.jade;
      jade.jadeMaterial = mesh.material;
      // The same material without shadows: what the test measures the shadows' share against.
      const m = mesh.material;
      const unshadowed = new JadeTranslucentMaterial(jade.extension, mesh.geometry.boundingBox,
                                                     m.uniforms.jadeTransmission.value === 1);
      unshadowed.setSmallestVariance(JadeTranslucentMaterial.smallestVariance(jade.extension,
                                                                              mesh.geometry.attributes.jadeTm));
      unshadowed.setLightPath(m.lightPath);
      unshadowed.shadows = false;
      jade.unshadowedMaterial = unshadowed;
      jade.standardMaterial = new THREE.MeshStandardMaterial({
        color: new THREE.Color().setRGB(...jade.extension.albedo), roughness: jade.extension.roughness, metalness: 0 });
    }
    // What each baked primitive's material draws with: Jade's choice of Fourier terms and the
    // small-t closed form for its t (choose_terms), and where it reads the light's path.
    return meshes.map((m) => `${m.name}: ${m.userData.jade.jadeMaterial.name}, ` +
                             `JADE_TERMS ${m.userData.jade.jadeMaterial.defines.JADE_TERMS}, ` +
                             `JADE_SMALL_T ${m.userData.jade.jadeMaterial.defines.JADE_SMALL_T}, ` +
                             `light path per ${m.userData.jade.jadeMaterial.lightPath}, ` +
                             `shadows ${m.userData.jade.jadeMaterial.shadows ? 'on' : 'off'}`);
  },
  render(options) {
    const { scene, camera } = sceneFor(options);
    renderer.render(scene, camera);
    const gl = renderer.getContext();
    const error = gl.getError();
    if (error !== gl.NO_ERROR) throw new Error(`WebGL error 0x${error.toString(16)}`);
    return renderer.domElement.toDataURL('image/png');
  },
  // Median milliseconds per frame of each material, `frames` frames each, in alternating blocks
  // of 5 (the CPU that SwiftShader runs on is shared: load that comes and goes hits both alike),
  // after `warmup` frames each. Each frame is finished by reading a pixel back (gl.finish alone
  // may return before the work is done).
  time(options, materials, frames, warmup = 3) {
    const gl = renderer.getContext();
    const pixel = new Uint8Array(4);
    const setups = materials.map((material) => sceneFor({ ...options, material }));
    const frame = (k) => {
      for (const mesh of meshes) mesh.material = mesh.userData.jade[`${materials[k]}Material`];
      setups[k].scene.add(root);
      const start = performance.now();
      renderer.render(setups[k].scene, setups[k].camera);
      gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, pixel);
      return performance.now() - start;
    };
    const times = materials.map(() => []);
    for (let k = 0; k < materials.length; ++k)
      for (let i = 0; i < warmup; ++i) frame(k);
    for (let done = 0; done < frames; done += 5)
      for (let k = 0; k < materials.length; ++k)
        for (let i = done; i < Math.min(done + 5, frames); ++i) times[k].push(frame(k));
    const median = (a) => { const b = [...a].sort((x, y) => x - y); return b[b.length >> 1]; };
    return times.map(median);
  },
  info() {
    setup(1, 1);
    const gl = renderer.getContext();
    const debug = gl.getExtension('WEBGL_debug_renderer_info');
    return { renderer: debug ? gl.getParameter(debug.UNMASKED_RENDERER_WEBGL) : gl.getParameter(gl.RENDERER),
             samples: gl.getParameter(gl.SAMPLES), three: THREE.REVISION };
  },
};
window.jadeTestReady = true;
