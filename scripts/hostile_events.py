#!/usr/bin/env python3
"""Hostile events during a run (docs/reliability.md, "Hostile input", the `events` row): what a
hostile user or a busy server does to a file while the tool works on it.

    scripts/hostile_events.py --tool build/motifmine [--python-dir build/python] [--timeout 60]

Also run by scripts/hostile_inputs.py. The probes:

  cut        an archive truncated to 200 bytes while verify, export, mine, words or search reads
             it, and under Python's Archive.rotations: exit 12 (a motifmine.Error of code 12)
             naming the file, never a signal
  race       two imports creating one new archive at once, 20 times: each exits 0 or 17 (busy,
             "run again"), and the archive verifies
  replaced   a take replaced by one at another rate and length while it is imported, 10 times:
             the archive holds one of the two takes whole, at its own rate
  signal     synth, and mine, ended by SIGTERM or SIGINT while writing: ended by that signal,
             and no temporary file ("*.tmp-*") left

A probe is *handled* when it behaves as above; else it is a crash, hang, unnamed (a refusal
that does not name the file), silent (a wrong answer with exit 0) or left-temp. Prints one line
per probe that is not handled; main() exits 1 if any.
"""
import argparse
import json
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CUT_BYTES = 200


def take_text(frames, fps):
    """A two-joint BVH take of `frames` frames at `fps`."""
    lines = ["HIERARCHY", "ROOT Hips", "{", "OFFSET 0 0 0",
             "CHANNELS 6 Xposition Yposition Zposition Zrotation Yrotation Xrotation",
             "JOINT Leg", "{", "OFFSET 0 -1 0", "CHANNELS 3 Zrotation Xrotation Yrotation",
             "End Site", "{", "OFFSET 0 -1 0", "}", "}", "}", "MOTION",
             "Frames: %d" % frames, "Frame Time: %.8f" % (1.0 / fps)]
    for f in range(frames):
        lines.append("%.3f 1 0 0 0 0 %d 0 0" % (0.01 * f, f % 30))
    return "\n".join(lines) + "\n"


def write_atomic(path, text):
    with open(path + ".writing", "w") as out:
        out.write(text)
    os.replace(path + ".writing", path)


def tool_run(tool, args, timeout):
    """(exit code or -signal, output); None as the code on a hang."""
    try:
        done = subprocess.run([tool] + args, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                              timeout=timeout)
    except subprocess.TimeoutExpired:
        return None, ""
    return done.returncode, done.stdout.decode("utf-8", "replace")


def classify_cut(code, output, path):
    if code is None:
        return "hang"
    if code < 0 or code == 1:
        return "crash"
    if code == 12:
        return "handled" if os.path.basename(path) in output else "unnamed"
    return "handled" if code == 0 else "crash"


def cut_while_running(tool, args, path, timeout, progress=True):
    """Runs the tool and truncates `path` once it has printed its first progress line (it has
    opened the file and is reading it), or, for a command without progress, 20 ms after its
    start; classifies the end."""
    extra = ["--progress", "json"] if progress else []
    process = subprocess.Popen([tool] + args + extra, stdout=subprocess.PIPE,
                               stderr=subprocess.PIPE)
    if progress:
        first = process.stderr.readline()
    else:
        time.sleep(0.02)
        first = b"-"
    if first:
        os.truncate(path, CUT_BYTES)
    try:
        out, err = process.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        process.kill()
        process.communicate()
        return "hang", "no end"
    output = (first + out + err).decode("utf-8", "replace")
    return classify_cut(process.returncode, output, path), "exit %s%s" % (
        process.returncode, "" if first else " (ended before the cut)")


