"""`sva-tools ground`: the ground view's picture from LCM traffic and its page.

The unit part feeds the view's state (sva_tools.ground.state) with messages, good and
bad. The end-to-end part runs inside a network namespace made for it (netns_run.sh):
a real sva_node, the ground server, and `sva-tools sim --via lcm --attach` flying
fixtures/scenarios/hand_loss.json (a UAV lost mid-visit); headless Chromium driven by
Selenium loads the page and the DOM must say what the traffic said. A screenshot goes
to $SVA_GROUND_ARTIFACTS (the build tree)."""
import json
import os
import re
import socket
import subprocess
import sys
import time
import urllib.request
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPO / "tools"))

from sva_tools.ground import state as gstate  # noqa: E402
from sva_tools.lcm import wire  # noqa: E402

SCENARIO = REPO / "fixtures" / "scenarios" / "hand_loss.json"
URL = "udpm://239.255.76.67:7667?ttl=0"
ARTIFACTS = Path(os.environ.get("SVA_GROUND_ARTIFACTS", "/tmp/sva_ground_artifacts"))
FRAME = {"lat": 43.6, "lon": 1.44, "alt_m": 150, "cell_m": 50, "tick_s": 2,
         "t0": "2026-05-01T10:00:00Z"}


def messages_of(doc):
    _, fleet, mission = wire.mission_messages(doc, 7, 7)
    return fleet, mission


# --- the picture, without network ---------------------------------------------------------

def test_bad_messages_are_counted_warnings_and_change_nothing_else():
    doc = json.loads(SCENARIO.read_text())["mission"]
    doc = {k: v for k, v in doc.items() if k != "change_penalty"}
    fleet, mission = messages_of(doc)
    g = gstate.Ground()
    g.on_message("SVA_FLEET", fleet.encode())
    g.on_message("SVA_MISSION", mission.encode())
    before = json.dumps({k: v for k, v in g.snapshot().items() if k not in ("version", "log")})
    assert g.warnings["count"] == 0 and len(g.uavs) == 3 and len(g.targets) == 4
    t = wire.types()
    bad_event = wire.event_message({"at": 1, "type": "clock"}, 1)
    bad_event.version = t.event_t.VERSION + 1
    bad_replan = t.replan_t()
    bad_replan.version = t.replan_t.VERSION + 1
    for channel, data in [("SVA_FLEET", b"\x00\x01garbage"),            # wrong fingerprint
                          ("SVA_MISSION", mission.encode()[:100]),       # truncated
                          ("SVA_PLAN", b""),                              # empty
                          ("SVA_EVENT", bad_event.encode()),              # wrong version
                          ("SVA_REPLAN", bad_replan.encode()),            # wrong version
                          ("SVA_STATUS", fleet.encode())]:                # another type
        g.on_message(channel, data)
    assert g.warnings["count"] == 6
    texts = [w["text"] for w in g.warnings["recent"]]
    assert (f"event_t.version is {t.event_t.VERSION + 1}, this view speaks version "
            f"{t.event_t.VERSION}") in texts
    assert (f"replan_t.version is {t.replan_t.VERSION + 1}, this tool speaks version "
            f"{t.replan_t.VERSION}") in texts
    assert any(x.startswith("100 bytes that are not a mission_t") for x in texts)
    after = json.dumps({k: v for k, v in g.snapshot().items()
                        if k not in ("version", "log", "warnings", "counts")})
    assert after == json.dumps({k: v for k, v in json.loads(before).items()
                                if k not in ("warnings", "counts")})
    g.on_message("OTHER_PLAN", b"junk")  # not the view's prefix: ignored
    assert g.warnings["count"] == 6


# FRAME as the view keeps it: at the frame's resolutions, t0 in UTC with milliseconds.
FRAME_KEPT = {"lat": 43.6, "lon": 1.44, "alt_m": 150.0, "cell_m": 50.0, "tick_s": 2.0,
              "t0": "2026-05-01T10:00:00.000Z"}


