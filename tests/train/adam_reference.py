"""PyTorch's numbers for tests/train/adam_test.cpp: torch.optim.Adam (float64,
the single-tensor path) training a 5-6-4-1 ReLU network with dropout after
both hidden layers on Friedman #1 data, with the same data, initial weights,
dropout masks and batches as the test, printed with 17 significant digits
as C++ initialisers: the final parameters in cnclab's flat layout (per layer
W column-major, then b) and the last epoch's mean mini-batch loss.

Everything is a closed form shared with the test (no random numbers):
  x_js = frac((5 s + j + 1) * 0.6180339887498949), j = 0..4, s = 0..59
  y_s  = (10 sin(pi x_0 x_1) + 20 (x_2 - 0.5)^2 + 10 x_3 + 5 x_4) / 10
         (Friedman 1991, Eq. 1 without noise, scaled by 1/10)
  w_k  = 0.5 sin(k + 1), k = 0..68
  dropout at update t (1, 2, ...), layer l (1, 2), unit i, sample s:
         kept (mask 1 / 0.8 = 1.25) unless (131 t + 31 l + 17 i + 7 s) mod 5 == 0
  batches of 16 in sample order (no shuffle), the last one of 12.

Usage: /usr/bin/python3 tests/train/adam_reference.py   (PyTorch 1.13, Debian 12)
"""
import math

import torch

torch.set_default_dtype(torch.float64)
SIZES = [5, 6, 4, 1]
N, BATCH, KEEP = 60, 16, 0.8

# (name, epochs, lr, betas, eps, weight_decay, amsgrad)
CASES = [
    ("one_epoch", 1, 0.01, (0.9, 0.999), 1e-8, 0.0, False),
    ("fifty_epochs", 50, 0.01, (0.9, 0.999), 1e-8, 0.0, False),
    ("fifty_epochs_decay_amsgrad", 50, 0.005, (0.8, 0.99), 1e-6, 0.01, True),
]


def data():
    x = torch.tensor([[((5 * s + j + 1) * 0.6180339887498949) % 1.0 for s in range(N)]
                      for j in range(5)])
    y = []
    for s in range(N):
        x0, x1, x2, x3, x4 = (float(x[j, s]) for j in range(5))
        d = x2 - 0.5
        y.append((10.0 * math.sin(math.pi * x0 * x1) + 20.0 * (d * d) + 10.0 * x3 + 5.0 * x4) / 10.0)
    return x, torch.tensor([y])


def initial_parameters():
    params, k = [], 0
    for l in range(1, len(SIZES)):
        n_in, n_out = SIZES[l - 1], SIZES[l]
        w = torch.empty(n_out, n_in)
        for c in range(n_in):  # column-major, as cnclab's flat vector
            for r in range(n_out):
                w[r, c] = 0.5 * math.sin(k + 1)
                k += 1
        b = torch.tensor([0.5 * math.sin(k + 1 + i) for i in range(n_out)])
        k += n_out
        params += [w.requires_grad_(), b.requires_grad_()]
    return params


def mask(t, l, units, samples):
    return torch.tensor([[0.0 if (131 * t + 31 * l + 17 * i + 7 * s) % 5 == 0 else 1.0 / KEEP
                          for s in samples] for i in range(units)])


def run(epochs, lr, betas, eps, weight_decay, amsgrad):
    x, y = data()
    params = initial_parameters()
    opt = torch.optim.Adam(params, lr=lr, betas=betas, eps=eps, weight_decay=weight_decay,
                           amsgrad=amsgrad, foreach=False)
    t, last_loss = 0, float("nan")
    for _ in range(epochs):
        losses = []
        for first in range(0, N, BATCH):
            samples = list(range(first, min(first + BATCH, N)))
            t += 1
            a = x[:, samples]
            for l in range(1, len(SIZES)):
                w, b = params[2 * (l - 1)], params[2 * (l - 1) + 1]
                a = w @ a + b[:, None]
                if l < len(SIZES) - 1:
                    a = torch.relu(a) * mask(t, l, SIZES[l], samples)
            loss = torch.nn.functional.mse_loss(a, y[:, samples])
            opt.zero_grad()
            loss.backward()
            opt.step()
            losses.append(float(loss))
        last_loss = sum(losses) / len(losses)
    flat = []
    for l in range(1, len(SIZES)):
        flat += params[2 * (l - 1)].detach().t().flatten().tolist()
        flat += params[2 * (l - 1) + 1].detach().tolist()
    return flat, last_loss


def main():
    print(f"// adam_reference.py's output (PyTorch {torch.__version__}).")
    for name, *options in CASES:
        flat, last_loss = run(*options)
        print(f"// {name}")
        print(f"{{\"{name}\", {last_loss:.17g},")
        print(" {" + ",\n  ".join(", ".join(f"{v:.17g}" for v in flat[i:i + 3])
                                   for i in range(0, len(flat), 3)) + "}},")


if __name__ == "__main__":
    main()
