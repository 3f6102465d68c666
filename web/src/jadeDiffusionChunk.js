// The transmission's diffused part for JadeTranslucentMaterial's vertex shader: Jade's
// diffused_light (shaders/include/transmission.glsl) tap for tap, a gather of the two-boundary
// diffusion dipole over a light's depth tile (docs/fidelity.md, "Light through thin parts"). It
// reads the uniforms and helpers of jadeShaderChunks.js's commonChunk (the tiles, jadeLightPath,
// jadeShape, jadeSpecular, the jadeDipole* constants).
export const diffusionChunk = /* glsl */ `
// mean_boundary_transmittance (shading.glsl): jadeBoundaryTransmittance averaged over the light's
// projected area, 1 - F0 - (grazing - F0)/21.
float jadeMeanBoundaryTransmittance()
{
    float f0 = jadeSpecular.x, grazing = max(1.0 - jadeSpecular.y, f0);
    return 1.0 - f0 - (grazing - f0) * (1.0 / 21.0);
}

// plane_flux (transmission.glsl): the flux through the surface at x (normal n) of a point source
// q = base + along * depth (per channel), per unit power, x's tangent plane an extrapolated
// boundary (q's image 2 z_b beyond it), in a medium of extinction sigma.
vec3 jadePlaneFlux(vec3 x, vec3 n, vec3 base, vec3 along, vec3 depth, vec3 zb, vec3 sigma)
{
    vec3 d0 = x - base;
    float nd = dot(n, d0), na = dot(n, along), da = dot(d0, along), dd = dot(d0, d0);
    vec3 r2 = max(vec3(dd) - 2.0 * depth * da + depth * depth, vec3(1e-30));
    vec3 a = max(vec3(nd) - depth * na, vec3(0.0));
    vec3 av = a + 2.0 * zb;
    vec3 v2 = r2 - a * a + av * av;
    vec3 r = sqrt(r2), v = sqrt(v2);
    return a * (1.0 + sigma * r) * exp(-sigma * r) / (r2 * r) + av * (1.0 + sigma * v) * exp(-sigma * v) / (v2 * v);
}

// dipole_exit (transmission.glsl): what enters at s (the light travelling along \`along\`, unit)
// and leaves through the surface at x, per unit flux: the dipole with both boundaries (the
// source z_r inside and its negative image z_r + 2 z_b outside the entry, each with its image
// beyond x's plane).
vec3 jadeDipoleExit(vec3 x, vec3 n, vec3 s, vec3 along, vec3 sigma)
{
    vec3 zr = jadeDipoleReal, zb = jadeDipoleBoundary;
    vec3 f = jadePlaneFlux(x, n, s, along, zr, zb, sigma) - jadePlaneFlux(x, n, s, along, -(zr + 2.0 * zb), zb, sigma);
    return jadeDipoleAlbedo.rgb * max(f, vec3(0.0));
}

// light_entry (transmission.glsl): where the light of tile t that passes \`tap\` (a point in the
// plane through x across the light; l towards the light, unit) first meets the object: layer 0's
// depth (1 where the line meets nothing) and the point.
float jadeLightEntry(sampler2D layers, JadeTile t, vec3 tap, vec3 l, out vec3 entry)
{
    float size = t.info.x;
    vec3 p = jadeTileCoords(t, tap);
    ivec2 texel = clamp(ivec2(p.xy * size), ivec2(0), ivec2(int(size) - 1));
    bool inside = all(greaterThanEqual(p.xy, vec2(0.0))) && all(lessThan(p.xy, vec2(1.0)));
    float first = inside ? texelFetch(layers, texel, 0).x : 1.0;
    entry = tap + l * ((p.z - first) * t.depth.y);
    return first;
}

// diffused_light (transmission.glsl): the light of one transmitter (towards it l, unit; its
// irradiance e at \`position\`) that entered the object where the light first meets it (layer 0
// of its tile) and diffused to \`position\` (normal n, unit): its exitance there. 24 taps on a
// golden-angle spiral in the plane through the point across the light, at radii spaced evenly in
// ln r from a twentieth of the light's path out to that path plus three diffusion lengths (within
// half the tile's width), faded out from n.l = 0 to kFacingCut; the pass that reads the taps finds the
// share of the disk the light meets, the part's width W in the transverse buckling B^2 = 2(pi/(W + 2 z_b))^2 added to
// sigma_tr^2. The spiral starts from the world's axes as Jade's (world space there, view space
// here: world_x, world_y are the world's x and y in view space), so that the taps are Jade's.
const int kJadeDiffusionTaps = 24;  // kDiffusionTaps
const float kJadeFacingCut = 0.2;   // kFacingCut

// gather_tap (transmission.glsl): tap i of \`count\` and its radius r, on the golden-angle spiral
// across the light, radii evenly spaced in ln r from inner (span = ln(reach/inner)).
vec3 jadeDiffusionTap(int i, int count, vec3 position, float inner, float span, vec3 side, vec3 up, float turn, out float r)
{
    r = inner * exp(span * (float(i) + 0.5) / float(count));
    float angle = float(i) * 2.39996323 + turn;
    return position + r * (cos(angle) * side + sin(angle) * up);
}

vec3 jadeDiffusedLight(sampler2D layers, JadeTile t, vec3 l, vec3 e, vec3 position, vec3 n, float turn, float path)
{
    float facing = clamp(1.0 - dot(n, l) / kJadeFacingCut, 0.0, 1.0);
    if (facing == 0.0) return vec3(0.0);
    vec3 world_y = mat3(viewMatrix)[1], world_x = mat3(viewMatrix)[0];
    vec3 side = normalize(abs(dot(l, world_y)) < 0.9 ? cross(l, world_y) : cross(l, world_x));
    vec3 up = cross(l, side), s;
    // The tile's width at this point: the gather stays inside it.
    float width = t.depth.z * t.info.x * (t.info.z > 1.5 ? length(position - t.origin) : 1.0);
    float reach = max(min(path + jadeDipoleSigma.w, 0.5 * width), 1e-30);
    float inner = max(0.05 * path, 1e-3 * reach), span = log(reach / inner);
    float covered = 0.0, total = 0.0;
    float r;
    vec4 entries[kJadeDiffusionTaps];  // where each tap enters (xyz), its ring's weight r^2 (w; 0: none)
    for (int i = 0; i < kJadeDiffusionTaps; ++i) {
        float first = jadeLightEntry(layers, t, jadeDiffusionTap(i, kJadeDiffusionTaps, position, inner, span, side, up, turn, r), l, s);
        entries[i] = vec4(s, first < 1.0 ? r * r : 0.0);
        covered += entries[i].w;
        total += r * r;
    }
    vec3 zb = jadeDipoleBoundary;
    vec3 buckling = min(JADE_PI / max(vec3(2.0 * reach * sqrt(covered / total)) + 2.0 * zb, vec3(1e-30)), vec3(1e18));
    vec3 sigma_tr = min(jadeDipoleSigma.rgb, vec3(1e18));
    vec3 sigma = sqrt(sigma_tr * sigma_tr + 2.0 * buckling * buckling);
    vec3 sum = vec3(0.0);
    for (int i = 0; i < kJadeDiffusionTaps; ++i) {
        vec3 d = position - entries[i].xyz;
        float out_share = max(dot(n, d), 0.0) * inversesqrt(max(dot(d, d), 1e-30));
        sum += (out_share * entries[i].w) * jadeDipoleExit(position, n, entries[i].xyz, -l, sigma);
    }
    float entry = jadeShape.w > 0.0 ? jadeMeanBoundaryTransmittance() : 1.0;
    return (2.0 * JADE_PI * span / float(kJadeDiffusionTaps) * entry * jadeDipoleAlbedo.w * facing) * sum * e;
}
`;
