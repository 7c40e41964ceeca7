"""scipy.optimize.least_squares(method='lm') (MINPACK lmder) with the analytic
Jacobian on the seed-000 network problem written by `cnclab_bench_lm prepare`.

    /usr/bin/python3 scripts/bench_lm_scipy.py DIR MAX_NFEV

Prints "seconds T sse S nfev N njev J". The network and parameter layout are
cnclab's (nn/mlp.hpp): 73-28-20-1, ReLU hidden, linear output; per layer W
(n_out x n_in, column-major) then b; residual = output - target.
"""
import argparse
import time

import numpy as np

SIZES = [73, 28, 20, 1]


def layers(w):
    out, off = [], 0
    for n_in, n_out in zip(SIZES[:-1], SIZES[1:]):
        W = w[off:off + n_in * n_out].reshape(n_in, n_out).T  # column-major n_out x n_in
        off += n_in * n_out
        b = w[off:off + n_out]
        off += n_out
        out.append((W, b))
    return out


def forward(w, x):
    acts = [x]
    ls = layers(w)
    for k, (W, b) in enumerate(ls):
        z = acts[-1] @ W.T + b
        acts.append(np.maximum(z, 0.0) if k + 1 < len(ls) else z)
    return acts


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("dir", help="folder written by `cnclab_bench_lm prepare`")
    parser.add_argument("max_nfev", type=int, help="function evaluations allowed")
    args = parser.parse_args()
    d, max_nfev = args.dir, args.max_nfev
    from scipy.optimize import least_squares  # after parsing: --help works without scipy

    x = np.fromfile(d + "/x.bin").reshape(-1, SIZES[0])
    y = np.fromfile(d + "/y.bin")
    w0 = np.fromfile(d + "/w0.bin")
    n = x.shape[0]

    def fun(w):
        return forward(w, x)[-1][:, 0] - y

    def jac(w):
        acts = forward(w, x)
        ls = layers(w)
        J = np.empty((n, w.size))
        offsets, off = [], 0
        for n_in, n_out in zip(SIZES[:-1], SIZES[1:]):
            offsets.append(off)
            off += (n_in + 1) * n_out
        delta = np.ones((n, 1))  # d output / d z_L (linear output)
        for k in range(len(ls) - 1, -1, -1):
            W, _ = ls[k]
            a_prev = acts[k]
            n_out, n_in = W.shape
            o = offsets[k]
            # column j n_out + i holds delta_i a_prev_j
            J[:, o:o + n_in * n_out] = (a_prev[:, :, None] * delta[:, None, :]).reshape(n, -1)
            J[:, o + n_in * n_out:o + (n_in + 1) * n_out] = delta
            if k > 0:
                delta = (delta @ W) * (acts[k] > 0)
        return J

    t0 = time.perf_counter()
    r = least_squares(fun, w0, jac=jac, method="lm", max_nfev=max_nfev,
                      xtol=1e-15, ftol=1e-15, gtol=1e-15)
    sec = time.perf_counter() - t0
    print(f"seconds {sec:.3f} sse {2 * r.cost:.9g} nfev {r.nfev} njev {r.njev}")


if __name__ == "__main__":
    main()
