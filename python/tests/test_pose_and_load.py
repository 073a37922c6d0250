"""Tests of rebuilding poses, loading a mined folder, the reprs and the keyword hints of the
Python module `motifmine` (docs/python.md), run by ctest as python_pose_and_load:

    PYTHONPATH=build/python MOTIFMINE_TOOL=build/motifmine /usr/bin/python3 -m pytest \
        python/tests/test_pose_and_load.py

A pose rebuilt from the module (skeleton, rotations, root) by forward kinematics in numpy is the
pose of the BVH file `motifmine export` writes for the same frames, on a synthetic archive and on
a real CMU take (/work/shared/data/mocap, skipped when absent).
"""
import json
import math
import os
import shutil
import subprocess

import numpy as np
import pytest

import motifmine

TOOL = os.environ.get("MOTIFMINE_TOOL", "build/motifmine")
MOCAP = os.environ.get("MOTIFMINE_MOCAP", "/work/shared/data/mocap")
CMU_TAKE = os.path.join(MOCAP, "bvh", "01_01.bvh")


def tool(*args):
    return subprocess.run([TOOL, *args], check=True, stdout=subprocess.PIPE, text=True).stdout


# Quaternions (w, x, y, z), numpy, shape (..., 4).
def q_multiply(a, b):
    w1, x1, y1, z1 = np.moveaxis(a, -1, 0)
    w2, x2, y2, z2 = np.moveaxis(b, -1, 0)
    return np.stack([w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2, w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
                     w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2, w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2],
                    axis=-1)


def q_rotate(q, v):
    """v (..., 3) turned by the unit quaternion q (..., 4)."""
    u, w = q[..., 1:], q[..., :1]
    t = 2 * np.cross(u, v)
    return v + w * t + np.cross(u, t)


def q_about(axis, radians):
    q = np.zeros(radians.shape + (4,))
    q[..., 0] = np.cos(radians / 2)
    q[..., 1 + "XYZ".index(axis)] = np.sin(radians / 2)
    return q


def forward_kinematics(parents, offsets, root_positions, rotations):
    """World joint positions (frames, joints, 3): the root at root_positions, every other joint
    at its parent's position plus its offset turned by the parent's world rotation; rotations
    (frames, joints, 4) are each joint's relative to its parent, the root's its world one."""
    frames, joints = rotations.shape[:2]
    world_rotation = np.zeros((frames, joints, 4))
    positions = np.zeros((frames, joints, 3))
    for joint, parent in enumerate(parents):
        if parent < 0:
            world_rotation[:, joint] = rotations[:, joint]
            positions[:, joint] = root_positions
            continue
        world_rotation[:, joint] = q_multiply(world_rotation[:, parent], rotations[:, joint])
        positions[:, joint] = positions[:, parent] + q_rotate(world_rotation[:, parent],
                                                              offsets[joint])
    return positions


def module_pose(archive, clip, start, end):
    """Forward kinematics over what the module gives: the clip's skeleton, the joints'
    rotations, the root's position and world rotation."""
    skeleton = archive.clip_skeleton(clip)
    rotations = archive.rotations(clip, start, end).astype(np.float64)
    rotations[:, 0] = archive.root_rotations(clip, start, end)
    return skeleton, forward_kinematics(skeleton.parents, skeleton.offsets,
                                        archive.root_positions(clip, start, end), rotations)


def bvh_pose(path):
    """(joint names, world positions (frames, joints, 3)) of a BVH file: OFFSETs, CHANNELS and
    the frame lines, rotations composed in channel order (R = R1 R2 R3), the root's position
    its OFFSET plus its position channels."""
    words = open(path).read().split()
    names, parents, offsets, channels, stack = [], [], [], [], []
    at, last = 0, -1
    while words[at] != "MOTION":
        word = words[at]
        if word in ("ROOT", "JOINT"):
            names.append(words[at + 1])
            parents.append(stack[-1] if stack else -1)
            last = len(names) - 1
            at += 2
        elif word == "End":  # End Site { OFFSET x y z }: no joint, no channels
            at += 8
        elif word == "{":
            stack.append(last)
            at += 1
        elif word == "}":
            stack.pop()
            at += 1
        elif word == "OFFSET":
            offsets.append([float(v) for v in words[at + 1:at + 4]])
            at += 4
        elif word == "CHANNELS":
            count = int(words[at + 1])
            channels.append(words[at + 2:at + 2 + count])
            at += 2 + count
        else:
            at += 1
    frames = int(words[at + 2])
    values = np.array(words[at + 6:], dtype=np.float64).reshape(frames, -1)
    rotations = np.zeros((frames, len(names), 4))
    root_positions = np.tile(np.array(offsets[0]), (frames, 1))
    column = 0
    for joint, joint_channels in enumerate(channels):
        q = np.tile([1.0, 0, 0, 0], (frames, 1))
        for channel in joint_channels:
            if channel.endswith("position"):
                root_positions[:, "XYZ".index(channel[0])] += values[:, column]
            else:
                q = q_multiply(q, q_about(channel[0], np.radians(values[:, column])))
            column += 1
        rotations[:, joint] = q
    return names, forward_kinematics(parents, np.array(offsets), root_positions, rotations)


