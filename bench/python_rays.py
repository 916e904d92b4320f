"""Times wavetrace.Bvh.intersect on rays written by wavetrace_bench (section python_rays).

usage: python_rays.py SCENE RAYS HITS: RAYS holds float32 records (origin, direction, tmin,
tmax); prints the median of three timed calls in seconds and writes each ray's t to HITS.
"""
import sys
import time

import numpy as np

import wavetrace as wt

scene_path, ray_path, hit_path = sys.argv[1:4]
records = np.fromfile(ray_path, dtype=np.float32).reshape(-1, 8)
# The arrays a user would have: contiguous (n, 3) origins and directions.
origins = np.ascontiguousarray(records[:, 0:3])
directions = np.ascontiguousarray(records[:, 3:6])
bvh = wt.Bvh(wt.load_scene(scene_path))
times = []
for _ in range(3):
    start = time.perf_counter()
    hits = bvh.intersect(origins, directions)
    times.append(time.perf_counter() - start)
hits.t.tofile(hit_path)
print(sorted(times)[1])
