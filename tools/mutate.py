#!/usr/bin/env python3
"""The mutation check (`make mutate`): plants each bug of tools/mutants.txt
in a copy of the tree, one at a time, builds the optimised test binary and
the program there, runs the suite until its first failure, and reports the
test that caught the bug, or SURVIVED. Exits non-zero if a mutant survives,
does not build, or its text is not found exactly once in its file (so a
file moved or rewritten under a mutant is loud, never silent).

The copy lives in build/mutate/tree and keeps its objects from run to run;
the first run starts from this checkout's build/ objects. Every file whose
content differs from the checkout's is rewritten with a fresh time stamp,
so make rebuilds exactly what a mutant (or an edit since) touched.

Usage: tools/mutate.py [--list] [--no-baseline] [NAME ...]
"""
import argparse
import os
import re
import shutil
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MUTANTS = os.path.join(ROOT, "tools", "mutants.txt")
TREE = os.path.join(ROOT, "build", "mutate", "tree")
LOGS = os.path.join(ROOT, "build", "mutate", "logs")
BINARIES = ["build/softrast", "build/softrast-tests"]
SEEDED_BUILD_DIRS = ["src", "tests", "rooms"]  # the optimised objects the two binaries need
TEST_TIMEOUT = 1200  # seconds: a mutant that hangs the suite counts as caught by the timeout


class Mutant:
    def __init__(self, name, line):
        self.name, self.line = name, line
        self.path = self.cpu = self.why = None
        self.find, self.replace = [], []

    def describe(self):
        return f"{self.name} ({self.path})"


def parse(path):
    mutants, current = [], None
    with open(path, encoding="utf-8") as f:
        for number, raw in enumerate(f, 1):
            line = raw.rstrip("\n")
            if line.startswith("#") or not line.strip():
                continue
            key, _, rest = line.partition(" ")
            if key == "mutant":
                current = Mutant(rest.strip(), number)
                mutants.append(current)
            elif current is None:
                sys.exit(f"{path}:{number}: a line before the first 'mutant'")
            elif key == "file":
                current.path = rest.strip()
            elif key == "cpu":
                current.cpu = rest.strip()
            elif key == "why":
                current.why = rest.strip()
            elif line.startswith("-"):
                current.find.append(line[1:])
            elif line.startswith("+"):
                current.replace.append(line[1:])
            else:
                sys.exit(f"{path}:{number}: not a mutant line: {line}")
    names = set()
    for m in mutants:
        if not m.path or not m.find:
            sys.exit(f"{path}:{m.line}: mutant {m.name} needs a 'file' and a '-' line")
        if m.name in names:
            sys.exit(f"{path}:{m.line}: a second mutant named {m.name}")
        names.add(m.name)
    return mutants


def snippet(lines):
    return "\n".join(lines)


def check_snippets(mutants, root):
    """The mutants whose text is not exactly once in their file, as messages."""
    problems = []
    for m in mutants:
        path = os.path.join(root, m.path)
        if not os.path.isfile(path):
            problems.append(f"{m.name}: {m.path} does not exist")
            continue
        with open(path, encoding="utf-8") as f:
            count = f.read().count(snippet(m.find))
        if count != 1:
            problems.append(f"{m.name}: its text occurs {count} times in {m.path}, not once")
    return problems


def cpu_flags():
    try:
        with open("/proc/cpuinfo", encoding="utf-8") as f:
            for line in f:
                if line.startswith("flags"):
                    return set(line.split(":", 1)[1].split())
    except OSError:
        pass
    return set()


def checkout_files():
    """The checkout's files, tracked and untracked, without what git ignores (build/)."""
    try:
        out = subprocess.run(["git", "ls-files", "-co", "--exclude-standard", "-z"], cwd=ROOT, check=True,
                             capture_output=True).stdout
        return [p for p in out.decode().split("\0") if p and os.path.isfile(os.path.join(ROOT, p))]
    except (OSError, subprocess.CalledProcessError):
        files = []
        for dirpath, dirnames, filenames in os.walk(ROOT):
            dirnames[:] = [d for d in dirnames if not (dirpath == ROOT and d in ("build", ".git"))]
            files += [os.path.relpath(os.path.join(dirpath, n), ROOT) for n in filenames]
        return files


def write_if_changed(path, data):
    """Writes data to path unless it holds it already; a write gets a fresh time stamp."""
    try:
        with open(path, "rb") as f:
            if f.read() == data:
                return
    except FileNotFoundError:
        os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "wb") as f:
        f.write(data)


def sync_tree():
    """The copy made equal to the checkout (its build/ aside)."""
    fresh = not os.path.isdir(TREE)
    files = checkout_files()
    if fresh:
        for p in files:  # time stamps kept, so the seeded objects are up to date
            os.makedirs(os.path.dirname(os.path.join(TREE, p)), exist_ok=True)
            shutil.copy2(os.path.join(ROOT, p), os.path.join(TREE, p))
        for d in SEEDED_BUILD_DIRS:
            if os.path.isdir(os.path.join(ROOT, "build", d)):
                shutil.copytree(os.path.join(ROOT, "build", d), os.path.join(TREE, "build", d))
        return
    wanted = set(files)
    for p in files:
        with open(os.path.join(ROOT, p), "rb") as f:
            write_if_changed(os.path.join(TREE, p), f.read())
    for dirpath, dirnames, filenames in os.walk(TREE):
        if dirpath == TREE:
            dirnames[:] = [d for d in dirnames if d != "build"]
        for n in filenames:
            rel = os.path.relpath(os.path.join(dirpath, n), TREE)
            if rel not in wanted:
                os.remove(os.path.join(TREE, rel))


