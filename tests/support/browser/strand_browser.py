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


def console_errors(driver):
    """Console messages of level SEVERE (uncaught errors, failed loads the page did not expect)."""
    return [e["message"] for e in driver.get_log("browser") if e.get("level") == "SEVERE"]


def expect(condition, message):
    if not condition:
        fail(message)


def fail(message):
    sys.stderr.write("browser test: " + message.replace("\n", " ") + "\n")
    sys.exit(1)
