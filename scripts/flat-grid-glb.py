#!/usr/bin/env python3
# A GLB of one N x N grid mesh (2 N^2 triangles) without normals, so the loader must give it
# flat normals: the load-time and memory case of issue 44 item 7.
#
#   scripts/flat-grid-glb.py N OUT.glb      (N = 2237: 10,008,338 triangles, 180 MB)
#   /usr/bin/time -f "%e s %M KB" rgraph render --scene OUT.glb --asset-root . \
#       --pipeline pipelines/deferred_msaa_4x.ron --width 64 --height 36 --out x.png
#
# Measured (release builds, lavapipe, the 2-core development machine, N = 2237):
# 3edba03 5.45-5.60 GB peak and 23.1-23.7 s of CPU; 2c4a948 3.74 GB and 19.2-20.9 s; 947b38e
# 3.75 GB and 14.3-20.6 s wall (the loader wrote out three vertices a triangle, 30M, for
# their face normals); since the renderers compute face normals themselves and the mesh keeps
# its 5M shared vertices, 1.45-1.61 GB and 3.8-4.2 s wall (November: 3.6 GB and 7.0 s).
import array
import json
import math
import struct
import sys

n, out = int(sys.argv[1]), sys.argv[2]
v = n + 1
positions = array.array("f")
for j in range(v):
    y = j / n
    row = [0.0] * (3 * v)
    for i in range(v):
        x = i / n
        # A gentle relief, so the faces' flat normals differ.
        row[3 * i : 3 * i + 3] = [x, 0.05 * math.sin(40 * x) * math.cos(40 * y), y]
    positions.extend(row)
indices = array.array("I")
for j in range(n):
    row = []
    for i in range(n):
        a = j * v + i
        row += [a, a + v, a + 1, a + 1, a + v, a + v + 1]
    indices.extend(row)
position_bytes, index_bytes = positions.tobytes(), indices.tobytes()
binary = position_bytes + index_bytes
document = {
    "asset": {"version": "2.0"},
    "buffers": [{"byteLength": len(binary)}],
    "bufferViews": [
        {"buffer": 0, "byteOffset": 0, "byteLength": len(position_bytes)},
        {"buffer": 0, "byteOffset": len(position_bytes), "byteLength": len(index_bytes)},
    ],
    "accessors": [
        {"bufferView": 0, "componentType": 5126, "count": v * v, "type": "VEC3",
         "min": [0, -0.05, 0], "max": [1, 0.05, 1]},
        {"bufferView": 1, "componentType": 5125, "count": len(indices), "type": "SCALAR"},
    ],
    "meshes": [{"name": "grid", "primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
    "nodes": [{"mesh": 0}],
    "scenes": [{"nodes": [0]}],
    "scene": 0,
}
text = json.dumps(document).encode()
text += b" " * (-len(text) % 4)
binary += b"\0" * (-len(binary) % 4)
with open(out, "wb") as f:
    f.write(b"glTF" + struct.pack("<II", 2, 12 + 8 + len(text) + 8 + len(binary)))
    f.write(struct.pack("<I", len(text)) + b"JSON" + text)
    f.write(struct.pack("<I", len(binary)) + b"BIN\0" + binary)
print(f"{out}: {len(indices) // 3} triangles")
