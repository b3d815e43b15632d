#!/usr/bin/python3
"""Measure, in Enki, a robot's front IR sensor against the distance to a wall.

Debian's Enki bindings (`apt-get install python3-enki2`, module `pyenki`, installed into Debian's
own /usr/bin/python3) give the e-puck and the Thymio II models. For each robot this script puts
the robot in a walled world with one front sensor facing the east wall, at perpendicular
distances on a 1 mm grid and at three incidence angles (0°, 30°, 60° between the sensor's axis
and the wall's normal), holds it still, reads the sensor SAMPLES times (Enki adds Gaussian
noise to every reading) and writes one CSV row per pose:

    robot, sensor, incidence_deg, perp_mm, axis_mm, samples, median, mean, sd,
    enki_formula, axis_formula

- `perp_mm`: distance from the sensor to the wall along the wall's normal (mm);
- `axis_mm`: distance along the sensor's axis = perp_mm / cos(incidence) (mm);
- `median`, `mean`, `sd`: of the SAMPLES readings (the median is unbiased by Enki's clamping
  to [0, m], the mean is not);
- `enki_formula`: Enki's noise-free value from its source (IRSensor.cpp: three rays at −15°, 0,
  +15°, F(left) + F(right) + F(centre) − 2·F(centre/cos 15°), clamped to [0, m]);
- `axis_formula`: F(axis_mm), what one ray along the axis reads (the robot files' model before
  sampling).

Poses where the body would overlap the wall are left out (Enki would push the robot away).
Then the head-on rows (incidence 0) give the response table: the medians, made non-increasing
with distance (a running minimum), sampled at most 64 distances so that the largest step
between consecutive samples is as small as possible. The tables are printed as TOML `[[ray]]`
blocks, ready for robots/<name>.toml.

Run from the repository root (about 30 s):

    /usr/bin/python3 bench/enki/probe_robots.py            # writes bench/enki/probe_robots.csv
    /usr/bin/python3 bench/enki/probe_robots.py --samples 101 --out /tmp/probe.csv
    /usr/bin/python3 bench/enki/probe_robots.py --out /tmp/probe.csv --bench configs/sensors
        # also configs/sensors/{epuck2,thymio2}-enki-bench.csv, calibrate's input format

Deterministic only up to Enki's noise (its random generator is seeded by Enki, not here); the
committed CSV is one run. Units: Enki works in cm; this script converts to mm.
"""

import argparse
import csv
import math
import statistics
import sys

import pyenki

# Each probed robot: its Enki class, the probed sensor (index into proximitySensorValues, the
# firmware's numbering), the sensor's mount and Enki's response constants, all from the Enki
# source (enki-community/enki @ bb486bf, enki/robots/e-puck/EPuck.cpp L84-91 and
# enki/robots/thymio2/Thymio2.cpp L49-55; see docs/robots-sources.md §1.3 and §2.1).
ROBOTS = {
    "epuck2": {
        "make": pyenki.EPuck,
        "sensor": 0,  # IR0 front-right
        "mount_cm": (3.35, -1.05),
        "facing_deg": -18.0,
        "m": 3731.0,
        "x0_cm": 0.3,
        "c_cm2": 0.7,
        "range_cm": 12.0,
    },
    "thymio2": {
        "make": pyenki.Thymio2,
        "sensor": 2,  # prox.horizontal[2] front middle
        "mount_cm": (7.95, 0.0),
        "facing_deg": 0.0,
        "m": 4505.0,
        "x0_cm": 0.03,
        "c_cm2": 73.0,
        "range_cm": 14.0,
    },
}

WORLD_CM = 100.0  # the walled square world's side (cm)
INCIDENCES_DEG = (0.0, 30.0, 60.0)
APERTURE_DEG = 15.0  # Enki's IRSensor: rays at −15°, 0, +15°
MAX_SAMPLES = 64  # the robot file's limit on samples per ray


def response(robot, x_cm):
    """Enki's per-ray response F(x) (IRSensor::responseFunction), x in cm."""
    m, x0, c, rng = robot["m"], robot["x0_cm"], robot["c_cm2"], robot["range_cm"]
    if x_cm < x0:
        return m
    if x_cm > rng:
        return 0.0
    return m * (c - x0 * x0) / (x_cm * x_cm - 2.0 * x0 * x_cm + c)


