"""tray-render --preview (docs/preview.md): the HTTP endpoints with a Python client, and the
page in Debian's Chromium (headless, driven by the DevTools protocol) where it is installed."""
import json
import re
import shutil
import subprocess
import time
import urllib.request

import OpenImageIO as oiio
import pytest

# About 6 s on 2 cores: long enough for several snapshots (one a second).
RENDER = ["--spp", "192", "--resolution", "240x180", "--aov", "depth,normal", "--progress",
          "none"]


def start(tray_render, scenes, out):
    proc = subprocess.Popen([tray_render, str(scenes / "textured.gltf"), *RENDER,
                             "--preview=any", "-o", str(out)],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    line = proc.stdout.readline()
    m = re.match(r"preview: (http://127\.0\.0\.1:\d+/)", line)
    assert m, line + proc.stderr.read()
    return proc, m.group(1)


def get(url):
    with urllib.request.urlopen(url, timeout=5) as r:
        return r.headers.get("Content-Type"), r.read()


def test_endpoints_follow_the_render(tray_render, scenes, tmp_path):
    out = tmp_path / "preview.exr"
    proc, url = start(tray_render, scenes, out)
    versions, fractions = set(), []
    try:
        kind, page = get(url)
        assert kind.startswith("text/html") and b"/status" in page
        while proc.poll() is None:
            try:
                status = json.loads(get(url + "status")[1])
            except OSError:
                break  # the render ended between poll() and the request
            if status["version"] > 0:
                versions.add(status["version"])
                fractions.append(status["fraction"])
                assert status["layers"] == ["beauty", "Z", "N"]
                for layer in ("beauty", "N"):
                    kind, bmp = get(f"{url}image.bmp?layer={layer}")
                    assert kind == "image/bmp" and bmp[:2] == b"BM"
                    assert int.from_bytes(bmp[18:22], "little") == 240  # width
                    assert int.from_bytes(bmp[22:26], "little", signed=True) == -180
                assert 0 <= status["samples"] <= 192 and status["eta"] >= 0
            time.sleep(0.3)
    finally:
        proc.wait(60)
    assert proc.returncode == 0, proc.stderr.read()
    assert len(versions) >= 2, versions  # the image was updated during the render
    assert fractions == sorted(fractions)
    # The render wrote its outputs as usual.
    assert oiio.ImageInput.open(str(out)).spec().getattribute("tray:status") == "complete"


def test_preview_port_is_checked(tray_render, scenes):
    r = subprocess.run([tray_render, str(scenes / "whitted.gltf"), "--preview=70000"],
                       capture_output=True, text=True)
    assert r.returncode == 2 and "--preview" in r.stderr


def chromium():
    for name in ("chromium", "chromium-browser"):
        if shutil.which(name):
            return shutil.which(name)
    return None


def test_page_in_chromium(tray_render, scenes, tmp_path):
    """Headless Chromium: the page loads, the image updates at least twice during the render,
    the layer switch shows the chosen layer."""
    browser = chromium()
    websocket = pytest.importorskip("websocket", reason="python3-websocket not installed")
    if not browser:
        pytest.skip("Debian's chromium is not installed")
    proc, url = start(tray_render, scenes, tmp_path / "chromium.exr")
    chrome = subprocess.Popen([browser, "--headless=new", "--no-sandbox", "--disable-gpu",
                               "--remote-debugging-port=0", f"--user-data-dir={tmp_path}/profile",
                               url], stderr=subprocess.PIPE, text=True)
    try:
        for line in chrome.stderr:  # "DevTools listening on ws://127.0.0.1:PORT/devtools/..."
            if "DevTools listening on" in line:
                port = int(re.search(r":(\d+)/", line).group(1))
                break
        pages = json.loads(get(f"http://127.0.0.1:{port}/json")[1])
        page = next(p for p in pages if p["type"] == "page")
        ws = websocket.create_connection(page["webSocketDebuggerUrl"], timeout=10)
        calls = iter(range(1, 10**6))

        def evaluate(expression):
            n = next(calls)
            ws.send(json.dumps({"id": n, "method": "Runtime.evaluate",
                                "params": {"expression": expression, "returnByValue": True}}))
            while True:
                reply = json.loads(ws.recv())
                if reply.get("id") == n:
                    return reply["result"]["result"].get("value")

        def wait_for(expression, seconds=20):
            end = time.time() + seconds
            while time.time() < end:
                value = evaluate(expression)
                if value:
                    return value
                time.sleep(0.2)
            raise AssertionError(f"timed out: {expression}")

        wait_for("Number(document.body.dataset.loads || 0) >= 2")  # two images shown
        assert proc.poll() is None  # ... while the render was still going
        assert "samples per pixel" in evaluate("document.getElementById('status').textContent")
        evaluate("const s = document.getElementById('layer'); s.value = 'N';"
                 "s.dispatchEvent(new Event('change')); 1")
        assert wait_for("document.body.dataset.layer == 'N' && "
                        "document.getElementById('image').complete && "
                        "document.getElementById('image').naturalWidth == 240")
        ws.close()
    finally:
        chrome.kill()
        chrome.wait()
        proc.wait(60)
    assert proc.returncode == 0
