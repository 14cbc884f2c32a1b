"""The live view in a real browser: Debian's headless Chromium on `egosim run`'s page,
with a real rospy node on the ROS side."""

from __future__ import annotations

import math
import socket
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import pytest

from tests.browser import ARTIFACTS, open_browser, wait_for
from tests.conftest import free_port
from tests.e2e.conftest import Simulator

pytestmark = pytest.mark.ros

EGO = ("/Ego_topic", "morai_msgs/EgoVehicleStatus")
SET_LIGHT = ("/SetTrafficLight", "morai_msgs/SetTrafficLight")
EVENT = ("/Service_MoraiEventCmd", "morai_msgs/MoraiEventCmdSrv")
RED = 1
OPTION_CTRL_MODE, AUTO = 1, 4
EGO_COLOUR = (0x3A, 0xA0, 0xFF)
RED_COLOUR = "#ff3b30"
SPEED_PLOT_COLOUR = (0x4A, 0xA8, 0xFF)
DRIVEN_S = 5.0
# Test-side network delay: the page's socket holds every message it receives until the
# test calls egosimTestRelease() (installed before the page's own scripts run).
HOLD_SOCKET_MESSAGES = """
window.egosimTestHeld = [];
class HeldSocket extends WebSocket {
  set onmessage(handler) {
    super.onmessage = (event) => {
      if (window.egosimTestHeld) window.egosimTestHeld.push(() => handler(event));
      else handler(event);
    };
  }
}
window.WebSocket = HeldSocket;
window.egosimTestRelease = () => {
  const held = window.egosimTestHeld;
  window.egosimTestHeld = null;
  held.forEach((deliver) => deliver());
};
"""


@pytest.fixture
def browser(tmp_path: Path) -> Iterator[Any]:
    driver = open_browser(tmp_path / "chromium-profile")
    try:
        yield driver
    finally:
        driver.quit()


@pytest.fixture
def viewed(egosim: Callable[..., Simulator], browser: Any) -> Callable[..., tuple[Simulator, Any]]:
    """`viewed(*args)`: egosim run with its view on a free port, open in the browser."""

    def start(*args: str) -> tuple[Simulator, Any]:
        port = free_port()
        simulator = egosim("--view-port", str(port), *args)
        browser.get(f"http://127.0.0.1:{port}/")
        wait_for(lambda: page(browser, "s.map && s.frame && s.connected"), "map and a frame")
        return simulator, browser

    return start


def page(browser: Any, expression: str) -> Any:
    """Evaluate a JS expression on the page; `s` is the view's page state."""
    return browser.execute_script(f"const s = window.egosimView; return ({expression});")


def sim_time(browser: Any) -> float:
    return page(browser, "s.frame.sim_time")


def pixel_at(browser: Any, x: float, y: float) -> tuple[int, int, int]:
    """Colour of the map canvas where world point (x, y) m is drawn."""
    return tuple(
        page(
            browser,
            f"""(() => {{
              const [px, py] = s.worldToScreen({x}, {y});
              const c = document.getElementById('world'), r = window.devicePixelRatio || 1;
              const g = c.getContext('2d');
              const d = g.getImageData(Math.round(px * r), Math.round(py * r), 1, 1).data;
              return [d[0], d[1], d[2]];
            }})()""",
        )
    )


def severe_console_entries(browser: Any) -> list[dict[str, Any]]:
    return [e for e in browser.get_log("browser") if e["level"] == "SEVERE"]


def look_at(browser: Any, x: float, y: float, scale: float) -> None:
    """Stop following and centre the view on (x, y) m at `scale` px/m."""
    page(browser, f"(s.follow = false, s.view.cx = {x}, s.view.cy = {y}, s.view.scale = {scale})")
    frames = page(browser, "s.framesReceived")
    wait_for(lambda: page(browser, "s.framesReceived") > frames + 1, "a redraw")


def test_page_loads_without_console_errors_and_shows_the_town(viewed) -> None:
    simulator, browser = viewed("--log-level", "DEBUG")
    assert page(browser, "s.map.name") == "town"
    assert page(browser, "s.map.lanes.length") > 100
    assert page(browser, "s.frame.objects.id.length") > 0
    nodes = browser.find_element("id", "nodes")
    wait_for(lambda: "/egosim" in nodes.text, "the ROS graph to list /egosim")
    browser.find_element("id", "fit").click()
    frames = page(browser, "s.framesReceived")
    wait_for(lambda: page(browser, "s.framesReceived") > frames + 1, "a redraw")
    assert not page(browser, "s.follow")
    ARTIFACTS.mkdir(parents=True, exist_ok=True)
    browser.save_screenshot(str(ARTIFACTS / "view_town.png"))
    ego = page(browser, "s.frame.egos[0]")
    look_at(browser, ego["x"] + 25, ego["y"] + 10, 9)
    browser.save_screenshot(str(ARTIFACTS / "view_ego.png"))
    assert severe_console_entries(browser) == []
    assert page(browser, "s.errors") == []
    # Leaving the page, as closing its tab does, is routine: a DEBUG line, nothing above.
    browser.get("about:blank")
    wait_for(lambda: "view: a browser left" in simulator.process.stderr_text(), "the departure")
    logged = simulator.process.stderr_text().splitlines()
    assert [line for line in logged if "browser" in line and " DEBUG " not in line] == []