def test_frame_rules_name_the_field():
    """The view checks a frame by the frame's contract, in the words of `sva validate`."""
    assert gstate.check_frame(FRAME) == FRAME_KEPT
    assert gstate.check_frame({**FRAME, "lat": 43.60000005})["lat"] == 43.6000001
    for edit, message in [({"lat": 91}, "frame.lat: must be <= 85, got 91"),
                          ({"cell_m": 0}, "frame.cell_m: must be >= 0.1, got 0"),
                          ({"t0": 5}, "frame.t0: must be a string, got integer"),
                          ({"t0": "2026-02-30T00:00:00Z"},
                           'frame.t0: must be a date of the calendar, got "2026-02-30T00:00:00Z"'),
                          ({"x": 1}, 'frame: unknown key "x"'),
                          ({"lon": "1"}, "frame.lon: must be a number, got string")]:
        with pytest.raises(gstate.FrameError) as e:
            gstate.check_frame({**FRAME, **edit})
        assert str(e.value) == message
    with pytest.raises(gstate.FrameError) as e:
        gstate.check_frame({**FRAME, "tick_s": 0}, "f.json: mission: frame")
    assert str(e.value) == "f.json: mission: frame.tick_s: must be >= 0.001, got 0"


def test_the_missions_frame_on_the_link_wins_over_frame():
    """A mission_t carrying a frame (present 1) sets the view's frame; a --frame that
    differs is noted in the log; a mission without one falls back to --frame."""
    doc = json.loads(SCENARIO.read_text())["mission"]
    other = {**FRAME, "lat": 47.3655, "lon": 8.5461, "t0": "2026-06-01T10:00:00.0005+02:00"}

    g = gstate.Ground("SVA_")  # no --frame
    _, mission = messages_of({**doc, "frame": other})
    g.on_message("SVA_MISSION", mission.encode())
    assert g.snapshot()["frame"] == {"lat": 47.3655, "lon": 8.5461, "alt_m": 150.0,
                                     "cell_m": 50.0, "tick_s": 2.0,
                                     "t0": "2026-06-01T08:00:00.001Z"}

    g = gstate.Ground("SVA_", gstate.check_frame(FRAME))
    _, same = messages_of({**doc, "frame": FRAME})
    g.on_message("SVA_MISSION", same.encode())
    assert g.snapshot()["frame"] == FRAME_KEPT
    assert not [e for e in g.snapshot()["log"] if e["kind"] == "frame"]
    g.on_message("SVA_MISSION", mission.encode())
    assert g.snapshot()["frame"]["lat"] == 47.3655
    notes = [e for e in g.snapshot()["log"] if e["kind"] == "frame"]
    assert len(notes) == 1 and "differs from --frame" in notes[0]["text"]
    _, bare = messages_of({k: v for k, v in doc.items() if k != "frame"})
    g.on_message("SVA_MISSION", bare.encode())
    assert g.snapshot()["frame"] == FRAME_KEPT
    assert g.warnings["count"] == 0


def test_bad_command_lines(tmp_path):
    env = dict(os.environ, PYTHONPATH=str(REPO / "tools"))
    bad = tmp_path / "f.json"
    bad.write_text(json.dumps({"mission": {"frame": {**FRAME, "tick_s": -1}}}))
    for args, message in [(["--speed", "0"], "--speed: must be > 0, got 0.0"),
                          (["--frame", str(bad)], "frame.tick_s: must be >= 0.001, got -1"),
                          (["--flight-log", str(tmp_path / "none.json")], "No such file"),
                          (["--flight-log", str(bad)], "not a flight log"),
                          (["--lcm-log", str(tmp_path / "none.lcmlog")], "none.lcmlog"),
                          (["--url", "bogus://x"], "--url bogus://x: Couldn't create LCM")]:
        r = subprocess.run([sys.executable, "-m", "sva_tools", "ground", *args],
                           capture_output=True, text=True, env=env, timeout=60)
        assert r.returncode == 2 and message in r.stderr, (args, r.stderr)


# --- end to end: node, ground server, simulator, browser ------------------------------------

