#!/usr/bin/env python3
"""Crash-consistency harness (docs/reliability.md, "Crash consistency"): kills `motifmine import`,
`trellis`, `mine` and `reindex` with SIGKILL at random moments and checks that what they leave is
the old version or the new one, never a damaged file, and that the next run finishes with the result of an uninterrupted run.

    scripts/crash_harness.py --tool build/motifmine --seed 1 --kills 100 [--commands import,mine]

For each command, once: a workload (a synthetic archive with planted motifs, its clips exported as
BVH takes in two batches) and a "before" state; an uninterrupted run from that state gives the
reference "after" state and its duration T. Then, `--kills` times: the before state is restored,
the command started and killed after a delay drawn uniformly from [0, 1.2 T) (seeded: the same
seed draws the same delays), and the invariants checked; this is repeated until `--kills` runs
were killed (a run whose delay outlasts it finishes, and is checked the same way):

  import   the archive verifies (`motifmine verify`) and is the before or the after version
           (generation and identity);
  trellis  the trellis file is the old one (another eps) or the new one, byte for byte, and
           verifies; a `.partial` file may be left;
  mine     each output (trellis.mtr, paths.mpa, motifs.json) is the old run's (another eps) or
           the new one's, byte for byte, and verifies;
  reindex  `motifmine verify OUTDIR` passes, the manifest names version 1 or 2, OUTDIR/motifs.json
           is version 1's or 2's, the archive verifies and is generation 1 or 2.

Then the command is run again, to the end: it must exit 0 and leave exactly the after state
(for mine and reindex: the same trellis, paths and motifs.json as the uninterrupted run, byte
for byte; the exact search is used, which is deterministic). Prints a table per command (kills,
old/new states seen, partial files, failures) and exits 1 if any check failed.
"""
import argparse
import hashlib
import json
import os
import random
import shutil
import signal
import subprocess
import sys
import tempfile
import time


def digest(path):
    if not os.path.exists(path):
        return None
    with open(path, "rb") as handle:
        return hashlib.sha256(handle.read()).hexdigest()


class Harness:
    def __init__(self, tool, work, seed):
        self.tool = os.path.abspath(tool)
        self.work = work
        self.rng = random.Random(seed)
        self.seed = seed

    def run(self, args, check=True, cwd=None):
        result = subprocess.run([self.tool] + args, cwd=cwd or self.work, capture_output=True,
                                text=True)
        if check and result.returncode != 0:
            raise RuntimeError("motifmine %s: exit %d\n%s%s" % (
                " ".join(args), result.returncode, result.stdout, result.stderr))
        return result

    def verify(self, path):
        result = self.run(["verify", path, "--quiet"], check=False)
        return result.returncode == 0, (result.stdout + result.stderr).strip()

    def archive_version(self, path):
        result = self.run(["info", path, "--json"])
        info = json.loads(result.stdout)
        return info["generation"], info["frames"]

    def timed(self, args):
        start = time.monotonic()
        self.run(args)
        return time.monotonic() - start

    def kill_during(self, args, delay):
        """Starts the command, kills it with SIGKILL after `delay` seconds (if still running).
        Returns True if it was killed, False if it had finished."""
        process = subprocess.Popen([self.tool] + args, cwd=self.work, stdout=subprocess.DEVNULL,
                                   stderr=subprocess.DEVNULL)
        try:
            process.wait(timeout=delay)
            return False
        except subprocess.TimeoutExpired:
            process.send_signal(signal.SIGKILL)
            process.wait()
            return True

    # The workload: a synthetic archive of `frames` frames with planted motifs, each clip a BVH
    # take; batch1 holds the first two thirds of the takes, batch2 the rest.
    def make_takes(self, frames):
        self.run(["synth", "synth.mfs", "--frames", str(frames), "--motifs", "2", "--seed",
                  str(self.seed), "--clip-seconds-min", "8", "--clip-seconds-max", "16",
                  "--quiet"])
        clips = json.loads(self.run(["info", "synth.mfs", "--json"]).stdout)["clips"]
        for batch in ("batch1", "batch2", "all"):
            os.makedirs(os.path.join(self.work, batch), exist_ok=True)
        for index, clip in enumerate(clips):
            batch = "batch1" if index < len(clips) * 2 // 3 else "batch2"
            out = os.path.join(batch, clip["name"] + ".bvh")
            self.run(["export", "synth.mfs", "--clip", clip["name"], "--out", out])
            shutil.copy(os.path.join(self.work, out), os.path.join(self.work, "all"))


