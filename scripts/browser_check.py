#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Opens HTML pages in headless Chromium, takes a screenshot of each, and
fails on a broken image or link.

For each page, Chromium (Debian's `chromium`, driven over the DevTools
protocol on a pipe: --remote-debugging-pipe, no network port) loads the
file, waits for its load event, and the page itself is asked, in the
browser, for every <img>: whether it loaded and its whole picture decodes
(HTMLImageElement.decode(): a missing file, a bad data: URI, a corrupt
image fail it), and for every <a href>. Chromium draws a truncated PNG as
far as it goes without an error, so every PNG (inline data: URI or file) is
also read to its end here: each chunk's CRC, IEND, the whole image data. A link is broken
when it points into the page (#id) at an id that is not there, or at a
local file (relative or file:) that does not exist; links to other schemes
(http:, mailto:) are listed, not followed (no network). Then a PNG
screenshot of the whole page is written.

Usage: browser_check.py PAGE.html... [--shots DIR] [--chromium PATH]
Exit status 0 when every page is clean, 1 when any image or link is
broken (each named on stderr), 2 when Chromium cannot be run.
"""
from __future__ import annotations

import argparse
import base64
import fcntl
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
import zlib
from pathlib import Path
from urllib.parse import unquote, urlparse

TIMEOUT_S = 120

# Evaluated in the page after its load event. HTMLImageElement.decode()
# rejects when the whole image cannot be decoded (naturalWidth alone misses
# a truncated PNG, whose header still gives the size).
PROBE = """(async () => JSON.stringify({
  images: await Promise.all(Array.from(document.images).map(async i => {
    let decoded = true, why = '';
    try { await i.decode(); } catch (e) { decoded = false; why = String(e); }
    return {src: i.getAttribute('src') || '', complete: i.complete, width: i.naturalWidth, decoded: decoded,
            why: why};
  })),
  links: Array.from(document.querySelectorAll('a[href]')).map(a => a.getAttribute('href')),
  ids: Array.from(document.querySelectorAll('[id]')).map(e => e.id),
  names: Array.from(document.querySelectorAll('a[name]')).map(e => e.getAttribute('name')),
  height: Math.max(document.body.scrollHeight, document.documentElement.scrollHeight),
  width: Math.max(document.body.scrollWidth, document.documentElement.scrollWidth)
}))()"""


class BrowserError(RuntimeError):
    pass


def find_chromium(given: str | None) -> str:
    for name in [given] if given else ["chromium", "chromium-browser", "google-chrome"]:
        path = shutil.which(name) if name else None
        if path:
            return path
    raise BrowserError("chromium not found (Debian package `chromium`; `make setup` installs it)")


class Chromium:
    """Headless Chromium and a DevTools protocol session over a pipe (fd 3
    in, fd 4 out, messages ended by NUL)."""

    def __init__(self, exe: str):
        self.profile = tempfile.TemporaryDirectory(prefix="pluecker-chromium-")
        to_chrome_r, self.to_chrome = os.pipe()
        self.from_chrome, from_chrome_w = os.pipe()
        # The child gets its ends as fd 3 and fd 4, inheritable across exec
        # (moved above 10 first: a pipe end may itself be fd 3 or 4; and
        # close_fds would close them again after this hook).
        def child_fds():
            high = [fcntl.fcntl(fd, fcntl.F_DUPFD, 10) for fd in (to_chrome_r, from_chrome_w)]
            for fd, target in zip(high, (3, 4)):
                os.dup2(fd, target, inheritable=True)
                os.close(fd)
        self.proc = subprocess.Popen(
            [exe, "--headless", "--no-sandbox", "--disable-gpu", "--no-first-run", "--no-default-browser-check",
             "--disable-extensions", "--disable-background-networking", "--hide-scrollbars",
             f"--user-data-dir={self.profile.name}", "--remote-debugging-pipe", "about:blank"],
            stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
            preexec_fn=child_fds, close_fds=False)
        os.close(to_chrome_r)
        os.close(from_chrome_w)
        self.buf = b""
        self.next_id = 0
        self.events: list[dict] = []

    def close(self) -> None:
        try:
            self.send("Browser.close")
        except (BrowserError, OSError):
            pass
        try:
            self.proc.wait(timeout=20)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            self.proc.wait()
        for fd in (self.to_chrome, self.from_chrome):
            try:
                os.close(fd)
            except OSError:
                pass
        self.profile.cleanup()

    def _read_message(self, deadline: float) -> dict:
        while b"\0" not in self.buf:
            if time.monotonic() > deadline:
                raise BrowserError("Chromium did not answer in time")
            chunk = os.read(self.from_chrome, 1 << 16)
            if not chunk:
                err = self.proc.stderr.read().decode(errors="replace") if self.proc.stderr else ""
                raise BrowserError(f"Chromium closed the DevTools pipe (exit {self.proc.poll()}): {err[-800:]}")
            self.buf += chunk
        msg, _, self.buf = self.buf.partition(b"\0")
        return json.loads(msg)

    def send(self, method: str, params: dict | None = None, session: str | None = None) -> dict:
        self.next_id += 1
        msg = {"id": self.next_id, "method": method, "params": params or {}}
        if session:
            msg["sessionId"] = session
        os.write(self.to_chrome, json.dumps(msg).encode() + b"\0")
        deadline = time.monotonic() + TIMEOUT_S
        while True:
            m = self._read_message(deadline)
            if m.get("id") == self.next_id:
                if "error" in m:
                    raise BrowserError(f"{method}: {m['error']}")
                return m.get("result", {})
            self.events.append(m)

    def wait_event(self, method: str, session: str) -> dict:
        deadline = time.monotonic() + TIMEOUT_S
        while True:
            for k, e in enumerate(self.events):
                if e.get("method") == method and e.get("sessionId") == session:
                    return self.events.pop(k)
            self.events.append(self._read_message(deadline))


def png_problem(data: bytes) -> str | None:
    """What is wrong with a PNG file, read to its end: signature, every
    chunk's length and CRC, IHDR first, IEND last, and the zlib stream of
    the IDAT chunks complete with one filter byte plus a row per scanline
    (non-interlaced). None when it is whole."""
    if not data.startswith(b"\x89PNG\r\n\x1a\n"):
        return "not a PNG (bad signature)"
    pos, idat, ihdr, end = 8, [], None, False
    while pos < len(data):
        if len(data) - pos < 12:
            return f"truncated chunk header at byte {pos}"
        n = int.from_bytes(data[pos:pos + 4], "big")
        kind, body = data[pos + 4:pos + 8], data[pos + 8:pos + 8 + n]
        if len(body) < n or len(data) < pos + 12 + n:
            return f"chunk {kind!r} at byte {pos} runs past the end of the data ({len(data)} bytes)"
        if zlib.crc32(kind + body) != int.from_bytes(data[pos + 8 + n:pos + 12 + n], "big"):
            return f"chunk {kind!r} at byte {pos}: CRC mismatch"
        if ihdr is None and kind != b"IHDR":
            return "first chunk is not IHDR"
        if kind == b"IHDR":
            ihdr = body
        elif kind == b"IDAT":
            idat.append(body)
        elif kind == b"IEND":
            end = True
            break
        pos += 12 + n
    if not end:
        return "no IEND chunk (truncated)"
    width, height = int.from_bytes(ihdr[0:4], "big"), int.from_bytes(ihdr[4:8], "big")
    depth, color, interlace = ihdr[8], ihdr[9], ihdr[12]
    try:
        raw = zlib.decompress(b"".join(idat))
    except zlib.error as e:
        return f"image data does not decompress: {e}"
    channels = {0: 1, 2: 3, 3: 1, 4: 2, 6: 4}.get(color)
    if channels and not interlace:
        want = height * (1 + (width * channels * depth + 7) // 8)
        if len(raw) != want:
            return f"{len(raw)} bytes of image data, {width}x{height} needs {want}"
    return None


def image_bytes(page: Path, src: str) -> bytes | None:
    """The bytes of an <img> src: a base64 data: URI or a local file."""
    if src.startswith("data:"):
        head, _, payload = src.partition(",")
        return base64.b64decode(payload) if head.endswith(";base64") else unquote(payload).encode()
    u = urlparse(src)
    if u.scheme in ("", "file"):
        path = Path(unquote(u.path))
        path = path if path.is_absolute() else page.parent / path
        return path.read_bytes() if path.is_file() else None
    return None


def broken_links(page: Path, links: list[str], ids: set[str]) -> tuple[list[str], list[str]]:
    """(broken, not followed) of the page's links."""
    broken, external = [], []
    for href in links:
        u = urlparse(href)
        if u.scheme in ("", "file"):
            target = unquote(u.path)
            if not target:  # "#id" in this page
                if u.fragment and u.fragment not in ids:
                    broken.append(f"{href} (no element with id '{u.fragment}')")
                continue
            path = Path(target) if u.scheme == "file" or target.startswith("/") else page.parent / target
            if not path.exists():
                broken.append(f"{href} ({path} does not exist)")
        elif u.scheme == "data":
            continue
        else:
            external.append(href)
    return broken, external


def check_page(browser: Chromium, page: Path, shot: Path) -> dict:
    """Loads the page, checks its images and links, writes the screenshot."""
    target = browser.send("Target.createTarget", {"url": "about:blank"})["targetId"]
    session = browser.send("Target.attachToTarget", {"targetId": target, "flatten": True})["sessionId"]
    browser.send("Page.enable", session=session)
    browser.send("Page.navigate", {"url": page.resolve().as_uri()}, session=session)
    browser.wait_event("Page.loadEventFired", session)
    got = browser.send("Runtime.evaluate", {"expression": PROBE, "returnByValue": True, "awaitPromise": True},
                       session=session)
    info = json.loads(got["result"]["value"])
    bad_images = []
    for i in info["images"]:
        if not (i["complete"] and i["decoded"] and i["width"] > 0):
            bad_images.append(f"{short(i['src'])} ({i['why'] or 'no picture'})")
            continue
        data = image_bytes(page, i["src"])
        why = png_problem(data) if data is not None and data.startswith(b"\x89PNG") else None
        if why:
            bad_images.append(f"{short(i['src'])} (PNG: {why})")
    bad_links, external = broken_links(page, info["links"], set(info["ids"]) | set(info["names"]))
    width, height = min(max(info["width"], 800), 4000), min(max(info["height"], 600), 16000)
    browser.send("Emulation.setDeviceMetricsOverride",
                 {"width": width, "height": height, "deviceScaleFactor": 1, "mobile": False}, session=session)
    png = base64.b64decode(browser.send("Page.captureScreenshot", {"format": "png", "captureBeyondViewport": True},
                                        session=session)["data"])
    shot.parent.mkdir(parents=True, exist_ok=True)
    shot.write_bytes(png)
    browser.send("Target.closeTarget", {"targetId": target})
    return {"page": str(page), "images": len(info["images"]), "links": len(info["links"]),
            "bad_images": bad_images, "bad_links": bad_links, "external_links": external,
            "screenshot": str(shot), "screenshot_bytes": len(png), "size": [width, height]}


def short(src: str) -> str:
    return src if len(src) <= 60 else src[:40] + "..." + src[-12:]


def check_pages(pages: list[Path], shots: Path, chromium: str | None = None) -> list[dict]:
    browser = Chromium(find_chromium(chromium))
    try:
        return [check_page(browser, p, shots / (p.stem + ".png")) for p in pages]
    finally:
        browser.close()


def main(argv: list[str]) -> int:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("pages", nargs="+", type=Path)
    p.add_argument("--shots", type=Path, default=None, help="screenshot folder (default: beside each page)")
    p.add_argument("--chromium", default=None)
    args = p.parse_args(argv)
    for page in args.pages:
        if not page.is_file():
            print(f"browser_check: {page}: no such file", file=sys.stderr)
            return 2
    try:
        results = check_pages(args.pages, args.shots or args.pages[0].parent / "screenshots", args.chromium)
    except BrowserError as e:
        print(f"browser_check: {e}", file=sys.stderr)
        return 2
    bad = 0
    for r in results:
        print(f"browser_check: {r['page']}: {r['images']} images, {r['links']} links, screenshot "
              f"{r['screenshot']} ({r['size'][0]}x{r['size'][1]}, {r['screenshot_bytes']:,} bytes)")
        for what in ("bad_images", "bad_links"):
            for item in r[what]:
                print(f"browser_check: {r['page']}: broken {what[4:-1]}: {item}", file=sys.stderr)
                bad += 1
        for href in r["external_links"]:
            print(f"browser_check: {r['page']}: not followed (no network): {href}")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
