"""Writes kheperax-maze.toml: Kheperax's "standard" maze as a fuzzymotiv room file.

Kheperax's maze is the unit square with seven interior wall segments (two more lie on the
border and are the outline here). fuzzymotiv walls are polygons, so each segment becomes a
10 mm thick quadrilateral around it; a segment that ends on the border stops 8 mm short of it
(obstacles may not touch the outline), a gap far narrower than the robot. Scale: the robot's
radius is the same fraction of the maze on both sides (Kheperax 0.015 of 1; fuzzymotiv
27.5 mm), so 1 Kheperax unit = 27.5 / 0.015 = 1833.3 mm. Home: Kheperax's start (0.15, 0.15),
heading 90 degrees. Run: python3 bench/kheperax/maze_room.py > bench/kheperax/kheperax-maze.toml
"""

import math

SCALE = 27.5 / 0.015  # mm per Kheperax unit
# kheperax/envs/maze_maps.py, "standard" (kheperax 0.2.0), without its two border segments.
SEGMENTS = [
    ((0.25, 0.25), (0.25, 0.75)),  # vertical middle
    ((0.14, 0.45), (0.0, 0.65)),  # obstacle top left
    ((0.25, 0.75), (0.0, 0.8)),  # wall to target
    ((0.25, 0.75), (0.66, 0.875)),  # wall top right
    ((0.355, 0.0), (0.525, 0.185)),  # obstacle bottom right
    ((0.25, 0.5), (0.75, 0.215)),  # funnel bottom
    ((1.0, 0.25), (0.435, 0.55)),  # funnel top
]
HALF = 5.0  # half the wall thickness, mm
MARGIN = 8.0  # gap left between a wall and the border, mm
SIDE = SCALE


def pull_in(p, q):
    """p moved towards q until it is MARGIN inside the border (if it is on or near it)."""
    (px, py), (qx, qy) = p, q
    length = math.hypot(qx - px, qy - py)
    ux, uy = (qx - px) / length, (qy - py) / length
    t = 0.0
    for c, u in ((px, ux), (py, uy)):
        for edge in (0.0, SIDE):
            if abs(c - edge) < MARGIN + HALF and u != 0:
                t = max(t, (MARGIN + HALF - abs(c - edge)) / abs(u))
    return (px + ux * t, py + uy * t)


def quad(a, b):
    a, b = [(x * SCALE, y * SCALE) for x, y in (a, b)]
    a, b = pull_in(a, b), pull_in(b, a)
    dx, dy = b[0] - a[0], b[1] - a[1]
    n = math.hypot(dx, dy)
    nx, ny = -dy / n * HALF, dx / n * HALF
    pts = [(a[0] + nx, a[1] + ny), (b[0] + nx, b[1] + ny), (b[0] - nx, b[1] - ny), (a[0] - nx, a[1] - ny)]
    return "[" + ",".join(f"[{x:.1f},{y:.1f}]" for x, y in pts) + "]"


side = f"{SIDE:.1f}"
print("# Kheperax's standard maze (kheperax 0.2.0) in millimetres: bench/kheperax/maze_room.py wrote it.")
print('name = "kheperax-maze"')
print(f"outline = [[0,0],[{side},0],[{side},{side}],[0,{side}]]")
print(f"home = {{ x = {0.15 * SCALE:.1f}, y = {0.15 * SCALE:.1f}, heading_deg = 90 }}")
for a, b in SEGMENTS:
    print()
    print("[[obstacles]]")
    print(f"outline = {quad(a, b)}")
