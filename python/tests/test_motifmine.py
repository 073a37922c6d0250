"""Tests of the Python module `motifmine` (docs/python.md), run by ctest as python_tests:

    PYTHONPATH=build/python MOTIFMINE_TOOL=build/motifmine /usr/bin/python3 -m pytest python/tests

They compare the module with the `motifmine` tool on the same input: the same motifs, and the
same rotations as the BVH that `motifmine export` writes.
"""
import json
import math
import os
import subprocess
import threading

import numpy as np
import pytest

import motifmine

TOOL = os.environ.get("MOTIFMINE_TOOL", "build/motifmine")
FRAMES = 20000  # a small built-in synthetic archive: 3 planted motifs
MOTIFS = 3


def tool(*args):
    return subprocess.run([TOOL, *args], check=True, stdout=subprocess.PIPE, text=True).stdout


@pytest.fixture(scope="module")
def mined(tmp_path_factory):
    """The module's and the tool's runs on the same synthetic archive."""
    root = tmp_path_factory.mktemp("mined")
    stages = []
    result = motifmine.mine(out_dir=str(root / "py"), synth_frames=FRAMES, synth_motifs=MOTIFS,
                            write_report=False,
                            progress=lambda stage, done, total: stages.append(stage))
    tool("mine", "--out", str(root / "cli"), "--synth-frames", str(FRAMES), "--synth-motifs",
         str(MOTIFS), "--quiet", "--no-report")
    with open(root / "cli" / "motifs.json") as f:
        expected = json.load(f)
    return result, expected, stages


def test_mine_finds_the_tools_motifs(mined):
    result, expected, _ = mined
    assert len(result.motifs) == len(expected["motifs"]) >= MOTIFS
    for motif, want in zip(result.motifs, expected["motifs"]):
        got = [(i.clip, i.start, i.end) for i in motif.instances]
        assert got == [(i["clip"], i["start"], i["end"]) for i in want["instances"]]
    assert [m.id for m in result.motifs] == list(range(len(result.motifs)))
    assert result.parameters.k_max == 256
    assert result.parameters.min_length_frames == 60
    assert result.parameters.eps == pytest.approx(expected["params"]["eps"], rel=1e-6)
    assert [c.name for c in result.clips] == [c["name"] for c in expected["clips"]]


def test_progress_reports_each_stage(mined):
    _, _, stages = mined
    seen = list(dict.fromkeys(stages))
    assert seen == ["synth", "trellis features", "trellis", "grow", "cluster"]


def test_archive_clips_and_frames(mined):
    result, expected, _ = mined
    archive = motifmine.Archive(result.archive_path)
    assert archive.frames == expected["frames"] == FRAMES
    assert archive.fps == 120.0
    assert sum(c.frames for c in archive.clips) == FRAMES
    assert archive.clips[0].first_frame == 0
    assert archive.clips[1].first_frame == archive.clips[0].frames
    assert len(archive.joint_names) == 31


def quaternion_about(axis, degrees):
    half = math.radians(degrees) / 2
    q = np.zeros(4)
    q[0] = math.cos(half)
    q[1 + "XYZ".index(axis)] = math.sin(half)
    return q


def multiply(a, b):
    w1, x1, y1, z1 = a
    w2, x2, y2, z2 = b
    return np.array([w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2, w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
                     w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2, w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2])


def bvh_rotations(path):
    """{joint: [quaternion per frame]} of a BVH file's rotation channels (R = R1 R2 R3 in the
    channel order), and the joint order of its hierarchy."""
    lines = open(path).read().splitlines()
    joints, channels = [], []
    for line in lines:
        words = line.split()
        if words and words[0] in ("ROOT", "JOINT"):
            joints.append(words[1])
        elif words and words[0] == "CHANNELS":
            channels.append(words[2:])
    start = lines.index("MOTION") + 3
    frames = []
    for line in lines[start:]:
        values = [float(v) for v in line.split()]
        column, per_joint = 0, {}
        for joint, names in zip(joints, channels):
            q = np.array([1.0, 0, 0, 0])
            for name in names:
                if name.endswith("rotation"):
                    q = multiply(q, quaternion_about(name[0], values[column]))
                column += 1
            per_joint[joint] = q
        frames.append(per_joint)
    return joints, frames


def test_rotations_are_what_export_writes(mined, tmp_path):
    result, _, _ = mined
    archive = motifmine.Archive(result.archive_path)
    clip = archive.clips[0].name
    rotations = archive.rotations(clip, 100, 140)
    assert rotations.shape == (40, 31, 4)
    assert rotations.dtype == np.float32
    np.testing.assert_allclose(np.linalg.norm(rotations, axis=2), 1.0, atol=1e-5)

    exported = tmp_path / "range.bvh"
    tool("export", result.archive_path, "--clip", clip, "--start", "100", "--end", "140",
         "--out", str(exported))
    joints, frames = bvh_rotations(exported)
    assert len(frames) == 40
    names = archive.joint_names
    for j, name in enumerate(names[1:], start=1):  # the root's rotation has its heading back
        for f in range(40):
            dot = abs(float(np.dot(rotations[f, j], frames[f][name])))
            assert dot == pytest.approx(1.0, abs=1e-5), (name, f)