def body_height(positions):
    return float(np.max(positions[..., 1]) - np.min(positions[..., 1]))


def check_pose_is_exports(archive, clip, start, end, tmp_path):
    """The module's pose of frames [start, end) of clip, against the exported BVH's."""
    skeleton, pose = module_pose(archive, clip, start, end)
    exported = tmp_path / (clip + ".bvh")
    tool("export", archive.path, "--clip", clip, "--start", str(start), "--end", str(end),
         "--out", str(exported))
    names, expected = bvh_pose(exported)
    assert sorted(names) == sorted(skeleton.source_joint_names)  # export's default: --names source
    order = [skeleton.source_joint_names.index(name) for name in names]
    height = body_height(expected)
    assert height > 0
    assert pose.shape == (end - start, len(names), 3)
    np.testing.assert_allclose(pose[:, order], expected, rtol=0, atol=1e-4 * height)
    # The module's own forward kinematics is the same pose.
    np.testing.assert_allclose(archive.world_positions(clip, start, end), pose, rtol=0,
                               atol=1e-6 * height)
    return skeleton, pose


@pytest.fixture(scope="module")
def synthetic(tmp_path_factory):
    root = tmp_path_factory.mktemp("synthetic")
    archive = str(root / "s.mfs")
    tool("synth", archive, "--frames", "15000", "--motifs", "2", "--seed", "3", "--quiet")
    return motifmine.Archive(archive)


def test_a_synthetic_pose_is_the_exported_bvhs(synthetic, tmp_path):
    clip = synthetic.clips[1]
    # A range that starts late in its clip: the root is integrated from the clip's first frame.
    skeleton, pose = check_pose_is_exports(synthetic, clip.name, 1000, 1090, tmp_path)
    assert skeleton.family == "cmu31"
    assert skeleton.joint_names == synthetic.joint_names
    assert skeleton.source_joint_names == synthetic.joint_names  # synthesised in canonical names
    assert skeleton.parents[0] == -1 and all(p < j for j, p in enumerate(skeleton.parents))
    assert skeleton.offsets.shape == (31, 3) and skeleton.offsets.dtype == np.float64
    # The root moves: its position is not the clip's start for every frame.
    assert np.ptp(synthetic.root_positions(clip.name, 1000, 1090)[:, [0, 2]], axis=0).max() > 1


def test_the_root_rotation_is_the_heading_times_the_stored_swing(synthetic):
    clip = synthetic.clips[0].name
    headings = synthetic.headings(clip, 0, 200)
    swing = synthetic.rotations(clip, 0, 200)[:, 0].astype(np.float64)
    rebuilt = q_multiply(q_about("Y", headings), swing)
    root = synthetic.root_rotations(clip, 0, 200)
    assert headings.shape == (200,) and root.shape == (200, 4)
    np.testing.assert_allclose(np.abs(np.sum(rebuilt * root, axis=1)), 1.0, atol=1e-6)
    assert np.all(np.abs(np.diff(headings)) < math.pi)  # unwrapped along the clip


def test_pose_ranges_are_checked_by_name(synthetic):
    clip = synthetic.clips[0]
    assert synthetic.root_positions(clip.name, 5, 5).shape == (0, 3)
    assert synthetic.world_positions(clip.name, 5, 5).shape == (0, 31, 3)
    with pytest.raises(motifmine.Error) as outside:
        synthetic.root_positions(clip.name, 0, clip.frames + 1)
    assert outside.value.code == 13 and clip.name in str(outside.value)
    with pytest.raises(motifmine.Error) as unknown:
        synthetic.world_positions("no_such_clip", 0, 10)
    assert unknown.value.code == 11 and "no_such_clip" in str(unknown.value)
    with pytest.raises(motifmine.Error) as unknown:
        synthetic.clip_skeleton("no_such_clip")
    assert unknown.value.code == 11
    with pytest.raises(ValueError) as negative:
        synthetic.headings(clip.name, -1, 10)
    assert "start" in str(negative.value)


