"""`cmake --install` puts the package where the Debian python finds it, with its libraries."""

import os
import pathlib
import subprocess
import sys

import pytest


def test_the_installed_package_imports_and_runs_without_the_build_tree(tmp_path):
    build, cmake = os.environ.get("STAGGER_BINARY_DIR"), os.environ.get("CMAKE_COMMAND")
    if not build or not cmake:
        pytest.skip("STAGGER_BINARY_DIR and CMAKE_COMMAND are not set; ctest sets them")
    prefix = tmp_path / "prefix"
    subprocess.run([cmake, "--install", build, "--prefix", str(prefix)], check=True, stdout=subprocess.DEVNULL)
    version = f"python{sys.version_info.major}.{sys.version_info.minor}"
    site = prefix / "lib" / version / "dist-packages"  # /usr/local/lib/python3.X/dist-packages by default
    assert (site / "stagger" / "__init__.py").is_file()
    script = ("import stagger; print(stagger.__file__); "
              f"sim = stagger.Simulation(stagger.load_scene({str(prefix / 'share/stagger/scenes/sod.toml')!r}, "
              "{'time.end': 0.01})); print(sim.run())")
    environment = {"PATH": "/usr/bin:/bin", "PYTHONPATH": str(site), "PYTHONDONTWRITEBYTECODE": "1"}
    ran = subprocess.run([sys.executable, "-c", script], env=environment, cwd=tmp_path, capture_output=True,
                         text=True, check=True)
    imported, status = ran.stdout.split()
    assert pathlib.Path(imported).is_relative_to(site) and status == "completed"
