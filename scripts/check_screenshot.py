#!/usr/bin/python3
"""Checks an RViz screenshot (scripts/screenshot.sh) for the impulse2d marker colours.

  check_screenshot.py SHOT.png --expect static,awake,asleep,... [--junit FILE --name NAME]

Finds the 3D view (the columns and rows mostly of the RViz configs' background colour), counts
the pixels of each marker colour in it (by hue, since RViz shades and antialiases the lines) and
fails unless every expected colour covers at least MIN_PIXELS, and unless the markers spread over
at least MIN_SPREAD of the view's width and height (a view that looks at the plane edge-on
squeezes them into a line). Writes one JUnit test case per expected colour, and one for the
spread, with --junit. Exit 0 when all are present, 1 when one is missing, 2 on bad input.
"""
import argparse
import colorsys
import sys
import xml.etree.ElementTree as ET

from PIL import Image

VIEW_BACKGROUND = (48, 48, 48)  # Global Options / Background Color in rviz/impulse2d_*.rviz
MIN_SPREAD = 0.2  # the scenes' bodies span most of the view in both directions
MIN_PIXELS = 40  # true marker colours cover hundreds; antialiased mixes of others a few dozen at most

# The colours of src/ros/markers.cpp, as hue ranges in degrees (saturated pixels only), and the
# static grey as a brightness range (the grid is drawn at 30% alpha and stays darker). The robot
# demo adds the colours of rviz/robot_demo.rviz and config/round_robot.urdf.
HUES = {
    "contact_point": [(345, 360), (0, 12)],  # red (1.0, 0.2, 0.2)
    "kinematic": [(22, 40)],                 # orange (1.0, 0.6, 0.1)
    "contact_normal": [(45, 62)],            # yellow (1.0, 0.9, 0.2)
    "awake": [(110, 150)],                   # green (0.2, 0.9, 0.3)
    "scan": [(170, 195)],                    # cyan LaserScan (0, 230, 230)
    "asleep": [(215, 240)],                  # blue (0.35, 0.45, 0.9)
    "robot": [(250, 280)],                   # violet RobotModel shell (0.55, 0.35, 0.85)
    "joint": [(285, 315)],                   # magenta (0.9, 0.3, 0.9)
    "odometry": [(318, 338)],                # pink Odometry arrows (255, 120, 200)
}
STATIC_GREY = (110, 200)  # 0..255 brightness of unsaturated pixels: grey (0.6, 0.6, 0.6), lit
COLOURS = ["static"] + list(HUES)


def view_box(image):
    """(left, top, right, bottom) of the 3D view: the span of columns and rows that are more than
    half background (grid lines and markers cover the rest)."""
    width, height = image.size
    pixels = image.load()
    columns = [0] * width
    rows = [0] * height
    for y in range(height):
        for x in range(width):
            if pixels[x, y] == VIEW_BACKGROUND:
                columns[x] += 1
                rows[y] += 1
    xs = [x for x in range(width) if columns[x] > height // 2]
    ys = [y for y in range(height) if rows[y] > width // 4]
    if not xs or not ys:
        return None
    return (xs[0], ys[0], xs[-1] + 1, ys[-1] + 1)


def classify(rgb):
    r, g, b = (c / 255.0 for c in rgb)
    hue, saturation, value = colorsys.rgb_to_hsv(r, g, b)
    if saturation < 0.06:
        return "static" if STATIC_GREY[0] <= value * 255 <= STATIC_GREY[1] else None
    if saturation < 0.35 or value < 0.25:
        return None  # antialiased edges and the grid
    degrees = hue * 360.0
    for name, ranges in HUES.items():
        if any(low <= degrees < high for low, high in ranges):
            return name
    return None


def count_colours(image, box):
    counts = dict.fromkeys(COLOURS, 0)
    for n, rgb in image.crop(box).getcolors(maxcolors=1 << 24):
        name = classify(rgb)
        if name:
            counts[name] += n
    return counts


def marker_spread(image, box):
    """Width and height of the box around every marker-coloured pixel, as fractions of the view."""
    view = image.crop(box)
    pixels = view.load()
    width, height = view.size
    xs, ys = [], []
    for y in range(height):
        for x in range(width):
            if classify(pixels[x, y]):
                xs.append(x)
                ys.append(y)
    if not xs:
        return 0.0, 0.0
    return (max(xs) - min(xs) + 1) / width, (max(ys) - min(ys) + 1) / height


def write_junit(path, suite, cases):
    root = ET.Element("testsuite", name=suite, tests=str(len(cases)),
                      failures=str(sum(1 for _, failure in cases if failure)))
    for name, failure in cases:
        case = ET.SubElement(root, "testcase", classname=suite, name=name)
        if failure:
            ET.SubElement(case, "failure", message=failure).text = failure
    ET.ElementTree(root).write(path, encoding="utf-8", xml_declaration=True)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("shot")
    parser.add_argument("--expect", required=True,
                        help="comma-separated, of: " + ", ".join(COLOURS))
    parser.add_argument("--junit", help="write a JUnit XML file here")
    parser.add_argument("--name", default="screenshot", help="the JUnit suite's name")
    args = parser.parse_args()
    expected = [c for c in args.expect.split(",") if c]
    unknown = [c for c in expected if c not in COLOURS]
    if unknown:
        parser.error("unknown colour(s) %s; known: %s" % (", ".join(unknown), ", ".join(COLOURS)))

    try:
        image = Image.open(args.shot).convert("RGB")
    except OSError as error:
        print("check_screenshot: cannot read %s: %s" % (args.shot, error), file=sys.stderr)
        return 2
    box = view_box(image)
    if box is None:
        failure = "no 3D view (no area of the background colour %s) in %s" % (
            VIEW_BACKGROUND, args.shot)
        cases = [(c, failure) for c in expected + ["spread"]]
    else:
        counts = count_colours(image, box)
        print("%s: 3D view %dx%d+%d+%d; pixels: %s" % (
            args.shot, box[2] - box[0], box[3] - box[1], box[0], box[1],
            ", ".join("%s %d" % (c, counts[c]) for c in COLOURS)))
        cases = [(c, None if counts[c] >= MIN_PIXELS else
                  "%s markers: %d pixels in the 3D view, expected >= %d" % (c, counts[c], MIN_PIXELS))
                 for c in expected]
        spread = marker_spread(image, box)
        print("%s: markers span %.0f%% x %.0f%% of the view" % (
            args.shot, 100 * spread[0], 100 * spread[1]))
        cases.append(("spread", None if min(spread) >= MIN_SPREAD else
                      "the markers span %.0f%% x %.0f%% of the view, expected >= %.0f%% each "
                      "(is the view looking at the plane?)" % (
                          100 * spread[0], 100 * spread[1], 100 * MIN_SPREAD)))
    for _, failure in cases:
        if failure:
            print("check_screenshot: FAILED: " + failure, file=sys.stderr)
    if args.junit:
        write_junit(args.junit, args.name, cases)
    return 1 if any(failure for _, failure in cases) else 0


if __name__ == "__main__":
    sys.exit(main())
