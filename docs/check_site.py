"""The built documentation site as a reader sees it: every page opened in headless Chromium,
offline, after MathJax has typeset it; fails on raw TeX (math left as source) or a broken image
(one that did not load). A CI step (.ci/run), kept out of `make test`.

    python docs/check_site.py [--site SITE]                 # SITE: docs/_build/html
    python docs/check_site.py --shots DIR PAGE ...        # also PNG screenshots of those pages

Chromium is driven through its DevTools protocol on a pipe (--remote-debugging-pipe: messages
as NUL-terminated JSON on file descriptors 3 and 4), so no driver package is needed; the
browser is Debian's chromium-headless-shell (or chromium), found on PATH or in $CHROMIUM.
"""

from __future__ import annotations

import argparse
import base64
import json
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
BROWSERS = ("chromium-headless-shell", "chromium", "chromium-browser")
WIDTH, HEIGHT = 1280, 900  # px: the window the reader used

# Evaluated in each page once it has loaded: waits for MathJax, then lists what a reader would
# see wrong. Raw TeX: a math element MathJax left untypeset, or TeX delimiters or commands in
# the text outside code.
CHECK = r"""(async () => {
  if (window.MathJax && MathJax.startup && MathJax.startup.promise) await MathJax.startup.promise;
  await Promise.all([...document.images].map(i => i.complete ? null :
      new Promise(r => { i.onload = i.onerror = r; })));
  const broken = [...document.images].filter(i => i.naturalWidth === 0).map(i => i.getAttribute('src'));
  const untypeset = [...document.querySelectorAll('.math')].filter(e => !e.querySelector('mjx-container'))
      .map(e => e.textContent.trim().slice(0, 80));
  const raw = [];
  const walker = document.createTreeWalker(document.body, NodeFilter.SHOW_TEXT);
  for (let n; (n = walker.nextNode());) {
    if (n.parentElement.closest('pre, code, script, style, mjx-container, .highlight, .math')) continue;
    if (/\\\(|\\\[|\$\$|\\(frac|mathrm|sum|qquad|begin)\b/.test(n.textContent)) raw.push(n.textContent.trim().slice(0, 80));
  }
  return JSON.stringify({broken, raw: untypeset.concat(raw)});
})()"""


