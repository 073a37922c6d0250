#!/usr/bin/env python3
"""The option sweep: every option of every command, and every keyword of the Python module,
given values it must survive (docs/guide.md, "Exit codes").

    scripts/option_sweep.py --tool build/motifmine [--python /usr/bin/python3]
        [--pythonpath build/python] [--jobs 2] [--timeout 30] [--keep DIR] [--verbose]

The commands are the ones `motifmine help` lists, each command's flags the ones its hidden
`--options-json` lists, with the range of each number (the option table's, or the command's own
from engine/cli/numeric_options.cc): a new command or flag is swept without an edit here, a
command without a base invocation below and a number without a range are failures. Every flag
taking a value is given 0, -1, nan, inf, 1e300, 99999999999 and x, and a value just outside each
end of its range, one flag at a time, in a base invocation that runs quickly on a tiny synthetic
archive (each run in a folder of its own, under a time limit). A run is

  accepted              exit 0 or 3;
  declined by the data  exit 11 to 17: a clip or file not found, a frame range outside the clip;
  refused               exit 2 (a usage error), the message on stderr naming the flag (--name);
  a failure             a signal, exit 1 (internal error), the time limit, a refusal that does not
                        name the flag, or a value outside the flag's range not refused.

Then every keyword of the module's functions (read from their signatures; mine()'s options from
motifmine.option_table()) is given 0, -1, nan, inf, 1e300, 99999999999 and "x", in /usr/bin/python3
processes of 40 calls (a crash ends one process; the calls after it go on in another). A call
returns (accepted), raises motifmine.Error for what the data said (declined), or raises TypeError
or ValueError (motifmine.OptionError is one) naming the keyword (refused); any other exception, a
refusal that names every argument (pybind11's own), a value outside the option table's range not
refused, a crash or the time limit is a failure. The runs go on --jobs at a time. Prints the counts
and every failure; exits 1 on any failure.
"""
import argparse
import concurrent.futures
import hashlib
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

VALUES = ["0", "-1", "nan", "inf", "1e300", "99999999999", "x"]
USAGE = 2
# docs/guide.md, "Exit codes": done (with warnings), and what the data said (10 + the status).
DONE_CODES = {0, 3}
DATA_CODES = {11, 12, 13, 14, 15, 16, 17}
# The outcomes that are not failures.
GOOD = ("accepted", "declined by the data", "refused")
CLIP = "synth_000000"

# How each command runs quickly on the fixture: {F} is the fixture folder. Outputs are relative:
# each run works in a folder of its own.
BASE = {
    "mine": ["{F}/tiny.mfs", "--out", "out", "--quiet"],
    "reindex": ["archive.mfs", "--watch", "{F}/watch", "--out", "out", "--min-age", "0",
                "--quiet"],
    "import": ["archive.mfs", "{F}/watch/take.bvh", "--quiet"],
    "info": ["{F}/tiny.mfs"],
    "verify": ["{F}/tiny.mfs"],
    "export": ["{F}/tiny.mfs", "--clip", CLIP, "--end", "100", "--out", "out.bvh"],
    "synth": ["out.mfs", "--frames", "2000", "--motifs", "1", "--motif-seconds-max", "1",
              "--clip-seconds-min", "4", "--clip-seconds-max", "8", "--instances-max", "3",
              "--quiet"],
    "trellis": ["{F}/tiny.mfs", "--out", "out.mtr", "--quiet"],
    "inspect-trellis": ["{F}/tiny.mfs", "--column", "0"],
    "grow": ["{F}/tiny.mfs", "--out", "out.mpa", "--quiet"],
    "cluster": ["{F}/tiny.mfs", "--out", "out", "--quiet"],
    "report": ["{F}/mined", "--archive", "{F}/tiny.mfs", "--out", "report.html"],
    "score": ["{F}/mined/motifs.json", "{F}/tiny.truth.json"],
    "export-motif": ["{F}/mined", "--motif", "0", "--out", "out"],
    "words": ["{F}/tiny.mfs", "--prefix", "words", "--epochs", "1", "--motifs", "8", "--quiet"],
    "search": ["{F}/tiny.mfs", "--clip", CLIP, "--start", "0", "--end", "200", "--out", "out",
               "--quiet"],
    "classify": ["{F}/tiny.mfs", "--groups", "2", "--out", "out", "--quiet"],
    "segment": ["{F}/tiny.mfs", "--out", "out", "--quiet"],
    "graph": ["{F}/tiny.mfs", "--start", CLIP, "--seconds", "2", "--out", "out", "--quiet"],
}

