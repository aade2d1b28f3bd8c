"""The draw page: a line dragged with the mouse on the canvas (line tool), plotted for the
default plotter. Expects one shape, a summary whose drawn length is the line's (300 x 150
canvas px at 4 px per mm: 83.9 mm), a G-code that puts the pen down and draws, the PNG
preview loaded and the HTML preview's canvas painted; then saved, listed in the gallery, and
reopened from its "open to edit" link with the drawing loaded, plotting the same length again.
Writes the G-code to DIR/drawn.gcode.
Usage: draw.py URL-of-/draw DIR
"""
import re
import sys
import urllib.request

from selenium.webdriver.common.action_chains import ActionChains
from selenium.webdriver.common.by import By

from strand_browser import console_errors, expect, open_browser, wait_for, wait_for_previews

url, out_dir = sys.argv[1], sys.argv[2]
driver = open_browser(out_dir + "/profile")
try:
    driver.get(url)
    state = lambda: driver.execute_script("return document.body.dataset.state")
    wait_for(lambda: state() == "ready", "the draw page to list its plotters")
    expect(driver.find_element(By.ID, "machine").get_attribute("value") == "xy-plotter-servo",
           "the default plotter is not selected")
    driver.find_element(By.CSS_SELECTOR, "button[data-tool=line]").click()
    canvas = driver.find_element(By.ID, "canvas")
    # from (100, 110) to (400, 260) in canvas pixels; offsets are from the canvas' centre
    chain = ActionChains(driver).move_to_element_with_offset(canvas, -200, -100).click_and_hold()
    for _ in range(10):
        chain.move_by_offset(30, 15)
    chain.release().perform()
    shapes = driver.execute_script("return document.body.dataset.shapes")
    expect(shapes == "1", "after one drag the canvas holds %s shapes, not 1" % shapes)
    driver.find_element(By.ID, "plot").click()
    wait_for(lambda: state() in ("done", "error"), "the plot to finish", timeout_s=60)
    expect(state() == "done", "the plot failed: " + driver.find_element(By.ID, "error").text)
    summary = driver.find_element(By.ID, "summary").text
    drawn = re.search(r"drawn\s+([0-9.]+) mm", summary)
    expect(drawn is not None, "no drawn length in the summary: " + summary)
    expect(abs(float(drawn.group(1)) - 83.85) < 1.0, "drawn %s mm, not the line's 83.85 mm" % drawn.group(1))
    gcode_url = driver.execute_script("return document.body.dataset.gcode")
    base = url.split("/draw")[0]
    gcode = urllib.request.urlopen(base + gcode_url, timeout=30).read().decode()
    with open(out_dir + "/drawn.gcode", "w") as f:
        f.write(gcode)
    lines = gcode.splitlines()
    downs = [i for i, l in enumerate(lines) if l.startswith("M280 P0 S30")]
    expect(len(downs) == 1, "%d pen-down commands for one line, not 1" % len(downs))
    after = lines[downs[0] + 1:]
    expect(any(l.startswith("G1 X") for l in after[:5]), "no drawing move after the pen goes down: %s" % after[:5])
    wait_for_previews(driver, "the line")
    driver.find_element(By.ID, "name").send_keys("a line")
    driver.find_element(By.ID, "save").click()
    wait_for(lambda: "saved (job" in driver.find_element(By.ID, "saved").text, "the save to be confirmed", timeout_s=60)
    driver.find_element(By.LINK_TEXT, "gallery").click()
    wait_for(lambda: driver.execute_script("return document.body.dataset.count") == "1", "the gallery to list the drawing")
    card = driver.find_element(By.CSS_SELECTOR, "#jobs .job")
    expect("a line" in card.text and "drawing plotted on xy-plotter-servo" in card.text, "the card shows: " + card.text)
    card.find_element(By.LINK_TEXT, "open to edit").click()
    wait_for(lambda: state() == "ready", "the drawing to reopen")
    expect(driver.execute_script("return document.getElementById('file').files.length") == 1, "the drawing is not loaded")
    driver.find_element(By.ID, "plot").click()
    wait_for(lambda: state() in ("done", "error"), "the reopened drawing to plot", timeout_s=60)
    again = re.search(r"drawn\s+([0-9.]+) mm", driver.find_element(By.ID, "summary").text)
    expect(again is not None and again.group(1) == drawn.group(1), "the reopened drawing plots differently: %s" %
           driver.find_element(By.ID, "summary").text)
    errors = console_errors(driver)
    expect(not errors, "console errors: %s" % errors)
finally:
    driver.quit()
