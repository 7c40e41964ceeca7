"""A report page checked as a file and in a real browser (Debian's chromium,
headless, from file:// with the network disabled); shared by the tests that
write `cnclab report` pages.
"""
import json
import os
import re
import shutil
import subprocess

CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")

# No request may leave the page: no proxy reachable, names resolve nowhere,
# and Chromium's own background traffic switched off so that any request in
# the log is the page's.
QUIET = ["--headless", "--no-sandbox", "--disable-gpu", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync",
         "--disable-default-apps", "--disable-extensions", "--disable-domain-reliability",
         "--metrics-recording-only", "--no-pings", "--proxy-server=http://127.0.0.1:9",
         "--host-resolver-rules=MAP * ~NOTFOUND", "--enable-logging=stderr", "--v=0"]

MAX_BYTES = 5 * 1024 * 1024


def require_chromium():
    if not CHROMIUM:
        raise SystemExit("chromium not found: scripts/setup installs it (CNCLAB_SETUP_TEST=1)")


def file_problems(path):
    """What is wrong with the page as a file: over 5 MB, a script, an
    external reference, a <link>, an image that is not a data URI."""
    problems = []
    text = open(path, encoding="utf-8").read()
    if os.path.getsize(path) > MAX_BYTES:
        problems.append(f"{path}: {os.path.getsize(path)} bytes, over 5 MB")
    if "<script" in text.lower():
        problems.append("a <script>")
    if "<link" in text.lower():
        problems.append("a <link>")
    external = re.findall(r'(?:src|href)\s*=\s*["\']?\s*(?:https?:|//)', text, re.I)
    if external:
        problems.append(f"external references {external[:3]}")
    images = re.findall(r"<img\b[^>]*>", text, re.I)
    not_data = [i[:80] for i in images if not re.search(r'src="data:image/png;base64,', i)]
    if not_data:
        problems.append(f"images that are no PNG data URI: {not_data[:3]}")
    if text.count("<style") != 1:
        problems.append(f"{text.count('<style')} <style> elements (one expected)")
    return problems


def open_in_chromium(url, profile, tmp):
    """(DOM, console lines, URLs the page asked for outside the file)."""
    netlog = os.path.join(tmp, "net.json")
    r = subprocess.run([CHROMIUM, *QUIET, f"--user-data-dir={profile}", f"--log-net-log={netlog}",
                        "--dump-dom", url], capture_output=True, text=True, timeout=120)
    console = [l for l in r.stderr.splitlines() if "CONSOLE" in l or "Uncaught" in l]
    text = open(netlog).read()
    try:
        log = json.loads(text)
    except ValueError:  # cut short at exit: close it
        log = json.loads(text.rstrip().rstrip(",") + "]}")
    start_job = log["constants"]["logEventTypes"]["URL_REQUEST_START_JOB"]
    leaving = set()
    for e in log["events"]:
        p = e.get("params") or {}
        # Chromium's own traffic (updater, clock, accounts) is browser-initiated
        # ("not an origin"); what the page asks for has its origin ("null" for file://).
        if e["type"] == start_job and p.get("initiator") != "not an origin":
            if not p.get("url", "file:").startswith(("file:", "data:", "about:", "chrome:")):
                leaving.add(p.get("url"))
    return r.stdout if r.returncode == 0 else "", console, sorted(leaving)


def screenshots(url, profile, out_dir, stem):
    """A 1280 px screenshot and the printed PDF of the page, to look at."""
    os.makedirs(out_dir, exist_ok=True)
    written = []
    for name, extra in [(f"{stem}-1280.png", ["--window-size=1280,2200", "--screenshot="]),
                        (f"{stem}-print.pdf", ["--print-to-pdf=", "--no-pdf-header-footer"])]:
        target = os.path.join(out_dir, name)
        args = [a + target if a.endswith("=") else a for a in extra]
        subprocess.run([CHROMIUM, *QUIET, f"--user-data-dir={profile}", *args, url],
                       capture_output=True, timeout=180)
        written.append(target)
    return written
