#!/usr/bin/env python3
"""How fast a long run's `mechkin view` page opens: the spatial slider-crank over
100,000 steps, the page written with the default --max-frames, then opened in
headless Chromium (SwiftShader WebGL, new empty profile, real time) N times;
prints the page size and the time from navigation start to the page's ready mark
(scene built, plots drawn, first frame rendered), median and maximum.

    /usr/bin/python3 tools/view_benchmark.py [build/mechkin] [N]
"""
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import view_screenshot as browser  # noqa: E402


def main():
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    cli = sys.argv[1] if len(sys.argv) > 1 else os.path.join(root, "build", "mechkin")
    runs = int(sys.argv[2]) if len(sys.argv) > 2 else 5
    work = tempfile.mkdtemp()
    doc = json.load(open(os.path.join(root, "mechanisms", "spatial-slider-crank.json")))
    doc["analysis"] = {"start": 0, "end": 100, "steps": 100000}
    src, page = os.path.join(work, "long.json"), os.path.join(work, "long.html")
    json.dump(doc, open(src, "w"))
    start = time.perf_counter()
    subprocess.run([cli, "view", src, "-o", page], check=True, capture_output=True)
    written = time.perf_counter() - start
    ready = []
    for _ in range(runs):
        url = "file://" + page + "#t=50"
        with tempfile.TemporaryDirectory() as profile:
            proc = subprocess.run([browser.CHROMIUM] + browser.FLAGS + ["--user-data-dir=" + profile, "--window-size=1400,900",
                                                                       "--dump-dom", url], capture_output=True, text=True, timeout=120)
        mark = proc.stdout.split('data-ready-ms="', 1)
        if len(mark) < 2:
            raise SystemExit("the page did not get ready: " + proc.stderr[-1000:])
        ready.append(int(mark[1].split('"', 1)[0]))
    print("rows: 100001, page: %.2f MB, written by mechkin view in %.2f s" % (os.path.getsize(page) / 1e6, written))
    print("ready after navigation start: median %d ms, max %d ms over %d loads" % (statistics.median(ready), max(ready), runs))


if __name__ == "__main__":
    main()
