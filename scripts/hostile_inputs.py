#!/usr/bin/env python3
"""The hostile-input corpus (docs/reliability.md, "Hostile input"): malformed, special, huge and
deep files handed to the tool as a user could, each run under a memory limit and a time limit.

    scripts/hostile_inputs.py --tool build/motifmine [--memory-mib 4096] [--timeout 60] [--keep DIR]

The corpus is made afresh in a temporary folder (seeded: the same files every run) from the kept
fuzz inputs in tests/data/fuzz/ and generated files:

  malformed  the kept parser fuzz inputs; truncations of a valid BVH, ASF and AMC take; seeded
             random bytes; numbers that are not finite, absurd or out of range; broken structure;
             names that are not UTF-8; damaged and truncated archives
  special    a FIFO, /dev/zero and /dev/urandom linked as takes, a dangling link, a link loop, a
             folder named like a take, a socket
  huge       a sparse take one byte over the 1 GiB limit, a take of 300 MB (mostly a sparse hole),
             a 64 MB line, a valid take of 100,000 frames of one still pose
  deep       BVH hierarchies 4,096 (the limit), 4,097 and 100,000 joints deep, an ASF of 100,000
             bones, 1,000,000 nested braces

Every take file goes through `import` into a new archive and `mine` (import and mine in one
run), every archive through `verify`, `info` and `mine`. A run is *handled* when it exits with
a code of docs/guide.md ("Exit codes") other than 1, and, when it refuses a take (exit 11, 13,
14), names the file. Otherwise it is a *hang* (killed at the time limit), a *crash* (a signal, or
exit 1, an internal error), an *out-of-memory* (std::bad_alloc or a kill under the memory limit)
or *unnamed*. Prints the counts per kind of input and exits 1 unless every run was handled.
"""
import argparse
import os
import random
import resource
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time

HANDLED_CODES = {0, 2, 3, 11, 12, 13, 14, 15, 16, 17}
TAKE_REFUSALS = {11, 13, 14}
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def bvh_text(joints_deep=1, frames=3, values=None):
    """A BVH take: a chain of `joints_deep` joints, each with three rotations."""
    lines = ["HIERARCHY", "ROOT j0", "{", "OFFSET 0 0 0",
             "CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation"]
    for j in range(1, joints_deep):
        lines += ["JOINT j%d" % j, "{", "OFFSET 0 1 0", "CHANNELS 3 Zrotation Xrotation Yrotation"]
    lines += ["End Site", "{", "OFFSET 0 1 0", "}"] + ["}"] * joints_deep
    lines += ["MOTION", "Frames: %d" % frames, "Frame Time: 0.0083333"]
    channels = 6 + 3 * (joints_deep - 1)
    for f in range(frames):
        row = values(f) if values else ["%.3f" % (f * 0.1)] + ["0"] * (channels - 1)
        lines.append(" ".join(row))
    return "\n".join(lines) + "\n"


def asf_text(bones):
    """An ASF skeleton of `bones` bones in one chain."""
    out = [":version 1.10", ":name chain", ":units", "  mass 1.0", "  length 1.0", "  angle deg",
           ":root", "  order TX TY TZ RX RY RZ", "  axis XYZ", "  position 0 0 0",
           "  orientation 0 0 0", ":bonedata"]
    for b in range(1, bones + 1):
        out += ["  begin", "    id %d" % b, "    name b%d" % b, "    direction 0 1 0",
                "    length 1", "    axis 0 0 0 XYZ", "    dof rx ry rz",
                "    limits (-180 180)", "    (-180 180)", "    (-180 180)", "  end"]
    out.append(":hierarchy")
    out.append("  begin")
    parent = "root"
    for b in range(1, bones + 1):
        out.append("    %s b%d" % (parent, b))
        parent = "b%d" % b
    out.append("  end")
    return "\n".join(out) + "\n"


def amc_text(bones, frames):
    out = [":FULLY-SPECIFIED", ":DEGREES"]
    for f in range(1, frames + 1):
        out.append(str(f))
        out.append("root %.2f 0 0 0 0 0" % (f * 0.1))
        out += ["b%d 0 0 0" % b for b in range(1, bones + 1)]
    return "\n".join(out) + "\n"


