#!/usr/bin/python3
"""The live page's figures (issue 30, `mechkin view --live`): the page's size and the
time of one re-solve of the parametric four-bar at 360 rows (a slider's move: the
overrides set, the file recompiled, assembled, solved to order 3 and redrawn).

Headless Chromium stops performance.now() under its virtual time, so the page is timed
from outside: wall time of the page making K re-solves (#bench=K) against the same
page making none, best of 3 each; (t_K - t_0)/K is one re-solve with its redraw. Node
runs the module alone (the solve without the page): its milliseconds per run, best of
5 runs of 20.

    /usr/bin/python3 tools/live_benchmark.py [build/mechkin] [build/live/mechkin_live.js]
"""
import json
import os
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "tools"))
import view_screenshot as browser  # noqa: E402

ROWS = 360
RESOLVES = 200

NODE_SCRIPT = r"""
const make = require(process.argv[2]);
const spec = require("fs").readFileSync(process.argv[3], "utf8");
make().then(function (M) {
  const load = M.cwrap("mk_live_load", "number", ["string"]), run = M.cwrap("mk_live_run", "number", ["number", "number"]);
  if (load(spec)) throw new Error(M.UTF8ToString(M._mk_live_error()));
  let best = Infinity;
  for (let r = 0; r < 5; ++r) {
    const t0 = process.hrtime.bigint();
    for (let i = 0; i < 20; ++i) if (!run(%d, 3)) throw new Error(M.UTF8ToString(M._mk_live_error()));
    best = Math.min(best, Number(process.hrtime.bigint() - t0) / 1e6 / 20);
  }
  console.log(best.toFixed(3));
});
""" % ROWS


def page_seconds(page, resolves):
    best = float("inf")
    for _ in range(3):
        start = time.perf_counter()
        attrs, _ = browser.dump_dom(page, "bench=%d" % resolves, budget=60000)
        best = min(best, time.perf_counter() - start)
        assert attrs.get("data-live-ready") == "1" and attrs.get("data-live-state") == "ok", attrs
    return best


def main():
    cli = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "build", "mechkin")
    module = sys.argv[2] if len(sys.argv) > 2 else os.path.join(ROOT, "build", "live", "mechkin_live.js")
    tmp = tempfile.mkdtemp()
    doc = json.load(open(os.path.join(ROOT, "mechanisms", "parametric-four-bar.json")))
    doc["analysis"]["steps"] = ROWS - 1
    src = os.path.join(tmp, "four-bar-360.json")
    json.dump(doc, open(src, "w"))
    page = os.path.join(tmp, "live.html")
    subprocess.run([cli, "view", "--live", src, "-o", page], check=True, capture_output=True)
    print("page: %s bytes (%.2f MB), of which the module %d bytes" % (
        os.path.getsize(page), os.path.getsize(page) / 1e6, os.path.getsize(module)))
    idle, busy = page_seconds(page, 0), page_seconds(page, RESOLVES)
    print("headless Chromium: one re-solve of %d rows with its redraw %.1f ms (%d re-solves %.2f s, page alone %.2f s)"
          % (ROWS, (busy - idle) / RESOLVES * 1e3, RESOLVES, busy, idle))
    script = os.path.join(tmp, "bench.js")
    open(script, "w").write(NODE_SCRIPT)
    env = dict(os.environ, NODE_PATH=os.environ.get("NODE_PATH", "/usr/share/nodejs"))
    ms = subprocess.run(["node", script, os.path.abspath(module), src], check=True, capture_output=True, text=True,
                        env=env).stdout.strip()
    print("Node (the module alone): one run of %d rows %s ms" % (ROWS, ms))


if __name__ == "__main__":
    main()
