#!/usr/bin/python3
"""Render a motion-capture take as images, for annotating repetitions.

What it is for: building the hand-made ground truth in tests/data/repetitions/
(which frame ranges of a real take repeat which movement). A person looks at
these images to find and place the repeated movements; nothing here mines
motifs or decides anything.

Input: one BVH file, normally one exported by motifmine itself, so that BVH
motion line k (0-based) is clip frame k:
    motifmine import X.mfs TAKE.amc --asf SKELETON.asf     (or: import X.mfs TAKE.bvh)
    motifmine export X.mfs --clip CLIP --out CLIP.bvh

Forward kinematics follows the HIERARCHY: per joint, the rotation channels in
the order they are listed, in degrees (R = R_ch1 * R_ch2 * R_ch3), child
position = parent position + parent world rotation * OFFSET. Y is up. The
body's heading comes from the hip joints: left = (left hip - right hip) made
horizontal, forward = left x up.

Usage (run with /usr/bin/python3; needs python3-numpy, python3-matplotlib):
    render_take.py CLIP.bvh --curves OUT.png [--start S --end E]
    render_take.py CLIP.bvh --similarity OUT.png [--start S --end E]
    render_take.py CLIP.bvh --figures OUT.png --frames 120,180,240
Frame numbers everywhere are 0-based BVH motion lines (= clip frames), and
--end is exclusive.
"""
import argparse
import re

import numpy as np
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

PARTS = (r"(?i:hip|femur|tibia|foot|toes|clavicle|humerus|radius|wrist|hand|finger|thumb|"
         r"shoulder|arm|forearm|upleg|leg|collar|shldr|thigh|shin|buttock)")
# "LeftArm", "LHipJoint", "lfemur", "lShldr" are left; "lowerback" is not.
LEFT_RE = re.compile(r"^(?i:left)|^l(?=[A-Z_])|^[lL](?=" + PARTS + ")")
RIGHT_RE = re.compile(r"^(?i:right)|^r(?=[A-Z_])|^[rR](?=" + PARTS + ")")
LEFT_COLORS = ("tab:blue", "tab:cyan")     # hands, feet
RIGHT_COLORS = ("tab:red", "tab:orange")


def parse_bvh(path):
    """Return (joints, motion): joints is a list of dicts (name, parent index,
    offset, channels; End Sites included with no channels), motion an F x C array."""
    tokens = open(path).read().split()
    joints, stack, i = [], [], 0
    while tokens[i] != "MOTION":
        t = tokens[i]
        if t in ("ROOT", "JOINT"):
            joints.append({"name": tokens[i + 1], "parent": stack[-1] if stack else -1,
                           "offset": None, "channels": []})
            i += 2
        elif t == "End":
            parent = stack[-1]
            joints.append({"name": joints[parent]["name"] + "_end", "parent": parent,
                           "offset": None, "channels": []})
            i += 2
        elif t == "{":
            stack.append(len(joints) - 1)
            i += 1
        elif t == "}":
            stack.pop()
            i += 1
        elif t == "OFFSET":
            joints[stack[-1]]["offset"] = np.array([float(x) for x in tokens[i + 1:i + 4]])
            i += 4
        elif t == "CHANNELS":
            n = int(tokens[i + 1])
            joints[stack[-1]]["channels"] = tokens[i + 2:i + 2 + n]
            i += 2 + n
        else:
            i += 1
    nframes = int(tokens[i + 2])
    j = tokens.index("Time:", i) + 2
    nch = sum(len(jt["channels"]) for jt in joints)
    motion = np.array(tokens[j:j + nframes * nch], dtype=float).reshape(nframes, nch)
    return joints, motion


def axis_rotation(axis, deg):
    """F x 3 x 3 rotation matrices about axis 'X', 'Y' or 'Z' by deg (F angles)."""
    a = np.radians(deg)
    c, s = np.cos(a), np.sin(a)
    m = np.zeros((len(a), 3, 3))
    k = "XYZ".index(axis)
    u, v = [x for x in range(3) if x != k]
    m[:, k, k] = 1.0
    m[:, u, u] = c
    m[:, v, v] = c
    m[:, u, v] = -s if k != 1 else s
    m[:, v, u] = s if k != 1 else -s
    return m


