"""wavebake.Store against an independent reader: zarr opens the same arrays,
and numpy decodes columns itself — the documented dither and dequantization
(DESIGN.md §1) and its own inverse Haar — to the values Store.column gives."""
import json
import math

import numpy as np
import pytest
import zarr

import wavebake


def mix(z):
    z = z + np.uint64(0x9E3779B97F4A7C15)
    z = (z ^ (z >> np.uint64(30))) * np.uint64(0xBF58476D1CE4E5B9)
    z = (z ^ (z >> np.uint64(27))) * np.uint64(0x94D049BB133111EB)
    return z ^ (z >> np.uint64(31))


def dither(seed, column, positions):
    with np.errstate(over="ignore"):
        h = mix(mix(mix(np.uint64(seed)) ^ np.uint64(column)) ^ positions.astype(np.uint64))
    return ((h >> np.uint64(40)).astype(np.float64) * 2.0**-24 - 0.5).astype(np.float32)


def inverse_haar(img, depth):
    """Orthonormal Haar, Mallat layout [LL HL; LH HH], steps undone last first."""
    img = img.astype(np.float64).copy()
    r = 1 / math.sqrt(2)
    for s in reversed(range(depth)):
        h, w = img.shape[0] >> s, img.shape[1] >> s
        blk = img[:h, :w].copy()
        for axis, n in ((0, h), (1, w)):
            if n < 2:
                continue
            lo, hi = np.split(blk, 2, axis=axis)
            out = np.empty_like(blk)
            idx_even = [slice(None)] * 2
            idx_odd = [slice(None)] * 2
            idx_even[axis], idx_odd[axis] = slice(0, None, 2), slice(1, None, 2)
            out[tuple(idx_even)] = (lo + hi) * r
            out[tuple(idx_odd)] = (lo - hi) * r
            blk = out
        img[:h, :w] = blk
    return img


def test_metadata_and_samples_match_zarr(stores):
    path = stores["cubes-wall"]
    s = wavebake.Store(str(path))
    root = zarr.open(str(path), mode="r")
    attrs = root.attrs.asdict()
    assert s.attrs == json.loads(json.dumps(attrs))
    assert s.params == attrs["params"]
    assert (s.width, s.height, s.light_res, s.columns) == (16, 16, 8, 6 * 8 * 8)
    assert s.layout == "camera:16x16"
    samples = s.samples
    np.testing.assert_array_equal(samples["grid"], root["samples/grid"][...])
    np.testing.assert_array_equal(samples["position"], root["samples/position"][...])
    np.testing.assert_array_equal(samples["albedo"], root["samples/albedo"][...])
    assert "vertex" not in samples  # a camera layout
    assert "Store(" in repr(s)


def test_columns_decode_as_numpy_decodes_them(stores):
    path = stores["cubes-wall"]
    s = wavebake.Store(str(path))
    root = zarr.open(str(path), mode="r")
    a = root.attrs.asdict()
    assert a["level_scaling"] == "uniform"  # s = 0 in the dequantize formula
    seed = a["params"]["seed"]
    indptr = root["transport/indptr"][...]
    indices, data = root["transport/indices"][...], root["transport/data"][...]
    depth, scale = root["transport/depth"][...], root["transport/scale"][...]
    checked = set()
    for m in range(s.columns):
        b, e = indptr[m], indptr[m + 1]
        if e == b or (int(depth[m]) in checked and m % 37):
            continue
        checked.add(int(depth[m]))
        pos = indices[b:e]
        values = ((data[b:e].astype(np.float64) - dither(seed, m, pos)) * np.float64(scale[m])).astype(np.float32)
        d, p, v = s.column(m, domain="wavelet")
        assert d == depth[m]
        np.testing.assert_array_equal(p, pos)
        np.testing.assert_array_equal(v, values)
        coeffs = np.zeros(s.width * s.height)
        coeffs[pos] = values
        image = inverse_haar(coeffs.reshape(s.height, s.width), int(depth[m]))
        ours = s.column(m)
        assert ours.shape == (s.height, s.width)
        np.testing.assert_allclose(ours, image, rtol=1e-5, atol=1e-6 * max(1e-12, np.abs(image).max()))
    assert len(checked) >= 2, checked  # more than one transform depth was exercised


def test_bad_column_and_path_are_named(stores, tmp_path):
    s = wavebake.Store(str(stores["furnace"]))
    with pytest.raises(IndexError, match="column"):
        s.column(s.columns)
    with pytest.raises(ValueError, match="domain"):
        s.column(0, domain="fourier")
    with pytest.raises(wavebake.NotFound, match="nothing.wbk"):
        wavebake.Store(str(tmp_path / "nothing.wbk"))
