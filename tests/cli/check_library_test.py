#!/usr/bin/env python3
"""`mechkin check` over a library of files (issue 31).

1. The files of a list (--files-from LIST and '-' for the standard input), checked
   with --jobs 2, give the same JSON lines as a serial run (as a set; with --sorted
   in the same order); the shards 1/3, 2/3, 3/3 together are the whole list, each
   file once; the exit status is the worst verdict's (0 only when all are ok).
2. --timeout: a file whose check would take minutes (a clearance sweep of 10^7
   steps) gets the verdict "timeout" and the files after it are still checked.
3. -o OUT --resume: the files OUT holds are not checked again, a last line cut
   short is replaced, and the final lines equal an uninterrupted run's; a line
   that is not a check result is refused (exit 2).
4. Unusable combinations exit 2: -o without jsonl, --resume without -o, a bad
   --shard; a single file's output is what it was (no summary on stderr).
5. --format sarif and gcc: a file with three errors gives three results whose
   line:column point at the offending keys (checked against the file's text).
6. A run of 60 generated files killed (SIGKILL) half way, then --resume, ends with
   the lines of an uninterrupted run.
7. Progress (files done, rate, time left) on stderr when it is a terminal, none
   when it is a pipe.
Usage: check_library_test.py SOURCE_DIR MECHKIN_BINARY
"""
import json
import os
import pty
import signal
import subprocess
import sys
import tempfile
import time

failures = []


def check(cond, what):
    if not cond:
        failures.append(what)


def run(exe, *args, stdin=None):
    return subprocess.run([exe, "check", *args], capture_output=True, text=True, input=stdin)


def corpus(src):
    files = sorted(os.path.join(src, "mechanisms", f) for f in os.listdir(os.path.join(src, "mechanisms"))
                   if f.endswith(".json"))
    invalid = sorted(os.path.join(src, "tests", "invalid", f) for f in os.listdir(os.path.join(src, "tests", "invalid"))
                     if f.endswith(".json"))
    return files + invalid[:20]


def lines_of(text):
    return [json.loads(line) for line in text.splitlines()]


def parallel_and_shards(exe, files, tmp):
    listing = os.path.join(tmp, "list.txt")
    with open(listing, "w") as f:
        f.write("\n".join(files) + "\n\n")  # an empty line is skipped
    serial = run(exe, "--format", "jsonl", "--files-from", listing)
    check(serial.returncode == 1, "a list with invalid files exits 1, not %d" % serial.returncode)
    ordered = lines_of(serial.stdout)
    check([o["file"] for o in ordered] == files, "the serial run reports the list's files in order")
    verdicts = {o["verdict"] for o in ordered}
    check(verdicts == {"ok", "invalid"}, "verdicts of the corpus: %s" % verdicts)
    check("mechkin check: %d files" % len(files) in serial.stderr and "slowest:" in serial.stderr,
          "the summary names the count and the slowest files: %r" % serial.stderr)
    piped = run(exe, "--format", "jsonl", "--jobs", "2", "--files-from", "-", stdin="\n".join(files))
    check(sorted(piped.stdout.splitlines()) == sorted(serial.stdout.splitlines()),
          "--jobs 2 gives the serial run's lines")
    in_order = run(exe, "--format", "jsonl", "--jobs", "2", "--sorted", "--files-from", listing)
    check(in_order.stdout == serial.stdout, "--jobs 2 --sorted gives the serial run's lines in its order")
    shards = [run(exe, "--format", "jsonl", "--shard", "%d/3" % i, "--files-from", listing) for i in (1, 2, 3)]
    names = [o["file"] for s in shards for o in lines_of(s.stdout)]
    check(sorted(names) == sorted(files), "the three shards hold every file once")
    check([o["file"] for o in lines_of(shards[1].stdout)] == files[1::3], "shard 2/3 is the files with index = 1 (mod 3)")
    ok_only = run(exe, "--format", "jsonl", *[f for f in files if "/mechanisms/" in f])
    check(ok_only.returncode == 0, "valid files only: exit 0, not %d" % ok_only.returncode)


def slow_file(src, tmp):
    with open(os.path.join(src, "mechanisms", "planar-four-bar.json")) as f:
        doc = json.load(f)
    doc["analysis"]["steps"] = 10000000
    for k in (0, 2):
        doc["bodies"][k]["shape"] = {"type": "sphere", "radius": 5, "center": doc["bodies"][k]["position"]}
    doc.setdefault("expect", {})["min_clearance"] = 1
    path = os.path.join(tmp, "slow.json")
    with open(path, "w") as f:
        json.dump(doc, f)
    return path


def timeout(exe, src, tmp):
    slow = slow_file(src, tmp)
    five_bar = os.path.join(src, "mechanisms", "five-bar.json")
    r = run(exe, "--format", "jsonl", "--timeout", "0.5", slow, five_bar)
    out = lines_of(r.stdout)
    check([o["verdict"] for o in out] == ["timeout", "ok"], "a slow file times out, the next is checked: %s" % r.stdout[:300])
    check(r.returncode == 1, "a timeout exits 1")
    check("the clearance sweep" in out[0]["errors"][0]["message"], "the timeout says where it stopped")
    text = run(exe, "--timeout", "0.5", slow)
    check(text.returncode == 1 and "overran its time limit of 0.5 s" in text.stdout, "the text report says timeout")


