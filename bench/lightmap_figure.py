#!/usr/bin/python3
"""The README's lightmap picture from a relit .glb (wavebake relight --out X.glb).

    /usr/bin/python3 bench/lightmap_figure.py SCENE.glb OUT.png

Left: the lightmap embedded in the glTF (its emissive texture). Right: the
glTF's meshes drawn by matplotlib, every triangle coloured by the lightmap
texel under its TEXCOORD_0 centroid — the glTF read with json + struct +
numpy alone, so the picture also shows that the UVs and the texture agree.
"""
import io
import json
import struct
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.image  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402

COMPONENTS = {"SCALAR": 1, "VEC2": 2, "VEC3": 3}
DTYPES = {5126: np.float32, 5125: np.uint32}


def main(glb_path, out):
    data = open(glb_path, "rb").read()
    json_len = struct.unpack_from("<I", data, 12)[0]
    gltf = json.loads(data[20:20 + json_len])
    binary = data[20 + json_len + 8:]

    def view_bytes(index):
        v = gltf["bufferViews"][index]
        return binary[v.get("byteOffset", 0):v.get("byteOffset", 0) + v["byteLength"]]

    def accessor(index):
        a = gltf["accessors"][index]
        n = COMPONENTS[a["type"]]
        raw = view_bytes(a["bufferView"])[a.get("byteOffset", 0):]
        return np.frombuffer(raw, DTYPES[a["componentType"]], a["count"] * n).reshape(-1, n)

    material = gltf["materials"][0]
    image = gltf["images"][gltf["textures"][material["emissiveTexture"]["index"]]["source"]]
    lightmap = matplotlib.image.imread(io.BytesIO(view_bytes(image["bufferView"])), format="png")
    h, w = lightmap.shape[:2]
    polygons, colours = [], []
    for mesh in gltf["meshes"]:
        prim = mesh["primitives"][0]
        pos = accessor(prim["attributes"]["POSITION"])
        uv = accessor(prim["attributes"]["TEXCOORD_0"])
        tris = accessor(prim["indices"]).reshape(-1, 3)
        centre = uv[tris].mean(axis=1)  # glTF UVs: origin at the image's top-left
        x = np.clip((centre[:, 0] * w).astype(int), 0, w - 1)
        y = np.clip((centre[:, 1] * h).astype(int), 0, h - 1)
        polygons.append(pos[tris][:, :, [0, 2, 1]])  # y up in the file, z up in the plot
        colours.append(lightmap[y, x, :3])
    polygons, colours = np.concatenate(polygons), np.concatenate(colours)

    fig = plt.figure(figsize=(10, 5))
    ax = fig.add_subplot(1, 2, 1)
    ax.imshow(lightmap, interpolation="nearest")
    ax.set_title(f"lightmap {w}×{h} (gutters dilated)")
    ax.axis("off")
    ax3 = fig.add_subplot(1, 2, 2, projection="3d")
    ax3.add_collection3d(Poly3DCollection(polygons, facecolors=colours, edgecolors="none"))
    lo, hi = polygons.reshape(-1, 3).min(0), polygons.reshape(-1, 3).max(0)
    centre, half = (lo + hi) / 2, (hi - lo).max() / 2
    for setter, c in zip((ax3.set_xlim, ax3.set_ylim, ax3.set_zlim), centre):
        setter(c - half, c + half)
    ax3.view_init(elev=15, azim=-60)
    ax3.axis("off")
    ax3.set_title("the glTF, textured by its lightmap")
    fig.tight_layout()
    fig.savefig(out, dpi=100)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit("usage: lightmap_figure.py SCENE.glb OUT.png")
    main(sys.argv[1], sys.argv[2])