def forward_kinematics(joints, motion):
    """World positions of every joint (End Sites included): F x J x 3."""
    nf = len(motion)
    pos = np.zeros((nf, len(joints), 3))
    rot = np.zeros((nf, len(joints), 3, 3))
    col = 0
    for j, jt in enumerate(joints):
        r = np.tile(np.eye(3), (nf, 1, 1))
        trans = np.zeros((nf, 3))
        for ch in jt["channels"]:
            if ch.endswith("rotation"):
                r = r @ axis_rotation(ch[0].upper(), motion[:, col])
            else:
                trans[:, "XYZ".index(ch[0].upper())] = motion[:, col]
            col += 1
        if jt["parent"] < 0:
            pos[:, j] = jt["offset"] + trans
            rot[:, j] = r
        else:
            p = jt["parent"]
            pos[:, j] = pos[:, p] + rot[:, p] @ jt["offset"]
            rot[:, j] = rot[:, p] @ r
    return pos


def side_of(joints, j):
    """'L', 'R' or 'C' for a joint: the side named by it or its nearest named ancestor."""
    while j >= 0:
        name = joints[j]["name"]
        if LEFT_RE.match(name):
            return "L"
        if RIGHT_RE.match(name):
            return "R"
        j = joints[j]["parent"]
    return "C"


def find_joint(joints, side, words):
    """Index of the first joint on `side` whose name contains one of `words`."""
    for w in words:
        for j, jt in enumerate(joints):
            if not jt["name"].endswith("_end") and w in jt["name"].lower() \
                    and side_of(joints, j) == side:
                return j
    raise SystemExit("no %s joint named like %s" % (side, words))


def hip_point(joints, pos, foot):
    """The first joint on the chain root -> foot that is not at the root: the hip."""
    chain = []
    j = foot
    while j > 0:
        chain.append(j)
        j = joints[j]["parent"]
    for j in reversed(chain):
        if np.linalg.norm(pos[0, j] - pos[0, 0]) > 1e-6:
            return j
    raise SystemExit("no hip joint found")


def body_frame(joints, pos):
    """Landmarks and root-relative heading-frame coordinates.

    Returns dict with 'local' (F x J x 3: forward, up, left relative to the
    root, heading removed; up is the absolute height), indices of the hands
    and feet, and the root height."""
    lf = find_joint(joints, "L", ["foot", "ankle"])
    rf = find_joint(joints, "R", ["foot", "ankle"])
    lh = find_joint(joints, "L", ["hand", "wrist"])
    rh = find_joint(joints, "R", ["hand", "wrist"])
    across = pos[:, hip_point(joints, pos, lf)] - pos[:, hip_point(joints, pos, rf)]
    across[:, 1] = 0.0
    left = across / np.linalg.norm(across, axis=1, keepdims=True)
    fwd = np.stack([-left[:, 2], np.zeros(len(left)), left[:, 0]], axis=1)
    rel = pos - pos[:, :1]
    local = np.stack([np.einsum("fjk,fk->fj", rel, fwd), pos[:, :, 1],
                      np.einsum("fjk,fk->fj", rel, left)], axis=2)
    return {"local": local, "lh": lh, "rh": rh, "lf": lf, "rf": rf,
            "root_y": pos[:, 0, 1]}


