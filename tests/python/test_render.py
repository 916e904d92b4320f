"""wavetrace.render: the CLI's image bit for bit, its options checked, progress, time limit,
Ctrl-C and the GIL."""
import subprocess
import sys
import textwrap
import threading

import numpy as np
import pytest

import wavetrace as wt
from conftest import ROOT, SCENES

SMALL = dict(width=48, height=40, spp=4, seed=7)


@pytest.mark.parametrize("engine,strategy,sampler", [
    ("wavefront", "mis", "independent"), ("megakernel", "mis", "independent"),
    ("wavefront", "bsdf", "independent"), ("wavefront", "mis", "sobol"),
    ("megakernel", "mis", "zsobol")])
def test_render_equals_the_cli_image_bit_for_bit(cli, cornell, tmp_path, engine, strategy,
                                                 sampler):
    out, var = tmp_path / "cli.exr", tmp_path / "cli-var.exr"
    cli("render", SCENES / "cornell.json", "--width", 48, "--height", 40, "--spp", 4, "--seed", 7,
        "--engine", engine, "--strategy", strategy, "--sampler", sampler, "-o", out,
        "--variance", var)
    image, variance = wt.render(cornell, engine=engine, strategy=strategy, variance=True,
                                sampler=sampler, **SMALL)
    assert image.dtype == np.float32 and image.shape == (40, 48, 3)
    assert np.array_equal(image, wt.read_image(out))
    assert np.array_equal(variance, wt.read_image(var))
    assert image.mean() > 0.01  # light arrives


@pytest.mark.parametrize("aov", ["albedo", "normal"])
def test_an_aov_equals_the_cli_image(cli, cornell, tmp_path, aov):
    out = tmp_path / f"{aov}.exr"
    cli("render", SCENES / "cornell.json", "--width", 32, "--height", 32, "--aov", aov,
        "-o", out)
    assert np.array_equal(wt.render(cornell, width=32, height=32, aov=aov), wt.read_image(out))


def test_depth_keeps_raw_distances(cornell):
    depth = wt.render(cornell, width=32, height=32, aov="depth")[..., 0]
    # The camera looks into the open box from z = -800: every wall is further than that, and
    # the corners of the image see past the box.
    seen = np.isfinite(depth)
    assert seen.mean() > 0.8 and np.all(depth[seen] > 800) and np.all(depth[~seen] == np.inf)


def test_the_scenes_defaults_are_used(cornell):
    image = wt.render(cornell, spp=1, max_depth=2)
    assert image.shape == (cornell.render.height, cornell.render.width, 3)


@pytest.mark.parametrize("option,value,name", [
    ("width", 0, "width"), ("spp", -1, "spp"), ("max_depth", 0, "max_depth"),
    ("engine", "gpu", "engine"), ("strategy", "path", "strategy"), ("aov", "uv", "aov"),
    ("threads", -2, "threads"), ("time_limit", -1.0, "time_limit"),
    ("sampler", "halton", "sampler")])
def test_bad_options_raise_naming_the_option(cornell, option, value, name):
    with pytest.raises(ValueError, match=name):
        wt.render(cornell, **{**SMALL, option: value})


def test_progress_sees_every_pass_and_may_stop_the_render(cornell):
    seen = []

    def progress(done, requested):
        seen.append((done, requested))
        return done < 1  # stop at the boundary after the first pass (one sample)
    image, stats = wt.render(cornell, width=32, height=32, spp=64, progress=progress,
                             return_stats=True)
    assert seen == [(0, 64), (1, 64)] and stats["spp"] == 1
    assert np.array_equal(image, wt.render(cornell, width=32, height=32, spp=1))
    seen.clear()
    wt.render(cornell, width=32, height=32, spp=3, progress=lambda d, r: seen.append(d))
    assert seen[0] == 0 and seen[-1] == 3 and seen == sorted(seen)


def test_an_exception_in_progress_stops_the_render_and_is_raised(cornell):
    def progress(done, requested):
        raise RuntimeError("from the callback")
    with pytest.raises(RuntimeError, match="from the callback"):
        wt.render(cornell, progress=progress, **SMALL)