def test_import_takes_then_open(mined, tmp_path):
    result, _, _ = mined
    take = tmp_path / "take.bvh"
    tool("export", result.archive_path, "--clip", "synth_000000", "--end", "600", "--out",
         str(take))
    imported = motifmine.import_takes(str(tmp_path / "a.mfs"), [str(take)])
    assert (imported.takes_imported, imported.frames_added) == (1, 600)
    again = motifmine.import_takes(str(tmp_path / "a.mfs"), [str(take)])
    assert (again.takes_imported, again.takes_already_present) == (0, 1)
    archive = motifmine.Archive(str(tmp_path / "a.mfs"))
    assert [(c.name, c.frames) for c in archive.clips] == [("take", 600)]


def test_errors_raise_with_message_and_code(tmp_path):
    with pytest.raises(motifmine.Error) as missing:
        motifmine.Archive(str(tmp_path / "absent.mfs"))
    assert "absent.mfs" in str(missing.value)
    assert missing.value.code == 11  # not found, as the tool's exit code
    with pytest.raises(motifmine.OptionError) as bad:
        motifmine.mine(out_dir=str(tmp_path / "out"), k_max=0)
    assert isinstance(bad.value, motifmine.Error) and isinstance(bad.value, ValueError)
    assert bad.value.code == 13
    assert "k_max must be a whole number in [1, 65535], not '0'" in str(bad.value)  # as given
    for keyword, value in [("groups", 0), ("min_length_frames", 0), ("eps", math.nan),
                           ("threads", 65537), ("synth_frames", 99999999999)]:
        with pytest.raises(ValueError) as refused:  # as the tool's usage errors, by name
            motifmine.mine(out_dir=str(tmp_path / "out"), **{keyword: value})
        assert keyword.split("_")[0] in str(refused.value), keyword
    assert not (tmp_path / "out").exists()
    with pytest.raises(TypeError):
        motifmine.mine(out_dir=str(tmp_path / "out"), no_such_option=1)
    with pytest.raises(ValueError):
        motifmine.mine(out_dir=str(tmp_path / "out"), progress=fail_at_once, synth_frames=20000,
                       synth_motifs=3, write_report=False)


def test_keywords_are_the_tools_flags_from_one_table(tmp_path):
    rows = motifmine.option_table()
    flags = {o["name"]: o for o in json.loads(tool("mine", "--options-json"))}
    assert len(rows) >= 37
    for row in rows:
        assert row["keyword"] == row["name"].replace("-", "_")
        flag = flags[row["name"]]  # every keyword is a flag of `motifmine mine`
        assert flag["table"]
        if row["type"] != "switch":
            assert (flag["default"] or "") == row["default"], row["name"]
        # A value no option takes (a list), or text for a switch.
        wrong = "yes" if row["type"] == "switch" else [1]
        with pytest.raises(TypeError) as refused:
            motifmine.mine(out_dir=str(tmp_path / "out"), **{row["keyword"]: wrong})
        assert row["keyword"] in str(refused.value)
    with pytest.raises(motifmine.Error) as bad:
        motifmine.mine(out_dir=str(tmp_path / "out"), pause_seconds=0)
    assert bad.value.code == 13
    assert "pause_seconds must be a number in (0, 3600], not '0'" in str(bad.value)
    assert not (tmp_path / "out").exists()


def test_every_functions_arguments_are_refused_by_name(tmp_path):
    archive = str(tmp_path / "a.mfs")
    for call, name, error in [
            (lambda: motifmine.build_words(archive, motifs=-1), "motifs", ValueError),
            (lambda: motifmine.build_words(archive, threads=float("nan")), "threads", ValueError),
            (lambda: motifmine.search(archive, "clip", 0, 10, top=0), "top", ValueError),
            (lambda: motifmine.search(archive, "clip", -1, 10), "start", ValueError),
            (lambda: motifmine.search(archive, 7, 0, 10), "clip", TypeError),
            (lambda: motifmine.import_takes(archive, "take.bvh"), "paths", TypeError),
            (lambda: motifmine.signatures(archive, allow_older=1), "allow_older", TypeError),
            (lambda: motifmine.mine(out_dir=archive, progress=3), "progress", TypeError)]:
        with pytest.raises(error) as refused:
            call()
        assert name in str(refused.value)
        assert "incompatible function arguments" not in str(refused.value)  # pybind11's own


def fail_at_once(stage, done, total):
    raise ValueError("stop")


def test_the_gil_is_released_while_mining(mined, tmp_path):
    result, _, _ = mined
    ticks = []
    stop = threading.Event()

    def tick():
        while not stop.is_set():
            ticks.append(1)
            stop.wait(0.001)

    ticker = threading.Thread(target=tick)
    ticker.start()
    try:
        motifmine.mine([result.archive_path], out_dir=str(tmp_path / "again"), write_report=False)
    finally:
        stop.set()
        ticker.join()
    assert len(ticks) > 10  # the other thread ran during the call


