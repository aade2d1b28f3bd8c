"""The design page with a robot cell: choosing kuka-iiwa14-wasp-cylinder shows the substrate's
fields on the thesis' cylinder (r 20, 80 mm), the job runs on it and lists the whole program
set (pose CSV, Sunrise, KRL, the extruder's G-code) with a working "download all (.zip)" link
and the poses drawn on the cylinder; then a tetrachiral lattice on an uploaded mesh
(samples/meshes/sphere-cap.stl) is run and saved. Nothing overlaps at 1366x768 or 390 px.
In the gallery (the caller saved "sleeve r25", a cylinder of radius 25 and length 90), the
sleeve's edit link carries its cylinder, the lattice is duplicated on its recorded mesh and
reopens on it without a file being chosen.
Writes DIR/workbench-robot.png, a screenshot (1366x1250, for docs/img).
Usage: robot_job.py URL-of-/ DIR
"""
import os
import sys
from urllib.parse import parse_qs, urlparse

from selenium.webdriver.common.by import By
from selenium.webdriver.support.ui import Select

from strand_browser import console_errors, expect, open_browser, wait_for

url, out_dir = sys.argv[1], sys.argv[2]
cap = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "samples", "meshes", "sphere-cap.stl")
driver = open_browser(out_dir + "/profile", width=1366, height=768)


def state():
    return driver.execute_script("return document.body.dataset.state")


def wait_done(what):
    wait_for(lambda: state() in ("done", "error"), what, timeout_s=60)
    expect(state() == "done", what + " failed: " + driver.find_element(By.ID, "general").text +
           " / " + driver.find_element(By.ID, "summary").text)


def files():
    return [a.text for a in driver.find_elements(By.CSS_SELECTOR, "#files a")]


def expect_painted(what):
    driver.switch_to.frame(driver.find_element(By.ID, "preview"))
    painted = "const c = document.getElementById('view'); if (!c || !c.width) return false;" \
              "const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;" \
              "const seen = new Set(); for (let i = 0; i < d.length; i += 4 * 97) seen.add(d[i] + ',' + d[i + 1] + ',' + d[i + 2]);" \
              "return seen.size > 2"
    wait_for(lambda: driver.execute_script(painted), "the preview to draw " + what)
    driver.switch_to.default_content()


def expect_fits(size):
    expect(driver.execute_script("return document.documentElement.scrollWidth <= document.documentElement.clientWidth"),
           "the page is wider than the window at " + size)


