"""First impressions: every workbench page opened fresh (an empty data directory) at 1366x768
and on a phone (390x844, mobile emulation). On every page and at both sizes: no error text
and no field marked bad, the page's form holds its example (the design page the thesis
scaffold of samples/scaffold-thesis.json, generated and checked ok; the slice page the
thesis' 0.6 mm nozzle and 1 mm gap; ...), nothing wider than the window, the page's top-level
blocks (the bar, the form, the result) apart, inside the window and holding their controls, the bar linking every
page, and no console errors. Writes DIR/workbench-<page>-<wide|phone>.png.
Usage: first_look.py BASE-URL DIR
"""
import sys

from selenium.webdriver.common.by import By

from strand_browser import console_errors, expect, open_browser, wait_for

base, out_dir = sys.argv[1].rstrip("/"), sys.argv[2]
pages = {"design": "/", "slice": "/slice", "draw": "/draw", "gallery": "/gallery", "sweep": "/sweep",
         "queue": "/queue"}

# When a page has finished loading.
ready = {
    "design": "return document.body.dataset.state === 'done' || document.body.dataset.state === 'error'",
    "slice": "return document.body.dataset.state === 'ready'",
    "draw": "return document.body.dataset.state === 'ready'",
    "gallery": "return document.body.dataset.count !== undefined",
    "sweep": "return document.body.dataset.ready === '1'",
    "queue": "return document.body.dataset.events === 'open'",
}
# The example each page's form opens on: element id -> value.
examples = {
    "design": {"generator": "scaffold", "machine": "deltawasp-2040-clay", "p-nozzle": "0.84", "p-gap": "1.6",
               "p-size": "36x36", "p-height": "13", "p-speed": "250"},
    "slice": {"machine": "deltawasp-2040-clay", "o-pattern": "scaffold", "p-nozzle": "0.6", "p-gap": "1",
              "o-perimeters": "1", "o-scale-to-fit": "30x30x30"},
    "draw": {"source": "canvas", "machine": "xy-plotter-servo", "text": "Strand", "text-size": "10"},
    "gallery": {},
    "sweep": {"base": "example", "key-1": "nozzle", "values-1": "0.6, 0.84", "key-2": "gap",
              "values-2": "0.8..1.6 step 0.4", "where": "gap >= nozzle"},
    "queue": {"baud": "115200", "firmware": "marlin"},
}
# The top-level blocks that must not overlap: the bar and main's children (or, on the queue
# page, its heading, form and machines).
blocks_js = """
const blocks = [document.querySelector('header')];
for (const e of document.querySelectorAll('main > *, body > #jobs, body > #status')) blocks.push(e);
const out = [];
for (const e of blocks) {
  if (!e) continue;
  const r = e.getBoundingClientRect();
  if (r.width < 1 || r.height < 1) continue;  // empty until something is shown
  // a control wider than its block (a long select) spills over its neighbour
  const spill = Array.from(e.querySelectorAll('*')).filter((c) => {
    const s = c.getBoundingClientRect();
    return s.width > 0 && s.height > 0 && (s.right > r.right + 0.5 || s.left < r.left - 0.5);
  }).map((c) => c.tagName.toLowerCase() + (c.id ? '#' + c.id : ''));
  out.push({name: e.tagName.toLowerCase() + (e.id ? '#' + e.id : ''), left: r.left, right: r.right,
            top: r.top + window.scrollY, bottom: r.bottom + window.scrollY, spill: spill});
}
return out;
"""
# Visible error text or a field marked bad.
errors_js = """
const out = [];
for (const e of document.querySelectorAll('.err, .error, #error, #general, #status, #add-error, #check.fail, input.bad')) {
  const r = e.getBoundingClientRect();
  const shown = r.width > 0 && r.height > 0 && getComputedStyle(e).visibility !== 'hidden';
  if (shown && (e.tagName === 'INPUT' || e.textContent.trim() !== '')) out.push((e.id || e.className) + ': ' + e.textContent.trim());
}
return out;
"""

for tag, width, height in (("wide", 1366, 768), ("phone", 390, 844)):
    driver = open_browser("%s/profile-%s" % (out_dir, tag), width=width, height=height)
    try:
        if tag == "phone":
            driver.execute_cdp_cmd("Emulation.setDeviceMetricsOverride",
                                   {"width": width, "height": height, "deviceScaleFactor": 1, "mobile": True})
        for page, path in pages.items():
            where = "%s at %s" % (path, tag)
            driver.get(base + path)
            wait_for(lambda: driver.execute_script(ready[page]), "%s to load" % where)
            if page == "design":
                expect(driver.execute_script("return document.body.dataset.state") == "done",
                       "%s: the example is not generated: %s" % (where, driver.find_element(By.ID, "summary").text))
                check = driver.find_element(By.ID, "check").text
                expect(check.startswith("check: ok"), "%s: %s" % (where, check))
            shown = driver.execute_script(errors_js)
            expect(not shown, "%s opens with errors: %s" % (where, shown))
            for key, want in examples[page].items():
                got = driver.find_element(By.ID, key).get_attribute("value")
                expect(got == want, "%s: #%s is %r, not the example's %r" % (where, key, got, want))
            if page == "gallery":
                expect("No saved designs yet" in driver.find_element(By.ID, "jobs").text, "%s: no word for an empty gallery" % where)
            inner, scroll, client = driver.execute_script(
                "return [window.innerWidth, document.documentElement.scrollWidth, document.documentElement.clientWidth]")
            expect(inner == width, "%s: the layout viewport is %d px wide, not %d (something too wide)" % (where, inner, width))
            expect(scroll <= client, "%s: the page is %d px wide in a %d px window" % (where, scroll, client))
            links = driver.execute_script(
                "return Array.from(document.querySelectorAll('header nav a')).map((a) => new URL(a.href).pathname)")
            missing = [p for p in pages.values() if p not in links]
            expect(not missing, "%s: the bar does not link %s (it links %s)" % (where, missing, links))
            blocks = driver.execute_script(blocks_js)
            expect(len(blocks) >= 2, "%s: the page's blocks were not found: %s" % (where, blocks))
            for b in blocks:
                expect(not b["spill"], "%s: %s's %s reach past its edge" % (where, b["name"], b["spill"]))
                expect(b["left"] >= -0.5 and b["right"] <= client + 0.5, "%s: %s sticks out of the window: %s" % (where, b["name"], b))
            for i, a in enumerate(blocks):
                for b in blocks[i + 1:]:
                    apart = (a["right"] <= b["left"] + 0.5 or b["right"] <= a["left"] + 0.5 or
                             a["bottom"] <= b["top"] + 0.5 or b["bottom"] <= a["top"] + 0.5)
                    expect(apart, "%s: %s and %s overlap: %s %s" % (where, a["name"], b["name"], a, b))
            driver.save_screenshot("%s/workbench-%s-%s.png" % (out_dir, page, tag))
            errors = console_errors(driver)
            expect(not errors, "%s: console errors: %s" % (where, errors))
    finally:
        driver.quit()