needs_netns = pytest.mark.skipif(not os.environ.get("SVA_LCM_NETNS"),
                                 reason="runs only inside a network namespace made for it "
                                        "(netns_run.sh)")


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def start_ground(*args):
    port = free_port()
    env = dict(os.environ, PYTHONPATH=str(REPO / "tools"))
    proc = subprocess.Popen([sys.executable, "-m", "sva_tools", "ground", "--port", str(port),
                             *args], env=env, stderr=subprocess.PIPE, text=True)
    end = time.monotonic() + 30
    while time.monotonic() < end:
        try:
            with urllib.request.urlopen(f"http://127.0.0.1:{port}/state.json", timeout=1) as r:
                json.load(r)
            return proc, port
        except OSError:
            if proc.poll() is not None:
                raise AssertionError(f"ground server exited: {proc.stderr.read()}")
            time.sleep(0.2)
    proc.kill()
    raise AssertionError("ground server did not answer within 30 s")


def stop(proc):
    proc.terminate()
    try:
        proc.communicate(timeout=10)
    except subprocess.TimeoutExpired:
        proc.kill()
        proc.communicate()


@pytest.fixture
def browser():
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    chromium = os.environ.get("SVA_CHROMIUM", "/usr/bin/chromium")
    driver_bin = os.environ.get("SVA_CHROMEDRIVER", "/usr/bin/chromedriver")
    if not (os.access(chromium, os.X_OK) and os.access(driver_bin, os.X_OK)):
        pytest.fail(f"{chromium} or {driver_bin} missing (scripts/deps/apt.txt: chromium, "
                    "chromium-driver)")
    opts = webdriver.ChromeOptions()
    opts.binary_location = chromium
    for a in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
              "--window-size=1400,1300", "--user-data-dir=" + str(ARTIFACTS / "chromium-profile")):
        opts.add_argument(a)
    d = webdriver.Chrome(service=Service(executable_path=driver_bin), options=opts)
    yield d
    d.quit()


READ_DOM = """
const t = id => document.getElementById(id).textContent;
const ids = ["replan-count", "node-state", "conn", "uav-count", "uav-lost-count", "plan-cost",
             "plan-covered", "plan-id", "node-plan-id", "warning-count", "refused-count", "now",
             "clock", "cursor"];
const out = {};
for (const i of ids) out[i] = t(i);
out.uavs = [...document.querySelectorAll("#map .uav")].map(
  u => [+u.getAttribute("data-id"), u.getAttribute("data-lost")]);
out.targets = [...document.querySelectorAll("#map circle.target")].map(
  c => [+c.getAttribute("data-id"), c.getAttribute("data-state")]);
out.replan_log = [...document.querySelectorAll("#event-log li.replan")].map(li => li.textContent);
out.warnings = [...document.querySelectorAll("#warnings li")].map(li => li.textContent);
out.replan_marks = document.querySelectorAll("#gantt .replan-mark").length;
const sc = document.getElementById("scale-text");
out.scale = sc ? sc.textContent : null;
return out;
"""


def dom(browser):
    """What the page shows, read in one go (the page redraws as updates come)."""
    return browser.execute_script(READ_DOM)


def wait_for(cond, timeout=20.0, what="condition"):
    end = time.monotonic() + timeout
    last = None
    while time.monotonic() < end:
        try:
            last = cond()
            if last:
                return last
        except Exception as e:  # the page is still drawing
            last = e
        time.sleep(0.1)
    raise AssertionError(f"timed out waiting for {what} (last: {last!r})")


