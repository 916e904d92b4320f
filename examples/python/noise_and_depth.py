"""Renders a scene at two sample counts and plots its noise against 1/sqrt(spp); then casts a
grid of rays from NumPy through the scene's BVH for a depth image.

    PYTHONPATH=build/python python3 examples/python/noise_and_depth.py scenes/cornell.json

writes noise.png (the plot) and depth.png to the current folder (--out to choose another).
"""
import argparse
import pathlib

import matplotlib
matplotlib.use("Agg")  # files only, no window
import matplotlib.pyplot as plt
import numpy as np

import wavetrace as wt

parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
parser.add_argument("scene", nargs="?", default="scenes/cornell.json")
parser.add_argument("--size", type=int, default=200, help="image side in pixels")
parser.add_argument("--spp", type=int, nargs=2, default=[4, 64], help="the two sample counts")
parser.add_argument("--out", type=pathlib.Path, default=pathlib.Path("."))
args = parser.parse_args()
args.out.mkdir(parents=True, exist_ok=True)
scene = wt.load_scene(args.scene)

# Noise: the standard error of the pixel means, from the renders' own per-pixel variance.
noise = []
for spp in args.spp:
    image, variance = wt.render(scene, spp=spp, width=args.size, height=args.size,
                                variance=True)
    noise.append(np.sqrt(variance.mean()))
    print(f"{spp:5d} spp: noise {noise[-1]:.4g}")
spp = np.array(args.spp, float)
print(f"noise ratio {noise[0] / noise[1]:.3f}, sqrt of the spp ratio {np.sqrt(spp[1] / spp[0]):.3f}")
wt.write_image(args.out / "render.png", image)
plt.figure(figsize=(5, 4))
plt.loglog(spp, noise, "o-", label="measured")
plt.loglog(spp, noise[0] * np.sqrt(spp[0] / spp), "--", label=r"$\propto 1/\sqrt{spp}$")
plt.xlabel("samples per pixel")
plt.ylabel("standard error of a pixel (RMS)")
plt.legend()
plt.tight_layout()
plt.savefig(args.out / "noise.png", dpi=100)

# Depth: a pinhole camera's rays, one per pixel centre, built in NumPy from the scene's camera.
cam = scene.camera
w = np.subtract(cam.look_from, cam.look_at)
w /= np.linalg.norm(w)
u = np.cross(cam.up, w)
u /= np.linalg.norm(u)
v = np.cross(w, u)
half = np.tan(np.radians(cam.vfov) / 2)
px = (np.arange(args.size) + 0.5) / args.size * 2 - 1
x, y = np.meshgrid(px * half, -px * half)
directions = (x[..., None] * u + y[..., None] * v - w).reshape(-1, 3).astype(np.float32)
origins = np.broadcast_to(np.float32(cam.look_from), directions.shape)
hits = wt.Bvh(scene).intersect(origins, directions)
depth = (hits.t * np.linalg.norm(directions, axis=1)).reshape(args.size, args.size)
print(f"depth: {hits.hit.mean():.1%} of the rays hit, nearest {depth.min():.4g}")
plt.figure(figsize=(5, 4))
plt.imshow(np.where(np.isfinite(depth), depth, np.nan), cmap="viridis")
plt.colorbar(label="distance")
plt.axis("off")
plt.tight_layout()
plt.savefig(args.out / "depth.png", dpi=100)