# The Python values: the same as the tool's, "x" a str.
PY_VALUES = {"0": 0, "-1": -1, "nan": float("nan"), "inf": float("inf"), "1e300": 1e300,
             "99999999999": 99999999999, "x": "x"}
# How each Python function runs quickly: {F} the fixture, {R} the call's own folder.
PY_BASE = {
    "mine": {"inputs": ["{F}/tiny.mfs"], "out_dir": "{R}/out"},
    "import_takes": {"archive": "{R}/a.mfs", "paths": ["{F}/watch/take.bvh"]},
    "build_words": {"archive": "{R}/tiny.mfs", "motifs": 8},
    "signatures": {"archive": "{F}/tiny.mfs"},
    "search": {"archive": "{F}/tiny.mfs", "clip": CLIP, "start": 0, "end": 200, "top": 5},
    "option_table": {},
    "Archive": {"path": "{F}/tiny.mfs"},
    "Archive.rotations": {"clip": CLIP, "start": 0, "end": 10},
    "Archive.clip_skeleton": {"clip": CLIP},
    "Archive.root_positions": {"clip": CLIP, "start": 0, "end": 10},
    "Archive.root_rotations": {"clip": CLIP, "start": 0, "end": 10},
    "Archive.headings": {"clip": CLIP, "start": 0, "end": 10},
    "Archive.world_positions": {"clip": CLIP, "start": 0, "end": 10},
    "load": {"out_dir": "{F}/mined"},
}
# Copied into {R} before the call: build_words writes beside its archive (words made with the
# same settings, so an accepted call reuses them).
PY_COPIES = {"build_words": ["tiny.mfs", "tiny.mwe", "tiny.mwm", "tiny.mws"]}
# Calls made by one Python process (a crash ends only its process: the rest go on in another).
PY_CALLS_A_PROCESS = 40
# mine()'s older keywords that are not an option's alias in the table (its docstring names them).
MINE_OLDER_KEYWORDS = ["min_length_seconds", "min_length_frames", "write_report"]


def tool_run(tool, args, cwd, timeout):
    """(exit code or None on timeout, stderr, seconds)."""
    start = time.monotonic()
    try:
        done = subprocess.run([tool] + args, cwd=cwd, stdin=subprocess.DEVNULL,
                              stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                              timeout=timeout)
        return done.returncode, done.stderr.decode("utf-8", "replace"), time.monotonic() - start
    except subprocess.TimeoutExpired:
        return None, "", time.monotonic() - start


def make_fixture(tool, root):
    """The tiny archive, its trellis, paths, words, a mined folder and a BVH take."""
    steps = [
        ["synth", "tiny.mfs", "--frames", "2000", "--motifs", "1", "--seed", "1",
         "--motif-seconds-max", "1", "--clip-seconds-min", "4", "--clip-seconds-max", "8",
         "--instances-max", "3", "--quiet"],
        ["trellis", "tiny.mfs", "--quiet"],
        ["grow", "tiny.mfs", "--quiet"],
        ["mine", "tiny.mfs", "--out", "mined", "--quiet"],
        ["words", "tiny.mfs", "--motifs", "8", "--quiet"],
        ["export", "tiny.mfs", "--clip", CLIP, "--end", "300", "--out", "watch/take.bvh"],
    ]
    os.makedirs(os.path.join(root, "watch"))
    for step in steps:
        code, err, _ = tool_run(tool, step, root, 300)
        if code != 0:
            sys.exit("option_sweep: making the fixture failed: motifmine %s: exit %s\n%s" %
                     (" ".join(step), code, err))


