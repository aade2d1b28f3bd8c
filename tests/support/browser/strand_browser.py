"""Headless Chromium through Debian's python3-selenium and chromium-driver, for the
workbench's interactive browser tests (typing, clicking, drawing on a canvas).

A test script imports this module, calls `open_browser(profile_dir)`, drives the page and
exits 0 when every expectation held; a failed one prints one line on stderr and exits 1.
The GoogleTest side runs the script with run_browser_script (tests/support/chromium.h).
"""
import os
import sys
import time

from selenium import webdriver
from selenium.webdriver.chrome.options import Options
from selenium.webdriver.chrome.service import Service


def open_browser(profile_dir, width=1200, height=900):
    options = Options()
    options.binary_location = "/usr/bin/chromium"
    for arg in ("--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
                "--disable-background-networking", "--disable-component-update", "--disable-sync",
                "--disable-dev-shm-usage", "--user-data-dir=" + profile_dir,
                "--window-size=%d,%d" % (width, height)):
        options.add_argument(arg)
    options.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    service = Service(executable_path="/usr/bin/chromedriver", log_path=os.devnull)
    driver = webdriver.Chrome(service=service, options=options)
    driver.set_page_load_timeout(60)
    driver.set_script_timeout(60)
    return driver


def wait_for(predicate, what, timeout_s=30.0, every_s=0.1):
    """Polls `predicate()` until it returns a true value (returned) or fails with `what`."""
    end = time.monotonic() + timeout_s
    last_error = None
    while time.monotonic() < end:
        try:
            value = predicate()
            if value:
                return value
        except Exception as e:  # the element may not exist yet
            last_error = e
        time.sleep(every_s)
    fail("timed out after %.0f s waiting for %s%s" % (timeout_s, what, " (%s)" % last_error if last_error else ""))


def wait_for_previews(driver, what, timeout_s=30.0):
    """Waits for a result's PNG thumbnail (#thumb) to load and its HTML preview (the #preview
    frame) to paint its canvas with more than one colour; `what` names what it draws."""
    wait_for(lambda: driver.execute_script(
        "const i = document.getElementById('thumb'); return i.complete && i.naturalWidth > 0"), "the PNG preview")
    driver.switch_to.frame(driver.find_element("id", "preview"))
    painted = "const c = document.getElementById('view'); if (!c || !c.width) return false;" \
              "const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;" \
              "const seen = new Set(); for (let i = 0; i < d.length; i += 4 * 97) seen.add(d[i] + ',' + d[i + 1] + ',' + d[i + 2]);" \
              "return seen.size > 1"
    wait_for(lambda: driver.execute_script(painted), "the HTML preview to draw " + what, timeout_s=timeout_s)
    driver.switch_to.default_content()


def console_errors(driver):
    """Console messages of level SEVERE (uncaught errors, failed loads the page did not expect)."""
    return [e["message"] for e in driver.get_log("browser") if e.get("level") == "SEVERE"]


def expect(condition, message):
    if not condition:
        fail(message)


def fail(message):
    sys.stderr.write("browser test: " + message.replace("\n", " ") + "\n")
    sys.exit(1)
