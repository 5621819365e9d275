#!/usr/bin/python3
"""rtedge-web in a real browser (Debian's chromium, headless, driven by
python3-selenium) against a real rtedged over udpm:// (run inside
tests/lcm/netns.sh: nothing leaves a private loopback).

The page loads; the overlay shows two different frames; moving the Canny
high slider changes the daemon's parameter (seen in the daemon's own
param_state_t, read here with the lcm package) and the edges layer (fewer
edge pixels at a high threshold); a value out of range is refused with its
reason, and so is one the daemon refuses (Canny low above high); Save
writes a configuration that `rtedged --check-config` accepts and that holds
the values set; the controls need the token. Screenshots are kept in
BUILD_DIR (web_*.png). Skipped (exit 77, with the reason) when chromium,
chromedriver, selenium, aiohttp or the lcm package is missing.

  test_web.py RTEDGED WEB TYPES_DIR BUILD_DIR CLIP
"""
import json
import os
import socket
import subprocess
import sys
import time
import urllib.request

RTEDGED, WEB, TYPES, BUILD, CLIP = sys.argv[1:6]
FAILURES = []


def skip(why):
    print("skipped: " + why)
    sys.exit(77)


def check(ok, what):
    print(("ok: " if ok else "FAIL: ") + what, flush=True)
    if not ok:
        FAILURES.append(what)


if os.environ.get("RTE_PYTHON_LCM"):
    sys.path.insert(0, os.environ["RTE_PYTHON_LCM"])
sys.path.insert(0, TYPES)
try:
    import cv2
    import lcm
    import numpy as np
    import rtedge
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service
    from selenium.webdriver.common.action_chains import ActionChains
    from selenium.webdriver.common.by import By
    from selenium.webdriver.common.keys import Keys
    from selenium.webdriver.support.ui import Select, WebDriverWait
    import aiohttp  # noqa: F401  (rtedge-web's)
except ImportError as e:
    skip("missing %s (python3-selenium, python3-aiohttp, python3-opencv, the lcm package)" % e.name)
CHROMEDRIVER = "/usr/bin/chromedriver"
if not os.path.exists(CHROMEDRIVER):
    skip("no %s (chromium-driver)" % CHROMEDRIVER)

tmp = os.path.join(BUILD, "web_test")
os.makedirs(tmp, exist_ok=True)
saved = os.path.join(tmp, "saved.conf")
if os.path.exists(saved):
    os.remove(saved)
TOKEN = "s3cret-token"


def free_port():
    s = socket.socket()
    s.bind(("127.0.0.1", 0))
    port = s.getsockname()[1]
    s.close()
    return port


port = free_port()
URL = "http://127.0.0.1:%d/" % port
env = dict(os.environ)
env["PYTHONPATH"] = os.pathsep.join(p for p in (os.environ.get("RTE_PYTHON_LCM"), TYPES) if p)
daemon = subprocess.Popen(
    [RTEDGED, "--source", CLIP, "--loop", "--set", "debug.enabled=true",
     "--set", "debug.rate_hz=10", "--set", "params.enabled=true",
     "--set", "params.save_path=" + saved],
    stderr=open(os.path.join(tmp, "rtedged.err"), "w"))
web = subprocess.Popen([sys.executable, WEB, "--types", TYPES, "--port", str(port),
                        "--token", TOKEN], env=env,
                       stdout=open(os.path.join(tmp, "web.out"), "w"),
                       stderr=open(os.path.join(tmp, "web.err"), "w"))

# The daemon's own word on its parameters, independent of the page.
states = []
lc = lcm.LCM("udpm://239.255.76.67:7667?ttl=0")
lc.subscribe("RTEDGE_PARAM_STATE", lambda ch, data: states.append(rtedge.param_state_t.decode(data)))