def test_the_ego_is_drawn_where_ego_topic_says(viewed, rospy_client) -> None:
    simulator, browser = viewed()
    client = rospy_client(simulator)
    client.subscribe(*EGO)
    status = client.next_message(EGO[0])
    x, y = status["position"]["x"], status["position"]["y"]
    drawn = page(browser, "s.frame.egos[0]")
    assert math.hypot(drawn["x"] - x, drawn["y"] - y) < 0.05
    assert math.isclose(math.degrees(drawn["yaw"]), status["heading"], abs_tol=0.1)
    look_at(browser, x, y, 20)
    # Half a metre ahead of the reference point lies inside the ego's body.
    colour = pixel_at(browser, x + 0.5 * math.cos(drawn["yaw"]), y + 0.5 * math.sin(drawn["yaw"]))
    assert colour == EGO_COLOUR


def test_pause_stops_sim_time_and_resume_restarts_it(viewed) -> None:
    _, browser = viewed()
    pause = browser.find_element("id", "pause")
    pause.click()
    wait_for(lambda: page(browser, "s.frame.paused"), "the world to pause")
    held = sim_time(browser)
    frames = page(browser, "s.framesReceived")
    wait_for(lambda: page(browser, "s.framesReceived") > frames + 10, "frames while paused")
    assert sim_time(browser) == held
    assert pause.text == "Resume"
    step = browser.find_element("id", "step")
    step.click()
    wait_for(lambda: sim_time(browser) > held, "a single step")
    stepped = sim_time(browser)
    assert page(browser, "s.frame.paused")
    pause.click()
    wait_for(lambda: sim_time(browser) > stepped + 0.5, "sim time to run again")
    assert stepped - held < 0.05  # one physics step, not a run


def test_keyboard_driving_moves_the_ego_forward(viewed) -> None:
    from selenium.webdriver.common.action_chains import ActionChains  # noqa: PLC0415
    from selenium.webdriver.common.keys import Keys  # noqa: PLC0415
    from selenium.webdriver.support.ui import Select  # noqa: PLC0415

    _, browser = viewed()
    Select(browser.find_element("id", "ctrl-mode")).select_by_value("1")
    wait_for(lambda: page(browser, "s.frame.egos[0].ctrl_mode") == 1, "keyboard mode")
    start = page(browser, "s.frame.egos[0]")
    browser.find_element("id", "world").click()
    ActionChains(browser).key_down(Keys.ARROW_UP).perform()
    try:
        wait_for(lambda: page(browser, "s.frame.egos[0].speed") > 3.0, "the ego to speed up")
        end = page(browser, "s.frame.egos[0]")
    finally:
        ActionChains(browser).key_up(Keys.ARROW_UP).perform()
    ahead = (end["x"] - start["x"]) * math.cos(start["yaw"]) + (end["y"] - start["y"]) * math.sin(
        start["yaw"]
    )
    assert ahead > 1.0
    assert end["gear"] == "drive"
    assert end["accel_pedal"] > 0


def test_a_light_set_red_by_ros_is_drawn_red(viewed, rospy_client) -> None:
    simulator, browser = viewed()
    ids = page(browser, "s.map.lights.map((light) => light.id)")
    aspects = page(browser, "s.frame.light_aspects")
    not_red = [
        light_id
        for light_id, aspect in zip(ids, aspects, strict=True)
        if aspect > 0 and not aspect & RED
    ]
    assert not_red, "some light shows something other than red"
    light_id = not_red[0]
    client = rospy_client(simulator)
    client.publish(*SET_LIGHT, {"trafficLightIndex": light_id, "trafficLightStatus": RED})
    wait_for(lambda: page(browser, f"s.lightColour({light_id!r})") == RED_COLOUR, "a red light")
    x, y = page(browser, f"s.map.lights.find((l) => l.id === {light_id!r}).position")
    page(browser, "document.getElementById('layers').hidden = true")
    look_at(browser, x, y, 10)
    assert pixel_at(browser, x, y) == (0xFF, 0x3B, 0x30)