@needs_netns
def test_the_page_shows_what_the_traffic_says(browser, tmp_path):
    import lcm
    from selenium.webdriver.common.by import By

    ARTIFACTS.mkdir(parents=True, exist_ok=True)
    scenario = json.loads(SCENARIO.read_text())
    lost_uav = next(e["uav"] for e in scenario["events"] if e["type"] == "uav_lost")
    record = tmp_path / "traffic.lcmlog"
    env = dict(os.environ, PYTHONPATH=str(REPO / "tools"))
    recorder = subprocess.Popen([sys.executable, "-m", "sva_tools", "lcm", "record", "-o",
                                 str(record), "--url", URL], env=env)
    time.sleep(1.0)  # lcm-logger subscribed before the first message
    node = subprocess.Popen([os.environ["SVA_NODE"], "--url", URL, "--algorithm", "sva",
                             "--change-penalty", str(scenario["change_penalty"]),
                             "--status-ms", "200"], stdout=subprocess.DEVNULL,
                            stderr=subprocess.PIPE, text=True)
    ground, port = start_ground("--url", URL)
    t = wire.types()
    seen = {"fleet": [], "replan": [], "plan": []}
    lc = lcm.LCM(URL)
    lc.subscribe("SVA_FLEET", lambda c, d: seen["fleet"].append(t.fleet_state_t.decode(d)))
    lc.subscribe("SVA_PLAN", lambda c, d: seen["plan"].append(t.plan_t.decode(d)))
    lc.subscribe("SVA_REPLAN", lambda c, d: seen["replan"].append(t.replan_t.decode(d)))
    try:
        out = tmp_path / "flight.json"
        r = subprocess.run([sys.executable, "-m", "sva_tools", "sim", str(SCENARIO), "--via",
                            "lcm", "--attach", "--out", str(out)], capture_output=True,
                           text=True, env=env, timeout=120)
        assert r.returncode == 0, r.stderr
        while lc.handle_timeout(300) > 0:
            pass  # every message of the flight, until the channels are quiet
        flight = json.loads(out.read_text())
        replans = seen["replan"]
        assert len(replans) == len(scenario["events"]) + 1  # a clock at tick 0, each event
        last = replans[-1].plan

        browser.get(f"http://127.0.0.1:{port}/")
        d = wait_for(lambda: (lambda d: d["replan-count"] == str(len(replans))
                              and d["node-state"] == "ready" and d)(dom(browser)),
                     what="every replan and a node status on the page")
        assert d["conn"] == "up"
        assert int(d["uav-count"]) == seen["fleet"][-1].uav_count == 3
        assert len(d["uavs"]) == 3
        assert {u for u, lost in d["uavs"] if lost == "true"} == {lost_uav}
        assert d["uav-lost-count"] == "1"
        assert d["plan-cost"] == str(last.cost) and d["plan-covered"] == str(last.covered)
        assert d["plan-id"] == str(last.plan_id)
        assert d["node-plan-id"] == str(last.plan_id)
        assert len(d["replan_log"]) == len(replans)
        assert any("replan of event" in x and "(uav_lost)" in x for x in d["replan_log"])
        # Targets by state: the lost one (under way with the lost UAV), the cancelled one.
        states = dict(d["targets"])
        outcome = {x["id"]: x["outcome"] for x in flight["targets"]}
        assert states[2] == "cancelled" == outcome[2]
        assert states[1] == "lost" == outcome[1]
        assert d["replan_marks"] == len(replans)
        assert d["scale"].endswith("cells")
        assert d["warning-count"] == "0"

        # Bad traffic: a malformed plan and an event_t of version 2, each one warning.
        lc.publish("SVA_PLAN", b"\x01\x02\x03 not a plan")
        wait_for(lambda: dom(browser)["warning-count"] == "1", what="the first warning")
        bad = wire.event_message({"at": 500, "type": "clock"}, 10**15)
        bad.version = 2
        lc.publish("SVA_EVENT", bad.encode())
        wait_for(lambda: dom(browser)["warning-count"] == "2", what="the second warning")
        # the node refused the version-2 event, and the page still works
        d = wait_for(lambda: (lambda d: d["refused-count"] == "1" and d)(dom(browser)),
                     what="the node's refusal")
        assert any("event_t.version is 2" in w for w in d["warnings"])
        assert any(w.startswith("SVA_PLAN: 14 bytes that are not a plan_t") for w in d["warnings"])
        assert d["plan-cost"] == str(last.cost) and d["warning-count"] == "2"
        browser.save_screenshot(str(ARTIFACTS / "ground_live.png"))
        assert (ARTIFACTS / "ground_live.png").stat().st_size > 10000
        live = json.loads(urllib.request.urlopen(f"http://127.0.0.1:{port}/state.json",
                                                 timeout=5).read())
    finally:
        recorder.send_signal(2)  # SIGINT: lcm-logger closes the log
        recorder.wait(timeout=10)
        stop(ground)
        stop(node)

    # The same traffic played back from the lcm-logger file, 20 times faster: the same
    # picture (the warnings included), without any network.
    player, port = start_ground("--lcm-log", str(record), "--speed", "20")
    try:
        def played():
            s = json.loads(urllib.request.urlopen(f"http://127.0.0.1:{port}/state.json",
                                                  timeout=5).read())
            return s["log"] and s["log"][-1]["kind"] == "end" and s
        s = wait_for(played, timeout=60, what="the end of the LCM log")
    finally:
        stop(player)
    assert s["replan_count"] == live["replan_count"] == len(replans) + 1  # the refused one too
    assert s["plan"]["cost"] == last.cost and s["plan"]["covered"] == last.covered
    assert s["warnings"]["count"] == 2
    assert [u["lost"] for u in s["uavs"]] == [u["lost"] for u in live["uavs"]]
    assert [t["state"] for t in s["targets"]] == [t["state"] for t in live["targets"]]