try:
    driver.get(url)
    wait_done("the first design")
    expect(not driver.find_element(By.ID, "substrate").is_displayed(), "substrate fields shown for a flat-bed printer")
    Select(driver.find_element(By.ID, "machine")).select_by_value("kuka-iiwa14-wasp-cylinder")
    wait_for(lambda: driver.find_element(By.ID, "substrate").is_displayed(), "the substrate's fields")
    value = lambda i: driver.find_element(By.ID, i).get_attribute("value")
    expect(value("s-type") == "cylinder" and value("s-radius") == "20" and value("s-length") == "80",
           "the substrate does not start on the thesis' cylinder: %s r %s l %s" % (value("s-type"), value("s-radius"), value("s-length")))
    wait_for(lambda: "cylinder r 20.000 mm" in driver.find_element(By.ID, "summary").text, "the job on the cylinder")
    wait_done("the job on the cylinder")
    names = files()
    for name in ("scaffold.csv", "Scaffold.java", "scaffold.src", "scaffold.dat", "scaffold.extruder.gcode", "download all (.zip)"):
        expect(name in names, "%s is not listed: %s" % (name, names))
    archive = driver.execute_async_script(
        "const done = arguments[0];"
        "fetch(document.getElementById('zip').href).then(async (r) => {"
        "  const b = new Uint8Array(await r.arrayBuffer());"
        "  done({status: r.status, type: r.headers.get('Content-Type'), head: Array.from(b.slice(0, 4)),"
        "        text: new TextDecoder('latin1').decode(b)}); });")
    expect(archive["status"] == 200 and archive["type"] == "application/zip" and archive["head"] == [80, 75, 3, 4],
           "the zip link does not answer a zip archive: %s %s %s" % (archive["status"], archive["type"], archive["head"]))
    for name in names[:-1]:
        expect(name in archive["text"], name + " is not in the archive")
    expect_painted("the poses on the cylinder")
    expect_fits("1366x768")
    apart = driver.execute_script(
        "const [a, b] = document.querySelectorAll('main > section');"
        "return a.getBoundingClientRect().right <= b.getBoundingClientRect().left")
    expect(apart, "the form and the result overlap")
    driver.set_window_size(1366, 1250)  # the docs' picture: the fields, the programs and the poses at once
    expect_painted("the poses on the cylinder")
    driver.save_screenshot(out_dir + "/workbench-robot.png")
    driver.set_window_size(1366, 768)

    # A tetrachiral lattice on the sphere cap, from the address, then saved.
    driver.get(url + "?generator=tetrachiral&machine=kuka-iiwa14-wasp-cylinder&substrate=mesh"
                     "&nozzle=1.2&cell=10&cols=3&rows=3&layers=3")
    wait_for(lambda: state() == "waiting", "the page to ask for the mesh")
    expect(driver.find_element(By.ID, "s-mesh").is_displayed() and not driver.find_element(By.ID, "s-radius").is_displayed(),
           "the mesh field is not the one shown")
    driver.find_element(By.ID, "s-mesh").send_keys(os.path.realpath(cap))
    wait_done("the job on the uploaded mesh")
    summary = driver.find_element(By.ID, "summary").text
    expect("mesh substrate.stl: 2808 triangles" in summary, "the summary: " + summary)
    names = files()
    for name in ("tetrachiral.csv", "tetrachiral.substrate.json", "substrate.stl", "download all (.zip)"):
        expect(name in names, "%s is not listed: %s" % (name, names))
    expect_painted("the poses on the mesh")
    driver.find_element(By.ID, "name").send_keys("cap lattice")
    driver.find_element(By.ID, "save").click()
    wait_for(lambda: driver.find_element(By.CSS_SELECTOR, "#saved a"), "the saved job's link")
    driver.set_window_size(390, 844)
    expect_fits("390 px")
    errors = console_errors(driver)
    expect(not errors, "console errors: %s" % errors)

    driver.set_window_size(1366, 768)
    driver.get(url + "gallery")
    count = lambda: driver.execute_script("return document.body.dataset.count")
    wait_for(lambda: count() == "2", "the gallery's two jobs")

    def card(name):
        return next(c for c in driver.find_elements(By.CSS_SELECTOR, "#jobs .job")
                    if c.find_element(By.TAG_NAME, "h2").text == name)

    edit = lambda name: card(name).find_element(By.LINK_TEXT, "open to edit").get_attribute("href")
    sleeve = parse_qs(urlparse(edit("sleeve r25")).query)
    expect(sleeve.get("substrate") == ["cylinder"] and sleeve.get("substrate-radius") == ["25"] and
           sleeve.get("substrate-length") == ["90"], "the sleeve's edit link lacks its cylinder: %s" % sleeve)
    card("cap lattice").find_element(By.XPATH, ".//button[text()='duplicate']").click()
    wait_for(lambda: count() == "3" or driver.find_element(By.ID, "status").text, "the duplicate on the recorded mesh")
    expect(count() == "3", "the duplicate failed: " + driver.find_element(By.ID, "status").text)
    driver.get(edit("cap lattice"))
    wait_done("the lattice reopened on its recorded mesh")
    note = driver.find_element(By.ID, "s-mesh-saved").text
    expect("using substrate.stl of saved job" in note, "no note of the recorded mesh: " + note)
    summary = driver.find_element(By.ID, "summary").text
    expect("mesh substrate.stl: 2808 triangles" in summary, "the reopened job's summary: " + summary)
    expect("mesh-job=" in driver.current_url, "the address lost the recorded mesh: " + driver.current_url)
    errors = console_errors(driver)
    expect(not errors, "console errors: %s" % errors)
finally:
    driver.quit()
