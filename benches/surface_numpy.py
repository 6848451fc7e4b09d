#!/usr/bin/env python3
"""The numpy counterpart of the criterion benchmark `surface/generate + radial PSD + moments NxN`
(benches/surface.rs), for a side-by-side comparison on the same machine.

Same three steps on the same grid and spectrum (PSD (3.16) with (3.17), a 2 um square scan):
  1. generate: Gaussian white noise, forward real FFT, filter sqrt(C(|q|)), inverse real FFT,
     mean removed and scaled to sigma_rms;
  2. forward FFT of the map and its periodogram;
  3. radial PSD by np.bincount over rings of width 2 pi / L, and the moments m0, m2, m4.

One thread (OMP/OPENBLAS/MKL_NUM_THREADS=1 are set before numpy is imported; numpy's pocketfft
is single-threaded anyway). The analysis transform is `rfft2` (half the work of a complex one)
unless `--fft2` is given (the full complex `fft2`, as a plain script would write it).

    python3 benches/surface_numpy.py [--fft2] [--repeat R] [N ...]

prints the median, min and max wall time per call [ms] of R calls (default 30) for each N.
"""

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_var] = "1"

import argparse  # noqa: E402
import statistics  # noqa: E402
import time  # noqa: E402

import numpy as np  # noqa: E402

RMS = 1.45e-9  # sigma_rms [m], (3.17)
LC = 20.1e-9  # L_c [m], (3.17)
EXPONENT = 3.28  # n, (3.17)
Q0 = 1.0e8  # cut-off q0 [1/m], (3.17)
LENGTH = 2e-6  # scan size [m]


def abc_psd(q):
    """Shape of (3.16) (the normalisation cancels in the rescaling to sigma_rms)."""
    return np.exp(-q / Q0) * (1.0 + (LC * q) ** 2) ** (-EXPONENT)


def pipeline(n, rng, full_fft):
    two_pi = 2.0 * np.pi
    qx = two_pi * np.fft.fftfreq(n, d=LENGTH / n)
    qx_half = two_pi * np.fft.rfftfreq(n, d=LENGTH / n)
    # 1. generate
    noise = rng.standard_normal((n, n))
    spec = np.fft.rfft2(noise)
    q_half = np.sqrt(qx[:, None] ** 2 + qx_half[None, :] ** 2)
    filt = np.sqrt(abc_psd(q_half))
    filt[0, 0] = 0.0
    spec *= filt
    z = np.fft.irfft2(spec, s=(n, n))
    z -= z.mean()
    z *= RMS / z.std()
    # 2. periodogram
    if full_fft:
        p = np.abs(np.fft.fft2(z)) ** 2 / float(n * n) ** 2
        q2 = qx[:, None] ** 2 + qx[None, :] ** 2
        w = None
    else:
        p = np.abs(np.fft.rfft2(z)) ** 2 / float(n * n) ** 2
        q2 = qx[:, None] ** 2 + qx_half[None, :] ** 2
        # Weight 2 for the columns whose mirror image is not stored.
        w = np.full(p.shape[1], 2.0)
        w[0] = 1.0
        if n % 2 == 0:
            w[-1] = 1.0
        p = p * w[None, :]
    p[0, 0] = 0.0
    # 3. radial PSD (bincount) and moments
    q = np.sqrt(q2)
    dq = two_pi / LENGTH
    ring = np.rint(q / dq).astype(np.int64).ravel()
    n_rings = n // 2
    ones = np.ones_like(p) if w is None else np.broadcast_to(w[None, :], p.shape)
    count = np.bincount(ring, weights=ones.ravel(), minlength=n_rings + 1)
    sum_c = np.bincount(ring, weights=p.ravel(), minlength=n_rings + 1)
    sum_q = np.bincount(ring, weights=(q * ones).ravel(), minlength=n_rings + 1)
    keep = slice(1, n_rings + 1)
    scale = LENGTH * LENGTH / (4.0 * np.pi**2)
    with np.errstate(invalid="ignore", divide="ignore"):
        radial_q = sum_q[keep] / count[keep]
        radial_c = scale * sum_c[keep] / count[keep]
    m0 = p.sum()
    m2 = 0.5 * (p * q2).sum()
    m4 = 0.375 * (p * q2 * q2).sum()
    return radial_q, radial_c, (m0, m2, m4)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("sizes", nargs="*", type=int, default=[256, 1024])
    ap.add_argument("--repeat", type=int, default=30)
    ap.add_argument("--fft2", action="store_true", help="complex fft2 for the analysis transform")
    args = ap.parse_args()
    rng = np.random.default_rng(1)
    print(f"numpy {np.__version__}, analysis transform {'fft2' if args.fft2 else 'rfft2'}")
    for n in args.sizes:
        _, _, (m0, m2, m4) = pipeline(n, rng, args.fft2)  # warm-up, and a sanity check
        assert abs(np.sqrt(m0) / RMS - 1.0) < 1e-9, m0
        times = []
        for _ in range(args.repeat if n <= 2048 else max(3, args.repeat // 10)):
            t0 = time.perf_counter()
            pipeline(n, rng, args.fft2)
            times.append(time.perf_counter() - t0)
        med = statistics.median(times) * 1e3
        print(
            f"generate + radial PSD + moments {n}x{n}: median {med:.2f} ms "
            f"(min {min(times) * 1e3:.2f}, max {max(times) * 1e3:.2f}, {len(times)} calls; "
            f"{med * 1e6 / (n * n):.2f} ns/point), m2 = {m2:.4e}, m4 = {m4:.4e}"
        )


if __name__ == "__main__":
    main()
