"""The repository README's five-line example runs as written, and
python/examples/readme_picture.py is those same lines."""
import os
import re

import numpy as np

from conftest import ROOT


def readme_example():
    text = open(os.path.join(ROOT, "README.md")).read()
    return re.search(r"```python\n(.*?)```", text, re.S).group(1)


def test_the_readmes_example_gives_a_colour_image_and_a_depth_array(monkeypatch):
    code = readme_example()
    assert len(code.strip().splitlines()) == 5
    monkeypatch.chdir(ROOT)  # it names assets/ from the repository's root
    scope = {}
    exec(compile(code, "README.md", "exec"), scope)
    color, depth = scope["color"], scope["depth"]
    assert color.shape == (480, 640, 3) and color.dtype == np.uint8
    assert depth.shape == (480, 640) and depth.dtype == np.float32
    drawn = depth > 0
    assert 0.1 < drawn.mean() < 0.9 and np.all(color[~drawn] == 0) and color[drawn].max() > 100


def test_the_picture_script_runs_the_readmes_lines():
    script = open(os.path.join(ROOT, "python", "examples", "readme_picture.py")).read()
    for line in readme_example().strip().splitlines():
        assert line in script, line
