"""Builds softrast._softrast against the library's installed archives.

The archives (build/libsoftrast.a, build/libsoftrast-files.a) are made by the
repository's Makefile, which this build runs first; the libraries they need
are the pkg-config packages the files library's .pc file requires, read from
tools/softrast-files.pc.in and tools/softrast.pc.in so the list is kept once.
"""
import os
import shlex
import subprocess
import sys

import numpy
from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
ARCHIVES = ["build/libsoftrast-files.a", "build/libsoftrast.a"]  # the files library first: it uses the core


def requires(pc_in):
    """The pkg-config packages a tools/*.pc.in names on its Requires line."""
    with open(os.path.join(ROOT, "tools", pc_in)) as f:
        for line in f:
            if line.startswith("Requires:"):
                return [p for p in line.split(":", 1)[1].replace(",", " ").split() if not p.startswith("softrast")]
    return []


def pkg_config(*args):
    packages = requires("softrast.pc.in") + requires("softrast-files.pc.in")
    try:
        out = subprocess.run(["pkg-config", *args, *packages], check=True, capture_output=True, text=True).stdout
    except (OSError, subprocess.CalledProcessError) as e:
        sys.exit(f"softrast: pkg-config {' '.join(args)} {' '.join(packages)} failed ({e}); "
                 "run `make` in the repository first (it installs the Debian packages it needs)")
    return shlex.split(out)


class BuildWithLibrary(build_ext):
    """Makes the library's archives before the extension links them."""

    def run(self):
        if not os.path.exists(os.path.join(ROOT, "Makefile")):
            sys.exit(f"softrast: {ROOT} is not the softrast repository: build the package from its python/ folder")
        env = {k: v for k, v in os.environ.items() if k not in ("MAKEFLAGS", "MFLAGS", "MAKELEVEL")}
        subprocess.run(["make", "-C", ROOT, "--no-print-directory", *ARCHIVES], check=True, env=env)
        super().run()


cflags = pkg_config("--cflags")
extra_compile_args = ["-std=c11", "-Wall", "-Wextra", "-Wno-missing-field-initializers"] + cflags
if os.environ.get("SOFTRAST_WERROR"):
    extra_compile_args.append("-Werror")

setup(
    ext_modules=[
        Extension(
            "softrast._softrast",
            sources=["src/module.c", "src/mesh.c", "src/renderer.c", "src/mesh_origin.c", "src/vertex_colours.c"],
            depends=["src/softrast_py.h"] + [os.path.join(ROOT, a) for a in ARCHIVES],
            # src/ for io/mesh_origin.c and io/vertex_colours.c (python/src/'s)
            include_dirs=[os.path.join(ROOT, "include"), os.path.join(ROOT, "src"), numpy.get_include()],
            extra_compile_args=extra_compile_args,
            extra_objects=[os.path.join(ROOT, a) for a in ARCHIVES],
            # The archives' symbols stay inside the extension.
            extra_link_args=pkg_config("--libs") + ["-lm", "-lpthread", "-Wl,--exclude-libs,ALL"],
        )
    ],
    cmdclass={"build_ext": BuildWithLibrary},
)
