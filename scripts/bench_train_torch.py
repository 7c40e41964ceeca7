#!/usr/bin/python3
"""The bench/bench_train.cpp workload in PyTorch (float32, one thread).

Same shape and optimiser: 73 -> 28 ReLU -> Dropout(0.5) -> 20 ReLU -> 1,
SGD(lr=1e-5, momentum=0.8), MSE, 13,860 samples, per-epoch shuffle, manual
batching (no DataLoader overhead). Prints "batch <b> samples_per_s <x>"
(median of repeats) like the C++ benchmark.
"""
import argparse
import statistics
import time

parser = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
parser.add_argument("repeats", nargs="?", type=int, default=5, help="timed repeats (default 5)")
repeats = parser.parse_args().repeats  # before importing torch: --help works without it

import torch  # noqa: E402

torch.set_num_threads(1)
torch.manual_seed(0)
N = 13860
x = torch.randn(N, 73)
y = torch.randn(N, 1)

for batch in (1, 32, 256):
    epochs = 1 if batch == 1 else 10
    rates = []
    for _ in range(repeats):
        model = torch.nn.Sequential(
            torch.nn.Linear(73, 28), torch.nn.ReLU(), torch.nn.Dropout(0.5),
            torch.nn.Linear(28, 20), torch.nn.ReLU(), torch.nn.Linear(20, 1))
        opt = torch.optim.SGD(model.parameters(), lr=1e-5, momentum=0.8)
        loss_fn = torch.nn.MSELoss()
        model.train()
        t0 = time.perf_counter()
        for _ in range(epochs):
            perm = torch.randperm(N)
            for i in range(0, N, batch):
                idx = perm[i:i + batch]
                opt.zero_grad(set_to_none=True)
                loss = loss_fn(model(x[idx]), y[idx])
                loss.backward()
                opt.step()
        rates.append(N * epochs / (time.perf_counter() - t0))
    print(f"batch {batch} samples_per_s {statistics.median(rates):.0f}", flush=True)