def restore(harness, snapshot, names):
    """Puts files and folders `names` back as they are in `snapshot` (removing what is not)."""
    for name in names:
        target = os.path.join(harness.work, name)
        if os.path.isdir(target):
            shutil.rmtree(target)
        elif os.path.exists(target):
            os.remove(target)
        for suffix in (".partial",):
            if os.path.exists(target + suffix):
                os.remove(target + suffix)
        source = os.path.join(snapshot, name)
        if os.path.isdir(source):
            shutil.copytree(source, target)
        elif os.path.exists(source):
            shutil.copy2(source, target)
    # Temporary files of killed runs beside the archive.
    for entry in os.listdir(harness.work):
        if ".tmp-" in entry:
            path = os.path.join(harness.work, entry)
            shutil.rmtree(path) if os.path.isdir(path) else os.remove(path)


def snapshot(harness, names, where):
    path = os.path.join(harness.work, where)
    if os.path.exists(path):
        shutil.rmtree(path)
    os.makedirs(path)
    for name in names:
        source = os.path.join(harness.work, name)
        if os.path.isdir(source):
            shutil.copytree(source, os.path.join(path, name))
        elif os.path.exists(source):
            shutil.copy2(source, os.path.join(path, name))
    return path


class Scenario:
    """One command under test: prepare() makes the before state and the reference after state;
    check() looks at what a killed run left; check_final() at what the next run left."""

    def __init__(self, harness):
        self.h = harness

    def state(self):
        raise NotImplementedError


class ImportScenario(Scenario):
    name = "import"
    files = ["archive.mfs"]

    def prepare(self):
        h = self.h
        h.run(["import", "archive.mfs", "batch1", "--first-frame", "keep", "--quiet"])
        self.before = snapshot(h, self.files, "before-import")
        self.old = h.archive_version("archive.mfs")
        self.args = ["import", "archive.mfs", "batch2", "--first-frame", "keep", "--quiet"]
        self.duration = h.timed(self.args)
        self.new = h.archive_version("archive.mfs")
        self.new_digest = digest(os.path.join(h.work, "archive.mfs"))

    def check(self):
        ok, message = self.h.verify("archive.mfs")
        if not ok:
            return None, "archive does not verify: " + message
        version = self.h.archive_version("archive.mfs")
        if version == self.old:
            return "old", None
        if version == self.new:
            return "new", None
        return None, "archive is version %s, neither %s nor %s" % (version, self.old, self.new)

    def check_final(self):
        version = self.h.archive_version("archive.mfs")
        ok, message = self.h.verify("archive.mfs")
        if not ok or version != self.new:
            return "after the rerun: %s, %s" % (version, message)
        return None


class TrellisScenario(Scenario):
    name = "trellis"
    files = ["full.mfs", "t.mtr"]

    def prepare(self):
        h = self.h
        h.run(["import", "full.mfs", "all", "--first-frame", "keep", "--quiet"])
        # The old version: a finished trellis of another eps at the same path.
        h.run(["trellis", "full.mfs", "--out", "t.mtr", "--search", "exact", "--eps", "1.0",
               "--quiet"])
        self.old_digest = digest(os.path.join(h.work, "t.mtr"))
        self.before = snapshot(h, self.files, "before-trellis")
        self.args = ["trellis", "full.mfs", "--out", "t.mtr", "--search", "exact", "--quiet"]
        self.duration = h.timed(self.args)
        self.new_digest = digest(os.path.join(h.work, "t.mtr"))

    def check(self):
        path = os.path.join(self.h.work, "t.mtr")
        ok, message = self.h.verify(path)
        if not ok:
            return None, "t.mtr does not verify: " + message
        current = digest(path)
        partial = os.path.exists(path + ".partial")
        if current == self.old_digest:
            return "old+partial" if partial else "old", None
        if current == self.new_digest:
            return "new", None
        return None, "t.mtr is neither the old nor the new trellis"

    def check_final(self):
        if digest(os.path.join(self.h.work, "t.mtr")) != self.new_digest:
            return "after the rerun t.mtr is not the uninterrupted build's"
        return None


