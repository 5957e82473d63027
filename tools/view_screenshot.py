#!/usr/bin/env python3
"""Headless Chromium helpers for `mechkin view` pages (used by the browser
tests), and the README's screenshot:

    /usr/bin/python3 tools/view_screenshot.py [build/mechkin] [docs/view-double-wishbone-suspension.png]
"""
import atexit
import base64
import fcntl
import json
import os
import re
import select
import subprocess
import sys
import tempfile

CHROMIUM = os.environ.get("MECHKIN_CHROMIUM", "chromium")
FLAGS = ["--headless", "--no-sandbox", "--enable-unsafe-swiftshader", "--hide-scrollbars", "--disable-background-networking",
         "--disable-component-update", "--disable-sync", "--no-first-run"]
REPLY_TIMEOUT = 120  # s: a page that never finishes its budget fails the test, not the suite


class Browser:
    """One headless Chromium kept open for many pages, driven over its DevTools pipe
    (--remote-debugging-pipe: commands on its fd 3, replies on its fd 4, each message
    JSON ended by a NUL). Starting Chromium took 2 of the 3.5 s a page cost when each
    page had its own (100 pages in the browser tests, 2026-12-06). Each page gets a new
    tab of the given size; like Chromium's --virtual-time-budget, the budget of virtual
    time starts when the page has loaded, and the page is read when it has run out."""

    def __init__(self):
        self.profile = tempfile.TemporaryDirectory()
        commands_read, commands_write = os.pipe()
        replies_read, replies_write = os.pipe()
        # Out of the way of 3 and 4, so that placing one cannot overwrite the other.
        child_commands = fcntl.fcntl(commands_read, fcntl.F_DUPFD, 10)
        child_replies = fcntl.fcntl(replies_write, fcntl.F_DUPFD, 10)
        os.close(commands_read)
        os.close(replies_write)

        def place_pipes():
            os.dup2(child_commands, 3)
            os.dup2(child_replies, 4)
        self.proc = subprocess.Popen([CHROMIUM] + FLAGS + ["--user-data-dir=" + self.profile.name,
                                                           "--remote-debugging-pipe", "about:blank"],
                                     preexec_fn=place_pipes, pass_fds=(3, 4),
                                     stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        os.close(child_commands)
        os.close(child_replies)
        self.commands = os.fdopen(commands_write, "wb", buffering=0)
        self.replies = replies_read
        self.pending = b""
        self.last_id = 0
        self.events = []

    def _message(self):
        while b"\0" not in self.pending:
            ready, _, _ = select.select([self.replies], [], [], REPLY_TIMEOUT)
            chunk = os.read(self.replies, 1 << 20) if ready else b""
            if not chunk:
                raise RuntimeError("chromium stopped answering (%s)" % ("exited" if ready else "timed out"))
            self.pending += chunk
        message, self.pending = self.pending.split(b"\0", 1)
        return json.loads(message)

    def send(self, method, params=None, session=None):
        """Runs one DevTools command and returns its result; events meanwhile are kept."""
        self.last_id += 1
        command = {"id": self.last_id, "method": method, "params": params or {}}
        if session:
            command["sessionId"] = session
        self.commands.write(json.dumps(command).encode() + b"\0")
        while True:
            message = self._message()
            if message.get("id") == self.last_id:
                if "error" in message:
                    raise RuntimeError("%s: %s" % (method, message["error"]))
                return message["result"]
            self.events.append(message)

    def wait_for(self, event, session):
        for k, message in enumerate(self.events):
            if message.get("method") == event and message.get("sessionId") == session:
                return self.events.pop(k)
        while True:
            message = self._message()
            if message.get("method") == event and message.get("sessionId") == session:
                return message
            self.events.append(message)

    def read_page(self, url, size, budget, read):
        """Opens url in a new tab of `size`, runs `budget` ms of virtual time after its
        load, returns read(session) and closes the tab."""
        target = self.send("Target.createTarget", {"url": "about:blank"})["targetId"]
        session = self.send("Target.attachToTarget", {"targetId": target, "flatten": True})["sessionId"]
        try:
            self.send("Emulation.setDeviceMetricsOverride",
                      {"width": size[0], "height": size[1], "deviceScaleFactor": 1, "mobile": False}, session)
            self.send("Page.enable", {}, session)
            self.send("Page.navigate", {"url": url}, session)
            self.wait_for("Page.loadEventFired", session)
            self.send("Emulation.setVirtualTimePolicy",
                      {"policy": "pauseIfNetworkFetchesPending", "budget": budget}, session)
            self.wait_for("Emulation.virtualTimeBudgetExpired", session)
            return read(session)
        finally:
            self.send("Target.closeTarget", {"targetId": target})
            self.events = [m for m in self.events if m.get("sessionId") != session]

    def close(self):
        try:
            self.send("Browser.close")
        except (RuntimeError, OSError):
            pass
        try:
            self.proc.wait(10)
        except subprocess.TimeoutExpired:
            self.proc.kill()
        self.commands.close()
        os.close(self.replies)
        self.profile.cleanup()


_browser = None


def _on_a_browser(url, size, budget, read, attempts=3):
    """read's answer for the page, from the shared browser; a browser that failed (a
    loaded CI machine now and then loses one) is replaced and the page tried again."""
    global _browser
    for attempt in range(attempts):
        if _browser is None:
            _browser = Browser()
        try:
            return _browser.read_page(url, size, budget, read)
        except (RuntimeError, OSError) as e:
            failure = e
            _browser.close()
            _browser = None
    raise RuntimeError("chromium failed %d times: %s" % (attempts, failure))


@atexit.register
def _close_browser():
    if _browser is not None:
        _browser.close()


def page_url(page, fragment=""):
    return "file://" + os.path.abspath(page) + ("#" + fragment if fragment else "")


def dump_dom(page, fragment="", size=(1200, 700), budget=4000):
    """The page's DOM after `budget` ms of virtual time: (body attributes dict, full text)."""
    def outer_html(session):
        reply = _browser.send("Runtime.evaluate", {"expression": "document.documentElement.outerHTML",
                                                    "returnByValue": True}, session)
        return reply["result"].get("value", "")
    dom = _on_a_browser(page_url(page, fragment), size, budget, outer_html)
    body = re.search(r"<body([^>]*)>", dom)
    attrs = dict(re.findall(r'([\w-]+)="([^"]*)"', body.group(1))) if body else {}
    return attrs, dom


def screenshot(page, png, fragment="", size=(1200, 700), budget=4000):
    """A PNG of the page (its viewport, `size`) after `budget` ms of virtual time."""
    def capture(session):
        return _browser.send("Page.captureScreenshot", {"format": "png"}, session)["data"]
    data = _on_a_browser(page_url(page, fragment), size, budget, capture)
    with open(png, "wb") as f:
        f.write(base64.b64decode(data))
    return png


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