def fixture_digest(root):
    """A digest of every file of the fixture (a run must not change it)."""
    digest = hashlib.sha256()
    for folder, dirs, files in sorted(os.walk(root)):
        dirs.sort()
        for name in sorted(files):
            if name.endswith(".lock"):
                continue  # flock files: created empty by readers
            path = os.path.join(folder, name)
            digest.update(path.encode())
            with open(path, "rb") as f:
                digest.update(f.read())
    return digest.hexdigest()


def commands(tool):
    out = subprocess.run([tool, "help"], capture_output=True, text=True, check=True).stdout
    body = out.split("commands:", 1)[1]
    return [line.split()[0] for line in body.splitlines() if line.strip()]


def command_options(tool, command):
    out = subprocess.run([tool, command, "--options-json"], capture_output=True, text=True,
                         check=True).stdout
    return json.loads(out)


def whole(text):
    return "%d" % text


def as_number(text, integral):
    """The number `text` reads as (a whole number when `integral`), or None."""
    if integral and not re.fullmatch(r"-?[0-9]+", text):
        return None
    try:
        number = int(text) if integral else float(text)
    except ValueError:
        return None
    return number if math.isfinite(number) else None


def outside_range(option, text):
    """Whether the flag's range refuses `text` (a flag without a range refuses nothing here)."""
    if "min" not in option:
        return False
    kind = option["kind"]
    if kind in ("groups", "radius") and text == "auto":
        return False
    if kind == "length" and not text.endswith("s"):  # frames: a whole number >= 1
        frames = as_number(text, True)
        return frames is None or frames < 1 or frames > option.get("frames_max", 1e9)
    if kind == "length":
        text = text[:-1]
    number = as_number(text, kind in ("count", "integer", "groups"))
    if number is None:
        return True
    if option.get("zero_allowed") and number == 0:
        return False
    low = number <= option["min"] if option.get("min_exclusive") else number < option["min"]
    return low or number > option["max"]


def range_probes(option):
    """Values just outside the option's range (each must be refused)."""
    # (outside_range tells; a probe that is inside, as 0 of a rate that takes 0, is accepted.)
    if "min" not in option:
        return []
    low, high, kind = option["min"], option["max"], option.get("kind", "number")
    suffix = "s" if kind == "length" else ""
    probes = []
    if kind in ("count", "integer", "groups"):
        if low > -2**63 and low - 1 not in (0, -1):
            probes.append(whole(low - 1))
        if high < 2**63:
            probes.append(whole(high + 1))
    else:
        if option.get("min_exclusive"):
            probes.append(repr(float(low)) + suffix)
        elif low != 0:
            probes.append(repr(low - max(abs(low), 1) / 2) + suffix)
        if high < 1e300:
            probes.append(repr(high * 2 if high > 0 else high + 1) + suffix)
    return [p for p in probes if p not in VALUES]


def with_value(base, flag, value):
    """The base invocation with --flag=value, replacing its value there if it has one."""
    args = list(base)
    if "--" + flag in args:
        at = args.index("--" + flag)
        del args[at:at + 2]
    return args + ["--%s=%s" % (flag, value)]


def names_flag(text, flag):
    return re.search(r"--%s(?![A-Za-z0-9-])" % re.escape(flag), text) is not None


def classify_cli(flag, code, err, outside):
    if code is None:
        return "timeout"
    if code < 0:
        return "signal %d" % -code
    if code == USAGE:
        return "refused" if names_flag(err, flag) else "refused without naming --" + flag
    if code not in DONE_CODES | DATA_CODES:
        return "exit %d" % code
    if outside:
        return "outside its range, not a usage error"
    return "accepted" if code in DONE_CODES else "declined by the data"


def cli_cases(tool, fixture):
    """(label, command, flag, args, outside-the-range) for every run, and failures found before."""
    cases, failures = [], []
    for command in commands(tool):
        if command not in BASE:
            failures.append("%s: no base invocation in option_sweep.py" % command)
            continue
        base = [a.replace("{F}", fixture) for a in BASE[command]]
        cases.append(("%s (base)" % command, command, None, base, False))
        for option in command_options(tool, command):
            if option["type"] == "switch":
                continue
            if option["type"] not in ("string", "other") and "min" not in option:
                failures.append("%s --%s: a number without a range in --options-json" %
                                (command, option["name"]))
            for value in VALUES + range_probes(option):
                cases.append(("%s --%s=%s" % (command, option["name"], value), command,
                              option["name"], with_value(base, option["name"], value),
                              outside_range(option, value)))
    return cases, failures


