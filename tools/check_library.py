#!/usr/bin/python3
"""Benchmark of `mechkin check` over a generated model library (issue 31).

Generates N mechanism files — a mix of valid four-bars of random Grashof
proportions (assembled in closed form), copies of the bundled mechanisms,
under-driven, over-driven and locked variants, files whose `expect` fails, and
the invalid corpus's broken files (tools/make_invalid_corpus.py) — then checks
them serially and with --jobs J (`--format jsonl -o`, each line synced), compares
the two outputs line for line (every verdict and every report, as sets: --jobs
finishes files out of order) and prints the throughput of each.

    /usr/bin/python3 tools/check_library.py [--files 10000] [--jobs 2] [--mechkin build/mechkin] [--dir DIR]
    /usr/bin/python3 tools/check_library.py --generate DIR --files 60 [--slow STEPS]   # only the files, DIR/list.txt

Exit status 0 when the outputs agree, 1 otherwise.
"""
import argparse
import copy
import json
import math
import os
import random
import resource
import shutil
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
import make_invalid_corpus  # noqa: E402  (its cases and valid base; writes nothing on import)
import make_mechanisms  # noqa: E402  (the closed-form assembly helpers)

Z = [0, 0, 1]


def four_bar(rng, name):
    """A Grashof crank-rocker (a + b <= c + d, a the shortest) assembled at a random crank angle."""
    a, b, c, d = rng.uniform(30, 45), rng.uniform(110, 130), rng.uniform(85, 95), rng.uniform(100, 110)
    th = math.radians(rng.uniform(0, 360))
    m = make_mechanisms
    A, D = [0.0, 0.0, 0.0], [d, 0.0, 0.0]
    B = [a * math.cos(th), a * math.sin(th), 0.0]
    C = m.circle_intersection_2d(B, b, D, c, upper=True)
    return {
        "mechkin": 1, "name": name, "units": {"length": "mm", "angle": "deg"},
        "bodies": [{"name": "crank", "position": m.r(m.mid(A, B))}, {"name": "coupler", "position": m.r(m.mid(B, C))},
                   {"name": "rocker", "position": m.r(m.mid(C, D))}],
        "joints": [
            {"name": "A", "type": "revolute", "body1": "ground", "body2": "crank", "origin": m.r(A), "axis": Z},
            {"name": "B", "type": "revolute", "body1": "crank", "body2": "coupler", "origin": m.r(B), "axis": Z},
            {"name": "C", "type": "revolute", "body1": "coupler", "body2": "rocker", "origin": m.r(C), "axis": Z},
            {"name": "D", "type": "revolute", "body1": "ground", "body2": "rocker", "origin": m.r(D), "axis": Z}],
        "drivers": [{"name": "motor", "type": "rotation", "joint": "A", "function": "360*t"}],
        "analysis": {"start": 0, "end": 1, "steps": 360},
        "outputs": [{"name": "rocker_angle", "type": "joint", "joint": "D"}],
        "expect": {"grubler": -2, "mobility": 1, "redundant": 3, "idle": 0, "driven": "full"}}


def under_driven(rng, name):
    doc = four_bar(rng, name)
    doc["drivers"] = []
    doc["expect"]["driven"] = "under"
    return doc


def over_driven(rng, name):
    doc = four_bar(rng, name)
    doc["drivers"].append({"name": "brake", "type": "rotation", "joint": "D", "function": "0"})
    doc["expect"]["driven"] = "over"
    return doc


def locked(rng, name):
    """The coupler pinned to the ground at the crank pin as well: a locked triangle."""
    doc = four_bar(rng, name)
    doc["joints"].append(dict(doc["joints"][1], name="pin", body1="ground"))
    del doc["expect"]
    return doc


def failed_expect(rng, name):
    doc = four_bar(rng, name)
    doc["expect"]["grubler"] = 1  # the count is -2
    return doc


def bundled():
    folder = os.path.join(ROOT, "mechanisms")
    docs = []
    for f in sorted(os.listdir(folder)):
        if f.endswith(".json"):
            with open(os.path.join(folder, f)) as fh:
                docs.append(json.load(fh))
    return docs


def invalid_text(k):
    name, _pointer, mutate, text = make_invalid_corpus.cases[k % len(make_invalid_corpus.cases)]
    if text is not None:
        return text
    doc = copy.deepcopy(make_invalid_corpus.BASE)
    mutate(doc)
    doc["name"] = "%s-%d" % (name, k)
    return json.dumps(doc, indent=1) + "\n"


KINDS = ["four-bar", "four-bar", "four-bar", "four-bar", "bundled", "under", "over", "locked", "failed", "invalid"]
MAKERS = {"four-bar": four_bar, "under": under_driven, "over": over_driven, "locked": locked, "failed": failed_expect}


