#!/usr/bin/env python3
"""`make bench`: the 3D viewer on a million moves (issue 34). Writes a 1M-move log-pile G-code
(serpentine_gcode.py: 8 layers of 62,500 rows, 1,000,008 moves), times `strand preview -o
x.html` (the layer blocks every viewer reads, built layer by layer, and the self-contained page)
and, with Debian's chromium and python3-selenium, opens the page in headless Chromium
(software WebGL) until the viewer says "drawn"; then the same on `strand serve`: a saved job
whose G-code is replaced by the million moves before its first view, GET /api/jobs/1/view
(the blocks built and cached) timed, and /view/1 opened until drawn (the blocks fetched in
ranges of at most 16 MiB). Budgets: the blocks and page in 10 s of cpu and 1 GiB, each page
drawn in 30 s, the server's index in 10 s.
Usage: view_bench.py STRAND"""
import os
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "support", "browser"))
BUILD_BUDGET_S, BUILD_BUDGET_BYTES, DRAW_BUDGET_S = 10.0, 1 << 30, 30.0


def main():
    strand = os.path.abspath(sys.argv[1])
    with tempfile.TemporaryDirectory() as d:
        gcode, html = os.path.join(d, "million.gcode"), os.path.join(d, "million.html")
        subprocess.run([sys.executable, os.path.join(HERE, "serpentine_gcode.py"), gcode, "--layers", "8",
                        "--rows", "62500", "--length", "200"], check=True)
        p = subprocess.Popen([strand, "preview", gcode, "-o", html], stdout=subprocess.PIPE, stderr=subprocess.DEVNULL)
        _, status, ru = os.wait4(p.pid, 0)
        out = p.stdout.read().decode().strip()
        if os.waitstatus_to_exitcode(status) != 0:
            sys.exit("view bench: strand preview failed")
        cpu, rss = ru.ru_utime + ru.ru_stime, ru.ru_maxrss * 1024
        print(f"view: {out}")
        print(f"view: blocks + page {cpu:.2f} s cpu (budget {BUILD_BUDGET_S:.0f}), peak {rss / 2**20:.0f} MiB "
              f"(budget {BUILD_BUDGET_BYTES >> 20}), G-code {os.path.getsize(gcode) / 2**20:.0f} MiB, "
              f"page {os.path.getsize(html) / 2**20:.0f} MiB")
        ok = cpu <= BUILD_BUDGET_S and rss <= BUILD_BUDGET_BYTES
        try:
            from strand_browser import open_browser
        except ImportError:
            print("view: page not timed (python3-selenium missing)")
            return 0 if ok else 1
        driver = open_browser(os.path.join(d, "profile"), width=1366, height=768)
        try:
            start = time.monotonic()
            driver.get("file://" + html)
            status = ""
            while time.monotonic() - start < 120 and not status.startswith(("drawn", "error")):
                time.sleep(0.2)
                status = driver.find_element("id", "status").text
            wall = time.monotonic() - start
        finally:
            driver.quit()
        print(f"view: page opened and drawn in {wall:.1f} s (budget {DRAW_BUDGET_S:.0f}); the page says: {status}")
        ok = ok and status.startswith("drawn") and wall <= DRAW_BUDGET_S
        ok = serve_bench(strand, d, gcode, open_browser) and ok
    return 0 if ok else 1


def open_until_drawn(open_browser, profile, url):
    driver = open_browser(profile, width=1366, height=768)
    try:
        start = time.monotonic()
        driver.get(url)
        status = ""
        while time.monotonic() - start < 120 and not status.startswith(("drawn", "error")):
            time.sleep(0.2)
            status = driver.find_element("id", "status").text
        return time.monotonic() - start, status
    finally:
        driver.quit()


def serve_bench(strand, d, gcode, open_browser):
    import json
    import shutil
    import urllib.request
    data = os.path.join(d, "data")
    server = subprocess.Popen([strand, "serve", "--port", "0", "--data", data], stdout=subprocess.PIPE,
                              stderr=subprocess.DEVNULL, text=True)
    try:
        base = server.stdout.readline().split()[2]  # "strand serve: http://127.0.0.1:N/ (data in ...)"
        job = {"name": "million", "generator": "scaffold", "machine": "deltawasp-2040-clay",
               "params": {"nozzle": 0.84, "gap": 1.6, "size": "20x20", "layers": 2}}
        req = urllib.request.Request(base + "api/jobs", json.dumps(job).encode(), {"Content-Type": "application/json"})
        saved = json.load(urllib.request.urlopen(req))
        shutil.copy(gcode, os.path.join(data, "jobs", str(saved["id"]), "scaffold.gcode"))
        start = time.monotonic()
        index = json.load(urllib.request.urlopen(base + "api/jobs/%d/view" % saved["id"]))
        built = time.monotonic() - start
        print(f"serve: GET /api/jobs/N/view built the blocks of {index['segments']} segments in {built:.1f} s "
              f"(budget {DRAW_BUDGET_S / 3:.0f})")
        wall, status = open_until_drawn(open_browser, os.path.join(d, "profile-serve"), base + "view/%d" % saved["id"])
        print(f"serve: /view/N opened and drawn in {wall:.1f} s (budget {DRAW_BUDGET_S:.0f}); the page says: {status}")
        return built <= DRAW_BUDGET_S / 3 and status.startswith("drawn") and wall <= DRAW_BUDGET_S
    finally:
        server.terminate()
        server.wait()


if __name__ == "__main__":
    sys.exit(main())
