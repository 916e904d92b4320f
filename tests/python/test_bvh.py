"""Rays from NumPy: batches equal the library's single-ray queries ray for ray."""
import numpy as np
import pytest

import wavetrace as wt
from conftest import SCENES


@pytest.fixture(scope="module")
def dragon():
    return wt.load_scene(SCENES / "dragon.json")


def random_rays(scene, n, seed=1):
    """Rays from points around the scene's bounds towards random points inside them."""
    rng = np.random.default_rng(seed)
    lo, hi = (np.array(b, np.float32) for b in scene.info()["bounds"])
    centre, radius = (lo + hi) / 2, np.linalg.norm(hi - lo)
    origins = centre + radius * rng.normal(size=(n, 3)).astype(np.float32)
    targets = lo + (hi - lo) * rng.random((n, 3), dtype=np.float32)
    return origins.astype(np.float32), (targets - origins).astype(np.float32)


def test_a_batch_equals_single_ray_queries_ray_for_ray(dragon):
    bvh = wt.Bvh(dragon)
    origins, directions = random_rays(dragon, 3000)
    tmax = np.full(3000, np.inf, np.float32)
    tmax[::3] = 0.5  # some rays end before the surface
    hits = bvh.intersect(origins, directions, tmax=tmax)
    assert 0.2 < hits.hit.mean() < 0.99
    for i in range(3000):
        one = bvh.intersect_one(origins[i], directions[i], 0.0, float(tmax[i]))
        assert (hits.t[i], hits.kind[i], hits.prim[i], hits.u[i], hits.v[i]) == one, i
    occluded = bvh.occluded(origins, directions, tmax=tmax)
    assert np.array_equal(occluded, hits.hit)


def test_hits_agree_with_the_geometry():
    s = wt.Scene()
    m = s.add_material(wt.Material(kind=wt.MaterialKind.Lambertian, albedo=s.add_solid((1, 1, 1))))
    centres = np.array([[0, 0, -5], [3, 0, -6], [-3, 1, -4]], np.float32)
    for c in centres:
        s.add_sphere(wt.Sphere(center=tuple(c), radius=1, material=m))
    rng = np.random.default_rng(3)
    d = np.column_stack([rng.uniform(-0.8, 0.8, 5000), rng.uniform(-0.5, 0.5, 5000),
                         -np.ones(5000)]).astype(np.float32)
    o = np.zeros_like(d)
    hits = wt.Bvh(s).intersect(o, d)
    # The nearest root of |t d - c| = 1 over the spheres, in double precision.
    dd = (d.astype(np.float64) ** 2).sum(1)
    best = np.full(5000, np.inf)
    for c in centres.astype(np.float64):
        b = d @ c
        disc = b * b - dd * (c @ c - 1)
        t = np.where(disc >= 0, (b - np.sqrt(np.maximum(disc, 0))) / dd, np.inf)
        best = np.minimum(best, t)
    assert np.array_equal(hits.hit, np.isfinite(best))
    assert np.allclose(hits.t[hits.hit], best[hits.hit], rtol=1e-5)
    assert set(hits.kind[hits.hit]) == {2}


def test_bad_rays_and_stale_bvhs_raise(cornell):
    scene = wt.load_scene(SCENES / "cornell.json")
    bvh = wt.Bvh(scene)
    with pytest.raises(ValueError, match="origins"):
        bvh.intersect(np.zeros((4, 2)), np.ones((4, 3)))
    with pytest.raises(ValueError, match="directions"):
        bvh.intersect(np.zeros((4, 3)), np.ones((3, 3)))
    with pytest.raises(ValueError, match="ray 2"):
        bvh.intersect(np.zeros((4, 3)), np.array([[1, 0, 0]] * 2 + [[0, 0, 0]] * 2))
    with pytest.raises(ValueError, match="tmax"):
        bvh.intersect(np.zeros((4, 3)), np.ones((4, 3)), tmax=np.ones(3))
    scene.add_sphere(wt.Sphere(center=(0, 0, 0), radius=1, material=0))
    with pytest.raises(RuntimeError, match="changed"):
        bvh.intersect(np.zeros((1, 3)), np.ones((1, 3)))
    assert wt.Bvh(scene).intersect(np.zeros((1, 3)), np.ones((1, 3))).hit[0]