def ray_distance(robot, perp_cm, angle_deg):
    """Distance (cm) along a ray at angle_deg from the wall's normal, or None if it misses
    the wall within the sensor's range (Enki keeps only hits nearer than the range)."""
    cos = math.cos(math.radians(angle_deg))
    if cos <= 1e-9:
        return None
    d = perp_cm / cos
    return d if d < robot["range_cm"] else None


def enki_formula(robot, perp_cm, incidence_deg):
    """Enki's noise-free three-ray value for a flat wall (IRSensor::updateRay, ::finalize)."""
    alpha = 1.0 / math.cos(math.radians(APERTURE_DEG))
    total = 0.0
    for k, offset in enumerate((-APERTURE_DEG, 0.0, APERTURE_DEG)):
        d = ray_distance(robot, perp_cm, incidence_deg + offset)
        if d is None:
            continue
        total += response(robot, d)
        if k == 1:
            total -= 2.0 * response(robot, d * alpha)
    return min(robot["m"], max(0.0, total))


def pose_for(robot, perp_cm, incidence_deg):
    """The robot pose (x, y in cm, angle in rad) putting the sensor perp_cm from the east wall
    with its axis incidence_deg from the wall's normal (+x)."""
    angle = math.radians(incidence_deg - robot["facing_deg"])
    mx, my = robot["mount_cm"]
    sx = mx * math.cos(angle) - my * math.sin(angle)
    sy = mx * math.sin(angle) + my * math.cos(angle)
    return WORLD_CM - perp_cm - sx, WORLD_CM / 2.0 - sy, angle


def measure(robot, perp_cm, incidence_deg, samples):
    """The sensor's readings at one pose, or None if the body overlaps the wall there.

    Each pose gets a new world and robot: Debian's Enki (1.6.99, packaged 2020) predates Enki
    commit 7dbaa0b (2021-05-18, "Fixed IR sensor initialisation", issue #68), so a ray keeps
    its last value when it stops hitting anything; a fresh robot's rays start at 0."""
    x, y, angle = pose_for(robot, perp_cm, incidence_deg)
    if not body_clear(robot, x, y, angle):
        return None
    world = pyenki.World(WORLD_CM, WORLD_CM, pyenki.Color(0.9, 0.9, 0.9))
    body = robot["make"]()
    world.addObject(body)
    readings = []
    for _ in range(samples):
        body.pos = (x, y)
        body.angle = angle
        body.leftSpeed = body.rightSpeed = 0.0
        world.step(0.1, 1)
        moved = math.hypot(body.pos[0] - x, body.pos[1] - y)
        if moved > 1e-9:
            return None  # Enki's collision pushed the body: it overlapped the wall
        readings.append(list(body.proximitySensorValues)[robot["sensor"]])
    return readings


def body_clear(robot, x, y, angle):
    """Whether the body's farthest point east stays inside the world (the e-puck is a disc;
    the Thymio's hull reaches 8 cm forward, 3 cm back and 5.5 cm sideways, Thymio2.cpp L74-86)."""
    if robot["make"] is pyenki.EPuck:
        return x + 3.7 <= WORLD_CM
    hull = [(8.0 * math.cos(math.radians(a)), 8.0 * math.sin(math.radians(a)))
            for a in range(-43, 44)] + [(-3.0, 5.5), (-3.0, -5.5)]
    east = max(x + px * math.cos(angle) - py * math.sin(angle) for px, py in hull)
    return east <= WORLD_CM


def probe(name, robot, samples, grid_mm):
    """All CSV rows of one robot."""
    rows = []
    for incidence in INCIDENCES_DEG:
        for perp_mm in grid_mm:
            readings = measure(robot, perp_mm / 10.0, incidence, samples)
            if readings is None:
                continue
            axis_mm = perp_mm / math.cos(math.radians(incidence))
            rows.append({
                "robot": name,
                "sensor": robot["sensor"],
                "incidence_deg": incidence,
                "perp_mm": perp_mm,
                "axis_mm": round(axis_mm, 3),
                "samples": samples,
                "median": statistics.median(readings),
                "mean": round(statistics.fmean(readings), 2),
                "sd": round(statistics.pstdev(readings), 2),
                "enki_formula": round(enki_formula(robot, perp_mm / 10.0, incidence), 2),
                "axis_formula": round(response(robot, axis_mm / 10.0), 2),
            })
    return rows


