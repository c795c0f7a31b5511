"""The package: what `import petroscope` loads, its minerals against the command line, and help()."""
import json
import os
import subprocess
import sys

import pytest

import petroscope


def test_import_loads_neither_image_libraries_nor_numpy():
    # The image libraries (libpng, libtiff, OpenEXR, and OpenCV with what it pulls in: over 200 shared
    # libraries) load only when a file is read or a chart drawn, numpy (0.2 s) when the first array is made:
    # `import petroscope` stays fast. OpenImageIO is loaded by nothing.
    probe = ("import sys, petroscope; maps = open('/proc/self/maps').read(); "
             "print('libpng' in maps, 'opencv' in maps, 'numpy' in sys.modules); "
             "import petroscope._files; maps = open('/proc/self/maps').read(); print('libpng' in maps, 'opencv' in maps, 'OpenImageIO' in maps)")
    lines = subprocess.run([sys.executable, "-c", probe], check=True, capture_output=True, text=True, env=os.environ).stdout.split()
    assert lines == ["False", "False", "False", "True", "True", "False"]


def test_minerals_agree_with_the_command_line():
    names = petroscope.minerals()
    assert "quartz" in names and "muscovite" in names
    binary = os.environ.get("PETROSCOPE_BINARY")
    if not binary:
        pytest.skip("the command-line tool is not built")
    shown = json.loads(subprocess.run([binary, "minerals", "show", "aragonite", "--wavelength", "589.3nm", "--json"], check=True,
                                      capture_output=True, text=True).stdout)
    aragonite = petroscope.mineral("aragonite")
    assert aragonite.optical_class == "biaxial"
    summary = aragonite.summary(589.3)
    n = aragonite.principal_n(589.3)
    assert sorted(n) == pytest.approx([summary["n_alpha"], summary["n_beta"], summary["n_gamma"]], abs=1e-15)
    for key in ("n_alpha", "n_beta", "n_gamma", "birefringence", "two_v_deg", "sign"):
        assert summary[key] == shown[key], key


def test_every_public_function_explains_its_arguments():
    for name in petroscope.__all__:
        doc = getattr(petroscope, name).__doc__
        assert doc and len(doc) > 40, name
    assert "thickness_um" in petroscope.conoscope.__doc__
    assert "ValueError" in petroscope.mineral.__doc__


def test_the_type_stubs_cover_every_public_name():
    import ast
    import pathlib

    stubs = ast.parse(pathlib.Path(petroscope.__file__).with_name("__init__.pyi").read_text())
    declared = {node.name for node in stubs.body if isinstance(node, (ast.FunctionDef, ast.ClassDef))}
    assert set(petroscope.__all__) - declared == set()
