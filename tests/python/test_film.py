"""Films: render into them, resume, save, load and merge parts, from Python and with the CLI."""
import numpy as np
import pytest

import wavetrace as wt
from conftest import SCENES

SIZE = dict(width=40, height=32, seed=3)


def test_parts_merged_in_python_equal_the_single_render(cornell, tmp_path):
    whole = wt.render(cornell, spp=8, **SIZE)
    a, b = wt.Film(), wt.Film()
    wt.render(cornell, spp=3, sample_offset=0, film=a, **SIZE)
    wt.render(cornell, spp=5, sample_offset=3, film=b, **SIZE)
    assert a.ranges == [(0, 3)] and b.ranges == [(3, 8)]
    merged = wt.Film.merge([b, a])
    assert merged.spp == 8 and merged.ranges == [(0, 8)]
    assert np.allclose(merged.mean(), whole, rtol=1e-6, atol=1e-6)
    b.save(tmp_path / "b.film")
    from_files = wt.Film.merge([a, tmp_path / "b.film"])
    assert np.array_equal(from_files.mean(), merged.mean())
    assert np.array_equal(from_files.variance(), merged.variance())


def test_a_render_into_a_film_resumes_it_bit_for_bit(cornell, tmp_path):
    film = wt.Film()
    wt.render(cornell, spp=3, film=film, **SIZE)
    film.save(tmp_path / "part.film")
    resumed = wt.Film.load(tmp_path / "part.film")
    image = wt.render(cornell, spp=4, film=resumed, **SIZE)
    assert resumed.spp == 7
    assert np.array_equal(image, wt.render(cornell, spp=7, **SIZE))
    with pytest.raises(wt.FilmError, match="continues there"):
        wt.render(cornell, spp=1, sample_offset=0, film=resumed, **SIZE)
    with pytest.raises(wt.FilmError, match="another render.*seed"):
        wt.render(cornell, spp=1, film=resumed, **{**SIZE, "seed": 4})


def test_python_and_cli_films_of_one_scene_file_merge(cli, cornell, tmp_path):
    cli("render", SCENES / "cornell.json", "--width", 40, "--height", 32, "--seed", 3, "--spp", 4,
        "--sample-offset", 4, "--film", tmp_path / "cli.film", "-o", tmp_path / "cli.exr")
    ours = wt.Film()
    wt.render(cornell, spp=4, film=ours, **SIZE)
    merged = wt.Film.merge([ours, tmp_path / "cli.film"])
    assert np.allclose(merged.mean(), wt.render(cornell, spp=8, **SIZE), rtol=1e-6, atol=1e-6)
    other = wt.Film()
    wt.render(cornell, spp=4, sample_offset=8, film=other, **{**SIZE, "width": 20})
    with pytest.raises(wt.FilmError, match="width"):
        wt.Film.merge([ours, other])
    with pytest.raises(wt.FilmError, match="overlap"):
        wt.Film.merge([ours, ours])