@needs_netns
def test_a_flight_log_with_a_frame_plays_in_metres_and_degrees(browser, tmp_path):
    from selenium.webdriver.common.action_chains import ActionChains
    from selenium.webdriver.common.by import By

    ARTIFACTS.mkdir(parents=True, exist_ok=True)
    env = dict(os.environ, PYTHONPATH=str(REPO / "tools"))
    out = tmp_path / "flight.json"
    r = subprocess.run([sys.executable, "-m", "sva_tools", "sim", str(SCENARIO), "--out",
                        str(out)], capture_output=True, text=True, env=env, timeout=120)
    assert r.returncode == 0, r.stderr
    flight = json.loads(out.read_text())
    frame = tmp_path / "frame.json"
    frame.write_text(json.dumps(FRAME))
    ground, port = start_ground("--flight-log", str(out), "--frame", str(frame), "--speed", "200")
    try:
        browser.get(f"http://127.0.0.1:{port}/")
        end = flight["end_tick"]
        d = wait_for(lambda: (lambda d: d["now"] == str(end) and d)(dom(browser)), timeout=30,
                     what="the end of the flight")
        time.sleep(0.5)  # the last tick drawn: the page no longer changes
        d = dom(browser)
        # tick_s 2: the clock of the last tick is t0 + 2 s per tick
        assert d["clock"] == time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime(1777629600 + 2 * end))
        assert d["scale"].endswith(" m") or d["scale"].endswith(" km")
        states = dict(d["targets"])
        want = {x["id"]: x["outcome"] for x in flight["targets"]}
        assert states == {k: ("expired" if v == "uncovered" else v) for k, v in want.items()}
        assert d["replan-count"] == str(len(flight["replans"]))
        assert {u for u, lost in d["uavs"] if lost == "true"} == {1}
        # the cursor over the depot (cell 0, 0) reads the frame's origin
        depot = browser.find_element(By.CSS_SELECTOR, "#map rect.depot")
        ActionChains(browser).move_to_element(depot).perform()
        cursor = wait_for(lambda: (lambda c: "°" in c and c)(dom(browser)["cursor"]), what="the cursor")
        m = re.match(r"cell \(0, 0\)  (-?[\d.]+)°, (-?[\d.]+)°  (-?\d+) m E, (-?\d+) m N$", cursor)
        assert m, cursor
        lat, lon, east, north = float(m[1]), float(m[2]), int(m[3]), int(m[4])
        # within half a cell (25 m) of the frame's origin: 25 m is 0.000225° of latitude
        # and 0.000311° of longitude at 43.6° N
        assert abs(east) <= 25 and abs(north) <= 25
        assert abs(lat - 43.6) <= 0.000225 and abs(lon - 1.44) <= 0.000311
        assert abs(lat - 43.6 - north / 6371008.8 * 57.29578) < 1e-6
        browser.save_screenshot(str(ARTIFACTS / "ground_flight_frame.png"))
    finally:
        stop(ground)
