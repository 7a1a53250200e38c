#!/usr/bin/env python3
"""Cost model of one distributed GI update, fitted to measurements made on
this 2-core machine (2026-12-03, Documentation/ParaView.md, "Scaling and cost
model"), extrapolated to 64-1024 ranks. Prints Markdown tables.

    cost_model.py [--net-alpha S] [--net-beta S_PER_BYTE]

Every constant below is a measurement; the extrapolation is the model's.
"""
import argparse
import math

# Shading (vtkPGIGlobalIllumination, bunny on a 128x128 ground, sky and a
# reflecting ground, shadowed bounce, flat proxies, one thread): seconds per
# update for (spheres, receivers).
SHADING = [(16, 289, 0.0216), (16, 54347, 0.2660), (32, 289, 0.0368), (32, 54347, 0.3896),
           (64, 289, 0.0183), (64, 54347, 0.7164), (128, 289, 0.0213), (128, 54347, 1.3318),
           (256, 289, 0.0273), (256, 54347, 1.8576)]
# The same with a hierarchy cut at 25 degrees: spheres -> (seconds, mean cut).
CUT = {32: (0.370, 21.3), 128: (0.642, 62.9), 512: (1.188, 151.3), 2048: (2.178, 316.2)}
# Proxy build (k-means, one piece of the bunny): (triangles, spheres, seconds).
BUILD = [(75408, 32, 0.4674), (49524, 16, 0.1527), (24809, 8, 0.0378), (9403, 4, 0.0128)]
# MPI all-gather on this machine (shared memory, np 2, median of 15):
ALPHA, BETA = 1.16e-6, 2.31e-10  # s, s per byte received
SPHERE_BYTES = 70.0  # on the wire per gathered sphere (2230 B for 32)
SAMPLER_RAYS_PER_SPHERE = 601.0  # 19232 rays for 32 spheres
SAMPLER_RAY_BYTES = 88.0  # received per ray per other rank
SAMPLER_SECONDS_PER_RAY = 0.055 / 19232  # serial sampler
IMAGE_BYTES_PER_PIXEL = 8.0  # IceT: RGBA8 + float depth


def least_squares(rows, columns):
    """Solves min |A x - b| for small dense A (normal equations)."""
    n = len(columns(rows[0])[0])
    ata = [[0.0] * n for _ in range(n)]
    atb = [0.0] * n
    for r in rows:
        a, b = columns(r)
        for i in range(n):
            atb[i] += a[i] * b
            for j in range(n):
                ata[i][j] += a[i] * a[j]
    for i in range(n):  # Gauss-Jordan
        p = ata[i][i]
        for j in range(n):
            ata[i][j] /= p
        atb[i] /= p
        for k in range(n):
            if k != i:
                f = ata[k][i]
                for j in range(n):
                    ata[k][j] -= f * ata[i][j]
                atb[k] -= f * atb[i]
    return atb


# t = F + N (a + b S)
F, A, B = least_squares(SHADING, lambda r: ([1.0, r[1], r[1] * r[0]], r[2]))
# t = c T s (k-means: every triangle against every sphere of its piece)
C_BUILD = sum(t for _, _, t in BUILD[:3]) / sum(tri * s for tri, s, _ in BUILD[:3])
# Power laws through the cut measurements (32 and 2048 spheres).
CUT_TIME_EXP = math.log(CUT[2048][0] / CUT[32][0]) / math.log(64)
CUT_SIZE_EXP = math.log(CUT[2048][1] / CUT[32][1]) / math.log(64)


def shading(spheres, receivers):
    return F + receivers * (A + B * spheres)


def shading_cut(spheres):
    """Per rank with 54,347 receivers, cut at 25 degrees (one object: pessimistic)."""
    return CUT[32][0] * (spheres / 32.0) ** CUT_TIME_EXP


def cut_size(spheres):
    return CUT[32][1] * (spheres / 32.0) ** CUT_SIZE_EXP


def allgather(ranks, bytes_per_rank, alpha, beta):
    if ranks < 2:
        return 0.0
    return alpha * math.ceil(math.log2(ranks)) + beta * (ranks - 1) * bytes_per_rank


def fmt_bytes(b):
    for unit, size in (("GB", 1e9), ("MB", 1e6), ("kB", 1e3)):
        if b >= size:
            return "%.3g %s" % (b / size, unit)
    return "%.0f B" % b