def test_a_cmu_take_pose_is_the_exported_bvhs_with_source_names(tmp_path):
    if not os.path.isfile(CMU_TAKE):
        pytest.skip("no CMU take at %s (the real-data check needs /work/shared/data/mocap)"
                    % CMU_TAKE)
    archive_path = str(tmp_path / "cmu.mfs")
    motifmine.import_takes(archive_path, [CMU_TAKE])
    archive = motifmine.Archive(archive_path)
    clip = archive.clips[0]
    assert clip.name == "01_01"
    skeleton, pose = check_pose_is_exports(archive, clip.name, 600, 720, tmp_path)
    # The BVH's own names, the archive's canonical ones beside them.
    lfemur = archive.joint_names.index("lfemur")
    assert skeleton.source_joint_names[lfemur] == "LeftUpLeg"
    assert skeleton.source_joint_names[0] == "Hips" and skeleton.joint_names[0] == "root"
    assert archive.skeleton.source_joint_names == skeleton.source_joint_names
    assert skeleton.joint_names == archive.joint_names  # unchanged: canonical
    # A person: the head above the feet by most of the body's height.
    head, foot = archive.joint_names.index("head"), archive.joint_names.index("lfoot")
    assert np.all(pose[:, head, 1] - pose[:, foot, 1] > 0.6 * body_height(pose))


def write_folder(path, motifs_json):
    os.makedirs(path, exist_ok=True)
    with open(os.path.join(path, "motifs.json"), "w") as f:
        json.dump(motifs_json, f)


SMALL_MOTIFS = {
    "version": 2, "archive": "archive.mfs", "frames": 900,
    "clips": [{"name": "walk", "source": "takes/walk.bvh", "frames": 600, "fps": 120.0,
               "first_frame": 0},
              {"name": "run", "source": "takes/run.bvh", "frames": 300, "fps": 60.0,
               "first_frame": 600}],
    "params": {"eps": 1.25, "kmax": 64, "branch": 5, "min_length": 60, "groups": "auto",
               "seed": 7},
    "motifs": [{"id": 0, "instances": [{"clip": "walk", "start": 100, "end": 220},
                                       {"clip": "run", "start": 30, "end": 90}]}],
}


def test_reprs_say_what_an_object_holds(tmp_path, synthetic):
    folder = str(tmp_path / "small")
    write_folder(folder, SMALL_MOTIFS)
    result = motifmine.load(folder)
    assert repr(result) == "<MineResult: 1 motif, 2 instances, 900 frames>"
    assert repr(result.motifs[0]) == "<Motif 0: 2 instances, mean 1.00 s>"
    assert repr(result.motifs[0].instances[0]) == "<Instance: walk frames [100, 220), 1.00 s>"
    assert repr(result.motifs[0].instances[1]) == "<Instance: run frames [30, 90), 1.00 s>"
    assert result.motifs[0].instances[1].seconds == 1.0
    assert repr(synthetic) == ("<Archive: %s, %d takes, 15000 frames at 120 fps, skeleton cmu31>"
                               % (synthetic.path, len(synthetic.clips)))
    assert repr(synthetic.skeleton) == "<Skeleton cmu31: 31 joints, root 'root'>"


def test_load_reads_a_hand_written_folder_and_tolerates_new_fields(tmp_path):
    document = json.loads(json.dumps(SMALL_MOTIFS))
    motif = document["motifs"][0]  # fields newer writers add, and ones no writer has yet
    motif.update({"representative": 0, "a_future_field": {"x": 1}})
    for instance, distance in zip(motif["instances"], [0.0, 0.5]):
        instance.update({"distance": distance, "file_first_frame": instance["start"] + 1,
                         "a_future_field": [1, 2]})
    document["summary"] = {"motifs": 1, "instances": 2, "covered_frames": 180, "extra": [1]}
    folder = str(tmp_path / "newer")
    write_folder(folder, document)
    result = motifmine.load(folder)
    assert [(i.clip, i.start, i.end, i.fps) for i in result.motifs[0].instances] == [
        ("walk", 100, 220, 120.0), ("run", 30, 90, 60.0)]
    assert [(c.name, c.source, c.first_frame, c.frames, c.fps) for c in result.clips] == [
        ("walk", "takes/walk.bvh", 0, 600, 120.0), ("run", "takes/run.bvh", 600, 300, 60.0)]
    p = result.parameters
    assert (p.eps, p.k_max, p.branch, p.min_length_frames, p.seed) == (1.25, 64, 5, 60, 7)
    assert p.eps_how == "" and result.timings == []  # no run.json
    assert result.archive_path == os.path.join(folder, "archive.mfs")  # relative to the folder
    assert result.motifs_path == os.path.join(folder, "motifs.json")


