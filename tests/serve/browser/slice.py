"""The slice page: the bone plug (samples/meshes/bone-plug.stl) chosen in the file input and
sliced with the page's defaults (scaffold, nozzle 0.6, gap 1, one perimeter, scale-to-fit
30x30x30). Expects the part's size (scaled to 30 x 30 x 18 mm), the mesh found sound, the
summary, the check, a link to the saved job and the HTML preview painted; the page no wider
than the window and its two columns apart. Writes DIR/workbench-slice.png, a screenshot.
Usage: slice.py URL-of-/slice DIR
"""
import os
import sys

from selenium.webdriver.common.by import By

from strand_browser import console_errors, expect, open_browser, wait_for, wait_for_previews

url, out_dir = sys.argv[1], sys.argv[2]
mesh = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "samples", "meshes", "bone-plug.stl")
driver = open_browser(out_dir + "/profile", width=1280, height=900)
try:
    driver.get(url)
    state = lambda: driver.execute_script("return document.body.dataset.state")
    wait_for(lambda: state() == "ready", "the slice page to list its machines and patterns")
    value = lambda i: driver.find_element(By.ID, i).get_attribute("value")
    expect(value("o-pattern") == "scaffold" and value("p-nozzle") == "0.6" and value("p-gap") == "1" and
           value("o-perimeters") == "1" and value("o-scale-to-fit") == "30x30x30",
           "the defaults are not the thesis' values: pattern %s, nozzle %s, gap %s, perimeters %s, fit %s" %
           (value("o-pattern"), value("p-nozzle"), value("p-gap"), value("o-perimeters"), value("o-scale-to-fit")))
    expect(value("machine") == "deltawasp-2040-clay", "the default machine is " + value("machine"))
    driver.find_element(By.ID, "file").send_keys(os.path.realpath(mesh))
    driver.find_element(By.ID, "slice").click()
    wait_for(lambda: state() in ("done", "error"), "the slice to finish", timeout_s=120)
    expect(state() == "done", "the slice failed: " + driver.find_element(By.ID, "error").text)
    part = driver.find_element(By.ID, "part").text
    expect("part 30.000 x 30.000 x 18.000 mm" in part, "the part's size is not shown: " + part)
    expect("no defects found" in part, "the plug's mesh is sound, the page says: " + part)
    summary = driver.find_element(By.ID, "summary").text
    expect("layers         34" in summary and "scale          1.5" in summary, "the summary: " + summary)
    expect(driver.find_element(By.ID, "check").text.startswith("check: ok"), "check: " + driver.find_element(By.ID, "check").text)
    saved = driver.find_element(By.ID, "saved")
    expect(saved.get_attribute("href").endswith("/gallery#job-" + driver.execute_script("return document.body.dataset.job")),
           "no link to the saved job: " + saved.get_attribute("href"))
    wait_for_previews(driver, "the part", timeout_s=60)
    expect(driver.execute_script("return document.documentElement.scrollWidth <= document.documentElement.clientWidth"),
           "the page is wider than the window")
    apart = driver.execute_script(
        "const [a, b] = document.querySelectorAll('main > section');"
        "return a.getBoundingClientRect().right <= b.getBoundingClientRect().left")
    expect(apart, "the form and the result overlap")
    driver.save_screenshot(out_dir + "/workbench-slice.png")
    errors = console_errors(driver)
    expect(not errors, "console errors: %s" % errors)
finally:
    driver.quit()
