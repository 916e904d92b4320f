"""What the Python tests share: the repository's scenes, the CLI beside the module, and small
renders of the Cornell box."""
import os
import pathlib
import subprocess

import pytest

import wavetrace as wt

ROOT = pathlib.Path(__file__).resolve().parents[2]
SCENES = ROOT / "scenes"


@pytest.fixture(scope="session")
def cli():
    path = os.environ.get("WAVETRACE_CLI", str(ROOT / "build" / "bin" / "wavetrace"))
    assert os.access(path, os.X_OK), f"no CLI at {path} (set WAVETRACE_CLI)"

    def run(*args):
        result = subprocess.run([path, *map(str, args)], capture_output=True, text=True)
        assert result.returncode == 0, result.stderr
        return result
    return run


@pytest.fixture(scope="session")
def cornell():
    return wt.load_scene(SCENES / "cornell.json")