def daemon_value(name, timeout=5.0):
    """The value of `name` in the daemon's newest param_state_t: every state
    waiting is read, then one more is awaited (the daemon answers each
    request and sends one every 2 s)."""
    while lc.handle_timeout(0) > 0:
        pass
    n = len(states)
    end = time.time() + timeout
    while time.time() < end and len(states) == n:
        lc.handle_timeout(100)
    if len(states) == n:
        return None
    for k in states[-1].keys[:states[-1].nkeys]:
        if k.name == name:
            return k.int_value if k.type in (1, 3) else k.real_value if k.type == 2 else k.text_value
    return None


def post(path, body, token):
    req = urllib.request.Request(URL + path.lstrip("/"), data=json.dumps(body).encode(),
                                 headers={"Content-Type": "application/json",
                                          **({"X-RTEdge-Token": token} if token else {})})
    try:
        with urllib.request.urlopen(req, timeout=5) as r:
            return r.status, json.load(r)
    except urllib.error.HTTPError as e:
        return e.code, json.load(e)


driver = None
try:
    # the web server up
    for _ in range(100):
        try:
            urllib.request.urlopen(URL + "api/state", timeout=1).read()
            break
        except OSError:
            time.sleep(0.1)
    opts = webdriver.ChromeOptions()
    for a in ("--headless=new", "--no-sandbox", "--disable-dev-shm-usage", "--disable-gpu",
              "--window-size=1400,1300"):
        opts.add_argument(a)
    try:
        driver = webdriver.Chrome(service=Service(CHROMEDRIVER), options=opts)
    except Exception as e:  # chromium cannot start here (no sandbox rights, no display libs)
        skip("chromium cannot start: %s" % str(e).splitlines()[0])
    driver.get(URL + "#token=" + TOKEN)
    wait = WebDriverWait(driver, 20)
    wait.until(lambda d: d.find_element(By.ID, "st-fps").text not in ("", "–"))
    wait.until(lambda d: d.find_elements(By.ID, "p-lane-canny_high-slider"))
    check(driver.title == "rtedge", "the page loads (title %r)" % driver.title)
    check("y4m:" in driver.find_element(By.ID, "source").text, "the source is shown")

    def overlay_png(name):
        wait.until(lambda d: d.execute_script(
            "const i = document.getElementById('overlay'); return i.complete && i.naturalWidth > 0"))
        png = driver.find_element(By.ID, "overlay").screenshot_as_png
        with open(os.path.join(tmp, "web_%s.png" % name), "wb") as f:
            f.write(png)
        return cv2.imdecode(np.frombuffer(png, np.uint8), cv2.IMREAD_COLOR)

    a = overlay_png("overlay_a")
    time.sleep(1.0)
    b = overlay_png("overlay_b")
    diff = float(np.mean(cv2.absdiff(a, b))) if a.shape == b.shape else 255.0
    check(a.shape[1] > 200 and diff > 1.0, "the overlay shows two different frames "
          "(%dx%d, mean difference %.1f)" % (a.shape[1], a.shape[0], diff))
    driver.save_screenshot(os.path.join(tmp, "web_page.png"))
    # The panels: per-stage bars, the lanes, the grasp objects as a table.
    wait.until(lambda d: d.find_elements(By.CSS_SELECTOR, "#objects tbody tr"))
    # (read in one script: the page rebuilds these as each update comes)
    names = driver.execute_script(
        "return [...document.querySelectorAll('#stages .bar span:first-child')]"
        ".map((e) => e.textContent)")
    check(len(names) == 11 and names[0] == "lane.gray" and "grasp.split" in names and
          names[-1] == "debug",
          "a bar per stage: %s" % names)
    check(driver.find_element(By.ID, "lane-offset").text.endswith("px") and
          driver.find_element(By.ID, "lane-right").text.startswith("seen"),
          "lane offset %r, right lane %r" % (driver.find_element(By.ID, "lane-offset").text,
                                             driver.find_element(By.ID, "lane-right").text))
    rows = driver.execute_script(
        "return [...document.querySelectorAll('#objects tbody tr')]"
        ".map((r) => [...r.cells].map((c) => c.textContent))")
    check(len(rows) > 0 and len(rows[0]) == 8 and 0 <= float(rows[0][7]) <= 1,
          "the grasp objects as a table, a score 0..1 last: %s" % rows[:2])

    # Dragging the ROI's top-left corner on the image moves the daemon's lane.roi.
    roi_before = daemon_value("lane.roi")
    corner = driver.find_element(By.CSS_SELECTOR, "#roi circle[data-index='1']")
    ActionChains(driver).click_and_hold(corner).move_by_offset(-60, 25).release().perform()
    time.sleep(0.5)
    roi_after = daemon_value("lane.roi")
    try:
        x0, y0 = map(float, roi_before.split(";")[1].split(","))
        x1, y1 = map(float, roi_after.split(";")[1].split(","))
        moved = x1 < x0 - 0.03 and y1 > y0 + 0.02
    except (AttributeError, ValueError, IndexError):
        moved = False
    check(moved, "dragging the ROI corner: lane.roi %r -> %r" % (roi_before, roi_after))
    driver.save_screenshot(os.path.join(tmp, "web_roi.png"))

    # Capture to browser: the MJPEG stream read by the page's own fetch(),
    # each part's X-Capture-Utime (the frame's capture, wall clock) against
    # the browser's clock when the part arrives. A figure, printed; checked
    # only for being live (under 2 s).
    lat = driver.execute_async_script("""
        const done = arguments[arguments.length - 1];
        (async () => {
          const r = await fetch('/stream.mjpg');
          const reader = r.body.getReader(), dec = new TextDecoder('latin1'), out = [];
          while (out.length < 30) {
            const { value, done: end } = await reader.read();
            if (end) break;
            const now = Date.now() * 1000;
            for (const m of dec.decode(value).matchAll(/X-Capture-Utime: (\\d+)/g))
              out.push((now - Number(m[1])) / 1000);
          }
          reader.cancel();
          done(out);
        })().catch((e) => done(String(e)));""")
    ok = isinstance(lat, list) and len(lat) >= 20
    if ok:
        lat = sorted(lat[1:])  # the first part may have waited in the server
        print("capture to browser over %d overlays at 10 Hz: p50 %.1f ms, max %.1f ms"
              % (len(lat), lat[len(lat) // 2], lat[-1]))
    check(ok and lat[-1] < 2000, "the overlay stream is live in the browser (%s)"
          % ("%.1f ms at most" % lat[-1] if ok else lat))

    def outcome_has(text, timeout=10):
        try:
            WebDriverWait(driver, timeout).until(
                lambda d: text in d.find_element(By.ID, "outcome").text)
            return True
        except Exception:
            return False

    # Fixed thresholds, then only the edges layer.
    Select(driver.find_element(By.ID, "p-lane-canny_mode")).select_by_value("fixed")
    check(outcome_has("applied"), "canny_mode = fixed applied: %s"
          % driver.find_element(By.ID, "outcome").text)
    check(daemon_value("lane.canny_mode") == "fixed", "the daemon's lane.canny_mode is fixed")
    for layer in ("roi", "segments", "lanes", "labels", "contours", "grasp"):
        cb = driver.find_element(By.ID, "layer-" + layer)
        if cb.is_selected():
            cb.click()
            time.sleep(0.3)
    wait.until(lambda d: daemon_value("debug.layers") == "edges")
    check(daemon_value("debug.layers") == "edges", "the layer toggles leave only edges")

    def edge_pixels(name):
        time.sleep(0.8)  # a few overlays with the new value
        img = overlay_png(name).astype(int)
        bgr = img[..., 0], img[..., 1], img[..., 2]
        return int(np.count_nonzero((bgr[0] > 170) & (bgr[2] > 170) & (bgr[1] < 110)))

    # Moving the Canny high slider: far right (few edges), then far left (many).
    slider = driver.find_element(By.ID, "p-lane-canny_high-slider")
    width = slider.size["width"]

    def drag_to(fraction):
        """Drags the slider's thumb to `fraction` of its track."""
        driver.execute_script("arguments[0].scrollIntoView({block: 'center'})", slider)
        lo, hi, v = (float(driver.execute_script("return arguments[0].%s" % a, slider))
                     for a in ("min", "max", "value"))
        at = (v - lo) / (hi - lo)
        thumb = 8  # px: the track is the width less the thumb
        x = lambda f: int((f - 0.5) * (width - 2 * thumb))  # noqa: E731
        ActionChains(driver).move_to_element_with_offset(slider, x(at), 0).click_and_hold() \
            .move_by_offset(x(fraction) - x(at), 0).release().perform()

    drag_to(0.9)
    check(outcome_has("applied (lane.canny_high)"), "the slider's value applied: %s"
          % driver.find_element(By.ID, "outcome").text)
    high = daemon_value("lane.canny_high")
    few = edge_pixels("edges_high")
    drag_to(0.1)
    outcome_has("applied (lane.canny_high)")
    low = daemon_value("lane.canny_high")
    many = edge_pixels("edges_low")
    check(high is not None and low is not None and high > 1200 and 50 <= low < 400,
          "moving the slider sets the daemon's lane.canny_high (%s, then %s)" % (high, low))
    check(many > 2 * few + 50, "the edges layer follows it (%d edge pixels at %s, %d at %s)"
          % (few, high, many, low))

    # Out of range: refused by the page's server with the reason.
    def type_into(element_id, text):
        box = driver.find_element(By.ID, element_id)
        box.click()  # focused, the page leaves its value alone
        box.send_keys(Keys.CONTROL, "a")
        box.send_keys(text, Keys.ENTER)

    type_into("p-lane-canny_high", "5000")
    check(outcome_has("5000 is out of range 0..2040"), "5000 refused with its reason: %s"
          % driver.find_element(By.ID, "outcome").text)
    driver.save_screenshot(os.path.join(tmp, "web_refused.png"))
    # Refused by the daemon: low above high (a check across keys).
    type_into("p-lane-canny_low", str(int(low) + 300))
    check(outcome_has("refused:") and "canny" in driver.find_element(By.ID, "outcome").text,
          "the daemon's refusal and reason shown: %s" % driver.find_element(By.ID, "outcome").text)
    check(daemon_value("lane.canny_high") == low, "the refused request changed nothing")

    # Save: written on the robot, accepted by --check-config, with the values set.
    driver.find_element(By.ID, "save").click()
    check(outcome_has("Saved"), "save answered: %s" % driver.find_element(By.ID, "outcome").text)
    check(driver.find_element(By.ID, "download").is_displayed(), "a download link is offered")
    driver.save_screenshot(os.path.join(tmp, "web_saved.png"))
    r = subprocess.run([RTEDGED, "--config", saved, "--check-config"], capture_output=True,
                       text=True)
    check(r.returncode == 0, "--check-config accepts the saved file: %s" % r.stderr.strip())
    check("canny_high = %d\n" % low in r.stdout and "canny_mode = fixed\n" in r.stdout and
          "layers = edges\n" in r.stdout, "the saved file holds the values set")
    with urllib.request.urlopen(URL + "api/config", timeout=5) as resp:
        check(resp.read().decode() == open(saved).read(), "/api/config is the file saved")

    # The controls need the token; the schema is checked before anything is sent.
    code, j = post("/api/params", {"values": {"lane.canny_high": 100}}, None)
    check(code == 403, "no token: %d %s" % (code, j.get("reason")))
    code, j = post("/api/params", {"values": {"source.path": "/etc/passwd"}}, TOKEN)
    check(code == 400 and "not a runtime key" in j["reason"], "a fixed key: %d %s"
          % (code, j.get("reason")))
    code, j = post("/api/params", {"values": {"lane.roi": "0,1;1,1\n[x]"}}, TOKEN)
    check(code == 400 and "printable" in j["reason"], "a newline in text: %d %s"
          % (code, j.get("reason")))
    code, j = post("/api/params", {"values": []}, TOKEN)
    check(code == 400, "values not an object: %d" % code)
finally:
    if driver:
        driver.quit()
    for p in (web, daemon):
        p.terminate()
        try:
            p.wait(timeout=5)
        except subprocess.TimeoutExpired:
            p.kill()

print("screenshots in %s" % tmp)
if FAILURES:
    print("%d failed" % len(FAILURES))
    sys.exit(1)
