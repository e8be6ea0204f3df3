"""Screenshots of the built documentation's main pages in headless Chromium, to check by eye that
they render offline (equations typeset by MathJax, tables, images).

    sphinx-build -W -b html docs docs/_build/html
    python scripts/screenshot_docs.py [docs/_build/html] [--out docs/_build/screenshots]

Needs Debian's ``chromium`` (``apt-get install chromium``). Chromium runs with networking off
(a proxy that does not exist), so a page that needs the network shows it. Not part of CI.
"""

import argparse
import shutil
import subprocess
import sys
from pathlib import Path

PAGES = ["index", "getting-started", "guide/index", "guide/track", "guide/fidelity",
         "guide/excitation", "guide/vehicle", "guide/long-runs", "guide/frequency-domain",
         "model", "validation", "api", "cli", "benchmarks", "development",
         "notebooks/01_eigen", "notebooks/04_speed"]


def screenshot(chromium: str, page: Path, png: Path, height: int) -> None:
    subprocess.run(
        [chromium, "--headless", "--no-sandbox", "--disable-gpu", "--hide-scrollbars",
         "--proxy-server=127.0.0.1:9", "--allow-file-access-from-files",
         "--virtual-time-budget=8000", f"--window-size=1280,{height}",
         f"--screenshot={png}", page.resolve().as_uri()],
        check=True, capture_output=True, timeout=120)


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("html", nargs="?", type=Path, default=Path("docs/_build/html"))
    p.add_argument("--out", type=Path, default=Path("docs/_build/screenshots"))
    p.add_argument("--height", type=int, default=2000, help="window height [px]")
    args = p.parse_args()
    chromium = shutil.which("chromium") or shutil.which("chromium-browser")
    if chromium is None:
        print("chromium not found: apt-get install chromium", file=sys.stderr)
        return 1
    args.out.mkdir(parents=True, exist_ok=True)
    for name in PAGES:
        page = args.html / f"{name}.html"
        if not page.exists():
            print(f"missing page {page}: build the docs first", file=sys.stderr)
            return 1
        png = args.out / f"{name.replace('/', '_')}.png"
        screenshot(chromium, page, png, args.height)
        print(png)
    return 0


if __name__ == "__main__":
    sys.exit(main())
