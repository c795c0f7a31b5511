"""Shared fixtures of the Python tests: the repository, scratch folders, and the command-line tool."""
import json
import os
import pathlib
import subprocess

import pytest

REPOSITORY = pathlib.Path(os.environ.get("PETROSCOPE_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))


@pytest.fixture
def repository():
    return REPOSITORY


@pytest.fixture
def run_cli(tmp_path):
    """Runs `petroscope ARGS -o tmp/NAME` and returns (image array, sidecar dict); skips without the tool."""
    binary = os.environ.get("PETROSCOPE_BINARY")
    if not binary:
        pytest.skip("the command-line tool is not built (PETROSCOPE_BINARY unset)")
    import petroscope

    def run(arguments, name="out.exr"):
        output = tmp_path / name
        subprocess.run([binary, *arguments, "-o", str(output)], check=True, capture_output=True, cwd=REPOSITORY)
        return petroscope.read_image(output), json.loads((tmp_path / (name + ".json")).read_text())

    return run