def run_cli_case(tool, work, index, case, timeout):
    label, command, flag, args, outside = case
    cwd = os.path.join(work, "cli%05d" % index)
    os.makedirs(cwd)
    code, err, seconds = tool_run(tool, [command] + args, cwd, timeout)
    shutil.rmtree(cwd, ignore_errors=True)
    if flag is None:  # the base invocation must work
        outcome = "accepted" if code == 0 else "base failed: exit %s" % code
    else:
        outcome = classify_cli(flag, code, err, outside)
    last = err.strip().splitlines()[-1:] if err.strip() else []
    return label, outcome, ["exit %s: %s" % (code, " ".join(last))], seconds


# ---- Python ----

SIGNATURE = re.compile(r"^(?:[\w.]+\.)?(\w+)\((.*)\) ->")


def signature_keywords(doc):
    """The argument names of a pybind11 signature line, and whether it takes **kwargs."""
    match = SIGNATURE.match((doc or "").strip().splitlines()[0] if doc else "")
    if not match:
        return None, False
    names, kwargs = [], False
    for part in match.group(2).split(", "):
        name = part.split(":")[0].strip()
        if name.startswith("**"):
            kwargs = True
        elif name not in ("*", "self", "") and not name.startswith("*"):
            names.append(name)
    return names, kwargs


def python_functions(module):
    """{function name: [keyword]} for every function and method of the module, and the option
    table's range of each of mine()'s keywords."""
    found, ranges = {}, {}
    for name in sorted(dir(module)):
        item = getattr(module, name)
        if name.startswith("_"):
            continue
        if isinstance(item, type):
            if issubclass(item, BaseException):
                continue
            for attr in ["__init__"] + sorted(dir(item)):
                if attr.startswith("_") and attr != "__init__":
                    continue
                method = getattr(item, attr, None)
                if not callable(method) or isinstance(method, property):
                    continue
                keywords, _ = signature_keywords(method.__doc__)
                if keywords is not None:
                    found[name if attr == "__init__" else name + "." + attr] = keywords
            continue
        if callable(item):
            keywords, kwargs = signature_keywords(item.__doc__)
            if keywords is None:
                continue
            if kwargs:  # mine(): the option table's keywords, their aliases, the older names
                for row in module.option_table():
                    keywords += [row["keyword"]] + list(row["aliases"])
                    if row["type"] in ("count", "integer", "number", "groups", "radius"):
                        for keyword in [row["keyword"]] + list(row["aliases"]):
                            ranges[keyword] = dict(row, kind=row["type"])
                keywords += MINE_OLDER_KEYWORDS
            found[name] = sorted(set(keywords), key=keywords.index)
    return {"functions": found, "ranges": ranges}


def py_fill(value, fixture, folder):
    if isinstance(value, str):
        return value.replace("{F}", fixture).replace("{R}", folder)
    if isinstance(value, list):
        return [py_fill(v, fixture, folder) for v in value]
    if isinstance(value, dict):
        return {k: py_fill(v, fixture, folder) for k, v in value.items()}
    return value


def py_call(module, function, kwargs, fixture):
    if "." in function:  # a method: of the object its class's base call makes
        cls, method = function.split(".")
        owner = getattr(module, cls)(**py_fill(PY_BASE[cls], fixture, ""))
        return getattr(owner, method)(**kwargs)
    return getattr(module, function)(**kwargs)


def py_outcome(module, keyword, error):
    """The outcome of a call that raised `error`."""
    text = str(error)
    named = re.search(r"(?<![A-Za-z0-9_])%s(?![A-Za-z0-9_])" % re.escape(keyword), text)
    generic = "incompatible function arguments" in text  # pybind11's: lists every argument
    if isinstance(error, (TypeError, ValueError)):
        return "refused" if named and not generic else "refused without naming " + keyword
    if isinstance(error, module.Error):
        code = getattr(error, "code", None)
        return "declined by the data" if code in DATA_CODES else "Error code %s" % code
    return "raised " + type(error).__name__


