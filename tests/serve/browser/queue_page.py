"""The queue page: a job queued on the simulated firmware's port is started with its button and
its progress, pushed over Server-Sent Events, reaches 100 %; then a screenshot.
Usage: queue_page.py URL-of-/queue DIR
"""
import sys

from selenium.webdriver.common.by import By

from strand_browser import console_errors, expect, open_browser, wait_for

url, out_dir = sys.argv[1], sys.argv[2]
driver = open_browser(out_dir + "/profile")
try:
    driver.get(url)
    wait_for(lambda: driver.execute_script("return document.body.dataset.events") == "open", "the event stream to open")
    def start():
        # The page redraws an entry's card on every event: find and press in one step, again
        # if the card was replaced in between.
        driver.find_element(By.CSS_SELECTOR, ".entry[data-state=queued] button.act-start").click()
        return True

    wait_for(start, "the queued entry's start button")
    try:
        wait_for(lambda: driver.find_element(By.CSS_SELECTOR, ".entry").get_attribute("data-percent") == "100",
                 "the progress to reach 100 %", timeout_s=60)
    except SystemExit:
        sys.stderr.write("page: %s; console: %s\n" % (driver.find_element(By.TAG_NAME, "body").text.replace("\n", " | ")[:600],
                                                     console_errors(driver)))
        raise
    text = driver.find_element(By.CSS_SELECTOR, ".entry").text
    expect("done" in text and "100.0 %" in text, "the entry does not say done at 100 %: " + text)
    driver.save_screenshot(out_dir + "/queue.png")
    errors = console_errors(driver)
    expect(not errors, "console errors: %s" % errors)
finally:
    driver.quit()
