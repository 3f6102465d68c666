// filament.glsl - the Filament mode's subsurface term: the subsurface shading model of Google's
// Filament renderer (google/filament, shaders/src/shading_model_subsurface.fs; the "Subsurface
// model" of its Materials documentation), written anew from the published formula. A peer to
// compare Jade with (docs/peers.md), not part of Jade's own shading.
//
// Per light, with NoL = saturate(N·L), Fd = k_d/π (Filament's default Lambert diffuse) and Fr the
// specular lobe (GGX, Smith height-correlated V, Schlick F, as mesh.frag's for every mode):
//   (Fd + Fr) · NoL · visibility                                 the surface BRDF, shadowed
// + subsurfaceColor · mix(back, 1, forward) · (1 − thickness) / π   the BTDF, not shadowed
//   forward = 2^{p · (saturate(V·(−L)) − 1)}                     a spherical Gaussian for pow(V·(−L), p)
//   back    = saturate(NoL · thickness + (1 − thickness)) / 2    a wrap that widens as the part thins
// all times the light's irradiance E. p = subsurfacePower. Filament leaves the BTDF unshadowed
// ("TODO: apply occlusion to the transmitted light" in its source); so does this mode.
// Deviations: no multiple-scattering energy compensation of Fr (Jade's lobe has none in any
// mode), and `thickness` and `subsurfaceColor` come from Jade's bake and the medium
// (jade::filament_subsurface) instead of an artist's map and colour picker.
#ifndef JADE_FILAMENT_GLSL
#define JADE_FILAMENT_GLSL

// Filament's `thickness` at a vertex with baked thickness t̄ (mesh units): a constant when
// FrameData::subsurface_thickness.y ≥ 0, else t̄ · x clamped to [0, 1]. Evaluated per vertex
// (mesh.vert) and interpolated, as a thickness map would be: interpolating t̄ itself overflowed
// for values near FLT_MAX at MSAA samples outside the triangle and lit such a part as the
// thinnest. A NaN counts as thick.
float filament_thickness(float baked)
{
    vec4 m = data.subsurface_thickness;
    float t = baked * m.x;
    return m.y >= 0.0 ? m.y : t < 1.0 ? max(t, 0.0) : 1.0;
}

// The BTDF above, per unit irradiance: what Filament adds for light l (unit, towards the light)
// seen from v (unit, towards the eye) at normal n.
vec3 filament_subsurface(vec3 n, vec3 v, vec3 l, float thickness)
{
    float no_l = clamp(dot(n, l), 0.0, 1.0), p = data.subsurface.w;
    float forward = exp2(clamp(dot(v, -l), 0.0, 1.0) * p - p);
    float back = clamp(no_l * thickness + (1.0 - thickness), 0.0, 1.0) * 0.5;
    return data.subsurface.rgb * (mix(back, 1.0, forward) * (1.0 - thickness) * (1.0 / JADE_PI));
}

#endif