def test_words_signatures_and_search_are_the_tools(tmp_path):
    archive = str(tmp_path / "s.mfs")
    tool("synth", archive, "--frames", "20000", "--motifs", "3", "--seed", "2", "--quiet")
    stages = []
    words = motifmine.build_words(archive, progress=lambda s, d, t: stages.append(s))
    assert words.takes == len(motifmine.Archive(archive).clips)
    assert words.words > 0 and words.motifs == 100
    assert words.signatures_path == str(tmp_path / "s.mws")
    assert "train" in stages

    names, signatures = motifmine.signatures(archive)
    assert names == [c.name for c in motifmine.Archive(archive).clips]
    assert signatures.shape == (len(names), words.motifs)
    assert signatures.dtype == np.float64
    assert (signatures >= 0).all() and (signatures.sum(axis=1) > 0).all()

    matches = motifmine.search(archive, names[0], 100, 400, top=3)
    tool("search", archive, "--clip", names[0], "--start", "100", "--end", "400", "--top", "3",
         "--out", str(tmp_path / "search"))
    with open(tmp_path / "search" / "search.json") as f:
        expected = json.load(f)["matches"]
    assert [(m.clip, m.start, m.end) for m in matches] == [
        (e["clip"], e["start"], e["end"]) for e in expected]
    assert [m.distance for m in matches] == pytest.approx([e["distance"] for e in expected])
    with pytest.raises(motifmine.Error) as missing:
        motifmine.search(archive, "no_such_clip", 0, 100)
    assert missing.value.code == 11


def two_commit_archive_with_its_newest_footer_damaged(tmp_path):
    """A two-take archive, one commit per take, whose last byte (the newest commit's footer) is
    flipped: only the first commit's version still validates."""
    archive = str(tmp_path / "two.mfs")
    tool("synth", str(tmp_path / "s.mfs"), "--frames", "20000", "--motifs", "3", "--seed", "2",
         "--quiet")
    for clip in ("synth_000000", "synth_000001"):
        tool("export", str(tmp_path / "s.mfs"), "--clip", clip, "--end", "600", "--out",
             str(tmp_path / (clip + ".bvh")))
        motifmine.import_takes(archive, [str(tmp_path / (clip + ".bvh"))])
    with open(archive, "r+b") as f:
        f.seek(-1, os.SEEK_END)
        last = f.read(1)
        f.seek(-1, os.SEEK_END)
        f.write(bytes([last[0] ^ 0xFF]))
    return archive


def test_a_damaged_newest_commit_is_refused_unless_allow_older(tmp_path):
    archive = two_commit_archive_with_its_newest_footer_damaged(tmp_path)
    out = tmp_path / "out"
    calls = [lambda **kw: motifmine.Archive(archive, **kw),
             lambda **kw: motifmine.mine([archive], out_dir=str(out), write_report=False, **kw),
             lambda **kw: motifmine.signatures(archive, **kw),
             lambda **kw: motifmine.search(archive, "synth_000000", 0, 300, **kw)]
    for call in calls:  # as `motifmine info` without --allow-older: exit 12
        with pytest.raises(motifmine.Error) as refused:
            call()
        assert refused.value.code == 12
        assert "footer" in str(refused.value) and "allow_older=True" in str(refused.value)
    assert subprocess.run([TOOL, "info", archive]).returncode == 12
    older = motifmine.Archive(archive, allow_older=True)  # the first commit: one take
    assert (older.frames, [c.name for c in older.clips]) == (600, ["synth_000000"])
    result = motifmine.mine([archive], out_dir=str(out), write_report=False, allow_older=True)
    assert [c.name for c in result.clips] == ["synth_000000"]
    with open(result.motifs_path) as f:
        assert json.load(f)["archive_version"]["generation"] == 1
    with pytest.raises(motifmine.Error):  # the keyword holds for its call only
        motifmine.Archive(archive)


def test_a_path_with_a_nul_is_a_value_error(tmp_path):
    archive = two_commit_archive_with_its_newest_footer_damaged(tmp_path)
    for call in [lambda: motifmine.Archive(archive + "\0junk"),
                 lambda: motifmine.mine([archive + "\0junk"], out_dir=str(tmp_path / "o")),
                 lambda: motifmine.mine(out_dir=str(tmp_path / "o\0junk")),
                 lambda: motifmine.import_takes(archive + "\0x", []),
                 lambda: motifmine.signatures(archive + "\0x")]:
        with pytest.raises(ValueError) as refused:
            call()
        assert "NUL" in str(refused.value)


def test_an_archive_cut_under_its_reader_is_damage_not_a_sigbus(tmp_path):
    archive = str(tmp_path / "cut.mfs")
    tool("synth", archive, "--frames", "60000", "--motifs", "2", "--seed", "4", "--quiet")
    opened = motifmine.Archive(archive)
    clip = opened.clips[-1]
    os.truncate(archive, 200)
    with pytest.raises(motifmine.Error) as cut:  # was: killed by signal 7
        opened.rotations(clip.name, 0, clip.frames)
    assert cut.value.code == 12
    assert archive + ": the file was cut while it was being read" in str(cut.value)
