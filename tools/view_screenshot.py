#!/usr/bin/env python3
"""Headless Chromium helpers for `mechkin view` pages (used by the browser
tests), and the README's screenshot:

    /usr/bin/python3 tools/view_screenshot.py [build/mechkin] [docs/view-double-wishbone-suspension.png]
"""
import os
import re
import subprocess
import sys
import tempfile

CHROMIUM = os.environ.get("MECHKIN_CHROMIUM", "chromium")
FLAGS = ["--headless", "--no-sandbox", "--enable-unsafe-swiftshader", "--hide-scrollbars", "--disable-background-networking",
         "--disable-component-update", "--disable-sync", "--no-first-run"]


def chromium(args, size=(1200, 700), budget=4000):
    """Chromium with a new empty profile, the window `size` and `budget` ms of virtual time."""
    with tempfile.TemporaryDirectory() as profile:
        cmd = [CHROMIUM] + FLAGS + ["--user-data-dir=" + profile, "--window-size=%d,%d" % size,
                                    "--virtual-time-budget=%d" % budget] + args
        return subprocess.run(cmd, capture_output=True, text=True, timeout=120)


def dump_dom(page, fragment="", size=(1200, 700), budget=4000):
    """The page's DOM after load: (body attributes dict, full text)."""
    url = "file://" + os.path.abspath(page) + ("#" + fragment if fragment else "")
    for _ in range(3):  # retried like screenshot(): a start that prints no DOM at all
        proc = chromium(["--dump-dom", url], size, budget)
        body = re.search(r"<body([^>]*)>", proc.stdout)
        if proc.returncode == 0 and body:
            break
    attrs = dict(re.findall(r'([\w-]+)="([^"]*)"', body.group(1))) if body else {}
    return attrs, proc.stdout


def screenshot(page, png, fragment="", size=(1200, 700), budget=4000, attempts=3):
    """A PNG of the page. Headless Chromium on a loaded CI machine now and then exits
    without writing the file (seen once in CI, stderr holding only the usual D-Bus
    noise), so a failed start is retried before the test is failed."""
    url = "file://" + os.path.abspath(page) + ("#" + fragment if fragment else "")
    for _ in range(attempts):
        if os.path.exists(png):
            os.remove(png)
        proc = chromium(["--screenshot=" + os.path.abspath(png), url], size, budget)
        if proc.returncode == 0 and os.path.exists(png):
            return png
    raise RuntimeError("chromium failed %d times (last exit code %d): %s"
                       % (attempts, proc.returncode, proc.stderr[-2000:]))


def main():
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    cli = sys.argv[1] if len(sys.argv) > 1 else os.path.join(root, "build", "mechkin")
    png = sys.argv[2] if len(sys.argv) > 2 else os.path.join(root, "docs", "view-double-wishbone-suspension.png")
    page = os.path.join(tempfile.mkdtemp(), "suspension.html")
    subprocess.run([cli, "view", os.path.join(root, "mechanisms", "double-wishbone-suspension.json"), "-o", page],
                   check=True)
    screenshot(page, png, "t=0.3", size=(1400, 900))
    try:  # a 256-colour palette keeps the README's image small
        from PIL import Image
        Image.open(png).convert("RGB").quantize(colors=256).save(png, optimize=True)
    except ImportError:
        pass
    print("screenshot written to", png)


if __name__ == "__main__":
    main()
