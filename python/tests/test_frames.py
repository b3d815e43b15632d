"""fm.frames and fm.save_gif: shapes, the robot and its path in the frames, stride, same bytes,
GIFs that decode with the right frame count, the output guard, bad input, the guide's section."""

import numpy as np
import pytest

import fuzzymotiv as fm

BODY = (199, 221, 236)  # fuzzymotiv_pipeline::render::frames::scene::BODY
PATH = (31, 119, 180)  # ... ::PATH
STEPS = {"trial.steps": 60}
GENOME = np.linspace(-1.0, 1.0, 68)


@pytest.fixture(scope="module")
def traj():
    return fm.simulate(GENOME, "H", seed=5, overrides=STEPS)


def mask(frame, rgb):
    return np.all(frame == np.array(rgb, dtype=np.uint8), axis=-1)


def test_shape_dtype_and_size(traj):
    f = fm.frames(traj, size=128)
    assert f.shape == (61, 128, 128, 3) and f.dtype == np.uint8
    assert fm.frames(traj, size=96, stride=60).shape == (2, 96, 96, 3)


def test_the_body_moves_with_the_robot_and_leaves_a_path(traj):
    f = fm.frames(traj, size=320)
    first, last = mask(f[0], BODY), mask(f[-1], BODY)
    assert first.sum() > 20 and last.sum() > 20
    # The body's centre moves as the robot does: x to the right, y up (rows grow downwards).
    (r0, c0), (r1, c1) = (np.argwhere(m).mean(axis=0) for m in (first, last))
    dx, dy = traj["x"][-1] - traj["x"][0], traj["y"][-1] - traj["y"][0]
    assert np.hypot(dx, dy) > 30, "the robot moved"
    scale = (c1 - c0) / dx if abs(dx) > abs(dy) else (r0 - r1) / dy
    assert 0.2 < scale < 0.6, scale  # pixels per mm of an 800 mm room in 320 pixels
    assert mask(f[0], PATH).sum() == 0
    assert mask(f[-1], PATH).sum() > 20


def test_stride_and_same_bytes(traj):
    every = fm.frames(traj, size=96)
    strided = fm.frames(traj, size=96, stride=7)
    picks = list(range(0, 61, 7)) + [60]
    assert np.array_equal(strided, every[picks])
    assert fm.frames(traj, size=96).tobytes() == every.tobytes()


def test_a_genome_is_run_as_simulate_runs_it(traj):
    from_genome = fm.frames(GENOME, "H", size=96, seed=5, overrides=STEPS)
    assert np.array_equal(from_genome, fm.frames(traj, size=96))


def test_poses_alone_are_enough(traj):
    """The Gymnasium env passes x, y, heading of the steps so far (sensors, action optional)."""
    poses = {k: traj[k][:11] for k in ("x", "y", "heading")}
    f = fm.frames(poses, "H", size=96)
    assert f.shape == (11, 96, 96, 3)
    with_sensors = dict(poses, sensors=traj["sensors"][:10], action=traj["action"][:10])
    g = fm.frames(with_sensors, "H", size=96)
    assert g.shape == f.shape and not np.array_equal(f, g)  # rays and labels drawn
    assert fm.frames(poses, "H", size=96, stride=11)[-1].tobytes() == f[-1].tobytes()


def gif_frames(data: bytes):
    """(width, height, frame count) of a GIF, walking its blocks (no imaging library needed)."""
    assert data[:6] == b"GIF89a"
    w, h, flags = int.from_bytes(data[6:8], "little"), int.from_bytes(data[8:10], "little"), data[10]
    i = 13 + (3 << ((flags & 7) + 1) if flags & 0x80 else 0)
    count = 0

    def skip_blocks(i):
        while data[i]:
            i += data[i] + 1
        return i + 1

    while data[i] != 0x3B:
        if data[i] == 0x21:  # extension
            i = skip_blocks(i + 2)
        elif data[i] == 0x2C:  # image
            count += 1
            lflags = data[i + 9]
            i += 10 + (3 << ((lflags & 7) + 1) if lflags & 0x80 else 0)
            i = skip_blocks(i + 1)
        else:
            raise AssertionError(f"bad block {data[i]:#x} at {i}")
    return w, h, count