def build(log):
    with open(log, "w") as out:
        return subprocess.run(["make", "--no-print-directory", "-j2"] + BINARIES, cwd=TREE, stdout=out,
                              stderr=subprocess.STDOUT).returncode == 0


FAILED = re.compile(r"^\[FAIL\] (\S+?):? ")
CRASHED = re.compile(r"[Tt]he test `?(\S+?)`? crashed|^\[CRASH\] (\S+?):? ")


def run_suite(log, fail_fast):
    """Runs the tests in the copy; returns (passed, the first failing test or a note)."""
    env = dict(os.environ, SOFTRAST_BIN="build/softrast", SOFTRAST_ROOT=TREE)
    args = ["./build/softrast-tests", "--jobs", "2", "--ascii", "--color=never"] + (["--fail-fast"] if fail_fast else [])
    with open(log, "w") as out:
        try:
            code = subprocess.run(args, cwd=TREE, env=env, stdout=out, stderr=subprocess.STDOUT,
                                  timeout=TEST_TIMEOUT).returncode
        except subprocess.TimeoutExpired:
            return False, f"the suite's time limit ({TEST_TIMEOUT} s)"
    with open(log, encoding="utf-8", errors="replace") as f:
        text = f.read().splitlines()
    for line in text:
        m = FAILED.search(line) or CRASHED.search(line)
        if m:
            return code == 0, next(g for g in m.groups() if g)
    return code == 0, "" if code == 0 else f"exit status {code} (no failing test named; see the log)"


def plant(m, undo=False):
    path = os.path.join(TREE, m.path)
    with open(path, encoding="utf-8") as f:
        text = f.read()
    old, new = snippet(m.find), snippet(m.replace)
    if undo:
        old, new = new, old
    assert text.count(old) == 1, f"{m.name}: the copy of {m.path} changed under the mutant"
    write_if_changed(path, text.replace(old, new).encode("utf-8"))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("names", nargs="*", help="only these mutants")
    ap.add_argument("--list", action="store_true", help="list the mutants and check their text, build nothing")
    ap.add_argument("--no-baseline", action="store_true", help="skip the run of the unmutated suite")
    args = ap.parse_args()

    mutants = parse(MUTANTS)
    unknown = [n for n in args.names if n not in {m.name for m in mutants}]
    if unknown:
        sys.exit(f"mutate: no mutant named {', '.join(unknown)} in tools/mutants.txt")
    if args.names:
        mutants = [m for m in mutants if m.name in args.names]
    problems = check_snippets(mutants, ROOT)
    if args.list or problems:
        for m in mutants:
            print(f"{m.name:40} {m.path}{'  (cpu ' + m.cpu + ')' if m.cpu else ''}\n    {m.why or ''}")
        for p in problems:
            print(f"mutate: {p}", file=sys.stderr)
        return 1 if problems else 0

    os.makedirs(LOGS, exist_ok=True)
    print(f"mutate: syncing {os.path.relpath(TREE, ROOT)}", flush=True)
    sync_tree()
    if not build(os.path.join(LOGS, "baseline-build.log")):
        print("mutate: the unmutated tree does not build (build/mutate/logs/baseline-build.log)")
        return 1
    if not args.no_baseline:
        started = time.time()
        passed, failure = run_suite(os.path.join(LOGS, "baseline.log"), fail_fast=False)
        if not passed:
            print(f"mutate: the unmutated suite fails ({failure}); nothing can be learnt from the mutants")
            return 1
        print(f"mutate: the unmutated suite passes ({time.time() - started:.0f} s)", flush=True)

    flags, results = cpu_flags(), []
    for i, m in enumerate(mutants, 1):
        head = f"[{i}/{len(mutants)}] {m.name}"
        if m.cpu and m.cpu not in flags:
            print(f"{head}: skipped (this CPU lacks {m.cpu})", flush=True)
            results.append((m, "skipped"))
            continue
        started = time.time()
        plant(m)
        try:
            if not build(os.path.join(LOGS, m.name + ".build.log")):
                verdict = "BROKEN: does not build (build/mutate/logs/" + m.name + ".build.log)"
            else:
                passed, failure = run_suite(os.path.join(LOGS, m.name + ".log"), fail_fast=True)
                verdict = "SURVIVED" if passed else f"caught by {failure}"
        finally:
            plant(m, undo=True)
        print(f"{head}: {verdict} ({time.time() - started:.0f} s)", flush=True)
        results.append((m, verdict))

    bad = [(m, v) for m, v in results if not (v.startswith("caught") or v == "skipped")]
    print(f"mutate: {len(results) - len(bad)} of {len(results)} mutants caught or skipped")
    for m, v in bad:
        print(f"mutate: {m.name}: {v}")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
