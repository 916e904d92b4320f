"""Images through the CLI's own code, and compare()'s numbers."""
import numpy as np
import pytest

import wavetrace as wt


def test_float_images_round_trip_exactly(tmp_path):
    rng = np.random.default_rng(0)
    image = rng.random((7, 9, 3), dtype=np.float32) * 10
    for ext in ("exr", "pfm"):
        wt.write_image(tmp_path / f"a.{ext}", image)
        assert np.array_equal(wt.read_image(tmp_path / f"a.{ext}"), image)
    grey = rng.random((5, 4), dtype=np.float32)
    wt.write_image(tmp_path / "g.exr", grey)
    assert np.array_equal(wt.read_image(tmp_path / "g.exr"), np.repeat(grey[..., None], 3, 2))


def test_png_is_srgb_encoded(tmp_path):
    image = np.full((2, 2, 3), 0.5, np.float32)
    wt.write_image(tmp_path / "a.png", image)
    back = wt.read_image(tmp_path / "a.png")
    assert np.allclose(back, 0.5, atol=0.005)
    with pytest.raises(wt.ImageError, match="nothing.png"):
        wt.read_image(tmp_path / "nothing.png")
    with pytest.raises(ValueError, match="shape"):
        wt.write_image(tmp_path / "b.exr", np.zeros((2, 2, 4), np.float32))


def test_compare_runs_the_z_tests(cornell):
    a, va = wt.render(cornell, width=32, height=32, spp=16, seed=1, variance=True)
    b, vb = wt.render(cornell, width=32, height=32, spp=16, seed=2, variance=True)
    same = wt.compare(a, b, va, vb)
    assert same["z_tested"] and same["pass"] and same["tests"] == (16 + 1) * 3
    assert same["block_z"].shape == (32, 32, 3)
    darker = wt.compare(0.8 * a, b, 0.64 * va, vb)
    assert not darker["pass"] and darker["failed"] > 0
    assert darker["mean_ours"] == pytest.approx(0.8 * same["mean_ours"], rel=1e-5)
    with pytest.raises(ValueError):
        wt.compare(a, b[:16])