def test_save_gif_writes_a_gif_with_every_frame(traj, tmp_path):
    out = tmp_path / "h.gif"
    assert fm.save_gif(traj, out, size=128, stride=4) == 16
    assert gif_frames(out.read_bytes()) == (128, 128, 16)
    frames = fm.frames(traj, size=128, stride=4)
    again = tmp_path / "again.gif"
    assert fm.save_gif(frames, again) == 16
    assert again.read_bytes() == out.read_bytes()
    try:
        from PIL import Image
    except ImportError:
        return
    with Image.open(out) as im:
        assert im.n_frames == 16 and im.size == (128, 128)
        im.seek(15)
        assert np.array_equal(np.asarray(im.convert("RGB"))[mask(frames[-1], BODY)][0], BODY)


def test_save_gif_keeps_other_files(traj, tmp_path):
    out = tmp_path / "h.gif"
    fm.save_gif(traj, out, size=96, stride=30)
    fm.save_gif(traj, out, size=96, stride=30)  # the same bytes: nothing to do
    with pytest.raises(fm.FuzzymotivError, match=r"exists with other contents.*force=True"):
        fm.save_gif(traj, out, size=96, stride=20)
    fm.save_gif(traj, out, size=96, stride=20, force=True)
    assert gif_frames(out.read_bytes())[2] == 4
    (tmp_path / "d.gif").mkdir()
    with pytest.raises(fm.FuzzymotivError, match="is a directory, which is never replaced"):
        fm.save_gif(traj, tmp_path / "d.gif", size=96, force=True)


@pytest.mark.parametrize(
    "call, message",
    [
        (lambda t: fm.frames(t, size=10), r"size: must be a frame side in 64\.\.=2048 pixels, got 10"),
        (lambda t: fm.frames(t, size=-3), r"size: .* got -3"),
        (lambda t: fm.frames(t, stride=0), r"stride: must be a whole number ≥ 1"),
        (lambda t: fm.frames(t, size=100.5), r"size: expected a whole number"),
        (lambda t: fm.frames(dict(t, x=t["x"] * np.nan)), r"x\[0\]: `NaN` is not a finite number"),
        (lambda t: fm.frames({"x": t["x"], "y": t["y"]}), r"trajectory: no `heading` column"),
        (lambda t: fm.frames(dict(t, y=t["y"][:5])), r"x, y and heading have 61, 5 and 61 values"),
        (lambda t: fm.frames(dict(t, sensors=t["sensors"][:, :3])), r"expected a \(T, 8\) array"),
        (lambda t: fm.frames(dict(t, sensors=t["sensors"][:7])), r"sensors: 7 rows for 61 poses"),
        (lambda t: fm.frames(dict(t, action=["jump"] * 60)), r"action\[0\] is `jump`"),
        (lambda t: fm.frames(t, "nowhere"), r"room nowhere: not a room of the config"),
        (lambda t: fm.frames(np.zeros(5), "H"), r"genome: 5 weights, but an 8-6-2 network needs 68"),
        (lambda t: fm.save_gif(t, "x.gif", fps=0), r"fps: must be a frame rate"),
        (lambda t: fm.save_gif(np.zeros((2, 8, 8, 3)), "x.gif"), r"uint8"),
        (lambda t: fm.save_gif(np.zeros((2, 8, 8, 4), np.uint8), "x.gif"), r"\(T, H, W, 3\)"),
        (
            lambda t: fm.frames({k: np.zeros(1000) for k in ("x", "y", "heading")}, "H", size=2048),
            r"1000 frames of 2048 × 2048 pixels need 11\.7 GiB, more than the 8 GiB",
        ),
        (lambda t: fm.save_gif(np.zeros((2, 0, 8, 3), np.uint8), "x.gif"), r"T, H, W ≥ 1"),
        (lambda t: fm.save_gif(np.zeros((2, 8, 0, 3), np.uint8), "x.gif"), r"T, H, W ≥ 1"),
        (lambda t: fm.save_gif(np.zeros((8, 8, 3), np.uint8), "x.gif"), r"shape \[8, 8, 3\].*frames\[None\]"),
    ],
)
def test_bad_input_is_named(traj, tmp_path, monkeypatch, call, message):
    monkeypatch.chdir(tmp_path)
    with pytest.raises(fm.FuzzymotivError, match=message):
        call(traj)
    assert not (tmp_path / "x.gif").exists()


def test_guide_frames_section(doc_blocks, tmp_path, monkeypatch):
    """The guide's "Frames and GIFs" code (docs/guide/python.md) runs as written."""
    (code,) = doc_blocks("docs/guide/python.md", "## Frames and GIFs")
    monkeypatch.chdir(tmp_path)
    scope: dict = {}
    exec(compile(code, "docs/guide/python.md (Frames and GIFs)", "exec"), scope)
    assert (tmp_path / "rollout-H.gif").is_file()