def python_worker(spec):
    """Runs the calls of one keyword, one line of JSON each (and one before, for a crash)."""
    import motifmine
    for index, call in enumerate(spec["calls"]):
        print(json.dumps({"begin": index}), flush=True)
        folder = tempfile.mkdtemp(dir=spec["work"])
        os.chdir(folder)  # a relative path ("x") is made here
        for name in PY_COPIES.get(call["function"], []):
            shutil.copy(os.path.join(spec["fixture"], name), folder)
        kwargs = py_fill(dict(PY_BASE[call["function"]]), spec["fixture"], folder)
        if call["keyword"] is not None:
            kwargs[call["keyword"]] = PY_VALUES[call["value"]]
        try:
            py_call(motifmine, call["function"], kwargs, spec["fixture"])
            outcome, message = "accepted", ""
        except Exception as error:  # the outcome is what is being measured
            outcome, message = py_outcome(motifmine, call["keyword"] or "", error), str(error)
        os.chdir(spec["work"])
        shutil.rmtree(folder, ignore_errors=True)
        print(json.dumps({"end": index, "outcome": outcome, "message": message[:300]}),
              flush=True)


def python_groups(args, fixture):
    """The calls, in groups of one process each, and failures found before."""
    folder = os.path.abspath(args.pythonpath)
    if not os.path.isdir(folder) or not any(n.startswith("motifmine") for n in os.listdir(folder)):
        print("option sweep: no Python module in %s: the Python part is skipped" % folder)
        return [], []
    probe = subprocess.run([args.python, os.path.abspath(__file__), "--list-python"],
                           env=python_env(args), capture_output=True, text=True)
    if probe.returncode != 0:
        return [], ["python: cannot list the module's functions: " + probe.stderr.strip()]
    groups, failures = [], []
    listed = json.loads(probe.stdout)
    for function, keywords in sorted(listed["functions"].items()):
        if function not in PY_BASE:
            failures.append("python %s(): no base call in option_sweep.py" % function)
            continue
        calls = [{"function": function, "keyword": None, "value": None}]
        for keyword in keywords:
            row = listed["ranges"].get(keyword) if function == "mine" else None
            calls += [{"function": function, "keyword": keyword, "value": v,
                       "outside": row is not None and py_outside_range(row, v)} for v in VALUES]
        groups += [calls[at:at + PY_CALLS_A_PROCESS]
                   for at in range(0, len(calls), PY_CALLS_A_PROCESS)]
    return groups, failures


def py_outside_range(row, value):
    """Whether the option table's range refuses the Python value (the text of VALUES)."""
    if value == "x":
        return True  # a str for a number: a TypeError, or a ValueError for "auto"'s kinds
    return outside_range(row, value)


def python_env(args):
    env = dict(os.environ)
    env["PYTHONPATH"] = os.path.abspath(args.pythonpath)
    return env


def label_of(call):
    if call["keyword"] is None:
        return "python %s() (base)" % call["function"]
    return "python %s(%s=%s)" % (call["function"], call["keyword"], call["value"])


def run_python_group(args, fixture, work, calls):
    """The outcomes of one group's calls; a crash ends the process, the rest go on in another."""
    results = []
    while calls:
        spec = {"calls": calls, "fixture": fixture, "work": work}
        start = time.monotonic()
        try:
            done = subprocess.run([args.python, os.path.abspath(__file__), "--python-worker",
                                   json.dumps(spec)], env=python_env(args), capture_output=True,
                                  text=True, timeout=args.timeout * len(calls))
            lines, code = done.stdout.splitlines(), done.returncode
        except subprocess.TimeoutExpired as expired:
            out = expired.stdout or b""
            lines = (out.decode() if isinstance(out, bytes) else out).splitlines()
            code = None
        seconds = time.monotonic() - start
        ended = [json.loads(line) for line in lines if line.startswith('{"end"')]
        for record in ended:
            call, outcome = calls[record["end"]], record["outcome"]
            if call.get("outside") and outcome in ("accepted", "declined by the data"):
                outcome = "outside its range, not a TypeError or ValueError"
            results.append((label_of(call), outcome, [record["message"]],
                            seconds / max(len(calls), 1)))
        if len(ended) == len(calls):
            break
        broken = calls[len(ended)]
        what = "timeout" if code is None else "crash (exit %s)" % code
        results.append((label_of(broken), what, [], seconds))
        calls = calls[len(ended) + 1:]
    for position, result in enumerate(results):
        if result[0].endswith("(base)") and result[1] != "accepted":
            results[position] = (result[0], "base failed: " + result[1]) + result[2:]
    return results


