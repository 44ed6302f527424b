"""Checks a headless render of `vantage view`'s page (render_test.sh).

The DOM must say the page finished without errors; the screenshot, outside the panel, must show
a drawn scene holding the top-face colours of the occupied cells (the height ramp the legend
declares) and the chosen view's colour.

With WHOLE_PNG (a building, seen from above without the height cut, while SCREENSHOT_PNG has
it): the cut must hide the top layers: the colours of the top tenth of the height ramp (the roof)
must cover far fewer pixels with the cut than without, while the lower cells still show.

Usage: check_render.py DOM_HTML SCREENSHOT_PNG [WHOLE_PNG]
"""
import re
import sys

import matplotlib.image
import numpy as np

kPanelRight = 380  # the panel is 330 px wide at 10 px from the left; its legend holds the colours
kBackground = (0x1E, 0x21, 0x28)


def fail(message):
    print(f"FAIL: {message}")
    sys.exit(1)


def hex_rgb(text):
    return np.array([int(text[i:i + 2], 16) for i in (1, 3, 5)], dtype=float)


def attribute(dom, element_id, name):
    match = re.search(rf'<[^>]*id="{element_id}"[^>]*>', dom)
    if not match:
        fail(f"the page has no #{element_id}")
    value = re.search(rf'{name}="([^"]*)"', match.group(0))
    if not value:
        fail(f"#{element_id} has no {name}")
    return value.group(1)


def count_near(pixels, colours, tolerance):
    """Pixels within `tolerance` (per channel, 0-255) of any of `colours`."""
    near = np.zeros(pixels.shape[0], dtype=bool)
    for colour in colours:
        near |= np.all(np.abs(pixels - colour) <= tolerance, axis=1)
    return int(near.sum())


def ramp_samples(ramp, lo=0.0, hi=1.0):
    """The height ramp between t = lo and hi, interpolated in sRGB as the page does, finely
    enough for 8-bit colours."""
    t = np.linspace(lo, hi, 512)
    x = t * (len(ramp) - 1)
    i = np.minimum(np.floor(x).astype(int), len(ramp) - 2)
    stops = np.array(ramp)
    return stops[i] + (stops[i + 1] - stops[i]) * (x - i)[:, None]


def scene_pixels(png_file):
    image = matplotlib.image.imread(png_file)
    rgb = np.round(image[:, :, :3] * 255.0)
    if rgb.shape[1] <= kPanelRight + 100:
        fail(f"screenshot too narrow: {rgb.shape[1]} px")
    return rgb[:, kPanelRight:, :].reshape(-1, 3)


def check_cut(dom, ramp, cut_file, whole_file):
    value, top = int(attribute(dom, "height-cut", "value")), int(attribute(dom, "height-cut", "max"))
    if value >= top:
        fail(f"the height cut was not applied (layer {value} of {top})")
    roof = ramp_samples(ramp, 0.9, 1.0)
    whole = count_near(scene_pixels(whole_file), roof, 3)
    cut = count_near(scene_pixels(cut_file), roof, 3)
    below = count_near(scene_pixels(cut_file), ramp_samples(ramp, 0.0, 0.85), 3)
    print(f"roof colours: {whole} px whole, {cut} px under the cut; lower cells {below} px")
    if whole < 1000:
        fail(f"the whole building shows only {whole} px of its top layers")
    if cut > 0.05 * whole:
        fail(f"the cut leaves {cut} px of the top layers ({whole} without it)")
    if below < 1000:
        fail(f"under the cut only {below} px of lower cells show")


def main(dom_file, png_file, whole_file=None):
    dom = open(dom_file, encoding="utf-8").read()
    state = attribute(dom, "status", "data-state")
    errors = re.search(r'id="errors"[^>]*>(.*?)</div>', dom, re.S)
    if state != "ready" or (errors and errors.group(1).strip()):
        fail(f"the page did not finish cleanly: state '{state}', errors: "
             f"{errors.group(1).strip() if errors else '?'}")
    # The controls a building needs (issue 27): a height cut that starts by hiding nothing,
    # a view from above, and how many of the best candidates are drawn.
    cut_max = attribute(dom, "height-cut", "max")
    uncut = attribute(dom, "height-cut", "value") == cut_max or whole_file is not None
    if not uncut or int(cut_max) < 1:
        fail(f"the height cut is not set up over the grid's layers (max {cut_max})")
    if not re.search(r'<button[^>]*id="top-view"', dom):
        fail("the page has no view-from-above button")
    if int(attribute(dom, "top-candidates", "max")) < 2:
        fail("the slider over the best candidates is not set up")
    ramp = [hex_rgb(c) for c in attribute(dom, "height-bar", "data-ramp").split(",")]
    chosen = hex_rgb(attribute(dom, "chosen-swatch", "data-color"))

    scene = scene_pixels(png_file)

    drawn = int((np.abs(scene - kBackground).max(axis=1) > 12).sum())
    if drawn < 0.01 * scene.shape[0]:
        fail(f"blank canvas: {drawn} of {scene.shape[0]} pixels differ from the background")
    occupied = count_near(scene, ramp_samples(ramp), 3)
    chosen_pixels = count_near(scene, [chosen], 3)
    print(f"drawn {drawn} px, occupied-cell colours {occupied} px, chosen-view colour "
          f"{chosen_pixels} px (of {scene.shape[0]})")
    if occupied < 100:
        fail(f"the occupied cells' colours cover only {occupied} px")
    # NOTE: a building seen whole from above draws its chosen view a few pixels wide.
    if chosen_pixels < (100 if whole_file is None else 5):
        fail(f"the chosen view's colour covers only {chosen_pixels} px")
    if whole_file is not None:
        check_cut(dom, ramp, png_file, whole_file)
    print("ok")


if __name__ == "__main__":
    if len(sys.argv) not in (3, 4):
        sys.exit(__doc__)
    main(*sys.argv[1:])
