"""EXR files from Python: written whole, read back bit for bit, refused before anything is written where the path
or the file is wrong."""

import numpy as np
import pytest

import grtrace


def test_a_frame_reads_back_bit_for_bit(tmp_path):
    frame = grtrace.render(metric="kerr", spin=0.7, scene="disk", camera_theta=70, width=40, height=30)
    path = tmp_path / "kerr.exr"
    frame.write_exr(str(path))
    assert (tmp_path / "kerr.png").exists()  # the preview beside it
    back = grtrace.read_exr(str(path))
    assert back.channel_names == frame.channel_names
    for name in frame.channel_names:
        assert np.array_equal(back[name].view(np.uint32), frame[name].view(np.uint32)), name
    assert back.header["metric"] == "kerr" and back.header["tracer"] == frame.report["tracer"]
    assert back.report == {}


def test_a_frame_of_ones_own_arrays(tmp_path):
    y, x = np.mgrid[0:8, 0:12]
    mine = grtrace.frame({"R": x / 11.0, "G": y / 7.0, "B": np.zeros((8, 12))}, {"note": "mine"})
    mine.write_exr(str(tmp_path / "mine.exr"), compression="piz", preview=False)
    assert not (tmp_path / "mine.png").exists()
    back = grtrace.read_exr(str(tmp_path / "mine.exr"))
    assert np.array_equal(back["R"], (x / 11.0).astype(np.float32))
    assert back.header["note"] == "mine"
    assert back.rgb().shape == (8, 12, 3)


def test_refusals_write_nothing(tmp_path):
    frame = grtrace.frame({"R": np.zeros((2, 2))})
    with pytest.raises(ValueError, match="must name an .exr file"):
        frame.write_exr(str(tmp_path / "frame.png"))
    with pytest.raises(ValueError, match="unknown compression"):
        frame.write_exr(str(tmp_path / "frame.exr"), compression="jpeg")
    with pytest.raises(ValueError, match="write_exr"):
        frame.write_exr(str(tmp_path / "missing" / "frame.exr"))
    assert list(tmp_path.iterdir()) == []
    with pytest.raises(ValueError, match="no such file"):
        grtrace.read_exr(str(tmp_path / "none.exr"))
    (tmp_path / "junk.exr").write_bytes(b"not an exr file at all")
    with pytest.raises(ValueError, match="junk.exr"):
        grtrace.read_exr(str(tmp_path / "junk.exr"))
    with pytest.raises(ValueError, match="2-d array"):
        grtrace.frame({"R": np.zeros(4)})
    with pytest.raises(ValueError, match="the others"):
        grtrace.frame({"R": np.zeros((2, 2)), "G": np.zeros((3, 2))})
