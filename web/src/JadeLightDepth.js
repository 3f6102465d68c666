// JadeLightDepth: the depths of the first surfaces along each directional light, by depth peeling
// (Jade's LightDepth, engine/src/shading/light_depth.cpp, shaders/light_depth.frag): one tile a
// light, an orthographic box that holds the bounding sphere. Four layers for a light that may
// shine through the object (the transmission term's path, transmitter_path in
// transmission.glsl), two for one that only casts shadows (shadow.glsl reads layers 0 and 1).
// Each tile is peeled into scratch targets (one layer each) and packed into one RGBA float
// texture (layers 0 … 3, 1 where there is none), Jade's atlas column.
import {
  Color, DoubleSide, FloatType, Matrix4, Mesh, NearestFilter, OrthographicCamera, PlaneGeometry, RGBAFormat, Scene,
  ShaderMaterial, Vector3, WebGLRenderTarget,
} from 'three';

export const kLayers = 4;   // LightDepth::kLayers
export const kMaxTiles = 4; // JADE_MAX_LIGHT_DEPTH_TILES
const kMargin = 1.1;        // LightDepth::kMargin: a tile spans 1.1 bounding radii each side

// light_depth.frag: layer k keeps the nearest surface beyond layer k − 1 at the same texel and
// writes its window depth (linear: the tile is orthographic). kPeelMargin as there.
const peelVertex = /* glsl */ `
void main() { gl_Position = projectionMatrix * modelViewMatrix * vec4(position, 1.0); }
`;
const peelFragment = /* glsl */ `
uniform sampler2D previous;
uniform float layer;
const float kPeelMargin = 1.0 / 1048576.0;
void main()
{
    if (layer > 0.5 && gl_FragCoord.z <= texelFetch(previous, ivec2(gl_FragCoord.xy), 0).r + kPeelMargin) discard;
    gl_FragColor = vec4(gl_FragCoord.z);
}
`;
// The layers into one texel: layers beyond `count` are 1 (no surface).
const packVertex = /* glsl */ `
void main() { gl_Position = vec4(position.xy, 0.0, 1.0); }
`;
const packFragment = /* glsl */ `
uniform sampler2D layer0;
uniform sampler2D layer1;
uniform sampler2D layer2;
uniform sampler2D layer3;
uniform float count;
void main()
{
    ivec2 at = ivec2(gl_FragCoord.xy);
    gl_FragColor = vec4(texelFetch(layer0, at, 0).r, count > 1.5 ? texelFetch(layer1, at, 0).r : 1.0,
                        count > 2.5 ? texelFetch(layer2, at, 0).r : 1.0, count > 3.5 ? texelFetch(layer3, at, 0).r : 1.0);
}
`;

const floatTarget = (size) => new WebGLRenderTarget(size, size, {
  type: FloatType, format: RGBAFormat, minFilter: NearestFilter, magFilter: NearestFilter, depthBuffer: true,
  generateMipmaps: false,
});

export class JadeLightDepth {
  constructor(size = 512) {
    this.size = size;  // RendererOptions::light_depth_size
    this.scratch = Array.from({ length: kLayers }, () => floatTarget(size));
    this.tiles = [];   // per tile: {target, viewProjection, range, key}
    this.peel = new ShaderMaterial({
      uniforms: { previous: { value: null }, layer: { value: 0 } },
      vertexShader: peelVertex,
      fragmentShader: peelFragment,
      side: DoubleSide,  // every surface along the light, facing it or not
    });
    this.pack = new ShaderMaterial({
      uniforms: { layer0: { value: null }, layer1: { value: null }, layer2: { value: null }, layer3: { value: null },
                  count: { value: kLayers } },
      vertexShader: packVertex,
      fragmentShader: packFragment,
      depthTest: false,
      depthWrite: false,
    });
    this.camera = new OrthographicCamera();
    this.scene = new Scene();
    this.proxy = new Mesh(undefined, this.peel);
    this.proxy.matrixAutoUpdate = false;
    this.proxy.frustumCulled = false;
    this.scene.add(this.proxy);
    this.packScene = new Scene();
    const quad = new Mesh(new PlaneGeometry(2, 2), this.pack);
    quad.frustumCulled = false;
    this.packScene.add(quad);
  }

  /**
   * Tile `k` of `mesh` along the directional light towards `direction` (world space), `layers`
   * deep, its box holding the bounding sphere (world centre, radius) as orthographic_tile does;
   * peeled again only when something changed. Returns {texture, viewProjection, range, texel}:
   * world → the tile's clip space, its depth range and texel size in world units.
   */
  update(renderer, k, mesh, direction, centre, radius, layers) {
    const l = direction.clone().normalize();
    const r = Math.max(radius, 1e-20) * kMargin;
    const key = [l.toArray(), centre.toArray(), r, layers, mesh.matrixWorld.elements, mesh.geometry.uuid].join();
    const tile = this.tiles[k] ??= { target: floatTarget(this.size), viewProjection: new Matrix4(), key: '' };
    tile.range = 2 * r;  // depth.y: far − near
    tile.texel = (2 * r) / this.size;  // depth.z
    if (tile.key === key) return { texture: tile.target.texture, ...tile };
    tile.key = key;
    const camera = this.camera;
    camera.left = -r, camera.right = r, camera.top = r, camera.bottom = -r, camera.near = r, camera.far = 3 * r;
    camera.up.copy(Math.abs(l.y) < 0.9 ? new Vector3(0, 1, 0) : new Vector3(1, 0, 0));
    camera.position.copy(centre).addScaledVector(l, 2 * r);
    camera.lookAt(centre);
    camera.updateMatrixWorld(true);
    camera.updateProjectionMatrix();
    tile.viewProjection.multiplyMatrices(camera.projectionMatrix, camera.matrixWorldInverse);

    this.proxy.geometry = mesh.geometry;
    this.proxy.matrixWorld.copy(mesh.matrixWorld);
    const target = renderer.getRenderTarget(), autoClear = renderer.autoClear;
    const clearColor = renderer.getClearColor(new Color()), clearAlpha = renderer.getClearAlpha();
    renderer.autoClear = true;
    renderer.setClearColor(0xffffff, 1);  // depth 1: no surface
    for (let layer = 0; layer < layers; ++layer) {
      this.peel.uniforms.layer.value = layer;
      this.peel.uniforms.previous.value = layer > 0 ? this.scratch[layer - 1].texture : null;
      renderer.setRenderTarget(this.scratch[layer]);
      renderer.render(this.scene, camera);
    }
    for (let layer = 0; layer < kLayers; ++layer) this.pack.uniforms[`layer${layer}`].value = this.scratch[layer].texture;
    this.pack.uniforms.count.value = layers;
    renderer.setRenderTarget(tile.target);
    renderer.render(this.packScene, camera);
    renderer.setRenderTarget(target);
    renderer.setClearColor(clearColor, clearAlpha);
    renderer.autoClear = autoClear;
    return { texture: tile.target.texture, ...tile };
  }

  dispose() {
    for (const t of [...this.scratch, ...this.tiles.map((tile) => tile.target)]) t.dispose();
    this.peel.dispose();
    this.pack.dispose();
  }
}
