#!/usr/bin/env python3
"""Checks README.md (ctest readme_check): its first lines after the title are the fenced block of
the two set-up commands, byte for byte; every relative link and image resolves to a file of the
repository; every script or doc it names in a code span exists; the screenshot is a PNG under
200 KB. Standard library only.

  scripts/check_readme.py [--root DIR] [--readme FILE]   (links resolved against DIR)

Prints one line per problem and exits 1 when there is any, 0 with "readme_check: ok" otherwise.
"""
import argparse
import pathlib
import re
import sys

# The set-up commands as README.md has always given them: users and CI copy them from there.
SETUP_BLOCK = [
    "```",
    "scripts/run.sh     # installs what is missing, builds, mines a synthetic archive with planted"
    " motifs, prints the summary",
    "scripts/test.sh    # installs what is missing, builds, runs the fast tests with ctest (--all:"
    " every test)",
    "```",
]
SCREENSHOT = "docs/images/report.png"
MAX_SCREENSHOT_BYTES = 200 * 1024
PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
# [text](target) and ![alt](target); a target ends at whitespace or the closing parenthesis.
LINK = re.compile(r"!?\[[^\]]*\]\(\s*([^)\s]+)(?:\s+\"[^\"]*\")?\s*\)")
# Code spans naming a repository file, e.g. `scripts/eval_repetitions.sh` or `docs/guide.md`.
NAMED_FILE = re.compile(r"`((?:scripts|docs|tests|examples)/[\w./-]+\.(?:sh|py|md|png))`")


def setup_block_problems(lines):
    """The title, blank lines, then exactly SETUP_BLOCK."""
    if not lines or not lines[0].startswith("# "):
        return ["README.md does not start with a '# ' title"]
    rest = lines[1:]
    while rest and rest[0].strip() == "":
        rest = rest[1:]
    if rest[: len(SETUP_BLOCK)] != SETUP_BLOCK:
        got = "\n".join(rest[: len(SETUP_BLOCK)])
        return ["the first thing after the title is not the set-up block, byte for byte:\n" + got]
    return []


def link_problems(text, root):
    """Links are relative to the top folder, where README.md is (also for a --readme copy)."""
    problems = []
    for target in LINK.findall(text):
        if re.match(r"^[a-z][a-z0-9+.-]*:", target) or target.startswith("#"):
            continue  # an address (https:, mailto:) or a heading of the README itself
        path = (root / target.split("#", 1)[0]).resolve()
        if not path.exists():
            problems.append(f"link to {target}: no such file")
        elif root not in path.parents and path != root:
            problems.append(f"link to {target}: outside the repository")
    for named in NAMED_FILE.findall(text):
        if not (root / named).exists():
            problems.append(f"`{named}` is named but does not exist")
    return problems


def screenshot_problems(text, root):
    if SCREENSHOT not in text:
        return [f"README.md does not show {SCREENSHOT}"]
    path = root / SCREENSHOT
    if not path.is_file():
        return [f"{SCREENSHOT}: no such file"]
    problems = []
    with open(path, "rb") as png:
        if png.read(len(PNG_SIGNATURE)) != PNG_SIGNATURE:
            problems.append(f"{SCREENSHOT} is not a PNG")
    size = path.stat().st_size
    if size >= MAX_SCREENSHOT_BYTES:
        problems.append(f"{SCREENSHOT} is {size} bytes, not under {MAX_SCREENSHOT_BYTES}")
    return problems


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    here = pathlib.Path(__file__).resolve().parent.parent
    parser.add_argument("--root", default=str(here), help="the repository (default: this one)")
    parser.add_argument("--readme", help="the file to check (default: ROOT/README.md)")
    args = parser.parse_args()
    root = pathlib.Path(args.root).resolve()
    readme = pathlib.Path(args.readme).resolve() if args.readme else root / "README.md"
    try:
        text = readme.read_text(encoding="utf-8")
    except OSError as error:
        print(f"readme_check: cannot read {readme}: {error.strerror}")
        return 1
    problems = setup_block_problems(text.split("\n"))
    problems += link_problems(text, root)
    problems += screenshot_problems(text, root)
    for problem in problems:
        print(f"readme_check: {readme}: {problem}")
    if problems:
        return 1
    print("readme_check: ok")
    return 0


if __name__ == "__main__":
    sys.exit(main())