MINE_OUTPUTS = ["trellis.mtr", "paths.mpa", "motifs.json"]


class MineScenario(Scenario):
    name = "mine"
    files = ["full.mfs", "out"]

    def prepare(self):
        h = self.h
        if not os.path.exists(os.path.join(h.work, "full.mfs")):
            h.run(["import", "full.mfs", "all", "--first-frame", "keep", "--quiet"])
        # The old version: a result mined with another eps.
        h.run(["mine", "full.mfs", "--out", "out", "--search", "exact", "--eps", "1.2",
               "--no-report", "--quiet"])
        self.old = {name: digest(os.path.join(h.work, "out", name)) for name in MINE_OUTPUTS}
        self.before = snapshot(h, self.files, "before-mine")
        self.args = ["mine", "full.mfs", "--out", "out", "--search", "exact", "--eps", "1.5",
                     "--no-report", "--quiet"]
        self.duration = h.timed(self.args)
        self.new = {name: digest(os.path.join(h.work, "out", name)) for name in MINE_OUTPUTS}

    def check(self):
        states = []
        for name in MINE_OUTPUTS:
            path = os.path.join(self.h.work, "out", name)
            if name != "motifs.json":
                ok, message = self.h.verify(path)
                if not ok:
                    return None, "%s does not verify: %s" % (name, message)
            else:
                try:
                    json.load(open(path))
                except (OSError, ValueError) as error:
                    return None, "motifs.json does not parse: %s" % error
            current = digest(path)
            if current == self.old[name]:
                states.append("old")
            elif current == self.new[name]:
                states.append("new")
            else:
                return None, "%s is neither the old run's nor the new one's" % name
        return "/".join(states), None

    def check_final(self):
        for name in MINE_OUTPUTS:
            if digest(os.path.join(self.h.work, "out", name)) != self.new[name]:
                return "after the rerun %s is not the uninterrupted run's" % name
        return None


class ReindexScenario(Scenario):
    name = "reindex"
    files = ["rx.mfs", "rxout", "incoming"]

    def reindex_args(self):
        return ["reindex", "rx.mfs", "--watch", "incoming", "--out", "rxout", "--min-age", "0",
                "--first-frame", "keep", "--search", "exact", "--no-report", "--quiet"]

    def prepare(self):
        h = self.h
        os.makedirs(os.path.join(h.work, "incoming"))
        for name in os.listdir(os.path.join(h.work, "batch1")):
            shutil.copy(os.path.join(h.work, "batch1", name), os.path.join(h.work, "incoming"))
        h.run(self.reindex_args())
        self.old_motifs = digest(os.path.join(h.work, "rxout", "motifs.json"))
        self.old_archive = h.archive_version("rx.mfs")
        for name in os.listdir(os.path.join(h.work, "batch2")):
            shutil.copy(os.path.join(h.work, "batch2", name), os.path.join(h.work, "incoming"))
        self.before = snapshot(h, self.files, "before-reindex")
        self.args = self.reindex_args()
        self.duration = h.timed(self.args)
        self.new_motifs = digest(os.path.join(h.work, "rxout", "motifs.json"))
        self.new_trellis = digest(os.path.join(h.work, "rxout", "v000002", "trellis.mtr"))
        self.new_archive = h.archive_version("rx.mfs")

    def manifest_version(self):
        with open(os.path.join(self.h.work, "rxout", "manifest.json")) as handle:
            return json.load(handle)["version"]

    def check(self):
        h = self.h
        ok, message = h.verify("rxout")
        if not ok:
            return None, "rxout does not verify: " + message
        ok, message = h.verify("rx.mfs")
        if not ok:
            return None, "rx.mfs does not verify: " + message
        archive = h.archive_version("rx.mfs")
        if archive not in (self.old_archive, self.new_archive):
            return None, "the archive is version %s" % (archive,)
        version = self.manifest_version()
        motifs = digest(os.path.join(h.work, "rxout", "motifs.json"))
        if version == 1 and motifs == self.old_motifs:
            state = "v1"
        elif version == 2 and motifs == self.new_motifs:
            state = "v2"
        elif version == 2 and motifs == self.old_motifs:
            state = "v2 (motifs.json not yet published)"
        else:
            return None, "manifest version %s with motifs.json of neither version" % version
        if archive == self.new_archive and version == 1:
            state += ", archive appended"
        return state, None

    def check_final(self):
        h = self.h
        if self.manifest_version() != 2:
            return "after the rerun the manifest is not version 2"
        if digest(os.path.join(h.work, "rxout", "motifs.json")) != self.new_motifs:
            return "after the rerun motifs.json is not the uninterrupted run's"
        if digest(os.path.join(h.work, "rxout", "v000002", "trellis.mtr")) != self.new_trellis:
            return "after the rerun the trellis is not the uninterrupted run's"
        ok, message = h.verify("rxout")
        return None if ok else "after the rerun: " + message


