#!/usr/bin/env python3
"""Cross-checks `radarslam eval` against an independent pure-Python transcription of the KITTI
devkit's calcSequenceErrors (4x4 matrices, general inverse, acos-of-trace rotation error).

Usage: devkit_crosscheck.py RADARSLAM_BINARY OXFORD_SEQUENCE_DIR
Builds ground truth by chaining gt/radar_odometry.csv, an estimate with a 1 % scale error and a
yaw drift of 5e-5 rad per metre (0.29 deg/100 m), writes both as TUM, runs `radarslam eval --json` and compares the
KITTI numbers. Exits 1 on a mismatch above 1e-6 (relative). Needs only the Python standard library.
"""
import bisect, json, math, os, subprocess, sys, tempfile


def mat(yaw, x, y):
    c, s = math.cos(yaw), math.sin(yaw)
    return [[c, -s, 0, x], [s, c, 0, y], [0, 0, 1, 0], [0, 0, 0, 1]]


def mul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(4)) for j in range(4)] for i in range(4)]


def inv(a):  # Gauss-Jordan, as general as the devkit's Matrix::inv
    n = 4
    m = [row[:] + [1.0 if i == j else 0.0 for j in range(n)] for i, row in enumerate(a)]
    for c in range(n):
        p = max(range(c, n), key=lambda r: abs(m[r][c]))
        m[c], m[p] = m[p], m[c]
        pv = m[c][c]
        m[c] = [v / pv for v in m[c]]
        for r in range(n):
            if r != c:
                f = m[r][c]
                m[r] = [x - f * y for x, y in zip(m[r], m[c])]
    return [row[n:] for row in m]


def devkit(gt, est, step, lengths=(100, 200, 300, 400, 500, 600, 700, 800)):
    dist = [0.0]
    for i in range(1, len(gt)):
        dist.append(dist[-1] + math.dist([gt[i][r][3] for r in range(3)], [gt[i - 1][r][3] for r in range(3)]))
    err = []
    for first in range(0, len(gt), step):
        for length in lengths:
            last = bisect.bisect_right(dist, dist[first] + length)  # first i with dist[i] > start + L
            if last >= len(dist):
                continue
            pose_delta_gt = mul(inv(gt[first]), gt[last])
            pose_delta_result = mul(inv(est[first]), est[last])
            e = mul(inv(pose_delta_result), pose_delta_gt)
            d = 0.5 * (e[0][0] + e[1][1] + e[2][2] - 1.0)
            err.append((math.acos(max(min(d, 1.0), -1.0)) / length, math.hypot(e[0][3], e[1][3], e[2][3]) / length))
    t = 100 * sum(x[1] for x in err) / len(err)
    r = 100 * 180 / math.pi * sum(x[0] for x in err) / len(err)
    return len(err), t, r


def main():
    binary, seq = sys.argv[1], sys.argv[2]
    rows = open(os.path.join(seq, "gt", "radar_odometry.csv")).read().strip().split("\n")[1:]
    gt, est = [], []
    g = [0.0, 0.0, 0.0]
    e = [0.0, 0.0, 0.0]
    for k, row in enumerate(rows):
        f = row.split(",")
        if k == 0:
            gt.append((int(f[1]), *g))
            est.append((int(f[1]), *e))
        dx, dy, dth = float(f[2]), float(f[3]), float(f[7])
        g = [g[0] + math.cos(g[2]) * dx - math.sin(g[2]) * dy, g[1] + math.sin(g[2]) * dx + math.cos(g[2]) * dy, g[2] + dth]
        ex, ey, eth = 1.01 * dx, 1.01 * dy, dth + 5e-5 * math.hypot(dx, dy)
        e = [e[0] + math.cos(e[2]) * ex - math.sin(e[2]) * ey, e[1] + math.sin(e[2]) * ex + math.cos(e[2]) * ey, e[2] + eth]
        gt.append((int(f[0]), *g))
        est.append((int(f[0]), *e))
    with tempfile.TemporaryDirectory() as tmp:
        files = {}
        for name, traj in (("gt", gt), ("est", est)):
            files[name] = os.path.join(tmp, name + ".txt")
            with open(files[name], "w") as out:
                for t, x, y, th in traj:
                    out.write("%d.%06d %.6f %.6f 0 0 0 %.9f %.9f\n" % (t // 10**6, t % 10**6, x, y, math.sin(th / 2), math.cos(th / 2)))
        report = os.path.join(tmp, "report.json")
        subprocess.run([binary, "eval", files["est"], files["gt"], "--json", report], check=True, stdout=subprocess.DEVNULL)
        ours = json.load(open(report))["kitti"]
        # Re-read the written files so both sides see the same (rounded) numbers.
        load = lambda fn: [mat(math.atan2(2 * (v[6] * v[5] + v[3] * v[4]), 1 - 2 * (v[4] ** 2 + v[5] ** 2)), v[0], v[1])
                           for v in ([float(x) for x in l.split()[1:]] for l in open(fn))]
        n, t, r = devkit(load(files["gt"]), load(files["est"]), ours["step_frames"])
    print("devkit (Python):  %d segments  %.9f %%  %.9f deg/100m" % (n, t, r))
    print("radarslam eval:   %d segments  %.9f %%  %.9f deg/100m" % (ours["segments"], ours["t_err_percent"], ours["r_err_deg_per_100m"]))
    ok = n == ours["segments"] and abs(t - ours["t_err_percent"]) <= 1e-6 * t and abs(r - ours["r_err_deg_per_100m"]) <= 1e-6 * r
    print("MATCH" if ok else "MISMATCH")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
