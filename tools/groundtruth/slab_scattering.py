#!/usr/bin/env python3
"""The scattered transmittance of a slab, by Monte Carlo: an independent, non-diffusion yardstick.

A slab of optical thickness τ behind smooth dielectric faces (relative index η), unit collimated
flux entering along its normal, isotropic scattering. One absorption-free random walk per τ
records after how many scattering events k each photon leaves through the far face; for a
single-scattering albedo a the transmittance that scattered at least once is Σ_{k≥1} a^k P_τ(k)
(and k = 0 is the ballistic e^{−τ}, a check). Used by transmission_study.py's `scattered` study.

  tools/groundtruth/.venv/bin/python tools/groundtruth/slab_scattering.py [--eta 1.5] [--out FILE.npz]
"""
import argparse

import numpy as np

TAUS = (0.05, 0.1, 0.2, 0.35, 0.5, 0.75, 1.0, 1.5, 2.0, 3.0, 4.0, 6.0, 8.0, 12.0, 16.0, 24.0)


def fresnel_inside(cos_i, eta):
    """Unpolarised reflectance from inside (index eta) out to index 1; 1 beyond the critical angle."""
    sin_t2 = eta * eta * (1 - cos_i * cos_i)
    cos_t = np.sqrt(np.maximum(0, 1 - sin_t2))
    rs = (eta * cos_i - cos_t) / (eta * cos_i + cos_t)
    rp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t)
    return np.where(sin_t2 >= 1, 1.0, 0.5 * (rs * rs + rp * rp))


def exit_histogram(tau, eta, photons=200000, kmax=4000, seed=1):
    """P(leaves through the far face after k scattering events), k = 0 … kmax."""
    rng = np.random.default_rng(seed)
    z, mu, k = np.zeros(photons), np.ones(photons), np.zeros(photons, dtype=np.int64)
    hist = np.zeros(kmax + 1)
    alive = np.arange(photons)
    while alive.size:
        zn = z[alive] + mu[alive] * -np.log(rng.random(alive.size))
        far, near = zn >= tau, zn <= 0
        inside = alive[~(far | near)]
        z[inside] = zn[~(far | near)]
        k[inside] += 1
        mu[inside] = rng.uniform(-1, 1, inside.size)
        gone = []
        for sel, face in ((far, tau), (near, 0.0)):
            hit = alive[sel]
            reflect = rng.random(hit.size) < fresnel_inside(np.abs(mu[hit]), eta)
            z[hit] = face
            mu[hit[reflect]] *= -1
            leave = hit[~reflect]
            if face == tau:
                np.add.at(hist, np.minimum(k[leave], kmax), 1.0)
            gone.append(leave)
        gone.append(alive[k[alive] > kmax])
        alive = np.setdiff1d(alive, np.concatenate(gone), assume_unique=True)
    return hist / photons


def table(eta=1.5):
    return np.array(TAUS), np.array([exit_histogram(t, eta) for t in TAUS])


def scattered_transmittance(taus, hists, tau, albedo):
    """Σ_{k≥1} albedo^k P_τ(k), interpolated in log τ (linear in τ below the first entry); per channel."""
    ks = np.arange(hists.shape[1])
    out = []
    for c in range(3):
        row = np.array([(h[1:] * np.clip(albedo[c], 0, 1) ** ks[1:]).sum() for h in hists])
        x = np.clip(tau[..., c], taus[0], taus[-1])
        v = np.interp(np.log(x), np.log(taus), row)
        out.append(np.where(tau[..., c] < taus[0], v * tau[..., c] / taus[0], v))
    return np.stack(out, -1)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--eta", type=float, default=1.5)
    ap.add_argument("--out", help="save the histograms (taus, hists) as .npz")
    a = ap.parse_args()
    taus, hists = table(a.eta)
    albedos = (0.6, 0.75, 0.9, 0.98, 1.0)
    print(f"slab behind smooth faces, eta {a.eta}: ballistic (check: e^-tau (1 - F0)) and scattered transmittance")
    f0 = ((a.eta - 1) / (a.eta + 1)) ** 2
    for t, h in zip(taus, hists):
        sc = [(h[1:] * al ** np.arange(1, h.size)).sum() for al in albedos]
        print(f"  tau {t:5.2f}: ballistic {h[0]:.4f} ({np.exp(-t) * (1 - f0):.4f}); scattered at albedo "
              + " ".join(f"{al:g}: {v:.4f}" for al, v in zip(albedos, sc)))
    if a.out:
        np.savez(a.out, taus=taus, hists=hists)


if __name__ == "__main__":
    main()