def fmt_s(s):
    if s < 1e-3:
        return "%.3g us" % (s * 1e6)
    if s < 1.0:
        return "%.3g ms" % (s * 1e3)
    return "%.3g s" % s


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--net-alpha", type=float, default=2e-6,
                        help="interconnect latency per all-gather step (assumed; default 2 us)")
    parser.add_argument("--net-beta", type=float, default=1e-10,
                        help="interconnect seconds per byte (assumed; default 10 GB/s)")
    args = parser.parse_args()
    ranks_list = [1, 2, 64, 256, 1024]
    print("Fitted: shading t = %.3g s + N (%.3g s + %.3g s x S); build t = %.3g s x triangles x "
          "spheres of the piece; cut size ~ S^%.2f, cut shading time ~ S^%.2f\n"
          % (F, A, B, C_BUILD, CUT_SIZE_EXP, CUT_TIME_EXP))

    n, tri, s = 54347, 75408, 32
    print("Strong scaling: this scene (%d receivers, %d occluder triangles, %d spheres) "
          "split over P ranks, per rank per update:\n" % (n, tri, s))
    print("| P | proxy build | proxies all-gather (net) | shading | sampler gather (bytes, net) "
          "| sampler rays | total | speed-up |")
    print("|---|---|---|---|---|---|---|---|")
    t1 = None
    for p in ranks_list:
        build = C_BUILD * (tri / p) * max(1.0, s / p)
        gather = allgather(p, s / p * SPHERE_BYTES, args.net_alpha, args.net_beta)
        shade = shading(s, n / p)
        rays = SAMPLER_RAYS_PER_SPHERE * s
        sampler_bytes = (p - 1) * rays * SAMPLER_RAY_BYTES
        sampler = allgather(p, rays * SAMPLER_RAY_BYTES, args.net_alpha, args.net_beta)
        trace = rays * SAMPLER_SECONDS_PER_RAY
        total = build + gather + shade + sampler + trace
        t1 = t1 or total
        print("| %d | %s | %s | %s | %s, %s | %s | %s | %.1fx |"
              % (p, fmt_s(build), fmt_s(gather), fmt_s(shade), fmt_bytes(sampler_bytes),
                 fmt_s(sampler), fmt_s(trace), fmt_s(total), t1 / total))

    print("\nWeak scaling: every rank holds this scene's size (%d receivers, %d triangles, %d "
          "spheres), S = %d P global spheres, per rank per update:\n" % (n, tri, s, s))
    print("| P | S | proxies received | all-gather (this machine) | all-gather (net) "
          "| shading, flat | shading, cut at 25 deg (cut size) | sampler received |")
    print("|---|---|---|---|---|---|---|---|")
    for p in ranks_list:
        big_s = s * p
        received = (p - 1) * s * SPHERE_BYTES
        print("| %d | %d | %s | %s | %s | %s | %s (%.0f) | %s |"
              % (p, big_s, fmt_bytes(received), fmt_s(allgather(p, s * SPHERE_BYTES, ALPHA, BETA)),
                 fmt_s(allgather(p, s * SPHERE_BYTES, args.net_alpha, args.net_beta)),
                 fmt_s(shading(big_s, n)), fmt_s(shading_cut(big_s)), cut_size(big_s),
                 fmt_bytes((p - 1) * SAMPLER_RAYS_PER_SPHERE * big_s * SAMPLER_RAY_BYTES)))

    # Where the gather's cost reaches 1% of the cheapest per-rank update.
    floor = shading_cut(s)
    p = 1
    while allgather(p, s * SPHERE_BYTES, args.net_alpha, args.net_beta) < 0.01 * floor:
        p *= 2
    print("\nThe proxies' all-gather (net) reaches 1%% of a %.3g s update at P = %d ranks "
          "(%s per rank)." % (floor, p, fmt_bytes((p - 1) * s * SPHERE_BYTES)))
    print("IceT, per frame and rank: up to %.0f bytes per pixel (1920x1080: %s), whatever GI "
          "runs." % (IMAGE_BYTES_PER_PIXEL, fmt_bytes(IMAGE_BYTES_PER_PIXEL * 1920 * 1080)))


if __name__ == "__main__":
    main()
