"""The 3D viewer (/view/{id}): waits for the saved job's toolpath to be drawn (WebGL, three.js
served by strand itself), moves the last-layer slider to layer 1 and reads the layer's stats
(strands, length) against the job's report from the API, scrubs the moves of that layer,
shows the travel moves and colours by speed; then opens DIR/standalone.html (what
`strand preview -o x.html` writes) from disk and reads the same layer there. Writes
DIR/workbench-view.png, a screenshot at 1366x768.
Usage: view.py URL-of-/view/{id} DIR
"""
import sys

from selenium.webdriver.common.by import By

from strand_browser import console_errors, expect, open_browser, wait_for

url, out_dir = sys.argv[1], sys.argv[2]
job = url.rstrip("/").split("/")[-1]
api = url.split("/view/")[0] + "/api/jobs/" + job
driver = open_browser(out_dir + "/profile", width=1366, height=768)


def drawn():
    text = driver.find_element(By.ID, "status").text
    expect(not text.startswith("error"), "the viewer failed: " + text)
    return text.startswith("drawn:")


def slide(element_id, value):
    driver.execute_script("const e = document.getElementById(arguments[0]); e.value = arguments[1];"
                          "e.dispatchEvent(new Event('input'))", element_id, value)


def stat(name):
    return driver.find_element(By.ID, "stat-" + name).text


def layer_one_matches(report_layer, where):
    slide("layer-to", 1)
    expect(driver.find_element(By.ID, "to-label").text.startswith("1 (z "), where + ": the slider did not move: " +
           driver.find_element(By.ID, "to-label").text)
    expect(stat("strands") == str(report_layer["strands"]), "%s: layer 1 has %s strands in the report, the viewer says %s" %
           (where, report_layer["strands"], stat("strands")))
    length = "%.1f mm" % report_layer["deposit_length_mm"]
    expect(stat("length") == length, "%s: layer 1 is %s long in the report, the viewer says %s" % (where, length, stat("length")))


try:
    driver.get(url)
    report = driver.execute_async_script(
        "fetch(arguments[0]).then(r => r.json()).then(j => arguments[1](j.report))", api)
    wait_for(drawn, "the toolpath to be drawn", timeout_s=60)
    layers = len(report["layers"])
    expect(driver.find_element(By.ID, "layer-to").get_attribute("max") == str(layers - 1),
           "the slider does not reach the last of %d layers" % layers)
    layer_one_matches(report["layers"][1], "/view")
    moves = int(stat("moves"))
    slide("move", 3)
    expect(driver.find_element(By.ID, "move-label").text.startswith("3 of "),
           "the move scrubber: " + driver.find_element(By.ID, "move-label").text)
    expect("line " in driver.find_element(By.ID, "move-label").text, "the move's G-code line is not shown")
    slide("move", moves)
    driver.find_element(By.ID, "travel").click()
    expect(driver.execute_script("return strandViewer.trav.mesh.visible"), "travel moves are not shown when ticked")
    driver.execute_script("const s = document.getElementById('colour'); s.value = 'speed'; s.dispatchEvent(new Event('change'))")
    expect("mm/min" in driver.find_element(By.ID, "legend").text, "colour by speed has no scale: " +
           driver.find_element(By.ID, "legend").text)
    driver.execute_script("const s = document.getElementById('colour'); s.value = 'feature'; s.dispatchEvent(new Event('change'))")
    slide("layer-to", layers - 1)
    expect(driver.execute_script("return document.documentElement.scrollWidth <= document.documentElement.clientWidth"),
           "the page is wider than the window")
    driver.save_screenshot(out_dir + "/workbench-view.png")
    errors = console_errors(driver)
    expect(not errors, "console errors: %s" % errors)
    driver.get("file://" + out_dir + "/standalone.html")
    wait_for(drawn, "the standalone viewer to draw", timeout_s=60)
    layer_one_matches(report["layers"][1], "standalone.html")
finally:
    driver.quit()