def resume(exe, files, tmp):
    out = os.path.join(tmp, "out.jsonl")
    whole = run(exe, "--format", "jsonl", "-o", out, *files)
    check(whole.stdout == "", "-o writes nothing to the standard output")
    with open(out) as f:
        reference = f.read().splitlines()
    check(len(reference) == len(files), "-o holds one line per file")
    # As if killed after 7 lines, the 8th half written.
    with open(out, "w") as f:
        f.write("\n".join(reference[:7]) + "\n" + reference[7][:40])
    again = run(exe, "--format", "jsonl", "-o", out, "--resume", *files)
    with open(out) as f:
        resumed = f.read().splitlines()
    check(sorted(resumed) == sorted(reference), "--resume completes the output to the same lines")
    check("%d files in" % (len(files) - 7) in again.stderr and "resumed: 7 files" in again.stderr,
          "the resumed run checks only the others: %r" % again.stderr)
    check(again.returncode == whole.returncode, "the resumed run exits as the whole run")
    with open(out, "a") as f:
        f.write("not json\n")
    bad = run(exe, "--format", "jsonl", "-o", out, "--resume", *files)
    check(bad.returncode == 2 and ":%d: not a line" % (len(files) + 1) in bad.stderr, "a foreign line is refused: %r" % bad.stderr)


def killed_then_resumed(exe, src, tmp):
    """60 generated files (tools/check_library.py), --jobs 2 -o OUT, SIGKILL once some
    lines are written, then --resume: the final lines are those of a run left alone."""
    folder = os.path.join(tmp, "library")
    # --slow: 24 of the files sweep their clearance over 20,000 steps (some 0.1 s each), room
    # to kill the run half way.
    subprocess.run([sys.executable, os.path.join(src, "tools", "check_library.py"), "--generate", folder, "--files", "60",
                    "--slow", "20000"], check=True)
    listing = os.path.join(folder, "list.txt")
    args = ["check", "--format", "jsonl", "--jobs", "2", "--files-from", listing, "-q"]
    reference = os.path.join(tmp, "reference.jsonl")
    subprocess.run([exe, *args, "-o", reference], check=False)
    with open(reference) as f:
        expected = sorted(f.read().splitlines())
    check(len(expected) == 60, "the uninterrupted run writes 60 lines, not %d" % len(expected))
    out = os.path.join(tmp, "killed.jsonl")
    proc = subprocess.Popen([exe, *args, "-o", out])
    written = 0
    while proc.poll() is None and written < 15:
        time.sleep(0.01)
        written = count_lines(out)
    proc.send_signal(signal.SIGKILL)
    proc.wait()
    at_kill = count_lines(out)
    check(proc.returncode == -signal.SIGKILL, "the run was killed (it ended with %s first)" % proc.returncode)
    check(15 <= at_kill < 60, "killed half way: %d of 60 lines written" % at_kill)
    subprocess.run([exe, *args, "-o", out, "--resume"], check=False)
    with open(out) as f:
        final = sorted(f.read().splitlines())
    check(final == expected, "after the kill and --resume the lines are the uninterrupted run's")