def write(path, content, mode="w"):
    with open(path, mode) as f:
        f.write(content)


def sparse(path, size, head=b""):
    with open(path, "wb") as f:
        f.write(head)
        f.truncate(size)


class Corpus:
    """Files by kind: (kind, path) for takes, archives kept apart."""

    def __init__(self, root, rng):
        self.root = root
        self.rng = rng
        self.takes = []     # (kind, path, asf or None)
        self.archives = []  # (kind, path)

    def take(self, kind, name, content=None, mode="w", asf=None):
        path = os.path.join(self.root, name)
        if content is not None:
            write(path, content, mode)
        self.takes.append((kind, path, asf))
        return path

    def archive(self, kind, name, content):
        path = os.path.join(self.root, name)
        write(path, content, "wb")
        self.archives.append((kind, path))


def make_corpus(root, tool, seed):
    rng = random.Random(seed)
    c = Corpus(root, rng)
    # Malformed: the kept fuzz inputs of the parsers.
    fuzz = os.path.join(ROOT, "tests", "data", "fuzz")
    for target, ext in (("bvh_parser", ".bvh"), ("amc_parser", ".amc"), ("asf_parser", ".asf")):
        folder = os.path.join(fuzz, target)
        for name in sorted(os.listdir(folder)) if os.path.isdir(folder) else []:
            data = open(os.path.join(folder, name), "rb").read()
            c.take("malformed", "fuzz-%s-%s%s" % (target, os.path.splitext(name)[0], ext),
                   data, "wb")
    # Truncations of valid takes.
    good = bvh_text(joints_deep=3, frames=40)
    asf = asf_text(3)
    amc = amc_text(3, 20)
    good_asf = os.path.join(root, "good.asf")
    write(good_asf, asf)
    for i, cut in enumerate(sorted(rng.sample(range(1, len(good)), 12))):
        c.take("malformed", "cut%02d.bvh" % i, good[:cut])
    for i, cut in enumerate(sorted(rng.sample(range(1, len(amc)), 6))):
        c.take("malformed", "cut%02d.amc" % i, amc[:cut], asf=good_asf)
    for i, cut in enumerate(sorted(rng.sample(range(1, len(asf)), 6))):
        cut_asf = os.path.join(root, "cut%02d_skeleton.asf" % i)
        write(cut_asf, asf[:cut])
        c.take("malformed", "cut%02d_take.amc" % i, amc, asf=cut_asf)
    for i in range(8):
        ext = (".bvh", ".amc")[i % 2]
        c.take("malformed", "random%02d%s" % (i, ext),
               bytes(rng.randrange(256) for _ in range(rng.randrange(1, 4096))), "wb",
               asf=good_asf if ext == ".amc" else None)
    # Numbers: not finite, absurd, out of range.
    for name, value in (("nan", "nan"), ("inf", "inf"), ("huge", "1e308"), ("tiny", "1e-320"),
                        ("overflow", "1e999"), ("neg-huge", "-1e308")):
        c.take("malformed", "root-%s.bvh" % name,
               bvh_text(frames=4, values=lambda f, v=value: [v, "0", "0", "0", "0", "0"]))
    base = bvh_text(frames=4)
    for name, old, new in (
            ("frames-huge", "Frames: 4", "Frames: 99999999999999999999"),
            ("frames-negative", "Frames: 4", "Frames: -4"),
            ("frames-too-many", "Frames: 4", "Frames: 4000000000"),
            ("frame-time-zero", "Frame Time: 0.0083333", "Frame Time: 0"),
            ("frame-time-tiny", "Frame Time: 0.0083333", "Frame Time: 1e-300"),
            ("frame-time-nan", "Frame Time: 0.0083333", "Frame Time: nan"),
            ("channels-huge", "CHANNELS 6", "CHANNELS 1000000000"),
            ("offset-nan", "OFFSET 0 0 0", "OFFSET nan 0 0"),
            ("no-end-site", "End Site", "JOINT x"),
            ("unbalanced", "}\nMOTION", "MOTION"),
            ("name-not-utf8", "ROOT j0", "ROOT j\xff0")):
        c.take("malformed", name + ".bvh", base.replace(old, new, 1).encode("latin-1"), "wb")
    c.take("malformed", "empty.bvh", "")
    c.take("malformed", "take\xff.bvh".encode("latin-1").decode("utf-8", "surrogateescape"),
           base)
    c.take("malformed", "amc-without-asf.amc", amc)
    c.take("malformed", "amc-frame-huge.amc",
           amc.replace("\n1\n", "\n99999999999999999999\n", 1), asf=good_asf)
    # Special files.
    os.mkfifo(os.path.join(root, "fifo.bvh"))
    c.take("special", "fifo.bvh")
    for name, target in (("zero.bvh", "/dev/zero"), ("urandom.amc", "/dev/urandom"),
                         ("dangling.bvh", os.path.join(root, "absent")),
                         ("loop.bvh", os.path.join(root, "loop.bvh"))):
        os.symlink(target, os.path.join(root, name))
        c.take("special", name, asf=good_asf if name.endswith(".amc") else None)
    os.makedirs(os.path.join(root, "folder.bvh"))
    c.take("special", "folder.bvh")
    sock = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    sock.bind(os.path.join(root, "socket.bvh"))
    c.take("special", "socket.bvh")
    c.socket = sock
    # Huge.
    sparse(os.path.join(root, "over-limit.bvh"), (1 << 30) + 1, good.encode())
    c.take("huge", "over-limit.bvh")
    sparse(os.path.join(root, "hole.bvh"), 300 << 20, base.replace("Frames: 4", "Frames: 9").encode())
    c.take("huge", "hole.bvh")
    c.take("huge", "long-line.bvh", base[:-1] + " " + "7" * (64 << 20) + "\n")
    c.take("huge", "long.bvh", bvh_text(joints_deep=2, frames=100000))
    # Deep.
    c.take("deep", "deep-4096.bvh", bvh_text(joints_deep=4096, frames=2))
    c.take("deep", "deep-4097.bvh", bvh_text(joints_deep=4097, frames=2))
    c.take("deep", "deep-100000.bvh", bvh_text(joints_deep=100000, frames=1))
    deep_asf = os.path.join(root, "deep.asf")
    write(deep_asf, asf_text(100000))
    c.take("deep", "deep_take.amc", amc_text(2, 2), asf=deep_asf)
    c.take("deep", "braces.bvh", "HIERARCHY\nROOT r\n" + "{\n" * 1000000)
    # Archives: made by the tool, then damaged.
    valid = os.path.join(root, "valid.mfs")
    good_bvh = os.path.join(root, "good.bvh")
    write(good_bvh, good)
    subprocess.run([tool, "import", valid, good_bvh, "--quiet"], stdout=subprocess.DEVNULL,
                   check=True)
    data = open(valid, "rb").read()
    c.archive("malformed", "empty.mfs", b"")
    c.archive("malformed", "random.mfs", bytes(rng.randrange(256) for _ in range(8192)))
    for i, cut in enumerate(sorted(rng.sample(range(1, len(data)), 10))):
        c.archive("malformed", "cut%02d.mfs" % i, data[:cut])
    for i in range(10):
        damaged = bytearray(data)
        damaged[rng.randrange(len(data))] ^= 1 << rng.randrange(8)
        c.archive("malformed", "flip%02d.mfs" % i, bytes(damaged))
    folder = os.path.join(fuzz, "frame_file_reader")
    for name in sorted(os.listdir(folder)) if os.path.isdir(folder) else []:
        c.archive("malformed", "fuzz-%s.mfs" % name.split(".")[0],
                  open(os.path.join(folder, name), "rb").read())
    os.symlink("/dev/zero", os.path.join(root, "zero.mfs"))
    c.archives.append(("special", os.path.join(root, "zero.mfs")))
    c.archives.append(("special", os.path.join(root, "fifo.bvh")))
    sparse(os.path.join(root, "hole.mfs"), 900 << 20, data[:128])
    c.archives.append(("huge", os.path.join(root, "hole.mfs")))
    return c


