#!/usr/bin/env python3
"""Writes a 1.3M-triangle test mesh and a scene around it, for measuring the previewer on a
large mesh:

    python3 tools/big_mesh.py DIR        # DIR/blob.obj (49 MB, 1,308,672 triangles), DIR/blob.json
    tests/gui/bench_previewer.sh build DIR/blob.json

The mesh is a closed sphere of 1024 segments by 640 rings with a smooth ripple (radius
1 +- 8 %), resting above a mirror-tinted floor."""
import math
import os
import sys

out_dir = sys.argv[1] if len(sys.argv) > 1 else "."
os.makedirs(out_dir, exist_ok=True)
W, H = 1024, 640  # 2 W (H - 1) triangles
with open(os.path.join(out_dir, "blob.obj"), "w") as f:
    w = f.write
    for j in range(H):
        th = math.pi * (j + 0.5) / H
        for i in range(W):
            ph = 2 * math.pi * i / W
            r = 1 + 0.08 * math.sin(7 * th) * math.cos(5 * ph)
            w("v %.6f %.6f %.6f\n" % (r * math.sin(th) * math.cos(ph), r * math.cos(th) + 1.1, r * math.sin(th) * math.sin(ph)))
    for j in range(H - 1):
        for i in range(W):
            a = j * W + i + 1
            b = j * W + (i + 1) % W + 1
            c = (j + 1) * W + (i + 1) % W + 1
            d = (j + 1) * W + i + 1
            w("f %d %d %d\nf %d %d %d\n" % (a, d, c, a, c, b))
with open(os.path.join(out_dir, "blob.json"), "w") as f:
    f.write("""{
  "camera": {"position": [0, 1.6, 4.5], "look_at": [0, 1.0, 0], "up": [0, 1, 0], "fov_y": 40},
  "image": {"width": 1280, "height": 720},
  "ambient": 0.1,
  "lights": [{"type": "point", "position": [2, 5, 4], "intensity": 0.9}],
  "materials": {"clay": {"ka": [0.2, 0.15, 0.1], "kd": [0.7, 0.5, 0.35], "ks": 0.4, "n": 60},
                "floor": {"ka": 0.1, "kd": 0.6, "ks": 0.1, "n": 10, "kr": 0.2}},
  "objects": [
    {"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "material": "floor"},
    {"type": "mesh", "file": "blob.obj", "material": "clay"}
  ]
}
""")