class Browser:
    """One headless Chromium and one page, driven over the DevTools pipe."""

    def __init__(self, executable: str):
        self.profile = tempfile.mkdtemp(prefix="formopt-chromium-")
        r_chrome, w_ours = os.pipe()  # we write, Chromium reads on its fd 3
        r_ours, w_chrome = os.pipe()  # Chromium writes on its fd 4
        # the shell moves the pipe's ends to fds 3 and 4, where Chromium expects them
        close = " ".join(f"{fd}<&-" for fd in (r_chrome, w_chrome) if fd not in (3, 4))
        redirect = f'exec "$0" "$@" 3<&{r_chrome} 4>&{w_chrome} {close}'
        self.proc = subprocess.Popen(
            ["/bin/sh", "-c", redirect, executable, "--headless", "--remote-debugging-pipe",
             "--no-sandbox", "--disable-gpu", "--no-first-run", f"--user-data-dir={self.profile}",
             f"--window-size={WIDTH},{HEIGHT}", "about:blank"],
            pass_fds=(r_chrome, w_chrome), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        os.close(r_chrome)
        os.close(w_chrome)
        self.send_file, self.recv_file = os.fdopen(w_ours, "wb"), os.fdopen(r_ours, "rb")
        self.next_id, self.buffer = 0, b""
        target = self.call("Target.createTarget", url="about:blank")["targetId"]
        self.session = self.call("Target.attachToTarget", targetId=target, flatten=True)["sessionId"]
        self.call("Page.enable", session=True)
        self.call("Emulation.setDeviceMetricsOverride", session=True, width=WIDTH, height=HEIGHT,
                  deviceScaleFactor=1, mobile=False)

    def call(self, method: str, session: bool = False, **params) -> dict:
        """Send one command, return its result; events in between are read and dropped, except
        that they are remembered when a page load ends (`self.loaded`)."""
        self.next_id += 1
        message = {"id": self.next_id, "method": method, "params": params}
        if session:
            message["sessionId"] = self.session
        self.send_file.write(json.dumps(message).encode() + b"\0")
        self.send_file.flush()
        while True:
            reply = self.receive()
            if reply.get("method") == "Page.loadEventFired":
                self.loaded = True
            if reply.get("id") == self.next_id:
                if "error" in reply:
                    raise RuntimeError(f"{method}: {reply['error']}")
                return reply["result"]

    def receive(self) -> dict:
        while b"\0" not in self.buffer:
            chunk = os.read(self.recv_file.fileno(), 1 << 16)
            if not chunk:
                raise RuntimeError("Chromium closed its DevTools pipe")
            self.buffer += chunk
        message, self.buffer = self.buffer.split(b"\0", 1)
        return json.loads(message)

    def open(self, url: str) -> None:
        self.loaded = False
        self.call("Page.navigate", session=True, url=url)
        while not self.loaded:
            if self.receive().get("method") == "Page.loadEventFired":
                self.loaded = True

    def evaluate(self, expression: str):
        result = self.call("Runtime.evaluate", session=True, expression=expression, awaitPromise=True,
                           returnByValue=True, timeout=60000)
        return result["result"].get("value")

    def screenshot(self, path: Path) -> None:
        shot = self.call("Page.captureScreenshot", session=True, format="png", captureBeyondViewport=False)
        path.write_bytes(base64.b64decode(shot["data"]))

    def close(self) -> None:
        try:
            self.call("Browser.close")
        except (RuntimeError, OSError):
            pass
        self.proc.wait(timeout=30)
        shutil.rmtree(self.profile, ignore_errors=True)


def browser_path() -> str:
    found = os.environ.get("CHROMIUM") or next(filter(None, map(shutil.which, BROWSERS)), None)
    if not found:
        sys.exit("check_site: no Chromium found (apt-get install chromium-headless-shell, or set CHROMIUM)")
    return found


def check(site: Path, shots: Path | None = None, pages: list[str] = ()) -> list[str]:
    """The problems of every page of `site`, one line each; screenshots of `pages` into `shots`."""
    problems = []
    browser = Browser(browser_path())
    try:
        for page in sorted(site.rglob("*.html")):
            name = str(page.relative_to(site))
            browser.open(page.resolve().as_uri())
            found = json.loads(browser.evaluate(CHECK))
            problems += [f"{name}: broken image {src}" for src in found["broken"]]
            problems += [f"{name}: raw TeX: {text!r}" for text in found["raw"]]
            for shot in (s for s in pages if s.split("#")[0] == name) if shots else ():
                shots.mkdir(parents=True, exist_ok=True)
                if "#" in shot:  # scrolled to the anchor
                    browser.evaluate(f"document.getElementById({shot.split('#')[1]!r}).scrollIntoView()")
                browser.screenshot(shots / (shot.replace("/", "_").replace(".html", "").replace("#", "-") + ".png"))
    finally:
        browser.close()
    return problems


def main() -> int:
    args = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    args.add_argument("--site", default=str(ROOT / "docs" / "_build" / "html"))
    args.add_argument("--shots", help="folder for screenshots of the pages named after it")
    args.add_argument("pages", nargs="*", help="pages to screenshot (paths in the site, e.g. api.html, "
                      "or api.html#modules: scrolled to that anchor)")
    a = args.parse_args()
    site = Path(a.site)
    if not (site / "index.html").exists():
        sys.exit(f"check_site: {site}: no index.html (make docs first)")
    problems = check(site, Path(a.shots) if a.shots else None, a.pages)
    for line in problems:
        print(line)
    pages = len(list(site.rglob("*.html")))
    print(f"check_site: {pages} pages, {len(problems)} problems (raw TeX, broken images)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
