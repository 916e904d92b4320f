"""wavetrace: a data-oriented wavefront path tracer, from Python.

Load or build a scene, render it into a NumPy array, trace batches of rays through its BVH,
keep, save and merge films::

    import wavetrace as wt
    scene = wt.load_scene("scenes/cornell.json")
    image = wt.render(scene, spp=16, width=256, height=256)   # float32 (256, 256, 3)
    wt.write_image("cornell.png", image)

Everything here is the C++ library beneath (``wavetrace._wavetrace``); this file adds the
progress bar, the result types and the documented behaviour on Ctrl-C.
"""
import sys
import time
from typing import Callable, NamedTuple, Optional, Union

import numpy as np

from ._wavetrace import (
    NONE, Background, Bvh, Camera, Film, FilmError, ImageError, Light, Material, MaterialKind,
    MediumBoundaries, Microfacet, PixelFilter, Quad, RenderSettings, Scene, SceneError, Sphere,
    SphereMapping, Texture, TextureFilter, TextureKind, TextureWrap, Transform, __version__, compare,
    load_scene, read_image, simd_target, write_image)
from . import _wavetrace

__all__ = [
    "NONE", "Background", "Bvh", "Camera", "Film", "FilmError", "Hits", "ImageError", "Light",
    "Material", "MaterialKind", "MediumBoundaries", "Microfacet", "PixelFilter", "Quad",
    "RenderInterrupted", "RenderSettings", "Scene", "SceneError", "Sphere", "SphereMapping",
    "Texture", "TextureFilter", "TextureKind", "TextureWrap", "Transform", "compare", "load_scene", "read_image", "render",
    "simd_target", "write_image",
]


class RenderInterrupted(KeyboardInterrupt):
    """Raised by render() when Ctrl-C (SIGINT) stopped it at a pass boundary.

    It is a KeyboardInterrupt, so an uncaught one ends a script as Ctrl-C does; caught, it
    holds the samples done: ``image`` (and ``variance`` if asked for) of ``spp`` samples per
    pixel, and a film passed to render() holds them too, so the render can be resumed.
    """

    def __init__(self, image, variance, spp, stats):
        super().__init__(f"render interrupted after {spp} samples per pixel")
        self.image = image
        self.variance = variance
        self.spp = spp
        self.stats = stats


class Hits(NamedTuple):
    """The closest hits of a batch of n rays (Bvh.intersect)."""
    t: np.ndarray      # float32 (n,): ray parameter of the hit, inf for a miss
    kind: np.ndarray   # int8 (n,): 0 triangle, 1 quad, 2 sphere; -1 for a miss
    prim: np.ndarray   # int32 (n,): the primitive's index among those of its kind; -1 for a miss
    u: np.ndarray      # float32 (n,): triangle: barycentric of v1; quad: alpha; sphere: 0
    v: np.ndarray      # float32 (n,): triangle: barycentric of v2; quad: beta; sphere: 0

    @property
    def hit(self) -> np.ndarray:
        """bool (n,): whether each ray hit something."""
        return self.kind >= 0


def _intersect(self, origins, directions, tmin=None, tmax=None) -> Hits:
    """The closest hit in [tmin, tmax] along each ray, as Hits.

    origins, directions: float32 (n, 3) (other arrays are converted); directions need not be
    unit length (t is in units of |d|). tmin, tmax: a number or one per ray (default 0, inf).
    Traced in parallel with the GIL released.
    """
    return Hits(*self._intersect(origins, directions, tmin, tmax))


Bvh.intersect = _intersect


