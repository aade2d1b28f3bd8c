"""The sweep page: a saved two-layer scaffold (job JOB) chosen as the base, its gap varied over
three values in the form, the sweep run and followed to 100 %, then the contact sheet shown and
the scatter of two manifest columns drawn (one dot per point that ran), redrawn when y changes.
Writes DIR/workbench-sweep.png, a screenshot.
Usage: sweep.py URL-of-/sweep?job=JOB DIR
"""
import sys

from selenium.webdriver.common.by import By
from selenium.webdriver.support.ui import Select

from strand_browser import console_errors, expect, open_browser, wait_for

url, out_dir = sys.argv[1], sys.argv[2]
driver = open_browser(out_dir + "/profile", width=1366, height=900)
try:
    driver.get(url)
    body = lambda key: driver.execute_script("return document.body.dataset." + key)
    wait_for(lambda: body("ready") == "1", "the sweep page to list the saved jobs")
    job = url.split("job=")[1]
    value = lambda i: driver.find_element(By.ID, i).get_attribute("value")
    expect(value("base") == job, "the base job is %s, not the one in the address (%s)" % (value("base"), job))
    expect("scaffold on deltawasp-2040-clay" in driver.find_element(By.ID, "base-params").text,
           "the base job's parameters are not shown: " + driver.find_element(By.ID, "base-params").text)
    Select(driver.find_element(By.ID, "key-1")).select_by_value("gap")
    driver.find_element(By.ID, "values-1").clear()
    driver.find_element(By.ID, "values-1").send_keys("1.2..2 step 0.4")
    Select(driver.find_element(By.ID, "key-2")).select_by_value("")
    driver.find_element(By.ID, "where").clear()
    seen = set()

    def finished():
        seen.add(driver.execute_script("return [document.getElementById('progress').value, document.getElementById('progress').max].join('/')"))
        return body("state") in ("ok", "failed")

    driver.find_element(By.ID, "run").click()
    wait_for(lambda: driver.find_element(By.ID, "general").text or finished(), "the sweep to finish", timeout_s=120)
    expect(not driver.find_element(By.ID, "general").text, "refused: " + driver.find_element(By.ID, "general").text)
    expect(body("state") == "ok", "the sweep failed: " + driver.find_element(By.ID, "report").text)
    expect(driver.execute_script("const p = document.getElementById('progress'); return p.value === p.max && p.max === 3"),
           "the progress bar does not end at 3 of 3: seen " + str(sorted(seen)))
    status = driver.find_element(By.ID, "report").text
    expect("3 point(s): 3 ran, 0 failed" in status, "the summary: " + status)
    wait_for(lambda: driver.execute_script("return document.getElementById('scatter').dataset.points") == "3",
             "the scatter to show the three points")
    xs = [o.get_attribute("value") for o in Select(driver.find_element(By.ID, "x")).options]
    expect(value("x") == "gap" and value("y") == "porosity", "the scatter plots %s against %s" % (value("y"), value("x")))
    expect("time_s" in xs and "ink_volume_ml" in xs and "name" not in xs, "the columns offered: %s" % xs)
    cx = driver.execute_script("return Array.from(document.querySelectorAll('#scatter circle')).map((c) => +c.getAttribute('cx'))")
    cy = driver.execute_script("return Array.from(document.querySelectorAll('#scatter circle')).map((c) => +c.getAttribute('cy'))")
    expect(cx == sorted(cx) and len(set(cx)) == 3, "the gaps are not left to right: %s" % cx)
    expect(cy == sorted(cy, reverse=True) and len(set(cy)) == 3, "porosity does not rise with the gap on the plot (y down in SVG): %s" % cy)
    Select(driver.find_element(By.ID, "y")).select_by_value("time_s")
    cy2 = driver.execute_script("return Array.from(document.querySelectorAll('#scatter circle')).map((c) => +c.getAttribute('cy'))")
    expect(cy2 != cy, "the scatter is not redrawn for y = time_s")
    sheet = driver.find_element(By.ID, "sheet")
    expect(sheet.is_displayed() and "/files/index.html" in sheet.get_attribute("src"), "the contact sheet is not shown")
    driver.switch_to.frame(sheet)
    wait_for(lambda: len(driver.find_elements(By.TAG_NAME, "img")) == 3, "the contact sheet's three thumbnails")
    driver.switch_to.default_content()
    expect(driver.execute_script("return document.documentElement.scrollWidth <= document.documentElement.clientWidth"),
           "the page is wider than the window")
    driver.save_screenshot(out_dir + "/workbench-sweep.png")
    errors = console_errors(driver)
    expect(not errors, "console errors: %s" % errors)
finally:
    driver.quit()