# ---- the sweep ----

def is_failure(outcome):
    return outcome not in GOOD


def counts_line(part, results):
    counts = {}
    for _, outcome, _, _ in results:
        counts[outcome] = counts.get(outcome, 0) + 1
    return ("%s: %d runs: %d accepted, %d declined by the data, %d refused, %d failures" %
            (part, len(results), counts.get("accepted", 0), counts.get("declined by the data", 0),
             counts.get("refused", 0), sum(1 for r in results if is_failure(r[1]))))


def report(results, seconds):
    """Prints the counts (the tool's runs, the Python calls) and the failures; returns them."""
    python = [r for r in results if r[0].startswith("python")]
    tool = [r for r in results if not r[0].startswith("python")]
    print("option sweep in %.1f s" % seconds)
    print("  " + counts_line("tool (command, flag, value)", tool))
    print("  " + counts_line("python (function, keyword, value)", python))
    slowest = sorted(results, key=lambda r: -r[3])[:3]
    print("  slowest: " + "; ".join("%s %.1f s" % (r[0], r[3]) for r in slowest))
    failures = [r for r in results if is_failure(r[1])]
    for label, outcome, message, _ in failures:
        print("FAIL %s: %s%s" % (label, outcome, (" | " + message[0]) if message else ""))
    return failures


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--tool", help="the motifmine binary")
    parser.add_argument("--python", default="/usr/bin/python3",
                        help="the Python the module is built for ('' to skip the Python part)")
    parser.add_argument("--pythonpath", default="build/python", help="where the module is")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--timeout", type=float, default=30, help="seconds a run may take")
    parser.add_argument("--keep", help="work in this folder and keep it")
    parser.add_argument("--verbose", action="store_true", help="print every run's outcome")
    parser.add_argument("--list-python", action="store_true", help=argparse.SUPPRESS)
    parser.add_argument("--python-worker", help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.list_python:
        import motifmine
        print(json.dumps(python_functions(motifmine)))
        return 0
    if args.python_worker:
        python_worker(json.loads(args.python_worker))
        return 0
    if not args.tool:
        parser.error("--tool is required")
    tool = os.path.abspath(args.tool)
    work = args.keep or tempfile.mkdtemp(prefix="option_sweep.")
    os.makedirs(work, exist_ok=True)
    fixture = os.path.join(work, "fixture")
    start = time.monotonic()
    make_fixture(tool, fixture)
    before = fixture_digest(fixture)
    cases, failed = cli_cases(tool, fixture)
    groups, py_failed = python_groups(args, fixture) if args.python else ([], [])
    results = [(f, "not swept", [], 0) for f in failed + py_failed]
    with concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
        # The Python groups first: the longest pieces of work, so the runs fill in after them.
        futures = [pool.submit(run_python_group, args, fixture, work, g) for g in groups]
        futures += [pool.submit(run_cli_case, tool, work, i, c, args.timeout)
                    for i, c in enumerate(cases)]
        for future in futures:
            result = future.result()
            results += result if isinstance(result, list) else [result]
    if fixture_digest(fixture) != before:
        results.append(("fixture", "changed by a run (runs must write only in their folder)",
                        [], 0))
    if args.verbose:
        for label, outcome, message, seconds in results:
            print("%-60s %-12s %5.2fs %s" % (label, outcome, seconds, " ".join(message)[:200]))
    failures = report(results, time.monotonic() - start)
    if not args.keep:
        shutil.rmtree(work, ignore_errors=True)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