class _ProgressBar:
    """A text progress bar on stderr (tqdm's when it is installed)."""

    def __init__(self, total):
        self.total = total
        self.done = 0
        self.start = time.monotonic()
        try:
            from tqdm import tqdm
            self.bar = tqdm(total=total, unit="spp", file=sys.stderr)
        except ImportError:
            self.bar = None

    def __call__(self, done, requested):
        if self.bar is not None:
            self.bar.update(done - self.done)
        else:
            elapsed = time.monotonic() - self.start
            width = 30
            filled = int(width * done / max(requested, 1))
            sys.stderr.write(f"\r[{'#' * filled}{'.' * (width - filled)}] "
                             f"{done}/{requested} spp  {elapsed:6.1f} s")
            sys.stderr.flush()
        self.done = done

    def close(self):
        if self.bar is not None:
            self.bar.close()
        else:
            sys.stderr.write("\n")
            sys.stderr.flush()


def render(scene: Scene, spp: Optional[int] = None, width: Optional[int] = None,
           height: Optional[int] = None, engine: str = "wavefront", strategy: str = "mis",
           seed: int = 0, threads: int = 0, max_depth: Optional[int] = None,
           aov: str = "color", sample_offset: Optional[int] = None,
           time_limit: Optional[float] = None,
           progress: Union[bool, Callable[[int, int], Optional[bool]]] = False,
           variance: bool = False, film: Optional[Film] = None, mis_heuristic: str = "power",
           wave_size: Optional[int] = None, schedule: str = "resident",
           sort_by_material: bool = False, return_stats: bool = False,
           sampler: Optional[str] = None, sampler_spp: Optional[int] = None):
    """Renders the scene; returns the image as float32 (height, width, 3), linear RGB.

    The same render as ``wavetrace render`` with the same options, bit for bit. None takes
    the scene's value (its size, spp and max_depth).

    - engine: "wavefront" or "megakernel"; strategy: "bsdf", "light", "mixture", "nee", "mis".
    - seed, sample_offset: the samples are [sample_offset, sample_offset + spp) of each pixel's
      sequence from this seed; parts of one render merge with Film.merge.
    - sampler: "independent" (a hash of each coordinate), "sobol" (Owen-scrambled Sobol
      points per pixel) or "zsobol" (one Owen-scrambled Sobol sequence over the pixels in a
      shuffled Morton order: blue-noise error), by default the scene's (scene.render.sampler,
      "sobol" unless set); the samples are a pure function of (seed, pixel, sample,
      dimension) in each. sampler_spp: the samples per pixel zsobol's sequence is laid out
      for (default sample_offset + spp): every part of one render states the same.
    - threads: worker threads (0: all). time_limit: seconds after which no pass starts.
    - aov: "color" (light transport), or "albedo", "normal", "depth" from primary rays (raw
      values: normals in [-1, 1], depth inf where nothing is hit).
    - progress: True for a progress bar on stderr (tqdm's if installed), or a callable
      progress(done, requested) called between passes with samples per pixel done; it may
      return False to stop the render there.
    - variance: also return the variance of each pixel's mean, as (image, variance).
    - film: a Film to render into: an empty one takes this render's settings; one holding
      samples of the same render is continued after its last sample (a resume).
    - return_stats: also return a dict (seconds, paths, rays, spp) last in the tuple.

    The GIL is released while rendering. Ctrl-C stops the render at the next pass boundary
    (passes last about half a second) and raises RenderInterrupted, a KeyboardInterrupt that
    holds the image of the samples done.
    """
    callback = progress
    bar = None
    if progress is True:
        bar = callback = _ProgressBar(spp if spp is not None else scene.render.spp)
    elif progress is False or progress is None:
        callback = None
    try:
        image, var, stats, interrupted = _wavetrace._render(
            scene, spp, width, height, engine, strategy, mis_heuristic, seed, threads, max_depth,
            sample_offset, 0.0 if time_limit is None else time_limit, wave_size, schedule,
            sort_by_material, aov, callback, variance, film, sampler, sampler_spp)
    finally:
        if bar is not None:
            bar.close()
    if interrupted:
        raise RenderInterrupted(image, var, stats["spp"], stats)
    result = (image,) + ((var,) if variance else ()) + ((stats,) if return_stats else ())
    return result[0] if len(result) == 1 else result
