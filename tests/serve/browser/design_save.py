"""The design page: a parameter changed by typing changes the summary and the preview's
canvas; Save puts the design in the gallery, where /gallery lists it by name.
Usage: design_save.py URL-of-/?generator=scaffold...&layers=2 DIR
"""
import sys

from selenium.webdriver.common.by import By

from strand_browser import console_errors, expect, open_browser, wait_for

url, out_dir = sys.argv[1], sys.argv[2]
driver = open_browser(out_dir + "/profile")
PICTURE = "const f = document.getElementById('preview').contentDocument;" \
          "const c = f && f.getElementById('view'); return c && c.width ? c.toDataURL() : null"


def picture_after(summary_part, before):
    """Waits for the summary to show `summary_part`, then for a painted preview other than `before`."""
    wait_for(lambda: summary_part in driver.find_element(By.ID, "summary").text and
             driver.execute_script("return document.body.dataset.state") == "done",
             "the summary to show '%s'" % summary_part.strip(), timeout_s=60)
    return wait_for(lambda: (lambda p: p if p and p != before else None)(driver.execute_script(PICTURE)),
                    "the preview canvas to be painted anew", timeout_s=60)


try:
    driver.get(url)
    two = picture_after("layers         2,", None)
    field = driver.find_element(By.ID, "p-layers")
    field.clear()
    field.send_keys("3")
    three = picture_after("layers         3,", two)
    expect(three != two, "the preview did not change")
    expect("layers=3" in driver.current_url, "the address does not follow the field: " + driver.current_url)
    driver.find_element(By.ID, "name").send_keys("browser save")
    driver.find_element(By.ID, "save").click()
    wait_for(lambda: "saved (job" in driver.find_element(By.ID, "saved").text, "the save to be confirmed")
    driver.find_element(By.LINK_TEXT, "gallery").click()
    wait_for(lambda: driver.execute_script("return document.body.dataset.count") == "1", "the gallery to list one job")
    titles = [h.text for h in driver.find_elements(By.CSS_SELECTOR, "#jobs .job h2")]
    expect(titles == ["browser save"], "the gallery shows %s" % titles)
    card = driver.find_element(By.CSS_SELECTOR, "#jobs .job")
    expect("layers = 3" in card.text, "the card does not show layers = 3: " + card.text)
    errors = console_errors(driver)
    expect(not errors, "console errors: %s" % errors)
finally:
    driver.quit()
