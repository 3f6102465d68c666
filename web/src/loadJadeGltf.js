// Loading a file written by `jade bake` into three.js: a GLTFLoader plugin for the
// JADE_materials_translucency material extension, and loadJadeGltf(), which returns the glTF
// scene with every baked primitive drawn by JadeTranslucentMaterial.
//
// GLTFLoader names an attribute it does not know by its lower-cased glTF name (_TM → _tm); the
// plugin renames the baked ones to the jade* names the material reads (a leading underscore is
// legal in GLSL ES but easy to collide with), and adds area-weighted vertex normals where the
// file has none (what Jade's prepare_mesh computes; GLTFLoader would draw such a mesh flat).
import { Box3, BufferAttribute, Color, MeshPhysicalMaterial } from 'three';
import { GLTFLoader } from 'three/examples/jsm/loaders/GLTFLoader.js';
import { JadeTranslucentMaterial } from './JadeTranslucentMaterial.js';

export const JADE_EXTENSION = 'JADE_materials_translucency';

const BAKED_ATTRIBUTES = {
  _tm: 'jadeTm',
  _thickness: 'jadeThickness',
  _scattering_normal: 'jadeScatteringNormal',
  _normal_spread: 'jadeNormalSpread',
  _ao: 'jadeAo',
};

// What three.js's own physically based material makes of the same glTF material: Jade's albedo,
// ior and roughness, and KHR_materials_volume / KHR_materials_diffuse_transmission where the file
// has them (else three.js's defaults: no transmission). For comparison (docs/web.md).
function physicalMaterial(extension, materialDef) {
  const m = new MeshPhysicalMaterial({
    color: new Color().setRGB(...extension.albedo),
    metalness: 0,
    roughness: extension.roughness,
    ior: extension.ior,
  });
  const volume = materialDef.extensions?.KHR_materials_volume;
  if (volume) {
    m.thickness = volume.thicknessFactor ?? 0;
    if (volume.attenuationColor) m.attenuationColor.setRGB(...volume.attenuationColor);
    if (volume.attenuationDistance !== undefined) m.attenuationDistance = volume.attenuationDistance;
    const diffuse = materialDef.extensions?.KHR_materials_diffuse_transmission;
    m.transmission = diffuse ? diffuse.diffuseTransmissionFactor ?? 0 : 1;
  }
  m.name = `${extension.name ?? 'jade'} (MeshPhysicalMaterial)`;
  return m;
}

/** GLTFLoader plugin: after the file is parsed, baked primitives get JadeTranslucentMaterial. */
export class JadeGltfPlugin {
  /**
   * options.lightPath: 'auto' (default), 'vertex' or 'fragment' (JadeTranslucentMaterial.setLightPath);
   * options.shadows: whether the mesh shadows its directional lights (default true).
   */
  constructor(parser, options = {}) {
    this.parser = parser;
    this.options = options;
    this.name = JADE_EXTENSION;
  }

  afterRoot(result) {
    const { parser, options } = this;
    const materials = parser.json.materials ?? [];
    const meshes = [];
    result.scene.traverse((object) => { if (object.isMesh) meshes.push(object); });
    for (const mesh of meshes) {
      const association = parser.associations.get(mesh.material);
      const index = association?.materials;
      const materialDef = index === undefined ? undefined : materials[index];
      const extension = materialDef?.extensions?.[JADE_EXTENSION];
      const geometry = mesh.geometry;
      if (!extension || !geometry.attributes._tm) continue;  // not baked: left to GLTFLoader
      for (const [from, to] of Object.entries(BAKED_ATTRIBUTES))
        if (geometry.attributes[from]) {
          geometry.setAttribute(to, geometry.attributes[from]);
          geometry.deleteAttribute(from);
        }
      if (!geometry.attributes.normal) geometry.computeVertexNormals();
      for (const needed of ['jadeScatteringNormal', 'jadeNormalSpread'])
        if (!geometry.attributes[needed])
          throw new Error(`${mesh.name}: baked primitive without ${needed === 'jadeScatteringNormal'
            ? '_SCATTERING_NORMAL' : '_NORMAL_SPREAD'} (re-bake it with a current jade bake)`);
      const hasThickness = Boolean(geometry.attributes.jadeThickness);
      if (!hasThickness) {
        // The transmission term is off without it; the attribute must still exist for the shader.
        const zeros = new Float32Array(geometry.attributes.position.count);
        geometry.setAttribute('jadeThickness', new BufferAttribute(zeros, 1));
      }
      geometry.computeBoundingBox();
      const box = new Box3().copy(geometry.boundingBox);
      const gltfMaterial = mesh.material;
      gltfMaterial.flatShading = false;  // GLTFLoader's choice for a file without normals
      gltfMaterial.needsUpdate = true;
      mesh.material = new JadeTranslucentMaterial(extension, box, hasThickness);
      mesh.material.setSmallestVariance(JadeTranslucentMaterial.smallestVariance(extension, geometry.attributes.jadeTm));
      mesh.material.setLightPath(options.lightPath ?? 'auto', JadeTranslucentMaterial.medianEdge(geometry));
      mesh.material.shadows = options.shadows ?? true;
      mesh.userData.jade = {
        extension,
        gltfMaterial,
        physicalMaterial: physicalMaterial(extension, materialDef),
      };
    }
  }
}

/**
 * Loads a baked .glb/.gltf from `url`; resolves to GLTFLoader's result, whose scene draws every
 * baked primitive with JadeTranslucentMaterial (mesh.userData.jade holds the extension and the
 * file's own and a MeshPhysicalMaterial for comparison). lightPath: where the transmission's path
 * is read ('auto', 'vertex', 'fragment'; JadeTranslucentMaterial.setLightPath); shadows: whether
 * the mesh shadows its directional lights (as jade render; false as --no-shadows).
 */
export async function loadJadeGltf(url, { loader = new GLTFLoader(), lightPath = 'auto', shadows = true } = {}) {
  loader.register((parser) => new JadeGltfPlugin(parser, { lightPath, shadows }));
  return loader.loadAsync(url);
}
