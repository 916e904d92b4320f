#!/usr/bin/env python3
"""Relative MSE of each sampler at equal samples per pixel against a converged reference.

usage: tools/sampler-error.py SCENE SPP REFERENCE_SPP [STRATEGY] [--cli PATH] [--size N]

Renders SCENE at N x N (default 64) with REFERENCE_SPP samples (Sobol sampler, seed 999) as
the reference, then at SPP with each sampler and seeds 0-5, one thread each, and prints the
mean over seeds of mean((image - reference)^2 / (reference^2 + 0.01)), the median speed the
renders report (Mpaths/s), and their product's ratio to the independent sampler's: the error
at equal time, were the error inversely proportional to the samples (it falls faster for the
Sobol samplers, so the ratio is conservative). "2x2" is the same relative MSE of the images
averaged over aligned 2 x 2 squares of pixels: what is left of the error when neighbouring
pixels are seen together, where zsobol's blue-noise error cancels.
"""
import argparse
import os
import re
import subprocess
import tempfile

import numpy as np


def read_pfm(path):
    with open(path, "rb") as f:
        if f.readline().strip() != b"PF":
            raise ValueError(f"{path}: not a colour PFM")
        width, height = map(int, f.readline().split())
        scale = float(f.readline())
        dtype = "<f4" if scale < 0 else ">f4"
        pixels = np.frombuffer(f.read(), dtype=dtype).reshape(height, width, 3)
    return pixels[::-1]


def main():
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    p = argparse.ArgumentParser()
    p.add_argument("scene")
    p.add_argument("spp", type=int)
    p.add_argument("reference_spp", type=int)
    p.add_argument("strategy", nargs="?", default="mis")
    p.add_argument("--cli", default=os.path.join(root, "build", "bin", "wavetrace"))
    p.add_argument("--size", type=int, default=64)
    a = p.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        def render(spp, sampler, seed):
            out = os.path.join(tmp, "image.pfm")
            r = subprocess.run([a.cli, "render", a.scene, "--spp", str(spp), "--width",
                                str(a.size), "--height", str(a.size), "--sampler", sampler,
                                "--seed", str(seed), "--strategy", a.strategy, "--threads", "1",
                                "-o", out], check=True, capture_output=True, text=True)
            speed = float(re.search(r"([0-9.]+) Mpaths/s", r.stderr).group(1))
            return read_pfm(out), speed

        reference = render(a.reference_spp, "sobol", 999)[0]
        cost = {}
        def squares(image):
            h, w = image.shape[0] // 2 * 2, image.shape[1] // 2 * 2
            return image[:h, :w].reshape(h // 2, 2, w // 2, 2, 3).mean(axis=(1, 3))

        def relative_mse(image, ref):
            return np.mean((image - ref) ** 2 / (ref ** 2 + 1e-2))

        for sampler in ("independent", "sobol", "zsobol"):
            errors, blurred, speeds = [], [], []
            for seed in range(6):
                image, speed = render(a.spp, sampler, seed)
                errors.append(relative_mse(image, reference))
                blurred.append(relative_mse(squares(image), squares(reference)))
                speeds.append(speed)
            error, speed = np.mean(errors), np.median(speeds)
            cost[sampler] = error / speed
            print(f"{os.path.basename(a.scene)} {a.strategy} {a.spp} spp {sampler}: relative MSE "
                  f"{error:.5f} (2x2: {np.mean(blurred):.5f}), {speed:.2f} Mpaths/s, error at "
                  f"equal time {cost[sampler] / cost['independent']:.2f}x independent's")


if __name__ == "__main__":
    main()