def test_a_read_only_view_shows_the_controls_disabled(viewed) -> None:
    _, browser = viewed("--view-readonly")
    assert page(browser, "s.hello.readonly")
    for control in ("pause", "reload", "load", "ctrl-mode"):
        assert not browser.find_element("id", control).is_enabled(), control
    browser.execute_script("send({op: 'pause'})")  # as a page with the buttons forced on would
    wait_for(lambda: "read-only" in browser.find_element("id", "message").text, "the refusal")
    assert not page(browser, "s.frame.paused")


def test_a_taken_view_port_leaves_the_simulator_running(egosim) -> None:
    with socket.socket() as taken:
        taken.bind(("127.0.0.1", 0))
        taken.listen()
        port = taken.getsockname()[1]
        simulator = egosim("--view-port", str(port))
    assert any(line.startswith("egosim: no view") for line in simulator.process.output)
    assert simulator.process.popen.poll() is None


def loading_items(browser: Any) -> dict[str, tuple[str, str]]:
    """The loading overlay's steps: id -> (state, text)."""
    items = browser.find_elements("css selector", "#loading li")
    return {item.get_attribute("id"): (item.get_attribute("class"), item.text) for item in items}


def test_the_page_shows_what_it_waits_for_until_the_first_frame(egosim, browser) -> None:
    port = free_port()
    egosim("--view-port", str(port))
    browser.execute_cdp_cmd("Network.enable", {})
    browser.execute_cdp_cmd("Network.setBlockedURLs", {"urls": ["*/map.json"]})
    browser.execute_cdp_cmd(
        "Page.addScriptToEvaluateOnNewDocument", {"source": HOLD_SOCKET_MESSAGES}
    )
    browser.get(f"http://127.0.0.1:{port}/")
    overlay = browser.find_element("id", "loading")
    # Connected, the map refused: the overlay says so and that it retries.
    wait_for(lambda: page(browser, "s.connected && s.mapError !== null"), "a failed map fetch")
    assert overlay.is_displayed()
    steps = loading_items(browser)
    assert steps["loading-connection"] == ("done", "connected to the simulator")
    assert steps["loading-map"][0] == "failed" and "retrying" in steps["loading-map"][1]
    assert steps["loading-frame"] == ("waiting", "waiting for the first frame…")
    ARTIFACTS.mkdir(parents=True, exist_ok=True)
    browser.save_screenshot(str(ARTIFACTS / "view_loading_map_refused.png"))
    # The map comes on the next try; no frame has been handed to the page yet.
    browser.execute_cdp_cmd("Network.setBlockedURLs", {"urls": []})
    wait_for(lambda: page(browser, "s.map !== null"), "the map on a retry")
    assert page(browser, "s.frame === null && s.loading") == "waiting for the first frame…"
    assert overlay.is_displayed()
    assert loading_items(browser)["loading-map"] == ("done", "map loaded")
    plot_text = page(browser, "document.getElementById('plot-speed').toDataURL()")
    browser.save_screenshot(str(ARTIFACTS / "view_waiting_for_the_first_frame.png"))
    # The first frame ends the loading state.
    page(browser, "window.egosimTestRelease()")
    wait_for(lambda: page(browser, "s.frame !== null"), "the first frame")
    wait_for(lambda: not overlay.is_displayed(), "the overlay to go")
    assert page(browser, "s.loading") is None
    wait_for(
        lambda: page(browser, "document.getElementById('plot-speed').toDataURL()") != plot_text,
        "the speed plot to draw its data",
    )
    assert severe_console_entries(browser) == []
    assert page(browser, "s.errors") == []


def columns_drawn_in(browser: Any, canvas_id: str, colour: tuple[int, int, int]) -> list[int]:
    """[canvas width, first column, last column] holding `colour` (device pixels)."""
    r, g, b = colour
    return page(
        browser,
        f"""(() => {{
          const c = document.getElementById('{canvas_id}');
          const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
          const near = (k) => Math.abs(d[k] - {r}) < 24 && Math.abs(d[k + 1] - {g}) < 24
            && Math.abs(d[k + 2] - {b}) < 24;
          let lo = Infinity, hi = -Infinity;
          for (let x = 0; x < c.width; x++) {{
            for (let y = 0; y < c.height; y++) {{
              if (near(4 * (y * c.width + x))) {{ lo = Math.min(lo, x); hi = Math.max(hi, x); }}
            }}
          }}
          return [c.width, lo, hi];
        }})()""",
    )


