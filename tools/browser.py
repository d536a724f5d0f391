"""Open local HTML pages in headless Chromium and report what a reader would see (no dependency but Chromium).

    python tools/browser.py build/book/07_sadowsky.html ...     # prints the report, saves screenshots

Chromium is driven over the DevTools protocol on a pipe (``--remote-debugging-pipe``: commands are written to
the browser's file descriptor 3, answers and events read from its descriptor 4, each message JSON ended by a
NUL byte), so no websocket library and no browser download are needed: the Debian package ``chromium``
(``/usr/bin/chromium``) is enough. The browser runs with every host name resolving to nothing, so a page that
needs the network shows it as failed requests and console errors instead of quietly fetching from a CDN.

:func:`inspect_page` loads one page at a given window width, waits for the load event and for MathJax (when
the page has it) to finish typesetting, and returns a :class:`PageReport`: the text a reader sees outside code
blocks, the images with their natural sizes, console errors and uncaught exceptions, requests that left the
machine, the layout facts the book's checks need (top of the first heading, height of the fixed header, wide
tables and whether they scroll), and the screenshot saved as PNG.
"""

from __future__ import annotations

import base64
import json
import os
import shutil
import subprocess
import sys
import tempfile
import threading
import time
from dataclasses import dataclass, field
from pathlib import Path
from queue import Empty, Queue

CANDIDATES = ("chromium", "chromium-browser", "google-chrome", "google-chrome-stable")


def find_chromium() -> str | None:
    """Path of a Chromium executable (``$CHROMIUM`` first, then the usual names on ``PATH``), or None."""
    env = os.environ.get("CHROMIUM")
    if env:
        return env if Path(env).exists() else None
    for name in CANDIDATES:
        path = shutil.which(name)
        if path:
            return path
    return None


class BrowserError(RuntimeError):
    """Chromium did not start, did not answer in time, or answered a command with an error."""


class Chromium:
    """A headless Chromium process driven over the DevTools pipe; use as a context manager."""

    def __init__(self, executable: str | None = None, timeout: float = 30.0):
        self.executable = executable or find_chromium()
        if self.executable is None:
            raise BrowserError("no Chromium found (apt-get install chromium, or set CHROMIUM=/path/to/it)")
        self.timeout = timeout
        self._next_id = 0
        self._events: Queue = Queue()
        self._answers: dict[int, dict] = {}
        self._cond = threading.Condition()

    def __enter__(self) -> Chromium:
        self._profile = tempfile.mkdtemp(prefix="ssi-chromium-")
        to_browser_r, self._to_browser = os.pipe()
        self._from_browser, from_browser_w = os.pipe()

        def child_fds():  # the browser reads commands on fd 3 and writes answers on fd 4
            a, b = os.dup(to_browser_r), os.dup(from_browser_w)  # above 4, so the dup2s cannot clobber
            os.dup2(a, 3)
            os.dup2(b, 4)

        args = [
            self.executable,
            "--headless=new",
            "--remote-debugging-pipe",
            f"--user-data-dir={self._profile}",
            "--no-sandbox",  # CI runs as root, where Chromium's sandbox refuses to start
            "--disable-gpu",
            "--disable-dev-shm-usage",
            "--no-first-run",
            "--no-default-browser-check",
            "--disable-extensions",
            "--disable-background-networking",
            "--disable-component-update",
            "--host-resolver-rules=MAP * ~NOTFOUND",  # offline: any host name fails to resolve
            "about:blank",
        ]
        self._proc = subprocess.Popen(
            args,
            stdin=subprocess.DEVNULL,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
            preexec_fn=child_fds,
            pass_fds=(3, 4),
        )
        os.close(to_browser_r)
        os.close(from_browser_w)
        self._reader = threading.Thread(target=self._read, daemon=True)
        self._reader.start()
        return self

    def __exit__(self, *exc) -> None:
        try:
            self.send("Browser.close", timeout=5.0)
        except BrowserError:
            pass
        try:
            self._proc.wait(timeout=10)
        except subprocess.TimeoutExpired:
            self._proc.kill()
            self._proc.wait()
        os.close(self._to_browser)
        self._reader.join(timeout=5)
        os.close(self._from_browser)
        shutil.rmtree(self._profile, ignore_errors=True)

    def _read(self) -> None:
        buf = b""
        while True:
            try:
                chunk = os.read(self._from_browser, 1 << 16)
            except OSError:
                chunk = b""
            if not chunk:
                with self._cond:
                    self._answers[-1] = {}
                    self._cond.notify_all()
                return
            buf += chunk
            *messages, buf = buf.split(b"\0")
            for raw in messages:
                msg = json.loads(raw)
                if "id" in msg:
                    with self._cond:
                        self._answers[msg["id"]] = msg
                        self._cond.notify_all()
                else:
                    self._events.put(msg)

    def send(self, method: str, params: dict | None = None, session: str | None = None, timeout=None) -> dict:
        """Send one DevTools command and return its result; raise :class:`BrowserError` on error/timeout."""
        self._next_id += 1
        msg = {"id": self._next_id, "method": method, "params": params or {}}
        if session:
            msg["sessionId"] = session
        data = json.dumps(msg).encode() + b"\0"
        try:
            os.write(self._to_browser, data)
        except OSError as err:
            raise BrowserError(f"Chromium closed its pipe before {method}: {err}") from err
        deadline = time.monotonic() + (timeout or self.timeout)
        with self._cond:
            while self._next_id not in self._answers:
                if -1 in self._answers:
                    raise BrowserError(f"Chromium exited before answering {method}")
                left = deadline - time.monotonic()
                if left <= 0:
                    raise BrowserError(f"Chromium did not answer {method} within {timeout or self.timeout} s")
                self._cond.wait(left)
            answer = self._answers.pop(self._next_id)
        if "error" in answer:
            raise BrowserError(f"{method}: {answer['error']}")
        return answer.get("result", {})

    def events(self, wait: float = 0.0):
        """Events received so far (and, with ``wait`` > 0, for up to ``wait`` seconds more)."""
        out = []
        deadline = time.monotonic() + wait
        while True:
            try:
                out.append(self._events.get(timeout=max(deadline - time.monotonic(), 0.0) if wait else 0.0))
            except Empty:
                return out


