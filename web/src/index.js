// jade-web: Jade's translucency-magnitude shading in three.js (docs/web.md).
export { JadeTranslucentMaterial } from './JadeTranslucentMaterial.js';
export { loadJadeGltf, JadeGltfPlugin, JADE_EXTENSION } from './loadJadeGltf.js';