def drive_on_autopilot(client: Any, seconds: float) -> None:
    """Put the main ego on autopilot and wait until it has driven `seconds` of sim time."""
    client.subscribe(*EGO)
    request = {"request": {"option": OPTION_CTRL_MODE, "ctrl_mode": AUTO, "gear": -1}}
    client.call(*EVENT, request)
    start = client.next_message(EGO[0])["header"]["stamp"]

    def driven() -> bool:
        status = client.next_message(EGO[0])
        return status["header"]["stamp"] - start >= seconds and status["velocity"]["x"] > 1.0

    wait_for(driven, f"{seconds} s of driving", timeout=60.0)


def test_a_page_opened_after_driving_shows_the_minute_before_it(
    egosim, browser, rospy_client
) -> None:
    port = free_port()
    simulator = egosim("--view-port", str(port))
    drive_on_autopilot(rospy_client(simulator), DRIVEN_S)
    browser.get(f"http://127.0.0.1:{port}/")
    wait_for(lambda: page(browser, "s.map && s.frame"), "map and a frame")
    opened = page(browser, "s.firstFrameTime")
    ego_id = page(browser, "s.frame.egos[0].id")
    samples = page(browser, f"s.samples.get({ego_id})")
    before = [k for k, t in enumerate(samples["t"]) if t < opened]
    # Samples every 0.1 s from before the page existed, the drive among them.
    assert samples["t"][0] <= opened - DRIVEN_S
    assert len(before) >= DRIVEN_S / 0.1 - 1
    assert max(samples["speed"][k] for k in before) > 1.0
    assert len(samples["x"]) == len(samples["t"])  # the trail too
    # The speed plot draws them: its line reaches back at least 5 s of its 60 s.
    width, drawn_from, drawn_to = columns_drawn_in(browser, "plot-speed", SPEED_PLOT_COLOUR)
    ratio = page(browser, "window.devicePixelRatio || 1")
    five_seconds_px = DRIVEN_S / 60.0 * (width - 38 * ratio)
    assert drawn_to - drawn_from >= five_seconds_px, (width, drawn_from, drawn_to)
    ARTIFACTS.mkdir(parents=True, exist_ok=True)
    browser.save_screenshot(str(ARTIFACTS / "view_opened_after_driving.png"))


def test_the_tooltip_follows_the_frames_under_a_still_mouse(egosim, browser, rospy_client) -> None:
    from selenium.webdriver.common.action_chains import ActionChains  # noqa: PLC0415

    port = free_port()
    simulator = egosim("--view-port", str(port))
    browser.get(f"http://127.0.0.1:{port}/")
    wait_for(lambda: page(browser, "s.map && s.frame && s.connected"), "map and a frame")
    page(browser, "s.view.scale = 12")
    moves = "window.egosimTestMoves"
    page(
        browser,
        f"({moves} = 0, document.getElementById('world').addEventListener("
        f"'mousemove', () => {{ {moves} += 1; }}))",
    )
    # The pointer onto the ego (followed: the view keeps it centred), then left alone.
    canvas = browser.find_element("id", "world")
    ego = page(browser, "s.frame.egos[0]")
    centre = page(
        browser,
        "s.worldToScreen(s.frame.egos[0].x + Math.cos(s.frame.egos[0].yaw) * "
        "s.frame.egos[0].centre_offset, s.frame.egos[0].y + Math.sin(s.frame.egos[0].yaw) * "
        "s.frame.egos[0].centre_offset)",
    )
    size = canvas.size
    ActionChains(browser).move_to_element_with_offset(
        canvas, round(centre[0] - size["width"] / 2), round(centre[1] - size["height"] / 2)
    ).perform()
    tooltip = browser.find_element("id", "tooltip")
    first = wait_for(lambda: page(browser, "s.tooltip"), "a tooltip on the ego")
    assert first.startswith(f"ego {ego['id']} · 0.0 km/h")
    moved = page(browser, moves)
    drive_on_autopilot(rospy_client(simulator), 1.0)
    # Its speed changes in the tooltip with the frames, the mouse still.
    wait_for(
        lambda: (
            (text := page(browser, "s.tooltip"))
            and text.startswith(f"ego {ego['id']}")
            and text != first
            and tooltip.text == text
        ),
        "the tooltip to show the ego's new speed",
    )
    browser.save_screenshot(str(ARTIFACTS / "view_tooltip_on_a_moving_ego.png"))
    # No longer followed, the ego drives out from under the pointer: the tooltip goes.
    page(browser, "s.follow = false")
    wait_for(lambda: page(browser, "s.tooltip") is None, "the tooltip to go with the ego")
    assert not tooltip.is_displayed()
    assert page(browser, moves) == moved  # all of it without a mouse move
