#!/usr/bin/env python3
"""Euclidean position error of a recording's VIO against its ground truth (SPEC §7; how
scenarios/mockup_inspection_flight.yaml was tuned).

    scripts/vio-error.py RECORDING [RECORDING ...]

vio.csv holds T_odom_body; the odom frame's origin is the first true body position and its yaw
the first true body yaw, z up (include/scantling/sim/vio.hpp). So each VIO position maps to the
world as p_world = p0 + Rz(yaw0) · p_odom, with p0 and yaw0 from the first pose of
groundtruth.tum, and is compared with the ground truth at the same stamp (the VIO samples the
clock ticks the ground truth is logged at). Every sample counts, valid or not (the pose of an
invalid sample is the drifting estimate). Prints mean, std (population), final and max, metres.
Pure Python (no numpy on the project's machines).
"""
import bisect
import csv
import math
import os
import statistics
import sys

STAMP_TOLERANCE_S = 1e-9  # stamps are the same clock ticks, printed exactly


def read_ground_truth(path):
    rows = [list(map(float, line.split())) for line in open(path)
            if line.strip() and not line.startswith("#")]
    return [r[0] for r in rows], [r[1:4] for r in rows], rows[0][4:8]


def yaw_of(qx, qy, qz, qw):
    return math.atan2(2 * (qx * qy + qz * qw), 1 - 2 * (qy * qy + qz * qz))


def vio_errors(recording):
    stamps, positions, q0 = read_ground_truth(os.path.join(recording, "groundtruth.tum"))
    p0, yaw0 = positions[0], yaw_of(*q0)
    c, s = math.cos(yaw0), math.sin(yaw0)
    errors = []
    with open(os.path.join(recording, "vio.csv")) as f:
        for row in csv.DictReader(f):
            t = float(row["stamp_s"])
            i = bisect.bisect_left(stamps, t - STAMP_TOLERANCE_S)
            if i == len(stamps) or abs(stamps[i] - t) > STAMP_TOLERANCE_S:
                sys.exit(f"vio-error: {recording}: no ground truth at the VIO stamp {t}")
            x, y, z = float(row["x"]), float(row["y"]), float(row["z"])
            p_world = (p0[0] + c * x - s * y, p0[1] + s * x + c * y, p0[2] + z)
            errors.append(math.dist(p_world, positions[i]))
    return errors


def main():
    if len(sys.argv) < 2:
        sys.exit("usage: scripts/vio-error.py RECORDING [RECORDING ...]")
    for recording in sys.argv[1:]:
        e = vio_errors(recording)
        print(f"{recording}: {len(e)} VIO samples, mean {statistics.mean(e):.4f} m, "
              f"std {statistics.pstdev(e):.4f} m, final {e[-1]:.4f} m, max {max(e):.4f} m")


if __name__ == "__main__":
    main()
