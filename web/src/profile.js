// The scattering profile's median radius, as Jade's CurvatureLut::length_scale (the mean over
// the channels of radius_for_tail(0.5), engine/src/bake/profile.cpp): the reach that sets the
// shadow filter's spacing (shadow_spacing in engine/src/shading/frame.cpp).

// tail (profile.cpp): 1 − cdf(r) of one channel's profile, from the extension's profile object.
function tail(p, r) {
  if (p.kind === 'burley') {
    const x = r / p.d;
    return 0.25 * Math.exp(-x) + 0.75 * Math.exp(-x / 3);
  }
  if (p.kind === 'dipole') {
    const s = p.sigmaTr, dr = Math.hypot(r, p.zR), dv = Math.hypot(r, p.zV);
    const norm = 1 + Math.exp(-s * (p.zV - p.zR));
    return (p.zR / dr * Math.exp(-s * (dr - p.zR)) + p.zV / dv * Math.exp(-s * (dv - p.zR))) / norm;
  }
  if (p.kind === 'gaussians') {
    let t = 0;
    p.weights.forEach((w, k) => { if (w > 0) t += w * Math.exp(-r * r / (2 * p.variances[k])); });
    return t;
  }
  throw new Error(`JADE_materials_translucency: profile kind '${p.kind}' is not burley, dipole or gaussians`);
}

// length_scale (profile.cpp): where the search starts.
function start(p) {
  if (p.kind === 'burley') return p.d;
  if (p.kind === 'dipole') return p.zV;
  return Math.sqrt(Math.max(...p.variances));
}

// radius_for_tail (profile.cpp): the radius beyond which a share t of the profile lies, bisected.
function radiusForTail(p, t) {
  let lo = 0, hi = start(p);
  if (!(hi > 0)) return 0;
  while (tail(p, hi) > t) lo = hi, hi *= 2;
  for (let i = 0; i < 200 && hi - lo > 1e-15 * hi; ++i) {
    const mid = 0.5 * (lo + hi);
    if (tail(p, mid) > t) lo = mid; else hi = mid;
  }
  return hi;
}

/** The mean over the channels of the profiles' median radii (length units of the bake). */
export function profileReach(profiles) {
  if (!Array.isArray(profiles) || profiles.length !== 3)
    throw new Error('JADE_materials_translucency: profiles is not three channel profiles');
  return profiles.reduce((sum, p) => sum + radiusForTail(p, 0.5), 0) / 3;
}
