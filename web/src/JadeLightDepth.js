// JadeLightDepth: the depths of the first surfaces along each light, by depth peeling (Jade's
// LightDepth, engine/src/shading/light_depth.cpp, shaders/light_depth.frag): one tile a light, an
// orthographic box that holds the bounding sphere for a directional light, a perspective cone
// from a point light (orthographic_tile, perspective_tile). Four layers for a light that may
// shine through the object (the transmission term's path, transmitter_path in
// transmission.glsl), two for one that only casts shadows (shadow.glsl reads layers 0 and 1).
// Each tile is peeled into scratch targets (one layer each) and packed into one RGBA float
// texture (layers 0 … 3, 1 where there is none), Jade's atlas column.
import {
  Color, DoubleSide, FloatType, MathUtils, Matrix4, Mesh, NearestFilter, OrthographicCamera, PerspectiveCamera,
  PlaneGeometry, RGBAFormat, Scene, ShaderMaterial, Vector2, Vector3, Vector4, WebGLRenderTarget,
} from 'three';

export const kLayers = 4;   // LightDepth::kLayers
export const kMaxTiles = 4; // JADE_MAX_LIGHT_DEPTH_TILES
const kMargin = 1.1;        // LightDepth::kMargin: a tile spans 1.1 bounding radii each side
export const kPointMinDistance = 1.05;  // LightDepth::kPointMinDistance: nearer, a point light gets no tile

// light_depth.frag: layer k keeps the nearest surface beyond layer k − 1 at the same texel (by
// the depth buffer's values, kept in .g for the next pass) and writes in .r what the shading
// subtracts: the window depth of an orthographic tile (linear), the distance from the light of a
// perspective one, (|p − origin| − near) / range. kPeelMargin as there.
const peelVertex = /* glsl */ `
varying vec3 vWorld;
void main()
{
    vec4 world = modelMatrix * vec4(position, 1.0);
    vWorld = world.xyz;
    gl_Position = projectionMatrix * viewMatrix * world;
}
`;
const peelFragment = /* glsl */ `
uniform sampler2D previous;
uniform float layer;
uniform vec4 origin;  // world position of a point light, w = 1; w = 0: orthographic
uniform vec2 depth;   // near, range
varying vec3 vWorld;
const float kPeelMargin = 1.0 / 1048576.0;
void main()
{
    if (layer > 0.5 && gl_FragCoord.z <= texelFetch(previous, ivec2(gl_FragCoord.xy), 0).g + kPeelMargin) discard;
    float linear = (length(vWorld - origin.xyz) - depth.x) / depth.y;
    gl_FragColor = vec4(origin.w > 0.5 ? linear : gl_FragCoord.z, gl_FragCoord.z, 0.0, 1.0);
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
      uniforms: { previous: { value: null }, layer: { value: 0 }, origin: { value: new Vector4() },
                  depth: { value: new Vector2() } },
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
    this.perspective = new PerspectiveCamera();
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
   * Tile `k` of `mesh` for `light` ({point: false, vector: towards the light} or {point: true,
   * vector: its position}, world space), `layers` deep, holding the bounding sphere (world
   * centre, radius) as orthographic_tile / perspective_tile do; peeled again only when something
   * changed. Returns {texture, viewProjection (world → the tile's clip space), origin (the point
   * light's world position, or null), near, range, texel (world units across a texel; per unit
   * of distance from a point light)}: Jade's LightTile.
   */
  update(renderer, k, mesh, light, centre, radius, layers) {
    const key = [light.point, light.vector.toArray(), centre.toArray(), radius, layers, mesh.matrixWorld.elements,
                 mesh.geometry.uuid].join();
    const tile = this.tiles[k] ??= { target: floatTarget(this.size), viewProjection: new Matrix4(), key: '' };
    let camera;
    const up = (dir) => (Math.abs(dir.y) < 0.9 ? new Vector3(0, 1, 0) : new Vector3(1, 0, 0));
    if (!light.point) {
      const l = light.vector.clone().normalize();
      const r = Math.max(radius, 1e-20) * kMargin;
      camera = this.camera;
      camera.left = -r, camera.right = r, camera.top = r, camera.bottom = -r, camera.near = r, camera.far = 3 * r;
      camera.up.copy(up(l));
      camera.position.copy(centre).addScaledVector(l, 2 * r);
      Object.assign(tile, { origin: null, near: r, range: 2 * r, texel: (2 * r) / this.size });
    } else {
      const axis = centre.clone().sub(light.vector), d = axis.length(), r = kMargin * radius;
      const dir = axis.divideScalar(d);
      const half = Math.min(Math.asin(Math.min(radius / d, 1)) * kMargin, MathUtils.degToRad(85));
      const near = Math.max(d - r, 0.5 * (d - radius)), far = d + r;
      camera = this.perspective;
      camera.fov = MathUtils.radToDeg(2 * half), camera.aspect = 1, camera.near = near, camera.far = far;
      camera.up.copy(up(dir));
      camera.position.copy(light.vector);
      Object.assign(tile, { origin: light.vector.clone(), near, range: far - near,
                            texel: (2 * Math.tan(half)) / this.size });
    }
    if (tile.key === key) return { texture: tile.target.texture, ...tile };
    tile.key = key;
    camera.lookAt(centre);
    camera.updateMatrixWorld(true);
    camera.updateProjectionMatrix();
    tile.viewProjection.multiplyMatrices(camera.projectionMatrix, camera.matrixWorldInverse);
    this.peel.uniforms.origin.value.set(...(tile.origin ? tile.origin.toArray() : [0, 0, 0]), tile.origin ? 1 : 0);
    this.peel.uniforms.depth.value.set(tile.near, tile.range);

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