@dataclass
class PageReport:
    """What one page showed in the browser (see :func:`inspect_page`)."""

    url: str
    text: str  # the rendered text outside <pre>, <code>, <script> and <style>
    images: list = field(default_factory=list)  # [{"src", "complete", "naturalWidth"}]
    console_errors: list = field(default_factory=list)  # console.error, uncaught exceptions, failed loads
    external_requests: list = field(default_factory=list)  # URLs that are not file:, data: or about:
    layout: dict = field(default_factory=dict)  # header height, first heading top, tables, page width
    math_elements: int = 0  # elements MathJax typeset
    screenshot: Path | None = None

    def problems(self) -> list[str]:
        """What a reader would see broken on the page (empty when it is fine): raw TeX delimiters ($$, \\(,
        \\[) in the text outside code, images that did not decode, console errors and exceptions, requests to
        the network, a page wider than the window, and a table running past its text column (into the
        sidebar or off the window) without a scroller."""
        problems = []
        for raw in ("$$", "\\(", "\\["):
            if raw in self.text:
                at = self.text.index(raw)
                problems.append(f"raw {raw!r} in the rendered text: {self.text[max(at - 40, 0) : at + 60]!r}")
        bad_images = [i["src"] for i in self.images if not i["naturalWidth"] > 0]
        if bad_images:
            problems.append(f"images not loaded: {bad_images}")
        problems += [f"console: {e}" for e in self.console_errors]
        problems += [f"request to the network: {u}" for u in self.external_requests]
        lay = self.layout
        if lay["page_width"] > lay["viewport_width"]:
            problems.append(f"page wider than the window: {lay['page_width']} > {lay['viewport_width']} px")
        for t in lay["tables"]:
            if t["right"] > lay["viewport_width"] and not t["scrolls"]:
                problems.append(
                    f"table cut at the window's edge (right edge {t['right']:.0f} px, no scroller)"
                )
        return problems


_TEXT_JS = r"""
(() => {
  const skip = new Set(["PRE", "CODE", "SCRIPT", "STYLE", "NOSCRIPT", "TEXTAREA"]);
  const walker = document.createTreeWalker(document.body, NodeFilter.SHOW_TEXT, {
    acceptNode(node) {
      for (let e = node.parentElement; e; e = e.parentElement) {
        if (skip.has(e.tagName)) return NodeFilter.FILTER_REJECT;
        if (e.classList && e.classList.contains("MathJax_Preview")) return NodeFilter.FILTER_REJECT;
        if (e.tagName === "MJX-ASSISTIVE-MML") return NodeFilter.FILTER_REJECT;
        const s = getComputedStyle(e);
        if (s.display === "none" || s.visibility === "hidden") return NodeFilter.FILTER_REJECT;
      }
      return NodeFilter.FILTER_ACCEPT;
    }
  });
  const parts = [];
  while (walker.nextNode()) parts.push(walker.currentNode.nodeValue);
  return parts.join("");
})()
"""

