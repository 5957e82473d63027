#!/usr/bin/env python3
"""Headless Chromium helpers for `mechkin view` pages (used by the browser
tests), and the README's screenshot:

    /usr/bin/python3 tools/view_screenshot.py [build/mechkin] [docs/view-spatial-slider-crank.png]
"""
import os
import re
import subprocess
import sys
import tempfile

CHROMIUM = os.environ.get("MECHKIN_CHROMIUM", "chromium")
FLAGS = ["--headless", "--no-sandbox", "--enable-unsafe-swiftshader", "--hide-scrollbars", "--window-size=1200,700",
         "--virtual-time-budget=4000"]


def dump_dom(page, fragment=""):
    """The page's DOM after load: (body attributes dict, full text)."""
    url = "file://" + os.path.abspath(page) + ("#" + fragment if fragment else "")
    proc = subprocess.run([CHROMIUM] + FLAGS + ["--dump-dom", url], capture_output=True, text=True, timeout=120)
    body = re.search(r"<body([^>]*)>", proc.stdout)
    attrs = dict(re.findall(r'([\w-]+)="([^"]*)"', body.group(1))) if body else {}
    return attrs, proc.stdout


def screenshot(page, png, fragment=""):
    url = "file://" + os.path.abspath(page) + ("#" + fragment if fragment else "")
    subprocess.run([CHROMIUM] + FLAGS + ["--screenshot=" + os.path.abspath(png), url], capture_output=True, timeout=120,
                   check=True)
    return png


def main():
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    cli = sys.argv[1] if len(sys.argv) > 1 else os.path.join(root, "build", "mechkin")
    png = sys.argv[2] if len(sys.argv) > 2 else os.path.join(root, "docs", "view-spatial-slider-crank.png")
    page = os.path.join(tempfile.mkdtemp(), "slider-crank.html")
    subprocess.run([cli, "view", os.path.join(root, "mechanisms", "spatial-slider-crank.json"), "-o", page], check=True)
    screenshot(page, png, "t=0.3")
    print("screenshot written to", png)


if __name__ == "__main__":
    main()