SCENARIOS = {"import": ImportScenario, "trellis": TrellisScenario, "mine": MineScenario,
             "reindex": ReindexScenario}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--tool", required=True, help="the motifmine binary")
    parser.add_argument("--seed", type=int, default=1, help="seed of the workload and the delays")
    parser.add_argument("--kills", type=int, default=100,
                        help="runs killed per command (runs that finish first come on top)")
    parser.add_argument("--commands", default="import,trellis,mine,reindex")
    parser.add_argument("--frames", type=int, default=16000, help="frames of the workload")
    parser.add_argument("--workdir", help="where to work (default: a temporary folder)")
    parser.add_argument("--keep", action="store_true", help="keep the work folder")
    parser.add_argument("--json", help="write the figures to this file too")
    args = parser.parse_args()

    work = args.workdir or tempfile.mkdtemp(prefix="motifmine-crash-")
    os.makedirs(work, exist_ok=True)
    harness = Harness(args.tool, work, args.seed)
    failures = []
    figures = {"seed": args.seed, "kills_per_command": args.kills, "frames": args.frames,
               "commands": {}}
    started = time.monotonic()
    try:
        harness.make_takes(args.frames)
        for name in args.commands.split(","):
            scenario = SCENARIOS[name](harness)
            scenario.prepare()
            states = {}
            killed = 0
            reruns = 0
            kill = -1
            # Until `--kills` runs were really killed (a delay past the run's end lets it
            # finish: checked all the same); at most ten times as many runs.
            while killed < args.kills and kill + 1 < 10 * args.kills:
                kill += 1
                restore(harness, scenario.before, scenario.files)
                delay = harness.rng.uniform(0, 1.2 * scenario.duration)
                if harness.kill_during(scenario.args, delay):
                    killed += 1
                state, problem = scenario.check()
                if problem:
                    failures.append("%s kill %d (after %.3f s): %s" % (name, kill, delay, problem))
                    continue
                states[state] = states.get(state, 0) + 1
                rerun = harness.run(scenario.args, check=False)
                reruns += 1
                problem = scenario.check_final() if rerun.returncode == 0 else (
                    "the rerun exited %d: %s" % (rerun.returncode, rerun.stderr.strip()))
                if problem:
                    failures.append("%s kill %d (after %.3f s): %s" % (name, kill, delay, problem))
            if killed < args.kills:
                failures.append("%s: only %d of %d runs killed" % (name, killed, args.kills))
            figures["commands"][name] = {"runs": kill + 1, "killed": killed,
                                         "uninterrupted_seconds": round(scenario.duration, 3),
                                         "states": states, "reruns_finished": reruns}
            print("%-8s %d runs, %d killed (T = %.2f s); left: %s; %d reruns" % (
                name, kill + 1, killed, scenario.duration,
                ", ".join("%s %d" % item for item in sorted(states.items())), reruns))
            sys.stdout.flush()
    finally:
        figures["seconds"] = round(time.monotonic() - started, 1)
        figures["failures"] = failures
        if args.json:
            with open(args.json, "w") as handle:
                json.dump(figures, handle, indent=2)
        if not args.keep and not args.workdir:
            shutil.rmtree(work, ignore_errors=True)
    for failure in failures:
        print("FAILED: " + failure)
    print("%d failure(s) in %.0f s" % (len(failures), figures["seconds"]))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