def probe_cut(tool, root, python_dir, timeout):
    source = os.path.join(root, "source.mfs")
    code, output = tool_run(tool, ["synth", source, "--frames", "600000", "--motifs", "3",
                                   "--seed", "1", "--quiet"], timeout)
    if code != 0:
        return [("cut: synth", "crash", output[-300:])]
    clip = json.loads(tool_run(tool, ["info", source, "--json"], timeout)[1])["clips"][0]
    commands = {  # name: (arguments, prints progress)
        "verify": (["verify", "{a}"], True),
        "export": (["export", "{a}", "--clip", clip["name"], "--out",
                    os.path.join(root, "e.bvh")], False),
        "mine": (["mine", "{a}", "--out", os.path.join(root, "cut-mined"), "--no-report"], True),
        "words": (["words", "{a}", "--epochs", "1"], True),
        "search": (["search", "{a}", "--clip", clip["name"]], False),
    }
    results = []
    for name, (command, progress) in commands.items():
        archive = os.path.join(root, "cut-%s.mfs" % name)
        if name == "search":  # it reads the words too: made first, on a smaller archive
            tool_run(tool, ["synth", archive, "--frames", "30000", "--motifs", "2", "--seed", "1",
                            "--quiet"], timeout)
            tool_run(tool, ["words", archive, "--epochs", "1", "--quiet"], timeout)
        else:
            shutil.copyfile(source, archive)
        outcome, detail = cut_while_running(tool, [a.format(a=archive) for a in command],
                                            archive, timeout, progress)
        results.append(("cut: " + name, outcome, detail))
    if python_dir and os.path.isdir(python_dir) and any(
            n.startswith("motifmine") for n in os.listdir(python_dir)):
        results.append(probe_cut_python(source, root, python_dir, clip, timeout))
    else:
        print("the Python module is not in %s: its cut probe is skipped" % python_dir)
    return results


def probe_cut_python(source, root, python_dir, clip, timeout):
    archive = os.path.join(root, "cut-python.mfs")
    shutil.copyfile(source, archive)
    script = ("import os, sys, motifmine\n"
              "a = motifmine.Archive(sys.argv[1])\n"
              "os.truncate(sys.argv[1], %d)\n"
              "try:\n"
              "    a.rotations(%r, 0, %d)\n"
              "    print('no error')\n"
              "except motifmine.Error as e:\n"
              "    print('code', e.code, e)\n" % (CUT_BYTES, clip["name"], clip["frames"]))
    env = dict(os.environ, PYTHONPATH=python_dir)
    try:
        done = subprocess.run(["/usr/bin/python3", "-c", script, archive], env=env,
                              stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=timeout)
    except subprocess.TimeoutExpired:
        return ("cut: python Archive.rotations", "hang", "")
    output = done.stdout.decode("utf-8", "replace")
    if done.returncode != 0:
        outcome = "crash"
    elif output.startswith("code 12") and "cut-python.mfs" in output:
        outcome = "handled"
    else:
        outcome = "silent" if "no error" in output else "unnamed"
    return ("cut: python Archive.rotations", outcome, output.strip()[-300:])


