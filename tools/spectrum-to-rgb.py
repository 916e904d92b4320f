#!/usr/bin/env python3
"""Prints the linear sRGB colour of a spectrum given as Mitsuba writes one in a scene,
"wavelength:value, wavelength:value, ...", by the method of Mitsuba's RGB variants
(tools/spectra.py), for converting Mitsuba scenes by hand:

  tools/spectrum-to-rgb.py "400:0, 500:8, 600:15.6, 700:18.4"            (an emitter's)
  tools/spectrum-to-rgb.py --reflectance "400:0.78, 500:0.78, 700:0.78"  (clamped to [0, 1])
"""
import sys

from spectra import to_rgb


def main():
    args = sys.argv[1:]
    bounded = bool(args) and args[0] == "--reflectance"
    if bounded:
        args = args[1:]
    if len(args) != 1:
        sys.exit(__doc__)
    try:
        points = [tuple(float(x) for x in pair.split(":")) for pair in args[0].split(",")]
    except ValueError:
        sys.exit("spectrum-to-rgb.py: expected wavelength:value pairs, got %r" % args[0])
    if len(points) < 2 or any(len(p) != 2 for p in points) or \
            any(b[0] <= a[0] for a, b in zip(points, points[1:])):
        sys.exit("spectrum-to-rgb.py: expected two or more wavelength:value pairs in "
                 "increasing wavelength")
    print("%.6f %.6f %.6f" % tuple(to_rgb(points, bounded)))


main()
