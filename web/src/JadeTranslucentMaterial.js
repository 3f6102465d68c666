// JadeTranslucentMaterial: Jade's default (tm) shading of a file written by `jade bake`, as a
// three.js ShaderMaterial. The per-vertex inputs are the baked attributes (GLTFLoader names them
// _tm, _thickness, _scattering_normal, _normal_spread; loadJadeGltf.js renames them to the
// jade* attributes read here) and the vertex normal; the parameters are those of the
// JADE_materials_translucency extension (docs/gltf.md). Lit by the scene's three.js
// DirectionalLights and PointLights (lights: true): colour × intensity is Jade's irradiance E
// (directional) or intensity (point, falling off as 1/d²). No shadows, no light-depth map: the
// transmission's path is the baked _THICKNESS (docs/web.md says what that changes).
import { ShaderMaterial, UniformsLib, UniformsUtils, Vector3, Vector4 } from 'three';
import { vertexShader, fragmentShader } from './jadeShaderChunks.js';

const finite = (x, what) => {
  if (!Number.isFinite(x)) throw new Error(`JADE_materials_translucency: ${what} is not a finite number (${x})`);
  return x;
};
const triple = (a, what) => {
  if (!Array.isArray(a) || a.length !== 3) throw new Error(`JADE_materials_translucency: ${what} is not an RGB triple`);
  return a.map((x, i) => Math.min(finite(x, `${what}[${i}]`), 3e38));
};

export class JadeTranslucentMaterial extends ShaderMaterial {
  /**
   * @param {object} extension the JADE_materials_translucency object of a glTF material
   * @param {{min: Vector3, max: Vector3}} bounds the mesh's bounding box (object space): Jade
   *   draws a light's transmission only when it can reach the eye past the bounding sphere
   * @param {boolean} hasThickness whether the mesh has _THICKNESS (the transmission term needs it)
   */
  constructor(extension, bounds, hasThickness = true) {
    super({
      uniforms: UniformsUtils.merge([UniformsLib.lights, {
        jadeAlbedoStrength: { value: new Vector4() },
        jadeSpecular: { value: new Vector4() },
        jadeExtinction: { value: new Vector4() },
        jadeDiffusion: { value: new Vector4() },
        jadeScatter: { value: new Vector3() },
        jadeSource: { value: new Vector3() },
        jadeExtrapolation: { value: new Vector3() },
        jadeShape: { value: new Vector4() },
        jadeBounds: { value: new Vector4() },
        jadeTransmission: { value: 0 },
      }]),
      vertexShader,
      fragmentShader,
      lights: true,
    });
    this.type = 'JadeTranslucentMaterial';
    this.isJadeTranslucentMaterial = true;
    this.name = extension.name ?? 'jade';
    this.setExtension(extension, hasThickness);
    this.setBounds(bounds.min, bounds.max);
  }

  /** The material's constants as Jade's material_constants (engine/src/shading/frame.cpp). */
  setExtension(x, hasThickness = true) {
    const u = this.uniforms;
    const albedo = triple(x.albedo, 'albedo');
    u.jadeAlbedoStrength.value.set(...albedo, finite(x.strength, 'strength'));
    const ior = finite(x.ior, 'ior'), roughness = finite(x.roughness, 'roughness');
    const f0 = ((ior - 1) / (ior + 1)) ** 2;
    u.jadeSpecular.value.set(f0, Math.max(roughness * roughness, 1e-3), finite(x.specular, 'specular'),
                             finite(x.spreadStrength, 'spreadStrength'));
    const t = x.transmission;
    if (typeof t !== 'object' || t === null) throw new Error('JADE_materials_translucency: no transmission object');
    u.jadeExtinction.value.set(...triple(t.sigmaT, 'transmission.sigmaT'), finite(t.weight, 'transmission.weight'));
    u.jadeDiffusion.value.set(...triple(t.sigmaTr, 'transmission.sigmaTr'),
                              finite(t.diffusionWeight, 'transmission.diffusionWeight'));
    u.jadeScatter.value.set(...triple(t.sigmaSReduced, 'transmission.sigmaSReduced'));
    u.jadeSource.value.set(...triple(t.sourceDepth, 'transmission.sourceDepth'));
    u.jadeExtrapolation.value.set(...triple(t.extrapolation, 'transmission.extrapolation'));
    const lobe = finite(t.lobe, 'transmission.lobe');
    u.jadeShape.value.set(lobe, (lobe + 1) / (2 * Math.PI), finite(t.normalMix, 'transmission.normalMix'),
                          x.boundaryTransmittance ? 1 : 0);
    // Transmission::enabled (jade/material.hpp): some weight, and a thickness to shine through.
    u.jadeTransmission.value = hasThickness && (t.weight > 0 || t.diffusionWeight > 0) ? 1 : 0;
    this.extension = x;
  }

  setBounds(min, max) {
    const centre = new Vector3().addVectors(min, max).multiplyScalar(0.5);
    this.uniforms.jadeBounds.value.set(centre.x, centre.y, centre.z, 0.5 * min.distanceTo(max));
  }
}