_LAYOUT_JS = r"""
(() => {
  const vw = window.innerWidth;
  let header = 0;
  for (const e of document.querySelectorAll("body *")) {
    const s = getComputedStyle(e);
    if ((s.position === "fixed" || s.position === "sticky") && s.display !== "none") {
      const r = e.getBoundingClientRect();
      if (r.top <= 0 && r.width >= vw * 0.5 && r.height > header) header = r.height;
    }
  }
  const h1 = document.querySelector("article h1, .md-content h1, main h1, h1");
  const scrolls = (e) => {
    for (; e && e !== document.body; e = e.parentElement) {
      const o = getComputedStyle(e).overflowX;
      if (o === "auto" || o === "scroll") return true;
    }
    return false;
  };
  const tables = Array.from(document.querySelectorAll("table")).map((t) => {
    const r = t.getBoundingClientRect();
    const column = (t.closest("article, .md-content, main") || document.body).getBoundingClientRect();
    // a table scrolls when it (display: block, overflow-x: auto) or an ancestor is a horizontal scroller
    return {width: t.scrollWidth, right: r.right, column_right: column.right, column_width: column.width,
            scrolls: scrolls(t)};
  });
  const verdict = document.querySelector(".verdict p.line, .verdict");
  return {
    viewport_width: vw,
    viewport_height: window.innerHeight,
    // the run report's verdict sentence: where its box ends, in CSS px from the top of the first screen
    verdict_bottom: verdict ? verdict.getBoundingClientRect().bottom : null,
    page_width: document.documentElement.scrollWidth,
    header_height: header,
    h1_top: h1 ? h1.getBoundingClientRect().top : null,
    h1_text: h1 ? h1.textContent.trim().slice(0, 80) : null,
    tables: tables,
  };
})()
"""

_IMAGES_JS = """Array.from(document.images).map(i => ({src: i.src.slice(0, 100), complete: i.complete,
  naturalWidth: i.naturalWidth}))"""

# the number of typeset equations once MathJax (3: startup.promise; 2: the Hub's queue) is done; -1 when the
# page has no MathJax (none loaded, or its script failed to load)
_MATHJAX_DONE_JS = """new Promise((resolve) => {
  const count = () => document.querySelectorAll("mjx-container, .MathJax, .MathJax_Display").length;
  const M = window.MathJax;
  if (M && M.startup && M.startup.promise) { M.startup.promise.then(() => resolve(count())); return; }
  if (M && M.Hub) { M.Hub.Queue(() => resolve(count())); return; }
  resolve(-1);
})"""


def _evaluate(browser: Chromium, session: str, expression: str, timeout=None):
    result = browser.send(
        "Runtime.evaluate",
        {"expression": expression, "returnByValue": True, "awaitPromise": True},
        session,
        timeout=timeout,
    )
    if "exceptionDetails" in result:
        raise BrowserError(f"page script failed: {result['exceptionDetails'].get('text')}")
    return result["result"].get("value")


