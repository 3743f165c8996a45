#!/usr/bin/python3
"""Writes a synthetic floor plan in map_server's format (a binary PGM and its YAML), to measure
how maps load (README "Maps"): rooms of `--room` m in a grid, walls 0.2 m thick with a doorway in
each, a few pieces of furniture per room, unknown space around the building.

  make_floor_plan.py OUT_PREFIX [--cells 4000] [--resolution 0.05] [--room 4.0] [--seed 1]
                     [--speckle 0.0]

--speckle F occupies that fraction of the free cells at random, one by one, as a noisy scan
leaves them: the worst case for merging cells into blocks.

writes OUT_PREFIX.pgm and OUT_PREFIX.yaml.
"""
import argparse
import os
import random


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("out")
    p.add_argument("--cells", type=int, default=4000)
    p.add_argument("--resolution", type=float, default=0.05)
    p.add_argument("--room", type=float, default=4.0)
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--speckle", type=float, default=0.0)
    a = p.parse_args()
    n, rng = a.cells, random.Random(a.seed)
    FREE, WALL, UNKNOWN = 254, 0, 205
    img = bytearray([UNKNOWN]) * (n * n)
    margin = n // 20
    lo, hi = margin, n - margin
    for y in range(lo, hi):
        img[y * n + lo:y * n + hi] = bytes([FREE]) * (hi - lo)

    def box(x0, y0, x1, y1, v=WALL):
        x0, y0, x1, y1 = max(x0, 0), max(y0, 0), min(x1, n), min(y1, n)
        for y in range(y0, y1):
            img[y * n + x0:y * n + x1] = bytes([v]) * (x1 - x0)

    room = int(a.room / a.resolution)
    wall = max(1, int(0.2 / a.resolution))
    door = int(0.9 / a.resolution)
    for y in range(lo, hi + 1, room):
        box(lo, y, hi, y + wall)
    for x in range(lo, hi + 1, room):
        box(x, lo, x + wall, hi)
    box(lo, hi - wall, hi, hi)  # the outer walls on the far sides, where the grid may stop short
    box(hi - wall, lo, hi, hi)
    for ry in range(lo, hi - wall, room):
        for rx in range(lo, hi - wall, room):
            # A doorway in the room's south and west walls, unless they are the outer walls.
            size = min(room, hi - rx), min(room, hi - ry)  # the last row and column may be short
            d = rng.randrange(wall + 2, max(wall + 3, size[0] - door - 2))
            if ry > lo:
                box(rx + d, ry, rx + d + door, ry + wall, FREE)
            d = rng.randrange(wall + 2, max(wall + 3, size[1] - door - 2))
            if rx > lo:
                box(rx, ry + d, rx + wall, ry + d + door, FREE)
            for _ in range(rng.randrange(0, 4) if min(size) == room else 0):  # tables, shelves
                w, h = rng.randrange(6, room // 3), rng.randrange(6, room // 3)
                x0 = rng.randrange(rx + 2 * wall, rx + room - w - 2 * wall)
                y0 = rng.randrange(ry + 2 * wall, ry + room - h - 2 * wall)
                box(x0, y0, x0 + w, y0 + h)
    for _ in range(int(a.speckle * (hi - lo) ** 2)):
        i = rng.randrange(lo, hi) * n + rng.randrange(lo, hi)
        if img[i] == FREE:
            img[i] = WALL
    with open(a.out + ".pgm", "wb") as f:
        f.write(b"P5\n%d %d\n255\n" % (n, n))
        f.write(bytes(img))
    with open(a.out + ".yaml", "w") as f:
        f.write("image: %s.pgm\nresolution: %g\norigin: [%g, %g, 0.0]\nnegate: 0\n"
                "occupied_thresh: 0.65\nfree_thresh: 0.196\n"
                % (os.path.basename(a.out), a.resolution, -n * a.resolution / 2,
                   -n * a.resolution / 2))


if __name__ == "__main__":
    main()
