#!/usr/bin/env python3
"""The CI examples of docs/ci.md (issue 31) do what they say.

1. docs/ci.md quotes .pre-commit-hooks.yaml and docs/ci/github-workflow.yml
   whole, and both parse as YAML with the keys pre-commit and GitHub read.
2. The hook's entry, run as pre-commit runs it (entry + the matching files),
   passes on this repository's mechanisms and fails (exit 1, a `file:line:col:
   error:` line) on a copy with a broken file and on one whose `expect` fails.
3. The workflow's check step, with the built mechkin for /opt/mechkin/build/mechkin,
   run in a git repository holding those files: exit 0 and a SARIF log without
   errors for the good files; exit 1 and an error result at the broken key.
Usage: check_ci_examples.py SOURCE_DIR MECHKIN_BINARY
"""
import json
import os
import re
import shlex
import shutil
import subprocess
import sys
import tempfile

import yaml

failures = []


def check(cond, what):
    if not cond:
        failures.append(what)


def quoted_whole(src):
    with open(os.path.join(src, "docs", "ci.md")) as f:
        doc = f.read()
    texts = {}
    for name in (".pre-commit-hooks.yaml", os.path.join("docs", "ci", "github-workflow.yml")):
        with open(os.path.join(src, name)) as f:
            texts[name] = f.read()
        check("```yaml\n" + texts[name] + "```" in doc, "docs/ci.md quotes %s whole" % name)
    hooks = yaml.safe_load(texts[".pre-commit-hooks.yaml"])
    hook = hooks[0]
    check(all(k in hook for k in ("id", "name", "entry", "language", "files")), "the hook has pre-commit's keys")
    workflow = yaml.safe_load(texts[os.path.join("docs", "ci", "github-workflow.yml")])
    steps = workflow["jobs"]["check"]["steps"]
    step = [s for s in steps if s.get("name") == "Check the mechanism files"][0]
    return hook, step["run"]


def repository(src, tmp, broken):
    """A git repository with the bundled mechanisms (and, `broken`, two bad files)."""
    repo = os.path.join(tmp, "repo-broken" if broken else "repo")
    shutil.copytree(os.path.join(src, "mechanisms"), os.path.join(repo, "mechanisms"))
    if broken:
        shutil.copy(os.path.join(src, "tests", "invalid", "unknown-joint-key.json"),
                    os.path.join(repo, "mechanisms", "zz-broken.json"))
        with open(os.path.join(src, "mechanisms", "planar-four-bar.json")) as f:
            doc = json.load(f)
        doc["expect"]["grubler"] = 1
        with open(os.path.join(repo, "mechanisms", "zz-wrong-expect.json"), "w") as f:
            json.dump(doc, f, indent=2)
    subprocess.run(["git", "init", "-q", repo], check=True)
    subprocess.run(["git", "-C", repo, "add", "-A"], check=True)
    return repo


def run_hook(hook, exe, repo):
    pattern = re.compile(hook["files"])
    files = sorted(os.path.join("mechanisms", f) for f in os.listdir(os.path.join(repo, "mechanisms")))
    files = [f for f in files if pattern.search(f)]
    argv = shlex.split(hook["entry"])
    check(argv[0] == "mechkin", "the entry runs mechkin")
    return subprocess.run([exe, *argv[1:], *files], cwd=repo, capture_output=True, text=True), files


def run_step(script, exe, repo, tmp):
    sarif = os.path.join(tmp, "mechkin.sarif")
    script = script.replace("/opt/mechkin/build/mechkin", exe).replace("> mechkin.sarif", "> " + shlex.quote(sarif))
    r = subprocess.run(["bash", "-eo", "pipefail", "-c", script], cwd=repo, capture_output=True, text=True)
    with open(sarif) as f:
        return r, json.load(f)["runs"][0]["results"]


def main():
    src, exe = sys.argv[1], os.path.abspath(sys.argv[2])
    hook, script = quoted_whole(src)
    with tempfile.TemporaryDirectory() as tmp:
        good, bad = repository(src, tmp, False), repository(src, tmp, True)
        r, files = run_hook(hook, exe, good)
        check(r.returncode == 0 and len(files) >= 20, "the hook passes the bundled files (%d): %s" % (len(files), r.stdout))
        r, files = run_hook(hook, exe, bad)
        check(r.returncode == 1, "the hook fails a broken file")
        check(re.search(r"^mechanisms/zz-broken\.json:\d+:\d+: error: /joints/0/axsi: ", r.stdout, re.M) is not None,
              "the hook prints file:line:col for the error: %s" % r.stdout)
        check("mechanisms/zz-wrong-expect.json:" in r.stdout and "expect grubler = 1 FAILED" in r.stdout,
              "the hook reports the failed expect: %s" % r.stdout)
        r, results = run_step(script, exe, good, tmp)
        check(r.returncode == 0 and not [x for x in results if x["level"] == "error"],
              "the workflow step passes the bundled files: %s %s" % (r.returncode, r.stderr))
        r, results = run_step(script, exe, bad, tmp)
        errors = [x for x in results if x["level"] == "error"]
        check(r.returncode == 1, "the workflow step fails on a broken file")
        rules = sorted(x["ruleId"] for x in errors)
        check(rules == ["mechkin/expect-failed", "mechkin/invalid"], "the errors found: %s" % rules)
    for f in failures:
        print("FAIL", f)
    print("%d failures" % len(failures))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