def test_a_time_limit_renders_whole_passes(cornell):
    # A limit no pass can meet: the first pass (one sample) is always rendered.
    image, stats = wt.render(cornell, width=32, height=32, spp=1000, time_limit=1e-9,
                             return_stats=True)
    assert stats["spp"] == 1
    assert np.array_equal(image, wt.render(cornell, width=32, height=32, spp=1))


def test_the_gil_is_released_while_rendering(cornell):
    # A Python thread counts while the render is inside a pass (between two progress calls):
    # with the GIL held by the render it could not run at all.
    inside, counted = threading.Event(), []
    stop = threading.Event()

    def count():
        inside.wait()
        n = 0
        while not stop.is_set():
            n += 1
        counted.append(n)

    counter = threading.Thread(target=count)
    counter.start()
    seen = []

    def progress(done, requested):
        if done == 0:
            inside.set()
        else:
            seen.append(done)
            stop.set()
        return done == 0
    try:
        wt.render(cornell, width=256, height=256, spp=8, progress=progress)
    finally:
        inside.set()
        stop.set()
        counter.join()
    assert counted[0] > 1000


def test_two_threads_render_concurrently_and_alike(cornell):
    expected = {seed: wt.render(cornell, **{**SMALL, "seed": seed}) for seed in (1, 2)}
    results = {}

    def run(seed):
        results[seed] = wt.render(cornell, **{**SMALL, "seed": seed})
    threads = [threading.Thread(target=run, args=(seed,)) for seed in (1, 2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for seed in (1, 2):
        assert np.array_equal(results[seed], expected[seed])


def test_sigint_stops_at_a_pass_boundary_and_the_interpreter_goes_on(tmp_path):
    # A real SIGINT, from a thread of the rendering process, once the render is under way.
    script = textwrap.dedent(f"""
        import os, signal, threading
        import numpy as np
        import wavetrace as wt
        scene = wt.load_scene({str(SCENES / 'cornell.json')!r})
        film = wt.Film()
        def progress(done, requested):
            if done == 1:
                threading.Timer(0.2, os.kill, (os.getpid(), signal.SIGINT)).start()
        try:
            wt.render(scene, width=64, height=64, spp=100000, film=film, progress=progress)
            print("not interrupted")
        except wt.RenderInterrupted as e:
            assert isinstance(e, KeyboardInterrupt)
            assert 1 <= e.spp < 100000 and film.spp == e.spp
            assert np.isfinite(e.image).all() and e.image.mean() > 0
            # The samples done are kept: resumed to a few more, the film equals a render of
            # them all at once, bit for bit.
            total = e.spp + 2
            wt.render(scene, width=64, height=64, spp=2, film=film)
            whole = wt.render(scene, width=64, height=64, spp=total)
            print("interrupted", e.spp, np.array_equal(film.mean(), whole))
    """)
    result = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                            timeout=120, cwd=ROOT)
    assert result.returncode == 0, result.stderr
    words = result.stdout.split()
    assert words[0] == "interrupted" and words[-1] == "True", result.stdout


def test_an_uncaught_interrupt_ends_a_script_as_ctrl_c_does(tmp_path):
    script = textwrap.dedent(f"""
        import os, signal, threading
        import wavetrace as wt
        scene = wt.load_scene({str(SCENES / 'cornell.json')!r})
        def progress(done, requested):
            if done == 1:
                threading.Timer(0.2, os.kill, (os.getpid(), signal.SIGINT)).start()
        wt.render(scene, width=64, height=64, spp=100000, progress=progress)
    """)
    result = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                            timeout=120, cwd=ROOT)
    assert result.returncode == 1 and "RenderInterrupted" in result.stderr


def test_the_scenes_sampler_is_the_default(cornell):
    assert cornell.render.sampler == "sobol"
    independent = wt.render(cornell, sampler="independent", **SMALL)
    assert not np.array_equal(independent, wt.render(cornell, **SMALL))
    cornell.render.sampler = "independent"
    try:
        assert np.array_equal(independent, wt.render(cornell, **SMALL))
        with pytest.raises(ValueError, match="sampler"):
            cornell.render.sampler = "halton"
    finally:
        cornell.render.sampler = "sobol"
