// The scattering profile's radii that the shading reads: the soft shadow's kernel as Jade's
// soft_shadow_kernel (engine/src/shading/frame.cpp; burley_shapes and burley_sample_radius in
// engine/src/shading/burley_diffusion.cpp), from radius_for_tail (engine/src/bake/profile.cpp).

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

// burley_sample_radius: the radius where the Burley profile of shape d holds a share u, the
// inverse of 1 − ¼e^{−r/d} − ¾e^{−r/(3d)}, bisected.
function burleySampleRadius(u, d) {
  return radiusForTail({ kind: 'burley', d }, 1 - u);
}

export const kSoftShadowTaps = 16;

/**
 * The soft shadow's kernel: the Burley shape d per channel (the profile's own d, or the Burley d
 * of the same median radius) and the widest of them, and the 16 tap radii of its inverse CDF at
 * (i + ½)/16 (length units of the bake). shape[3] = 0 turns the soft shadow off.
 */
export function softShadowKernel(profiles) {
  if (!Array.isArray(profiles) || profiles.length !== 3)
    throw new Error('JADE_materials_translucency: profiles is not three channel profiles');
  const median = burleySampleRadius(0.5, 1);
  const shape = profiles.map((p) => (p.kind === 'burley' ? p.d : radiusForTail(p, 0.5) / median));
  const sampled = Math.max(...shape);
  if (!(sampled > 0) || !Number.isFinite(sampled))
    return { shape: [0, 0, 0, 0], radii: new Array(kSoftShadowTaps).fill(0), median: 0 };
  const radii = Array.from({ length: kSoftShadowTaps }, (_, i) => burleySampleRadius((i + 0.5) / kSoftShadowTaps, sampled));
  return { shape: [...shape.map((d) => Math.max(d, 1e-30)), sampled], radii, median: burleySampleRadius(0.5, sampled) };
}