def progress(exe, tmp):
    """Progress lines on a terminal's stderr (a pty here), none on a pipe."""
    listing = os.path.join(tmp, "library", "list.txt")
    args = [exe, "check", "--format", "jsonl", "--jobs", "2", "--files-from", listing]
    master, slave = pty.openpty()
    proc = subprocess.Popen(args, stdout=subprocess.DEVNULL, stderr=slave)
    os.close(slave)
    seen = b""
    while True:
        try:
            chunk = os.read(master, 4096)
        except OSError:  # EIO: the child closed the terminal
            break
        if not chunk:
            break
        seen += chunk
    os.close(master)
    proc.wait()
    check(b"\r\x1b[K" in seen and b"/60 files, " in seen and b" files/s" in seen and b" s left" in seen,
          "progress on a terminal: %r" % seen[:200])
    check(b"mechkin check: 60 files" in seen, "the summary follows the progress: %r" % seen[-300:])
    piped = subprocess.run(args, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    check(b"\r" not in piped.stderr and b"mechkin check: 60 files" in piped.stderr, "no progress on a pipe")


def count_lines(path):
    try:
        with open(path, "rb") as f:
            return f.read().count(b"\n")
    except FileNotFoundError:
        return 0


THREE_ERRORS = (
    '{"mechkin": 1, "name": "Gelenk\u2013Pr\u00fcfung \\"3\\"", "bodys": [],\n'
    ' "bodies": [{"name": "b", "position": [0, 0, 0]}, {"name": "c", "position": [1, 0, 0]}],\n'
    ' "joints": [\n'
    '\t{"name": "j", "type": "revolut", "body1": "ground", "body2": "b", "origin": [0, 0, 0], "axis": [0, 0, 1]},\n'
    '\t{"name": "k", "type": "spherical", "body1": "b", "body2": "bb", "origin": [1, 0, 0]}]}\n')


def text_at(text, line, column):
    """The text from line:column on (1-based; columns in code points, as Python indexes str)."""
    return text.split("\n")[line - 1][column - 1:]


def sarif_and_gcc(exe, tmp):
    """Three errors (an unknown top-level key after non-ASCII and escaped text, an unknown
    joint type after a tab, an unknown body): three SARIF results, each at its key."""
    path = os.path.join(tmp, "three errors.json")
    with open(path, "w", encoding="utf-8") as f:
        f.write(THREE_ERRORS)
    r = run(exe, "--format", "sarif", path)
    check(r.returncode == 1, "sarif: an invalid file exits 1")
    log = json.loads(r.stdout)
    check(log["version"] == "2.1.0" and log["runs"][0]["tool"]["driver"]["name"] == "mechkin", "a SARIF 2.1.0 log of mechkin")
    results = log["runs"][0]["results"]
    check(len(results) == 3, "three results, not %d: %s" % (len(results), [x["message"]["text"] for x in results]))
    want = {"/bodys": (1, '"bodys"'), "/joints/0/type": (4, '"type"'), "/joints/1/body2": (5, '"body2"')}
    for res in results:
        pointer = res["properties"]["pointer"]
        loc = res["locations"][0]["physicalLocation"]
        region = loc["region"]
        check(loc["artifactLocation"]["uri"].endswith("three%20errors.json"), "the URI is the path, encoded")
        check(res["ruleId"] == "mechkin/invalid" and res["level"] == "error" and res["message"]["text"],
              "rule, level and message of %s" % pointer)
        line, key = want.get(pointer, (0, "?"))
        check(region["startLine"] == line, "%s on line %d, not %d" % (pointer, line, region["startLine"]))
        check(text_at(THREE_ERRORS, region["startLine"], region["startColumn"]).startswith(key),
              "%s at %d:%d is %r" % (pointer, region["startLine"], region["startColumn"],
                                     text_at(THREE_ERRORS, region["startLine"], region["startColumn"])[:20]))
    gcc = run(exe, "--format", "gcc", path)
    places = ["%s:%d:%d: error: %s: " % (path, x["locations"][0]["physicalLocation"]["region"]["startLine"],
                                         x["locations"][0]["physicalLocation"]["region"]["startColumn"],
                                         x["properties"]["pointer"]) for x in results]
    errors = [line for line in gcc.stdout.splitlines() if ": error: " in line]
    check(len(errors) == 3 and all(any(e.startswith(p) for e in errors) for p in places),
          "gcc lines at the SARIF places: %s" % gcc.stdout)
    clean = run(exe, "--format", "gcc", os.path.join(os.path.dirname(exe), "..", "mechanisms", "missing.json"))
    check(clean.returncode == 1 and ": error: cannot open" in clean.stdout, "an unreadable file: a placeless gcc line")


def refusals(exe, files, tmp):
    out = os.path.join(tmp, "x.jsonl")
    full = run(exe, "--format", "jsonl", "-o", "/dev/full", *files)
    check(full.returncode == 1 and "writing the output failed: No space left on device" in full.stderr,
          "a full output fails the run: %d %r" % (full.returncode, full.stderr))
    dash = run(exe, "--format", "jsonl", "-o", "-", files[0])
    check(dash.returncode == 0 and json.loads(dash.stdout)["verdict"] == "ok" and not os.path.exists("-"),
          "-o - writes the standard output")
    for args in (["-o", out, files[0]], ["--format", "jsonl", "--resume", files[0]],
                 ["--format", "jsonl", "-o", "-", "--resume", files[0]], ["--shard", "4/3", files[0]],
                 ["--shard", "1/0", files[0]], ["--files-from", os.path.join(tmp, "missing.txt")], []):
        r = run(exe, *args)
        check(r.returncode == 2, "check %s exits 2, not %d" % (" ".join(args), r.returncode))
    one = run(exe, files[0])
    check(one.returncode == 0 and one.stderr == "", "one file: no summary")


def main():
    """check_library_test.py SRC EXE [kill]: without `kill` the checks of the bundled
    files; with it the kill, --resume and progress runs over 60 generated files, five
    whole checks of a slow library (a separate ctest, kept out of the sanitizer stage)."""
    src, exe = sys.argv[1], sys.argv[2]
    files = corpus(src)
    with tempfile.TemporaryDirectory() as tmp:
        if sys.argv[3:] == ["kill"]:
            killed_then_resumed(exe, src, tmp)
            progress(exe, tmp)
        else:
            parallel_and_shards(exe, files, tmp)
            timeout(exe, src, tmp)
            resume(exe, files, tmp)
            refusals(exe, files, tmp)
            sarif_and_gcc(exe, tmp)
    for f in failures:
        print("FAIL", f)
    print("%d failures" % len(failures))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
