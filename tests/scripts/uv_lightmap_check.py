"""Independent checks of a uv store and its glTF (tests/scripts/uv_lightmap.sh).

The store through zarr + numpy: samples/grid and the chart rectangles
samples/uv_rects (disjoint, inside the lightmap, each holding exactly the
texels the manifest counts for its mesh). The .glb and .gltf through json +
struct + numpy alone (no glTF library): the GLB container, every accessor
inside its buffer view and buffer, POSITION min/max equal to the data,
indices in range, TEXCOORD_0 in [0, 1] and landing on chart or gutter texels
of the embedded lightmap, which is the PNG the relight wrote.
"""
import base64
import io
import json
import struct
import sys

import matplotlib.image
import numpy as np
import zarr

d = sys.argv[1]
root = zarr.open(d + "/s.wbk", mode="r")
attrs = json.load(open(d + "/s.wbk/.zattrs"))
assert root.attrs.asdict() == attrs  # zarr's own reader decodes the attributes (ASCII)
W, H = attrs["W"], attrs["H"]
grid = np.asarray(root["samples/grid"])
rects = np.asarray(root["samples/uv_rects"])
domains = np.asarray(root["samples/uv_domains"])
assert grid.shape == (H, W), grid.shape
assert rects.shape == (2, 4) and domains.shape == (2, 4), (rects.shape, domains.shape)
S = attrs["S"]
assert (grid >= 0).sum() == S == np.asarray(root["samples/position"]).shape[0]
owner = np.full((H, W), -1)
for i, (x, y, w, h) in enumerate(rects):
    assert 0 <= x and 0 <= y and x + w <= W and y + h <= H, rects
    assert (owner[y:y + h, x:x + w] == -1).all(), "charts overlap"
    owner[y:y + h, x:x + w] = i
    texels = int((grid[y:y + h, x:x + w] >= 0).sum())
    assert texels == attrs["uv"]["meshes"][i]["texels"] > 0, (i, texels)
assert (grid[owner == -1] == -1).all(), "a sample outside every chart"
assert attrs["uv"]["meshes"][0]["name"] and attrs["uv"]["fill"] == "push-pull"

png = open(d + "/lightmap.png", "rb").read()
lightmap = matplotlib.image.imread(io.BytesIO(png), format="png")
assert lightmap.shape[:2] == (H, W), lightmap.shape

COMPONENTS = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4}
DTYPES = {5126: np.float32, 5125: np.uint32, 5123: np.uint16}


def read_glb(path):
    data = open(path, "rb").read()
    magic, version, length = struct.unpack_from("<4sII", data, 0)
    assert magic == b"glTF" and version == 2 and length == len(data), (magic, version, length)
    json_len, json_type = struct.unpack_from("<I4s", data, 12)
    assert json_type == b"JSON"
    gltf = json.loads(data[20:20 + json_len])
    off = 20 + json_len
    bin_len, bin_type = struct.unpack_from("<I4s", data, off)
    assert bin_type == b"BIN\0"
    return gltf, [data[off + 8:off + 8 + bin_len]]


def read_gltf(path):
    gltf = json.load(open(path))
    buffers = []
    for b in gltf["buffers"]:
        uri = b["uri"]
        if uri.startswith("data:"):
            buffers.append(base64.b64decode(uri.split(",", 1)[1]))
        else:
            buffers.append(open(d + "/" + uri, "rb").read())
    return gltf, buffers


def accessor(gltf, buffers, i):
    a = gltf["accessors"][i]
    view = gltf["bufferViews"][a["bufferView"]]
    buf = buffers[view["buffer"]]
    declared = gltf["buffers"][view["buffer"]]["byteLength"]
    assert view.get("byteOffset", 0) + view["byteLength"] <= declared <= len(buf), (view, declared)
    dtype = np.dtype(DTYPES[a["componentType"]])
    n = COMPONENTS[a["type"]]
    start = view.get("byteOffset", 0) + a.get("byteOffset", 0)
    assert start + a["count"] * n * dtype.itemsize <= view.get("byteOffset", 0) + view["byteLength"]
    v = np.frombuffer(buf, dtype=dtype, count=a["count"] * n, offset=start).reshape(a["count"], n)
    if "min" in a:
        assert np.allclose(v.min(0), a["min"]) and np.allclose(v.max(0), a["max"]), i
    return v


def image_bytes(gltf, buffers, index):
    img = gltf["images"][index]
    if "bufferView" in img:
        view = gltf["bufferViews"][img["bufferView"]]
        o = view.get("byteOffset", 0)
        return buffers[view["buffer"]][o:o + view["byteLength"]]
    uri = img["uri"]
    assert uri.startswith("data:image/png;base64,"), uri[:40]
    return base64.b64decode(uri.split(",", 1)[1])


for name, (gltf, buffers) in [("glb", read_glb(d + "/scene.glb")),
                              ("gltf", read_gltf(d + "/scene.gltf"))]:
    assert gltf["asset"]["version"] == "2.0"
    assert len(gltf["meshes"]) == 2, name
    mat = gltf["materials"][0]
    tex = gltf["textures"][mat["emissiveTexture"]["index"]]
    assert mat["emissiveFactor"] == [1.0, 1.0, 1.0], mat
    assert mat["pbrMetallicRoughness"]["baseColorFactor"][:3] == [0.0, 0.0, 0.0], mat
    embedded = image_bytes(gltf, buffers, tex["source"])
    assert embedded[:8] == b"\x89PNG\r\n\x1a\n", name
    assert embedded == png, name + ": the embedded texture is not the written lightmap"
    for mesh in gltf["meshes"]:
        prim = mesh["primitives"][0]
        pos = accessor(gltf, buffers, prim["attributes"]["POSITION"])
        uv = accessor(gltf, buffers, prim["attributes"]["TEXCOORD_0"])
        idx = accessor(gltf, buffers, prim["indices"])
        assert len(pos) == len(uv) and idx.max() < len(pos), name
        assert (uv >= 0).all() and (uv <= 1).all(), name
        # glTF UVs have their origin at the image's top-left: texel (x, y).
        # Each triangle's UV centroid lies on its chart, so on a texel of
        # the chart or its gutter: lit (L = 1), not the black background.
        tri = uv[idx.reshape(-1, 3)].mean(axis=1)
        tx = np.clip((tri[:, 0] * W).astype(int), 0, W - 1)
        ty = np.clip((tri[:, 1] * H).astype(int), 0, H - 1)
        assert (lightmap[ty, tx, :3].max(axis=1) > 0.2).all(), name
print("uv_lightmap_check: ok")
