// JadeTranslucentMaterial: Jade's default (tm) shading of a file written by `jade bake`, as a
// three.js ShaderMaterial. The per-vertex inputs are the baked attributes (GLTFLoader names them
// _tm, _thickness, _scattering_normal, _normal_spread; loadJadeGltf.js renames them to the
// jade* attributes read here) and the vertex normal; the parameters are those of the
// JADE_materials_translucency extension (docs/gltf.md). Lit by the scene's three.js
// DirectionalLights and PointLights (lights: true): colour × intensity is Jade's irradiance E
// (directional) or intensity (point, falling off as 1/d²). Up to four lights get a depth tile of
// the mesh (JadeLightDepth.js) when they may shine through the object towards the eye (the
// transmission's path: the longer of the baked _THICKNESS and the path from where the light
// enters, per vertex or per fragment as Jade picks, setLightPath) or when the material draws
// shadows (`shadows`, default on, as jade render); a point light within 1.05 bounding radii gets
// none (its path is the thickness, it casts no shadow), as in Jade.
import { Matrix4, ShaderMaterial, UniformsLib, UniformsUtils, Vector3, Vector4 } from 'three';
import { vertexShader, fragmentShader } from './jadeShaderChunks.js';
import { JadeLightDepth, kMaxTiles, kPointMinDistance } from './JadeLightDepth.js';
import { softShadowKernel } from './profile.js';

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
        jadeDipoleAlbedo: { value: new Vector4() },
        jadeDipoleSigma: { value: new Vector4() },
        jadeDipoleReal: { value: new Vector3() },
        jadeDipoleBoundary: { value: new Vector3() },
        jadeShape: { value: new Vector4() },
        jadeBounds: { value: new Vector4() },
        jadeTransmission: { value: 0 },
        jadeTileLayers: { value: [] },  // per light (sized in onBeforeRender)
        jadeTileMatrix: { value: [] },
        jadeTileInfo: { value: [] },
        jadeTileDepth: { value: [] },
        jadeTileOrigin: { value: [] },
        jadeSoftShadow: { value: new Vector4() },
        jadeSoftShadowRadius: { value: new Array(16).fill(0) },
        jadeSoftShadowMedian: { value: 0 },
      }]),
      vertexShader,
      fragmentShader,
      lights: true,
      // Every term (right for any t) and the path per fragment until told otherwise.
      defines: { JADE_TERMS: 6, JADE_SMALL_T: 1, JADE_PATH_PER_VERTEX: 0, JADE_SHADOWS: 1 },
    });
    this.type = 'JadeTranslucentMaterial';
    this.isJadeTranslucentMaterial = true;
    this.name = extension.name ?? 'jade';
    this.setExtension(extension, hasThickness);
    this.setBounds(bounds.min, bounds.max);
    this.lightDepth = null;  // made on the first draw that needs a depth tile
  }

  /** Whether the mesh shadows the directional lights (jade render's default; --no-shadows: off). */
  get shadows() { return this.defines.JADE_SHADOWS === 1; }

  set shadows(on) {
    const value = on ? 1 : 0;
    if (this.defines.JADE_SHADOWS !== value) this.defines.JADE_SHADOWS = value, this.needsUpdate = true;
  }

  /**
   * three.js calls this before each draw with the material: the lights' depth tiles, as Jade's
   * record_transmission chooses them: lights that may shine through the object towards the eye
   * (LightDepth::may_transmit: every point light) first, then, with shadows, the others, at most
   * four; a point light only from 1.05 bounding radii (can_tile). Each is peeled again only when
   * it, the mesh or its transform moved. Slots follow three.js's light uniforms: the directional
   * lights, then the point lights, each in the scene's order.
   */
  onBeforeRender(renderer, scene, camera, geometry, object) {
    const u = this.uniforms;
    const directional = [], point = [];
    scene.traverseVisible((o) => {
      if (!o.layers.test(camera.layers)) return;
      if (o.isDirectionalLight) directional.push(o);
      else if (o.isPointLight) point.push(o);
    });
    const lights = [
      ...directional.map((light) => ({ point: false, vector: new Vector3().setFromMatrixPosition(light.matrixWorld)
        .sub(new Vector3().setFromMatrixPosition(light.target.matrixWorld)) })),
      ...point.map((light) => ({ point: true, vector: new Vector3().setFromMatrixPosition(light.matrixWorld) })),
    ];
    const n = Math.max(lights.length, 1);
    const layers = u.jadeTileLayers.value = new Array(n).fill(null);
    const matrices = u.jadeTileMatrix.value = Array.from({ length: n }, () => new Matrix4());
    const infos = u.jadeTileInfo.value = Array.from({ length: n }, () => new Vector4());
    const depths = u.jadeTileDepth.value = Array.from({ length: n }, () => new Vector4());
    const origins = u.jadeTileOrigin.value = Array.from({ length: n }, () => new Vector3());
    const b = u.jadeBounds.value;
    const centre = new Vector3(b.x, b.y, b.z).applyMatrix4(object.matrixWorld);
    const radius = b.w * object.matrixWorld.getMaxScaleOnAxis();
    const eye = new Vector3().setFromMatrixPosition(camera.matrixWorld);
    const distance = eye.distanceTo(centre);
    const towardsEye = eye.clone().sub(centre).divideScalar(distance);
    const usable = (l) => (l.point ? l.vector.distanceTo(centre) >= kPointMinDistance * Math.max(radius, 1e-20)
                                   : l.vector.length() > 0);
    const transmits = lights.map((l) => u.jadeTransmission.value === 1 &&
      (l.point || !(distance > radius) || towardsEye.dot(l.vector.clone().normalize().negate()) > -radius / distance));
    const wanted = lights.map((l, i) => (!usable(l) ? 0 : transmits[i] ? 2 : this.shadows ? 1 : 0));
    const chosen = [];
    for (const priority of [2, 1])
      for (let i = 0; i < lights.length && chosen.length < kMaxTiles; ++i) if (wanted[i] === priority) chosen.push(i);
    chosen.sort((x, y) => x - y);  // tiles in the lights' order
    if (chosen.length === 0) return;
    this.lightDepth ??= new JadeLightDepth();
    if (!this.softShadow) {
      // The kernel's radii in view space: the object's scale (the camera's matrices are rigid).
      const k = softShadowKernel(this.extension.profiles), scale = object.matrixWorld.getMaxScaleOnAxis();
      this.softShadow = k;
      u.jadeSoftShadow.value.set(...k.shape.slice(0, 3).map((d) => d * scale), k.shape[3] * scale);
      u.jadeSoftShadowRadius.value = k.radii.map((r) => r * scale);
      u.jadeSoftShadowMedian.value = k.median * scale;
    }
    chosen.forEach((i, k) => {
      const tile = this.lightDepth.update(renderer, k, object, lights[i], centre, radius, transmits[i] ? 4 : 2);
      layers[i] = tile.texture;
      matrices[i].multiplyMatrices(tile.viewProjection, camera.matrixWorld);
      infos[i].set(this.lightDepth.size, 0, tile.origin ? 2 : 1, 0);
      depths[i].set(tile.near, tile.range, tile.texel, 0);
      if (tile.origin) origins[i].copy(tile.origin).applyMatrix4(camera.matrixWorldInverse);
    });
  }

  dispose() {
    this.lightDepth?.dispose();
    super.dispose();
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
    // The dipole of the diffused transmission from the medium's depths, per channel: z_r = z_s − z_b
    // (= 1/σ_t'), α' = σ_s' z_r clamped to [0, 1] (0 where z_r = 0), z_b; the gather's reach past
    // the light's path 3/σ_tr of the channel reaching furthest among those with α' > 0.
    const sigmaTr = triple(t.sigmaTr, 'transmission.sigmaTr');
    const sigmaS = triple(t.sigmaSReduced, 'transmission.sigmaSReduced');
    const source = triple(t.sourceDepth, 'transmission.sourceDepth');
    const boundary = triple(t.extrapolation, 'transmission.extrapolation');
    const real = source.map((z, c) => Math.max(z - boundary[c], 0));
    const reducedAlbedo = real.map((z, c) => (z > 0 ? Math.min(Math.max(sigmaS[c] * z, 0), 1) : 0));
    let smallest = 0;
    for (let c = 0; c < 3; ++c)
      if (reducedAlbedo[c] > 0 && (smallest === 0 || sigmaTr[c] < smallest)) smallest = sigmaTr[c];
    u.jadeDipoleAlbedo.value.set(...reducedAlbedo.map((a) => a / (4 * Math.PI)),
                                 finite(t.diffusionWeight, 'transmission.diffusionWeight'));
    u.jadeDipoleSigma.value.set(...sigmaTr, smallest > 0 ? 3 / smallest : 3e38);
    u.jadeDipoleReal.value.set(...real);
    u.jadeDipoleBoundary.value.set(...boundary);
    const lobe = finite(t.lobe, 'transmission.lobe');
    u.jadeShape.value.set(lobe, (lobe + 1) / (2 * Math.PI), finite(t.normalMix, 'transmission.normalMix'),
                          x.boundaryTransmittance ? 1 : 0);
    // Transmission::enabled (jade/material.hpp): some weight, and a thickness to shine through.
    u.jadeTransmission.value = hasThickness && (t.weight > 0 || t.diffusionWeight > 0) ? 1 : 0;
    this.extension = x;
  }

  /**
   * choose_terms (engine/src/shading/mesh_pipeline.cpp): the fewest Fourier terms whose first
   * omitted one, (2/π) e^{−2(K+1)²t} / (4(K+1)² − 1), stays within 2e-5 at the mesh's smallest
   * variance t (largest there), and the closed form only where some t is below 0.3².
   */
  setSmallestVariance(tMin) {
    const t = Math.max(Number.isFinite(tMin) ? tMin : 0, 0);
    let terms = 6;
    const smallT = t < 0.3 * 0.3 ? 1 : 0;
    if (!smallT)
      for (let k = 1; k < 6; ++k) {
        const next = (k + 1) * (k + 1);
        if ((2 / Math.PI) * Math.exp(-2 * next * t) / (4 * next - 1) <= 2e-5) { terms = k; break; }
      }
    if (this.defines.JADE_TERMS !== terms || this.defines.JADE_SMALL_T !== smallT) {
      this.defines.JADE_TERMS = terms;
      this.defines.JADE_SMALL_T = smallT;
      this.needsUpdate = true;
    }
  }

  /**
   * Where the light's path through the object is read: 'vertex' (interpolated), 'fragment', or
   * 'auto' with the mesh's median edge length (object space): per vertex where it spans at most 8
   * texels of the light-depth tile, as Jade's resolve_light_path.
   */
  setLightPath(where, medianEdge = Infinity) {
    if (!['auto', 'vertex', 'fragment'].includes(where))
      throw new Error(`light path '${where}' is not auto, vertex or fragment`);
    const texel = (2 * 1.1 * this.uniforms.jadeBounds.value.w) / 512;  // LightDepth::kMargin, light_depth_size
    const perVertex = where === 'vertex' || (where === 'auto' && medianEdge <= 8 * texel) ? 1 : 0;
    this.lightPath = perVertex ? 'vertex' : 'fragment';
    if (this.defines.JADE_PATH_PER_VERTEX !== perVertex) {
      this.defines.JADE_PATH_PER_VERTEX = perVertex;
      this.needsUpdate = true;
    }
  }

  /** The median length of the triangles' edges (mesh_vertices.cpp's median_edge). */
  static medianEdge(geometry) {
    const p = geometry.attributes.position, index = geometry.index;
    const corner = (i) => (index ? index.getX(i) : i);
    const count = index ? index.count : p.count;
    const edges = [];
    const a = new Vector3(), b = new Vector3();
    for (let i = 0; i + 2 < count; i += 3)
      for (let e = 0; e < 3; ++e) {
        a.fromBufferAttribute(p, corner(i + e));
        b.fromBufferAttribute(p, corner(i + ((e + 1) % 3)));
        edges.push(a.distanceTo(b));
      }
    if (edges.length === 0) return Infinity;
    edges.sort((x, y) => x - y);
    return edges[edges.length >> 1];
  }

  /**
   * The bound on the smallest variance Jade's renderer passes to choose_terms: strength × the
   * smallest t_m of any vertex and channel (the spread only adds to t).
   */
  static smallestVariance(extension, tm) {
    let smallest = Infinity;
    for (let i = 0; i < tm.count; ++i)
      for (let c = 0; c < 3; ++c) smallest = Math.min(smallest, tm.getComponent(i, c));
    return extension.strength * smallest;
  }

  setBounds(min, max) {
    const centre = new Vector3().addVectors(min, max).multiplyScalar(0.5);
    this.uniforms.jadeBounds.value.set(centre.x, centre.y, centre.z, 0.5 * min.distanceTo(max));
  }
}
