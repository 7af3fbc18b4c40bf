#!/usr/bin/env python3
"""Writes the tiny synthetic seed corpora of the fuzz targets into test/fuzz/seeds/<target>/.

seeds/rawlog/ is not written here: one_scan_gz.rawlog is `radarslam convert` of a one-scan Oxford
folder holding seeds/polar_png_oxford/oxford.png, one_scan_plain.rawlog the same decompressed
(MRPT reads plain and gzip rawlogs; mutations of the plain one reach the deserializer).
frame_with_scan_and_nullptr.rawlog is written here from the plain one: the same scan inside an
mrpt::obs::CSensoryFrame, then a nullptr object (the other two entry forms the reader accepts).

Our own data only (never copied from a dataset): small valid examples of every format so the
fuzzer starts from inputs that pass the first checks. scripts/fuzz.sh adds the real files from
../shared/data/real at run time (never committed). Stdlib only; re-run after a format change.
"""
import os
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))


def png_grey(rows):
    """8-bit greyscale PNG of `rows` (lists of ints 0..255), no filter, deterministic."""
    h, w = len(rows), len(rows[0])

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))

    raw = b"".join(b"\x00" + bytes(r) for r in rows)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 0, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def oxford_style_rows(first_stamp, step, azimuths=8, bins=16):
    rows = []
    for a in range(azimuths):
        meta = struct.pack("<qHB", first_stamp + a * step, a * 5600 // azimuths, 255)
        rows.append(list(meta) + [(a * 31 + b * 17) % 256 for b in range(bins)])
    return rows


def put(target, name, data):
    d = os.path.join(HERE, "seeds", target)
    os.makedirs(d, exist_ok=True)
    with open(os.path.join(d, name), "wb") as f:
        f.write(data if isinstance(data, bytes) else data.encode())


# Oxford (us, stamp = first azimuth), MulRan oxford-form (ns, stamp = last), Boreas (us, middle):
# the file names the harness uses are in fuzz_polar_png_oxford.cpp.
put("polar_png_oxford", "oxford.png", png_grey(oxford_style_rows(1547120788016733, 625)))
put("polar_png_oxford", "mulran.png", png_grey(oxford_style_rows(1564718976161407002 - 7 * 625000, 625000)))
put("polar_png_oxford", "boreas.png", png_grey(oxford_style_rows(1606417230036848 - 4 * 625, 625)))
put("polar_png_transposed", "bins16_az8.png", png_grey([[(b * 13 + a * 7) % 256 for a in range(8)] for b in range(16)]))

ray = "".join("%d,%.6f,%d,%d,%s\n" % (1564718976161407002 - (7 - a) * 625000, a * 45.0, a * 700, a,
                                      ",".join(str((a + b) * 9 % 256) for b in range(6))) for a in range(8))
put("mulran_ray_csv", "ray.csv", ray)

put("gt_oxford", "radar_odometry.csv",
    "source_timestamp,destination_timestamp,x,y,z,roll,pitch,yaw,source_radar_timestamp,destination_radar_timestamp\n"
    "1547120788266733,1547120788016733,0.5,0.01,0,0,0,0.002,1547120788141733,1547120787891733\n"
    "1547120788516733,1547120788266733,0.6,-0.01,0,0,0,-0.001,1547120788391733,1547120788141733\n")
put("gt_boreas", "radar_poses.csv",
    "GPSTime,easting,northing,altitude,vel_east,vel_north,vel_up,roll,pitch,heading,angvel_z,angvel_y,angvel_x\n"
    "1606417230036848,100.0,200.0,150.0,1,0,0,3.13,0.02,0.24,0,0,0\n"
    "1606417230286848,100.25,200.0,150.0,1,0,0,3.13,0.02,0.25,0,0,0\n")
put("gt_mulran", "global_pose.csv",
    "1564718976161407002,1,0,0,10,0,1,0,20,0,0,1,5\n"
    "1564718976411407002,0.9998,-0.02,0,10.5,0.02,0.9998,0,20.1,0,0,1,5\n")
put("radiate_frame_times", "Navtech_Polar.txt",
    "Frame: 000001 Time: 1574859771.744660272\nFrame: 000002 Time: 1574859771.977525228\n")
put("oxford_timestamps", "radar.timestamps", "1547120788016733 1\n1547120788266733 1\n1547120788516733 0\n")
put("trajectory_files", "poses.tum",
    "# t x y z qx qy qz qw\n1547120788.016733000 0 0 0 0 0 0 1\n1547120788.266733000 0.5 0.01 0 0 0 0.001 0.9999995\n")
put("trajectory_files", "poses.kitti",
    "1 0 0 0 0 1 0 0 0 0 1 0\n0.9998 -0.02 0 0.5 0.02 0.9998 0 0.01 0 0 1 0\n")
put("trajectory_files", "poses13.kitti",
    "1547120788016733 1 0 0 0 0 1 0 0 0 0 1 0\n1547120788266733 1 0 0 0.5 0 1 0 0 0 0 1 0\n")
put("trajectory_files", "times.txt", "0.000000e+00\n2.500000e-01\n")
put("yaml_params", "config.yaml",
    "cartesian:\n  size_px: 701\n  m_per_px: 0.25\n  fixed_point_maps: true\n"
    "peak_cloud:\n  min_peak_prominence: 30\n  min_range_m: 2.5\n  smoothing_bins: 0\n")


def map_seed():
    """A tiny map directory (maps/README.md) joined as fuzz_map_load.cpp expects: manifest.yaml,
    parameters.yaml, keyframes.bin, points.bin, graph.bin separated by SEP."""
    import hashlib
    sep = b"\n=RSLM-PART=\n"

    def header(magic, count):
        return magic + struct.pack("<IIQ", 1, 0, count)

    params = b"odometry:\n  tracking:\n    min_inliers: 10\n"
    kf = header(b"RSLMKEYF", 2)
    for i in range(2):
        pts = b"".join(struct.pack("<fff", 1.5 * p + i, -2.0 * p, 40.0 + p) for p in range(3))
        desc = struct.pack("<4f", 0.1, 0.2, 0.3, 0.4) if i == 0 else b""
        kf += struct.pack("<QqdddII", i, 1547120788016733000 + i * 250000000, 2.0 * i, 0.1 * i, 0.01 * i,
                          3, len(desc) // 4) + pts + desc
    points = header(b"RSLMPNTS", 2)
    points += struct.pack("<QddI", 0, 1.0, 2.0, 2) + struct.pack("<QQ", 0, 1)
    points += struct.pack("<QddI", 1, -3.0, 4.5, 1) + struct.pack("<Q", 1)
    graph = header(b"RSLMGRPH", 1)
    graph += struct.pack("<QQddd", 0, 1, 2.0, 0.1, 0.01) + struct.pack("<9d", 100, 0, 0, 0, 100, 0, 0, 0, 1000)
    graph += struct.pack("<I", 0)
    files = [("parameters", "parameters.yaml", params), ("keyframes", "keyframes.bin", kf),
             ("points", "points.bin", points), ("graph", "graph.bin", graph)]
    manifest = ("# radarslam map manifest (format: maps/README.md)\nformat_version: 1\n"
                "created_ns: 1700000000000000000\ncreated_utc: \"2023-11-14T22:13:20Z\"\n"
                "software_version: \"0.1.0\"\nsource_dataset: \"fuzz\"\nsensor:\n  num_azimuths: 400\n"
                "  num_bins: 3768\n  range_resolution_m: 0.0438\n  range_offset_m: 0.0219\n"
                "counts:\n  keyframes: 2\n  points: 2\n  edges: 1\nfiles:\n")
    for key, name, data in files:
        manifest += "  %s:\n    name: \"%s\"\n    bytes: %d\n    sha256: \"%s\"\n" % (
            key, name, len(data), hashlib.sha256(data).hexdigest())
    return sep.join([manifest.encode()] + [f[2] for f in files])


put("map_load", "tiny_map.bin", map_seed())
put("yaml_params", "modules.yaml",
    "odometry:\n  matching:\n    radius_m: 5\n  tracking:\n    min_inliers: 10\n"
    "m2dp:\n  rings: 8\nloop_detector:\n  max_candidates: 5\nloop_verifier:\n  min_inliers: 20\n"
    "pose_graph:\n  max_iterations: 50\n")


def radar_scan_sample(azimuths=16, bins=16, first_ns=1600000000000000000, step_ns=15625000):
    """A plausible RadarScan sample in the field layout fuzz_dds_radar_scan.cpp decodes."""
    import math
    stamps = [first_ns + a * step_ns for a in range(azimuths)]
    mid = stamps[0] // 2 + stamps[-1] // 2
    head = struct.pack("<IIddiIB", azimuths, bins, 0.0438, 0.0219, mid // 10**9, mid % 10**9, 5) + b"radar"
    head += struct.pack("<HHHI", azimuths, azimuths, azimuths, azimuths * bins)
    return (head + struct.pack("<%dq" % azimuths, *stamps) +
            struct.pack("<%dd" % azimuths, *[2 * math.pi * a / azimuths for a in range(azimuths)]) +
            bytes([1] * azimuths) + bytes((a * 31 + b * 17) % 256 for a in range(azimuths) for b in range(bins)))


put("dds_radar_scan", "scan_16x16.bin", radar_scan_sample())


# Nesting just past YamlParams' limit (kMaxYamlDepth = 64) in the three forms the pre-scan
# counts (flow brackets, flow maps, block indentation) and an out-of-range value: mutations
# explore both sides of the depth limit and of the range checks.
put("yaml_params", "deep_nesting.yaml",
    "odometry:\n  keypoints:\n    max_keypoints: 1e9\n" +
    "x: " + "[" * 70 + "]" * 70 + "\n" +
    "y: " + "{a: " * 40 + "1" + "}" * 40 + "\n" +
    "".join(" " * i + "z:\n" for i in range(70)) + " " * 70 + "w: 1\n")


def sensory_frame_seed():
    """MRPT's layout: 0x80 | name length, class name, version byte, body, end flag 0x88."""
    with open(os.path.join(HERE, "seeds", "rawlog", "one_scan_plain.rawlog"), "rb") as f:
        scan = f.read()
    name = b"mrpt::obs::CSensoryFrame"
    null_object = bytes([0x80 | 7]) + b"nullptr" + b"\x88"
    return bytes([0x80 | len(name)]) + name + b"\x02" + struct.pack("<I", 2) + scan + null_object + b"\x88"


put("rawlog", "frame_with_scan_and_nullptr.rawlog", sensory_frame_seed())
