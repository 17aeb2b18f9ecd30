#!/usr/bin/env python3
"""Checks one viewer page as headless Chromium left it (tests/view/browser_test.sh).

DOM (--dump-dom after the virtual-time budget): <html data-ready="1" data-errors="0">.
Logs (Chromium's stderr with --enable-logging): no uncaught error or console error of the page.
PNG (--screenshot): not blank (pixel variance above a threshold), body A's orange and body B's
blue each cover enough pixels (src/view/web/viewer/colours.js keeps other colours off those
hues), and with --min-red the contact red covers at least that many; with --differs-from, at least
--min-differing pixels differ from another screenshot of the same view (what it adds is drawn).
"""
import argparse
import re
import sys

import matplotlib.image
import numpy as np


def hue_mask(rgb, lo, hi, min_sat=0.35, min_val=0.15):
    """Pixels whose hue (degrees) is in [lo, hi] and that are saturated and bright enough."""
    r, g, b = rgb[..., 0], rgb[..., 1], rgb[..., 2]
    mx, mn = rgb.max(axis=-1), rgb.min(axis=-1)
    d = np.where(mx - mn > 1e-6, mx - mn, 1.0)
    h = np.where(mx == r, (g - b) / d % 6, np.where(mx == g, (b - r) / d + 2, (r - g) / d + 4)) * 60.0
    sat = np.where(mx > 0, (mx - mn) / np.maximum(mx, 1e-6), 0)
    return (h >= lo) & (h <= hi) & (sat >= min_sat) & (mx >= min_val) & (mx - mn > 1e-6)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--page", required=True)
    ap.add_argument("--dom", required=True)
    ap.add_argument("--png", required=True)
    ap.add_argument("--logs", nargs="*", default=[])
    ap.add_argument("--replay", action="store_true")
    ap.add_argument("--expect-text", default=None, help="text the page's DOM must contain")
    ap.add_argument("--expect-attr", action="append", default=[], metavar="NAME=VALUE",
                    help="an attribute <html> must hold with that value (repeatable)")
    ap.add_argument("--differs-from", default=None, metavar="PNG",
                    help="a screenshot of the same view without something: with --min-differing, how many "
                         "pixels must differ from it")
    ap.add_argument("--min-differing", type=int, default=0)
    ap.add_argument("--min-red", type=int, default=0,
                    help="pixels of the contact red the screenshot must hold outside the panel (data-panel)")
    a = ap.parse_args()
    failures = []

    dom = open(a.dom, encoding="utf-8", errors="replace").read()
    html = re.search(r"<html[^>]*>", dom)
    tag = html.group(0) if html else ""
    if 'data-ready="1"' not in tag:
        failures.append("the page never drew its first frame (no data-ready on <html>: %s)" % tag[:200])
    errors = re.search(r'data-errors="(\d+)"', tag)
    if not errors:
        failures.append("the page's error handler did not run (no data-errors on <html>)")
    elif errors.group(1) != "0":
        shown = re.search(r'<pre id="errors"[^>]*>(.*?)</pre>', dom, re.S)
        failures.append("JavaScript errors: " + (shown.group(1) if shown else errors.group(1)))
    for pair in a.expect_attr:
        name, _, value = pair.partition("=")
        got = re.search(r'\b%s="([^"]*)"' % re.escape(name), tag)
        if not got or got.group(1) != value:
            failures.append("<html> has %s=%s, expected %s" % (name, got.group(1) if got else "(none)", value))
    if a.expect_text and a.expect_text not in dom:
        failures.append("the page does not show '%s'" % a.expect_text)
    if a.replay and 'id="readout"></span>' in dom:
        failures.append("the replay readout is empty (no frame shown)")

    for log in a.logs:
        for line in open(log, encoding="utf-8", errors="replace"):
            if "CONSOLE" in line and ("Uncaught" in line or "console.error" in line or ":ERROR:" in line):
                failures.append("%s: %s" % (log, line.strip()))

    img = matplotlib.image.imread(a.png)[..., :3].astype(float)
    if img.max() > 1.0:
        img /= 255.0
    variance = float(img.var())
    orange = int(hue_mask(img, 15, 42).sum())
    blue = int(hue_mask(img, 205, 228).sum())
    # The contact red (#ff1010, saturation 0.94): hue within 8 degrees of 0, saturation above 0.9
    # (the force arrow, #ff3030, has 0.81).
    red_mask = hue_mask(img, 0, 8, min_sat=0.9, min_val=0.5) | hue_mask(img, 352, 360, min_sat=0.9, min_val=0.5)
    panel = re.search(r'data-panel="(\d+),(\d+),(\d+),(\d+)"', tag)
    if panel:  # the legend's swatches are not points; 8 px of margin
        x, y, w, h = (int(v) for v in panel.groups())
        red_mask[max(0, y - 8):y + h + 8, max(0, x - 8):x + w + 8] = False
    red = int(red_mask.sum())
    print("%s: %dx%d, pixel variance %.4f, orange (body A) %d px, blue (body B) %d px, red (contact) %d px"
          % (a.page, img.shape[1], img.shape[0], variance, orange, blue, red))
    if a.differs_from:
        other = matplotlib.image.imread(a.differs_from)[..., :3].astype(float)
        if other.max() > 1.0:
            other /= 255.0
        if other.shape != img.shape:
            failures.append("%s is %s, the screenshot %s" % (a.differs_from, other.shape, img.shape))
        else:
            differing = int((np.abs(img - other).max(axis=-1) > 0.1).sum())
            print("%s: %d pixels differ from %s" % (a.page, differing, a.differs_from))
            if differing < a.min_differing:
                failures.append("only %d pixels differ from %s (at least %d expected)"
                                % (differing, a.differs_from, a.min_differing))
    if red < a.min_red:
        failures.append("points in contact (red) cover only %d pixels" % red)
    if variance < 0.002:
        failures.append("the screenshot is blank (variance %.5f)" % variance)
    if orange < 2000:
        failures.append("body A (orange) covers only %d pixels" % orange)
    if blue < 2000:
        failures.append("body B (blue) covers only %d pixels" % blue)

    for f in failures:
        print("FAILED %s: %s" % (a.page, f))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
