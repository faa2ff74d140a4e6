"""cmake --install puts a complete package where the interpreter under that prefix finds it."""
import os
import pathlib
import subprocess
import sys

import pytest

from conftest import PAPER_BRICK


def test_the_installed_package_imports_and_solves(tmp_path):
    build = os.environ.get("FRICON_BUILD_DIR")
    site = os.environ.get("FRICON_PYTHON_INSTALL_DIR")
    if not build or not site:
        pytest.skip("FRICON_BUILD_DIR / FRICON_PYTHON_INSTALL_DIR are not set")
    subprocess.run(["cmake", "--install", build, "--prefix", str(tmp_path)], check=True,
                   capture_output=True)
    assert (tmp_path / "bin" / "fricon").exists()
    env = {"PATH": os.environ.get("PATH", ""), "PYTHONPATH": str(tmp_path / site),
           "HOME": str(tmp_path)}
    code = ("import fricon; r = fricon.solve(%r, threads=1); "
            "print(fricon.__file__); print(r.converged)" % str(PAPER_BRICK))
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True,
                         cwd=tmp_path)
    assert out.returncode == 0, out.stderr
    where, converged = out.stdout.split()
    assert pathlib.Path(where).is_relative_to(tmp_path) and converged == "True"
