// JadeLightPaths: the depths of the first four surfaces along one directional light, by depth
// peeling (Jade's LightDepth, engine/src/shading/light_depth.cpp, shaders/light_depth.frag), for
// the transmission term's path through the object from where the light enters
// (transmitter_path in transmission.glsl: the longer of it and the baked thickness).
// Jade tiles up to four transmitting lights; this class serves one, the first directional light
// that may shine through the object towards the eye (the others use the thickness alone).
import {
  Color, DoubleSide, FloatType, Matrix4, Mesh, NearestFilter, OrthographicCamera, RGBAFormat, Scene, ShaderMaterial,
  Vector3, WebGLRenderTarget,
} from 'three';

export const kLayers = 4;  // LightDepth::kLayers
const kMargin = 1.1;       // LightDepth::kMargin: the tile spans 1.1 bounding radii each side

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

export class JadeLightPaths {
  constructor(size = 512) {
    this.size = size;  // RendererOptions::light_depth_size
    this.targets = [];
    for (let k = 0; k < kLayers; ++k) {
      this.targets.push(new WebGLRenderTarget(size, size, {
        type: FloatType, format: RGBAFormat, minFilter: NearestFilter, magFilter: NearestFilter,
        depthBuffer: true, generateMipmaps: false,
      }));
    }
    this.material = new ShaderMaterial({
      uniforms: { previous: { value: null }, layer: { value: 0 } },
      vertexShader: peelVertex,
      fragmentShader: peelFragment,
      side: DoubleSide,  // every surface along the light, facing it or not
    });
    this.camera = new OrthographicCamera();
    this.scene = new Scene();
    this.proxy = new Mesh(undefined, this.material);
    this.proxy.matrixAutoUpdate = false;
    this.proxy.frustumCulled = false;
    this.scene.add(this.proxy);
    this.viewProjection = new Matrix4();
    this.key = '';
  }

  /**
   * Peels `mesh` along the directional light towards `direction` (world space), its tile holding
   * the bounding sphere (world centre, radius) as orthographic_tile does. Skips the passes when
   * nothing changed since the last call.
   */
  update(renderer, mesh, direction, centre, radius) {
    const l = direction.clone().normalize();
    const r = Math.max(radius, 1e-20) * kMargin;
    const key = [l.toArray(), centre.toArray(), r, mesh.matrixWorld.elements, mesh.geometry.uuid].join();
    if (key === this.key) return;
    this.key = key;
    const camera = this.camera;
    camera.left = -r, camera.right = r, camera.top = r, camera.bottom = -r, camera.near = r, camera.far = 3 * r;
    camera.up.copy(Math.abs(l.y) < 0.9 ? new Vector3(0, 1, 0) : new Vector3(1, 0, 0));
    camera.position.copy(centre).addScaledVector(l, 2 * r);
    camera.lookAt(centre);
    camera.updateMatrixWorld(true);
    camera.updateProjectionMatrix();
    this.viewProjection.multiplyMatrices(camera.projectionMatrix, camera.matrixWorldInverse);
    this.range = 2 * r;  // depth.y: far − near

    this.proxy.geometry = mesh.geometry;
    this.proxy.matrixWorld.copy(mesh.matrixWorld);
    const target = renderer.getRenderTarget(), autoClear = renderer.autoClear;
    const clearColor = renderer.getClearColor(new Color()), clearAlpha = renderer.getClearAlpha();
    renderer.autoClear = true;
    renderer.setClearColor(0xffffff, 1);  // depth 1: no surface
    for (let k = 0; k < kLayers; ++k) {
      this.material.uniforms.layer.value = k;
      this.material.uniforms.previous.value = k > 0 ? this.targets[k - 1].texture : null;
      renderer.setRenderTarget(this.targets[k]);
      renderer.render(this.scene, camera);
    }
    renderer.setRenderTarget(target);
    renderer.setClearColor(clearColor, clearAlpha);
    renderer.autoClear = autoClear;
  }

  dispose() {
    for (const t of this.targets) t.dispose();
    this.material.dispose();
  }
}