def limit_memory(mib):
    def apply():
        resource.setrlimit(resource.RLIMIT_AS, (mib << 20, mib << 20))
    return apply


def run(tool, args, memory_mib, timeout):
    """(outcome, exit code, output) of one run."""
    try:
        done = subprocess.run([tool] + args, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                              preexec_fn=limit_memory(memory_mib), timeout=timeout)
    except subprocess.TimeoutExpired:
        return "hang", None, ""
    output = done.stdout.decode("utf-8", "surrogateescape")
    if "bad_alloc" in output or "out of memory" in output.lower():
        return "out-of-memory", done.returncode, output
    if done.returncode < 0:
        killed = -done.returncode == signal.SIGKILL
        return ("out-of-memory" if killed else "crash"), done.returncode, output
    if done.returncode not in HANDLED_CODES:
        return "crash", done.returncode, output
    return "handled", done.returncode, output


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--tool", required=True)
    parser.add_argument("--memory-mib", type=int, default=4096)
    parser.add_argument("--timeout", type=float, default=60)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--keep", help="make the corpus here and keep it")
    args = parser.parse_args()
    tool = os.path.abspath(args.tool)
    root = args.keep or tempfile.mkdtemp(prefix="motif-hostile-")
    if args.keep:
        os.makedirs(root)
    try:
        corpus = make_corpus(root, tool, args.seed)
        jobs = []  # (kind, label, args, take path or None)
        for n, (kind, path, asf) in enumerate(corpus.takes):
            extra = ["--asf", asf] if asf else []
            out = os.path.join(root, "out%03d" % n)
            jobs.append((kind, "import", ["import", out + ".mfs", path, "--quiet"] + extra, path))
            jobs.append((kind, "mine", ["mine", path, "--out", out, "--quiet", "--no-report"]
                         + extra, path))
        for n, (kind, path) in enumerate(corpus.archives):
            out = os.path.join(root, "mined%03d" % n)
            for command in (["verify", path, "--quiet"], ["info", path],
                            ["mine", path, "--out", out, "--quiet", "--no-report"]):
                jobs.append((kind, command[0], command, None))
        counts = {}
        failures = []
        slowest = []  # (seconds, command)
        peak = (0, "")  # (peak resident KiB of any run, its command)
        for kind, label, command, take in jobs:
            start = time.monotonic()
            outcome, code, output = run(tool, command, args.memory_mib, args.timeout)
            slowest = sorted(slowest + [(time.monotonic() - start, " ".join(command))])[-3:]
            max_rss = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
            if max_rss > peak[0]:
                peak = (max_rss, " ".join(command))
            if outcome == "handled" and take and code in TAKE_REFUSALS:
                # The take, or for an AMC take the ASF skeleton it is read with.
                named = [take] + command[command.index("--asf") + 1:][:1] if "--asf" in command \
                    else [take]
                if not any(os.path.basename(n) in output for n in named):
                    outcome = "unnamed"
            row = counts.setdefault(kind, {})
            row[outcome] = row.get(outcome, 0) + 1
            if outcome != "handled":
                failures.append("%s: motifmine %s -> %s (exit %s)\n%s" % (
                    outcome, " ".join(command), outcome, code, output[-600:]))
        kinds = ("handled", "hang", "crash", "out-of-memory", "unnamed")
        print("%-10s %5s %8s %5s %6s %14s %8s" % (("input", "runs") + kinds))
        total = {k: 0 for k in kinds}
        for kind in ("malformed", "special", "huge", "deep"):
            row = counts.get(kind, {})
            print("%-10s %5d %8d %5d %6d %14d %8d" % ((kind, sum(row.values())) +
                                                      tuple(row.get(k, 0) for k in kinds)))
            for k in kinds:
                total[k] += row.get(k, 0)
        print("%-10s %5d %8d %5d %6d %14d %8d" % (("all", sum(total.values())) +
                                                  tuple(total[k] for k in kinds)))
        print("%d take files, %d archives, memory limit %d MiB, time limit %g s" % (
            len(corpus.takes), len(corpus.archives), args.memory_mib, args.timeout))
        print("largest peak resident memory: %.0f MiB (motifmine %s)" % (
            peak[0] / 1024, peak[1].replace(root + "/", "")))
        for seconds, command in reversed(slowest):
            print("slowest: %.2f s (motifmine %s)" % (seconds, command.replace(root + "/", "")))
        for failure in failures:
            print(failure, file=sys.stderr)
        return 1 if failures else 0
    finally:
        if not args.keep:
            shutil.rmtree(root, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