def test_load_refuses_a_folder_without_motifs_by_its_path(tmp_path):
    missing = str(tmp_path / "absent")
    with pytest.raises(motifmine.Error) as refused:
        motifmine.load(missing)
    assert refused.value.code == 11 and missing in str(refused.value)
    empty = tmp_path / "empty"
    empty.mkdir()
    with pytest.raises(motifmine.Error) as refused:
        motifmine.load(str(empty))
    assert refused.value.code == 11
    assert str(empty / "motifs.json") in str(refused.value)
    write_folder(str(tmp_path / "bad"), {"version": 2})
    with pytest.raises(motifmine.Error) as bad:
        motifmine.load(str(tmp_path / "bad"))
    assert bad.value.code == 13 and "motifs.json" in str(bad.value)
    with pytest.raises(TypeError) as wrong:
        motifmine.load(3)
    assert "out_dir" in str(wrong.value)


def test_load_gives_back_what_mine_returned(tmp_path):
    out = str(tmp_path / "mined")
    mined = motifmine.mine(out_dir=out, synth_frames=15000, synth_motifs=2, no_report=True)
    loaded = motifmine.load(out)
    assert len(loaded.motifs) == len(mined.motifs) >= 2

    def instances(result):
        return [[(m.id, i.clip, i.start, i.end, i.fps) for i in m.instances]
                for m in result.motifs]

    assert instances(loaded) == instances(mined)
    assert [(c.name, c.source, c.first_frame, c.frames, c.fps) for c in loaded.clips] == [
        (c.name, c.source, c.first_frame, c.frames, c.fps) for c in mined.clips]
    fields = ("eps", "eps_how", "k_max", "branch", "min_length_frames", "seed")
    assert [getattr(loaded.parameters, f) for f in fields] == [
        getattr(mined.parameters, f) for f in fields]
    assert [(t.stage, t.reused) for t in loaded.timings] == [
        (t.stage, t.reused) for t in mined.timings]
    assert [t.seconds for t in loaded.timings] == pytest.approx([t.seconds for t in mined.timings])
    assert (loaded.archive_path, loaded.motifs_path) == (mined.archive_path, mined.motifs_path)
    assert repr(loaded) == repr(mined)
    # A moved folder still finds the archive inside it.
    moved = str(tmp_path / "moved")
    shutil.move(out, moved)
    assert motifmine.load(moved).archive_path == os.path.join(moved, "archive.mfs")
    assert instances(motifmine.load(moved)) == instances(mined)


def test_an_unknown_keyword_names_the_nearest(tmp_path):
    out = str(tmp_path / "out")
    for given, nearest in [("kmaxx", "kmax"), ("k_maxx", "k_max"), ("synth_frame", "synth_frames"),
                           ("eps_angel", "eps_angle"), ("allow_olders", "allow_older")]:
        with pytest.raises(TypeError) as refused:
            motifmine.mine(out_dir=out, **{given: 1})
        assert str(refused.value) == (
            "mine(): unknown keyword '%s': did you mean '%s'?" % (given, nearest))
    with pytest.raises(TypeError) as refused:
        motifmine.mine(out_dir=out, zzzzzzzz=1)
    assert str(refused.value) == (
        "mine(): unknown keyword 'zzzzzzzz' (motifmine.option_table() lists them)")
    assert not os.path.exists(out)


def test_a_folder_of_two_families_imports_onto_the_cmu_body(tmp_path):
    daz_take = os.path.join(MOCAP, "bvh_daz", "02_01.bvh")
    if not (os.path.isfile(CMU_TAKE) and os.path.isfile(daz_take)):
        pytest.skip("no CMU and Daz takes under %s (the real-data check needs "
                    "/work/shared/data/mocap)" % MOCAP)
    archive_path = str(tmp_path / "mixed.mfs")
    imported = motifmine.import_takes(archive_path, [daz_take, CMU_TAKE])
    assert (imported.takes_imported, imported.takes_mapped) == (2, 1)
    archive = motifmine.Archive(archive_path)
    assert len(archive.joint_names) == 31 and archive.joint_names[1] == "lhipjoint"
