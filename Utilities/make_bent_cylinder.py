#!/usr/bin/env python3
"""Writes the bent-cylinder test mesh (OFF): a closed tube of radius r whose
axis is a half circle of radius R standing on z = 0 (an arch), so it shadows
and lights itself and the ground. Usage: make_bent_cylinder.py OUT.off"""
import math
import sys

R, r = 0.9, 0.22          # arch radius, tube radius
rings, segments = 97, 40  # along the arch, around the tube


def main(path):
    points, faces = [], []
    for i in range(rings):
        t = math.pi * i / (rings - 1)
        axis = (R * math.cos(t), 0.0, R * math.sin(t))
        # Frame: the arc's inward normal and the y axis span the tube's ring.
        n = (-math.cos(t), 0.0, -math.sin(t))
        for j in range(segments):
            a = 2 * math.pi * j / segments
            c, s = math.cos(a), math.sin(a)
            points.append((axis[0] + r * c * n[0], r * s, axis[2] + r * c * n[2]))
    for i in range(rings - 1):
        for j in range(segments):
            a, b = i * segments + j, i * segments + (j + 1) % segments
            faces.append((a, a + segments, b))
            faces.append((b, a + segments, b + segments))
    # Flat caps on the ground at both ends.
    for ring, flip in ((0, False), (rings - 1, True)):
        centre = len(points)
        t = math.pi * ring / (rings - 1)
        points.append((R * math.cos(t), 0.0, 0.0))
        for j in range(segments):
            a, b = ring * segments + j, ring * segments + (j + 1) % segments
            faces.append((centre, b, a) if not flip else (centre, a, b))
    with open(path, "w") as f:
        f.write("OFF\n%d %d 0\n" % (len(points), len(faces)))
        for p in points:
            f.write("%.6f %.6f %.6f\n" % p)
        for t in faces:
            f.write("3 %d %d %d\n" % t)


if __name__ == "__main__":
    main(sys.argv[1])