def frame_axis(ax, start, end):
    """Grid every 30 frames, labelled ticks every 60 or 120."""
    step = 60 if end - start <= 900 else 120
    ax.set_xticks(np.arange((start // step) * step, end + 1, step))
    ax.set_xticks(np.arange((start // 30) * 30, end + 1, 30), minor=True)
    ax.grid(True, which="both", alpha=0.4)
    ax.set_xlim(start, end - 1)


def render_curves(bf, out, start, end):
    """Heights, forward and sideways offsets of hands and feet, root height."""
    t = np.arange(start, end)
    loc = bf["local"][start:end]
    rows = [("hand height", 1, "hands"), ("foot height", 1, "feet"),
            ("hand forward", 0, "hands"), ("hand sideways (+left)", 2, "hands"),
            ("foot forward", 0, "feet"), ("foot sideways (+left)", 2, "feet")]
    fig, axes = plt.subplots(len(rows) + 1, 1, figsize=(max(12, (end - start) / 60), 16), sharex=True)
    for ax, (title, k, what) in zip(axes, rows):
        ci = 0 if what == "hands" else 1
        lj, rj = (bf["lh"], bf["rh"]) if what == "hands" else (bf["lf"], bf["rf"])
        ax.plot(t, loc[:, lj, k], color=LEFT_COLORS[ci], label="left")
        ax.plot(t, loc[:, rj, k], color=RIGHT_COLORS[ci], label="right")
        ax.set_ylabel(title, fontsize=8)
        ax.legend(loc="upper right", fontsize=7)
        frame_axis(ax, start, end)
    axes[-1].plot(t, bf["root_y"][start:end], color="k")
    axes[-1].set_ylabel("root height", fontsize=8)
    frame_axis(axes[-1], start, end)
    axes[-1].set_xlabel("frame")
    fig.tight_layout()
    fig.savefig(out, dpi=80)


def render_similarity(bf, out, start, end):
    """Pose distance between frames i and j (root-relative, heading removed); dark = similar."""
    f = bf["local"][start:end].copy()
    f[:, :, 1] -= bf["root_y"][start:end, None]
    f = f.reshape(len(f), -1)
    sq = (f * f).sum(1)
    d = np.sqrt(np.maximum(sq[:, None] + sq[None, :] - 2 * f @ f.T, 0))
    fig, ax = plt.subplots(figsize=(12, 11))
    im = ax.imshow(d, cmap="gray", origin="upper", vmax=np.percentile(d, 60),
                   extent=(start - 0.5, end - 0.5, end - 0.5, start - 0.5), interpolation="nearest")
    step = 60 if end - start <= 900 else 120
    ticks = np.arange((start // step) * step, end, step)
    ax.set_xticks(ticks)
    ax.set_yticks(ticks)
    ax.tick_params(axis="x", labelrotation=90, labelsize=7)
    ax.tick_params(axis="y", labelsize=7)
    ax.grid(True, alpha=0.25, color="yellow")
    ax.set_xlabel("frame j")
    ax.set_ylabel("frame i")
    fig.colorbar(im, ax=ax, fraction=0.03, label="pose distance")
    fig.tight_layout()
    fig.savefig(out, dpi=100)


def render_figures(joints, bf, out, frames, per_row=8):
    """Side (forward-up) and front (left-up) stick figures at the given frames,
    up to per_row frames a row, each frame as a side view above a front view."""
    loc = bf["local"]
    colors = {"L": "tab:blue", "R": "tab:red", "C": "k"}
    size = np.median(loc[:, :, 1].max(axis=1))  # standing height, in the take's units
    ncol = min(per_row, len(frames))
    nrow = 2 * ((len(frames) + per_row - 1) // per_row)
    fig, axes = plt.subplots(nrow, ncol, figsize=(2.4 * ncol, 3.4 * nrow), squeeze=False)
    for ax in axes.flat:
        ax.axis("off")
    for c, fr in enumerate(frames):
        for r, (k, name) in enumerate([(0, "side"), (2, "front")]):
            ax = axes[2 * (c // per_row) + r][c % per_row]
            ax.axis("on")
            for j, jt in enumerate(joints):
                p = jt["parent"]
                if p >= 0:  # front view: the performer's left is on screen right
                    ax.plot([loc[fr, p, k], loc[fr, j, k]], [loc[fr, p, 1], loc[fr, j, 1]],
                            color=colors[side_of(joints, j)], lw=1.5)
            ax.set_aspect("equal")
            ax.set_xlim(-0.55 * size, 0.55 * size)
            ax.set_ylim(-0.05 * size, 1.15 * size)
            ax.set_xticks([])
            ax.set_yticks([])
            ax.set_title("%d %s" % (fr, name), fontsize=9)
    fig.suptitle("blue = left, red = right; side: forward to the right; front: seen from the front", fontsize=9)
    fig.tight_layout()
    fig.savefig(out, dpi=80)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("bvh")
    ap.add_argument("--curves")
    ap.add_argument("--similarity")
    ap.add_argument("--figures")
    ap.add_argument("--frames", help="comma-separated frames for --figures")
    ap.add_argument("--start", type=int, default=0)
    ap.add_argument("--end", type=int, help="exclusive; default: end of take")
    a = ap.parse_args()
    joints, motion = parse_bvh(a.bvh)
    pos = forward_kinematics(joints, motion)
    bf = body_frame(joints, pos)
    end = len(motion) if a.end is None else min(a.end, len(motion))
    print("%s: %d frames, %d joints" % (a.bvh, len(motion), len(joints)))
    if a.curves:
        render_curves(bf, a.curves, a.start, end)
    if a.similarity:
        render_similarity(bf, a.similarity, a.start, end)
    if a.figures:
        render_figures(joints, bf, a.figures, [int(x) for x in a.frames.split(",")])


if __name__ == "__main__":
    main()