def probe_race(tool, root, timeout):
    take = os.path.join(root, "race.bvh")
    write_atomic(take, take_text(400, 60.0))
    results = []
    for attempt in range(20):
        archive = os.path.join(root, "race%02d.mfs" % attempt)
        runs = [subprocess.Popen([tool, "import", archive, take, "--quiet"],
                                 stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
                for _ in range(2)]
        ends = [(run.wait(timeout), run.stdout.read().decode("utf-8", "replace")) for run in runs]
        bad = [(code, text) for code, text in ends
               if code not in (0, 17) or (code == 17 and "run again" not in text)]
        verify_code, _ = tool_run(tool, ["verify", archive, "--quiet"], timeout)
        outcome = "crash" if bad else ("silent" if verify_code != 0 else "handled")
        results.append(("race %d" % attempt, outcome, "exits %s, verify %s" % (
            [code for code, _ in ends], verify_code) + (" %s" % bad if bad else "")))
    return results


def probe_replaced(tool, root, timeout):
    versions = {60.0: 40, 120.0: 295}
    texts = {fps: take_text(frames, fps) for fps, frames in versions.items()}
    take = os.path.join(root, "replaced.bvh")
    results = []
    for attempt in range(10):
        write_atomic(take, texts[60.0])
        stop = threading.Event()

        def flip():
            while not stop.is_set():
                for fps in (120.0, 60.0):
                    write_atomic(take, texts[fps])
        flipper = threading.Thread(target=flip)
        flipper.start()
        archive = os.path.join(root, "replaced%02d.mfs" % attempt)
        code, output = tool_run(tool, ["import", archive, take, "--quiet"], timeout)
        stop.set()
        flipper.join()
        if code != 0:
            results.append(("replaced %d" % attempt, classify_cut(code, output, take), output))
            continue
        info = json.loads(tool_run(tool, ["info", archive, "--json"], timeout)[1])
        whole = versions.get(info["fps"]) == info["frames"]
        results.append(("replaced %d" % attempt, "handled" if whole else "silent",
                        "%s frames at %s fps" % (info["frames"], info["fps"])))
    return results


def temporaries(folder):
    return [name for name in os.listdir(folder) if ".tmp-" in name]


def signal_once(tool, args, folder, signal_number, timeout):
    """Starts the tool, signals it once a temporary file of it exists, and classifies the end."""
    process = subprocess.Popen([tool] + args, stdout=subprocess.DEVNULL,
                               stderr=subprocess.DEVNULL)
    deadline = time.monotonic() + timeout
    while not temporaries(folder) and process.poll() is None and time.monotonic() < deadline:
        time.sleep(0.005)
    if process.poll() is not None:
        return "handled", "ended before a temporary file was seen"
    process.send_signal(signal_number)
    try:
        process.wait(timeout)
    except subprocess.TimeoutExpired:
        process.kill()
        return "hang", "did not end"
    if temporaries(folder):
        return "left-temp", ", ".join(temporaries(folder))
    if process.returncode != -signal_number:
        return "crash", "exit %s" % process.returncode
    return "handled", ""


def probe_signal(tool, root, timeout):
    results = []
    source = os.path.join(root, "signal-source.mfs")
    tool_run(tool, ["synth", source, "--frames", "200000", "--motifs", "3", "--seed", "2",
                    "--quiet"], timeout)
    for signal_number in (signal.SIGTERM, signal.SIGINT):
        name = signal.Signals(signal_number).name
        folder = os.path.join(root, "signal-" + name)
        os.makedirs(folder)
        outcome, detail = signal_once(
            tool, ["synth", os.path.join(folder, "s.mfs"), "--frames", "20000000", "--quiet"],
            folder, signal_number, timeout)
        results.append(("signal: synth " + name, outcome, detail))
        mined = os.path.join(folder, "mined")
        os.makedirs(mined)
        outcome, detail = signal_once(tool, ["mine", source, "--out", mined, "--quiet"], mined,
                                      signal_number, timeout)
        results.append(("signal: mine " + name, outcome, detail))
    return results


def run_probes(tool, root, python_dir=None, timeout=60):
    """(probe, outcome, detail) of every probe, made in `root`."""
    return (probe_cut(tool, root, python_dir, timeout) + probe_race(tool, root, timeout) +
            probe_replaced(tool, root, timeout) + probe_signal(tool, root, timeout))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--tool", required=True)
    parser.add_argument("--python-dir", help="where the motifmine module is (build/python)")
    parser.add_argument("--timeout", type=float, default=60)
    args = parser.parse_args()
    root = tempfile.mkdtemp(prefix="motif-events-")
    try:
        results = run_probes(os.path.abspath(args.tool), root, args.python_dir, args.timeout)
    finally:
        shutil.rmtree(root, ignore_errors=True)
    counts = {}
    for probe, outcome, detail in results:
        print("%-32s %-9s %s" % (probe, outcome, detail))
        group = counts.setdefault(probe.split(":")[0].split(" ")[0], {})
        group[outcome] = group.get(outcome, 0) + 1
    for group, outcomes in counts.items():
        print("%-8s %3d probes: %s" % (group, sum(outcomes.values()), ", ".join(
            "%d %s" % (n, outcome) for outcome, n in sorted(outcomes.items()))))
    return 1 if any(r[1] != "handled" for r in results) else 0


if __name__ == "__main__":
    sys.exit(main())
