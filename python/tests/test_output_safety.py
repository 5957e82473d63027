"""Issue 24: Motion.to_csv/to_json never overwrite the model's own file (by inode:
the path, a symlink or a hard link to it); the file stays byte for byte."""
import os
import shutil

import pytest

import mechkin

HERE = os.path.dirname(os.path.abspath(__file__))
BUNDLED = os.path.join(HERE, "..", "..", "mechanisms", "parametric-slider-crank.json")


@pytest.mark.parametrize("writer", ["to_csv", "to_json"])
@pytest.mark.parametrize("alias", ["itself", "symlink", "hardlink"])
def test_motion_writers_refuse_the_model_file(tmp_path, writer, alias):
    path = tmp_path / "model.json"
    shutil.copy(BUNDLED, path)
    original = path.read_bytes()
    target = path
    if alias == "symlink":
        target = tmp_path / "link.csv"
        os.symlink(path, target)
    elif alias == "hardlink":
        target = tmp_path / "hard.csv"
        os.link(path, target)
    motion = mechkin.load(path).run()
    with pytest.raises(RuntimeError, match="onto the input file"):
        getattr(motion, writer)(target)
    assert path.read_bytes() == original
    getattr(motion, writer)(tmp_path / "elsewhere.out")  # another path is written
    assert (tmp_path / "elsewhere.out").read_bytes().startswith(b"t [s]," if writer == "to_csv" else b"{")