def inspect_page(
    browser: Chromium,
    page: Path | str,
    screenshot: Path | None = None,
    width: int = 1280,
    height: int = 900,
    views: dict | None = None,
) -> PageReport:
    """Load ``page`` (a local file) in a fresh tab of ``browser`` at ``width`` x ``height`` px (CSS pixels).

    Waits for the load event and for MathJax's typesetting queue to empty, then collects the
    :class:`PageReport`. With ``screenshot`` the viewport (the top of the page as a reader first sees it) is
    saved there as PNG; ``views`` maps more PNG paths to CSS selectors: the page is scrolled to the first
    element matching each (skipped when none does) and the viewport saved there too.
    """
    url = page if isinstance(page, str) else Path(page).resolve().as_uri()
    target = browser.send("Target.createTarget", {"url": "about:blank"})["targetId"]
    session = browser.send("Target.attachToTarget", {"targetId": target, "flatten": True})["sessionId"]
    try:
        for domain in ("Page", "Runtime", "Log", "Network"):
            browser.send(f"{domain}.enable", {}, session)
        browser.send(
            "Emulation.setDeviceMetricsOverride",
            {"width": width, "height": height, "deviceScaleFactor": 1, "mobile": False},
            session,
        )
        browser.events()  # drop what came before the navigation
        nav = browser.send("Page.navigate", {"url": url}, session)
        if nav.get("errorText"):
            raise BrowserError(f"cannot open {url}: {nav['errorText']}")
        events = []
        deadline = time.monotonic() + browser.timeout
        while not any(e.get("method") == "Page.loadEventFired" for e in events):
            if time.monotonic() > deadline:
                raise BrowserError(f"{url} did not finish loading within {browser.timeout} s")
            events += browser.events(wait=0.2)
        n_math = _evaluate(browser, session, _MATHJAX_DONE_JS, timeout=browser.timeout)
        report = PageReport(url=url, text=_evaluate(browser, session, _TEXT_JS))
        report.math_elements = max(int(n_math), 0)
        report.images = _evaluate(browser, session, _IMAGES_JS)
        report.layout = _evaluate(browser, session, _LAYOUT_JS)
        if screenshot is not None:
            shot = browser.send("Page.captureScreenshot", {"format": "png"}, session)
            screenshot = Path(screenshot)
            screenshot.parent.mkdir(parents=True, exist_ok=True)
            screenshot.write_bytes(base64.b64decode(shot["data"]))
            report.screenshot = screenshot
        for path, selector in (views or {}).items():
            found = _evaluate(
                browser,
                session,
                f"(() => {{ const e = document.querySelector({json.dumps(selector)}); "
                "if (!e) return false; e.scrollIntoView({block: 'center'}); return true; })()",
            )
            if found:
                shot = browser.send("Page.captureScreenshot", {"format": "png"}, session)
                Path(path).parent.mkdir(parents=True, exist_ok=True)
                Path(path).write_bytes(base64.b64decode(shot["data"]))
        events += browser.events(wait=0.2)
        for e in events:
            if e.get("sessionId") not in (None, session):
                continue
            method, p = e.get("method"), e.get("params", {})
            if method == "Runtime.consoleAPICalled" and p.get("type") in ("error", "assert"):
                args = " ".join(str(a.get("value", a.get("description", ""))) for a in p.get("args", []))
                report.console_errors.append(f"console.{p['type']}: {args}")
            elif method == "Runtime.exceptionThrown":
                d = p.get("exceptionDetails", {})
                report.console_errors.append(
                    "exception: " + str(d.get("exception", {}).get("description") or d.get("text"))
                )
            elif method == "Log.entryAdded" and p.get("entry", {}).get("level") == "error":
                entry = p["entry"]
                report.console_errors.append(
                    f"{entry.get('source')}: {entry.get('text')} {entry.get('url', '')}"
                )
            elif method == "Network.requestWillBeSent":
                req_url = p.get("request", {}).get("url", "")
                if not req_url.startswith(("file:", "data:", "about:", "blob:")):
                    report.external_requests.append(req_url)
        return report
    finally:
        browser.send("Target.closeTarget", {"targetId": target})


def main(argv=None) -> int:
    pages = sys.argv[1:] if argv is None else argv
    if not pages:
        print("usage: python tools/browser.py PAGE.html [...]  (screenshots go to build/browser/)")
        return 2
    with Chromium() as browser:
        for page in pages:
            shot = Path("build/browser") / (Path(page).stem + ".png")
            views = {shot.with_name(shot.stem + "-math.png"): "mjx-container[display]"}
            views[shot.with_name(shot.stem + "-figure.png")] = ".jp-OutputArea-output img"
            r = inspect_page(browser, Path(page), shot, views=views)
            print(
                f"{page}: {len(r.images)} images ({sum(i['naturalWidth'] > 0 for i in r.images)} loaded), "
                f"{r.math_elements} math elements, {len(r.console_errors)} console errors, "
                f"{len(r.external_requests)} external requests; header {r.layout['header_height']:.0f} px, "
                f"first heading at {r.layout['h1_top']} px; screenshot {shot}"
            )
            for line in r.console_errors + r.external_requests:
                print("   ", line)
    return 0


if __name__ == "__main__":
    sys.exit(main())