def head_on_curve(rows):
    """(distance mm, reading) of the head-on rows up to the last non-zero reading: medians
    rounded to whole numbers, made non-increasing by a running minimum."""
    curve, low = [], math.inf
    for row in rows:
        if row["incidence_deg"] != 0.0:
            continue
        low = min(low, round(row["median"]))
        curve.append((row["perp_mm"], low))
    while curve and curve[-1][1] == 0:
        curve.pop()
    return curve


def greedy_samples(curve, tolerance):
    """Sample indices such that, read as 'the first sample at or beyond d', every grid
    distance's reading is at most `tolerance` above its sample's reading; the last point is
    always a sample."""
    picks, start = [], 0
    while start < len(curve):
        end = start
        while end + 1 < len(curve) and curve[start][1] - curve[end + 1][1] <= tolerance:
            end += 1
        picks.append(end)
        start = end + 1
    return picks


def table(curve):
    """The fewest-error table of at most MAX_SAMPLES samples: the smallest whole tolerance whose
    greedy sampling fits, and that tolerance."""
    lo, hi = 0, max(r for _, r in curve)
    while lo < hi:
        mid = (lo + hi) // 2
        if len(greedy_samples(curve, mid)) <= MAX_SAMPLES:
            hi = mid
        else:
            lo = mid + 1
    return [curve[i] for i in greedy_samples(curve, lo)], lo


def print_table(name, rows):
    """Print the robot file's [[ray]] block derived from the head-on rows."""
    curve = head_on_curve(rows)
    if not curve:
        print(f"# {name}: no head-on reading above 0", file=sys.stderr)
        return
    samples, tolerance = table(curve)
    print(f"# {name}: {len(samples)} samples, largest step between samples {tolerance}")
    print("[[ray]]\nangle_deg = 0.0")
    print("distance_mm = [" + ", ".join(f"{d:.1f}" for d, _ in samples) + "]")
    print("reading = [" + ", ".join(str(r) for _, r in samples) + "]\n")


def write_bench(name, robot, path, per_distance=5):
    """Enki's robot as if measured on a bench, in `fuzzymotiv calibrate`'s format: every sensor
    alike, so sensor 0 only (its table then serves all), head-on, every 5 mm out to 5 mm beyond
    the range, `per_distance` readings each, rounded to whole numbers as firmware reports them."""
    last_mm = int(robot["range_cm"] * 10) + 5
    with open(path, "w") as f:
        f.write(f"# Enki's {name} model measured as on a bench (bench/enki/probe_robots.py --bench):\n"
                f"# its sensor {robot['sensor']} head-on to a wall, {per_distance} readings per distance,"
                " Enki's noise included.\n# Not a real robot: a stand-in for your own measurements.\n"
                "sensor,distance_mm,reading\n")
        for d in range(5, last_mm + 1, 5):
            readings = measure(robot, d / 10.0, 0.0, per_distance)
            for v in readings or []:
                f.write(f"0,{d},{round(v)}\n")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--samples", type=int, default=2001, help="readings per pose")
    parser.add_argument("--out", default="bench/enki/probe_robots.csv", help="CSV to write")
    parser.add_argument("--bench", metavar="DIR",
                        help="also write DIR/<robot>-enki-bench.csv for `fuzzymotiv calibrate`")
    args = parser.parse_args()
    if args.samples < 1:
        parser.error("--samples must be at least 1")
    all_rows = []
    for name, robot in ROBOTS.items():
        last_mm = int(robot["range_cm"] * 10) + 5
        rows = probe(name, robot, args.samples, [float(d) for d in range(0, last_mm + 1)])
        print_table(name, rows)
        all_rows.extend(rows)
        if args.bench:
            write_bench(name, robot, f"{args.bench}/{name}-enki-bench.csv")
    with open(args.out, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(all_rows[0].keys()), lineterminator="\n")
        writer.writeheader()
        writer.writerows(all_rows)
    print(f"wrote {len(all_rows)} rows to {args.out}", file=sys.stderr)


if __name__ == "__main__":
    main()