def slowed(doc, steps):
    """Spheres on the crank and the rocker and `expect min_clearance` 0 (it holds): the check
    sweeps the clearance over `steps` steps."""
    doc["analysis"]["steps"] = steps
    for k in (0, 2):
        doc["bodies"][k]["shape"] = {"type": "sphere", "radius": 5, "center": doc["bodies"][k]["position"]}
    doc["expect"]["min_clearance"] = 0
    return doc


def generate(folder, count, seed=31, slow_steps=0):
    """Writes `count` files and folder/list.txt (their paths, one a line); returns the paths.
    slow_steps > 0: the four-bars of random proportions sweep their clearance over that many steps."""
    rng = random.Random(seed)
    os.makedirs(folder, exist_ok=True)
    base = bundled()
    paths = []
    for i in range(count):
        kind = KINDS[i % len(KINDS)]
        name = "%s-%05d" % (kind, i)
        if kind == "invalid":
            text = invalid_text(i // len(KINDS))
        elif kind == "bundled":
            doc = copy.deepcopy(base[(i // len(KINDS)) % len(base)])
            doc["name"] = "%s (copy %d)" % (doc.get("name", "bundled"), i)
            text = json.dumps(doc, indent=2) + "\n"
        else:
            doc = MAKERS[kind](rng, name)
            text = json.dumps(slowed(doc, slow_steps) if slow_steps and kind == "four-bar" else doc, indent=2) + "\n"
        path = os.path.join(folder, name + ".json")
        with open(path, "w", encoding="latin-1" if kind == "invalid" else "utf-8", newline="") as f:
            f.write(text)
        paths.append(path)
    with open(os.path.join(folder, "list.txt"), "w") as f:
        f.write("\n".join(paths) + "\n")
    return paths


def timed_check(exe, listing, jobs, out):
    """The run's result, wall-clock and CPU seconds (user + system), and its lines."""
    if os.path.exists(out):
        os.remove(out)
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.monotonic()
    r = subprocess.run([exe, "check", "--format", "jsonl", "--files-from", listing, "--jobs", str(jobs), "-o", out],
                       capture_output=True, text=True)
    seconds = time.monotonic() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime
    with open(out) as f:
        lines = f.read().splitlines()
    return r, seconds, cpu, lines


def report(what, lines, seconds, cpu, code):
    print("%-9s %d files in %.2f s: %.0f files/s; CPU %.2f s (%.0f files per CPU-second); exit %d; load %.1f" % (
        what, len(lines), seconds, len(lines) / seconds, cpu, len(lines) / max(cpu, 1e-9), code, os.getloadavg()[0]))


def verdict_counts(lines):
    counts = {}
    for line in lines:
        v = json.loads(line)["verdict"]
        counts[v] = counts.get(v, 0) + 1
    return counts


def benchmark(args):
    folder = args.dir or tempfile.mkdtemp(prefix="mechkin-library-")
    t0 = time.monotonic()
    paths = generate(folder, args.files)
    print("generated %d files in %s (%.1f s)" % (len(paths), folder, time.monotonic() - t0))
    listing = os.path.join(folder, "list.txt")
    print("%d cores; load average %.1f before the runs" % (os.cpu_count(), os.getloadavg()[0]))
    serial, t1, c1, lines1 = timed_check(args.mechkin, listing, 1, os.path.join(folder, "serial.jsonl"))
    report("serial:", lines1, t1, c1, serial.returncode)
    parallel, t2, c2, lines2 = timed_check(args.mechkin, listing, args.jobs, os.path.join(folder, "parallel.jsonl"))
    report("--jobs %d:" % args.jobs, lines2, t2, c2, parallel.returncode)
    print("verdicts:", ", ".join("%d %s" % (n, v) for v, n in sorted(verdict_counts(lines1).items())))
    same = sorted(lines1) == sorted(lines2) and len(lines1) == len(paths)
    same = same and serial.returncode == parallel.returncode
    print("outputs agree line for line: %s" % ("yes" if same else "NO"))
    if not args.dir:
        shutil.rmtree(folder)
    return 0 if same else 1


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--files", type=int, default=10000)
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--mechkin", default=os.path.join(ROOT, "build", "mechkin"))
    ap.add_argument("--dir", help="keep the files and outputs here (default: a temporary folder, removed)")
    ap.add_argument("--generate", metavar="DIR", help="only write the files and DIR/list.txt")
    ap.add_argument("--slow", type=int, default=0, metavar="STEPS",
                    help="with --generate: the random four-bars sweep their clearance over STEPS steps (slower checks)")
    args = ap.parse_args()
    if args.generate:
        generate(args.generate, args.files, slow_steps=args.slow)
        return 0
    return benchmark(args)


if __name__ == "__main__":
    sys.exit(main())
