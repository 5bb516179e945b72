"""wavebake.relight: the white furnace (L = 1 on an unoccluded albedo-1
plane relights to 1, DESIGN.md §1), rotation as the documented shift of the
lat-long map (+90 degrees moves it by -width/4 pixels), numpy environments
and their errors."""
import numpy as np
import pytest

import wavebake

ALL = 10**6  # more terms than columns: every wavelet light


def unmasked(store):
    return store.samples["grid"] >= 0


def test_white_furnace(stores):
    s = wavebake.Store(str(stores["furnace"]))
    image = wavebake.relight(s, "builtin:constant", terms=ALL)
    assert image.shape == (16, 16, 3) and image.dtype == np.float32
    mask = unmasked(s)
    assert mask.sum() > 100
    assert np.isnan(image[~mask]).all()
    b = image[mask]
    assert np.sqrt(np.mean((b - 1) ** 2)) < 0.01, np.abs(b - 1).max()
    # Turning a constant environment changes nothing.
    turned = wavebake.relight(s, "builtin:constant", terms=ALL, rotate=77)
    np.testing.assert_allclose(turned[mask], b, atol=1e-5)


def test_numpy_environment_equals_its_spec(stores):
    path = str(stores["furnace"])  # a path works as well as a Store
    ones = np.ones((16, 32, 3), np.float32)
    a = wavebake.relight(path, ones, terms=ALL)
    b = wavebake.relight(path, "builtin:constant", terms=ALL)
    mask = ~np.isnan(b)
    np.testing.assert_allclose(a[mask], b[mask], rtol=1e-5)


def test_rotation_is_the_documented_shift(stores):
    s = wavebake.Store(str(stores["cubes-wall"]))
    rng = np.random.default_rng(5)
    env = rng.uniform(0.1, 1.0, (32, 64, 3)).astype(np.float32)
    env[8:12, 10:14] = 40.0  # a bright patch
    turned = wavebake.relight(s, env, terms=64, rotate=90)
    shifted = wavebake.relight(s, np.roll(env, -64 // 4, axis=1), terms=64)
    mask = unmasked(s)
    np.testing.assert_allclose(turned[mask], shifted[mask], rtol=1e-5, atol=1e-6)
    unturned = wavebake.relight(s, env, terms=64)
    assert np.abs(unturned[mask] - turned[mask]).max() > 1e-2  # the patch moved


def test_more_terms_never_hurt_all_is_all(stores):
    s = wavebake.Store(str(stores["cubes-wall"]))
    n = s.columns
    np.testing.assert_array_equal(wavebake.relight(s, "builtin:sky", terms=n),
                                  wavebake.relight(s, "builtin:sky", terms=ALL))


def test_bad_inputs_are_named(stores):
    s = wavebake.Store(str(stores["furnace"]))
    with pytest.raises(ValueError, match="env"):
        wavebake.relight(s, np.ones((16, 16, 3)))
    negative = np.ones((8, 16, 3))
    negative[2, 3, 1] = -1
    with pytest.raises(ValueError, match="radiance"):
        wavebake.relight(s, negative)
    with pytest.raises(ValueError, match="terms"):
        wavebake.relight(s, "builtin:sky", terms=0)
    with pytest.raises(ValueError, match="rotate"):
        wavebake.relight(s, "builtin:sky", rotate=float("nan"))
    with pytest.raises(wavebake.NotFound, match="no-such.hdr"):
        wavebake.relight(s, "no-such.hdr")


def read_exr_zip_float(path):
    """A reader of the EXR files `wavebake relight` writes (scanline, ZIP
    blocks of 16 lines, FLOAT channels B, G, R) that shares no code with
    OpenEXR or the module: the OpenEXR file layout and its ZIP predictor."""
    import struct
    import zlib
    data = open(path, "rb").read()
    assert struct.unpack_from("<I", data, 0)[0] == 20000630, "not an EXR file"
    pos, header = 8, {}
    while data[pos] != 0:
        name_end = data.index(b"\0", pos)
        type_end = data.index(b"\0", name_end + 1)
        size = struct.unpack_from("<i", data, type_end + 1)[0]
        header[data[pos:name_end].decode()] = data[type_end + 5:type_end + 5 + size]
        pos = type_end + 5 + size
    pos += 1
    assert header["compression"] == b"\x03", "ZIP_COMPRESSION"
    x0, y0, x1, y1 = struct.unpack("<4i", header["dataWindow"])
    width, height = x1 - x0 + 1, y1 - y0 + 1
    channels, cpos = [], 0  # name, a null, then type, linear + 3 reserved, x and y sampling
    chlist = header["channels"]
    while chlist[cpos] != 0:
        end = chlist.index(b"\0", cpos)
        channels.append(chlist[cpos:end].decode())
        assert struct.unpack_from("<i", chlist, end + 1)[0] == 2, "FLOAT channels"
        cpos = end + 17
    blocks = (height + 15) // 16
    offsets = struct.unpack_from(f"<{blocks}Q", data, pos)
    image = np.empty((height, width, 3), np.float32)
    for offset in offsets:
        y, size = struct.unpack_from("<ii", data, offset)
        raw = data[offset + 8:offset + 8 + size]
        lines = min(16, height - (y - y0))
        if size < lines * width * 12:
            d = np.frombuffer(zlib.decompress(raw), np.uint8).astype(np.int64)
            d[1:] -= 128  # the predictor stored differences + 128 after the first byte
            t = (np.cumsum(d) % 256).astype(np.uint8)
            half = (len(t) + 1) // 2
            raw = np.empty_like(t)
            raw[0::2], raw[1::2] = t[:half], t[half:]
            raw = raw.tobytes()
        block = np.frombuffer(raw, "<f4").reshape(lines, len(channels), width)
        for c, name in enumerate(channels):
            image[y - y0:y - y0 + lines, :, "RGB".index(name)] = block[:, c, :]
    return image


def test_equals_the_command_line_runtime(stores, tmp_path):
    """The module and `wavebake relight` (the C++ runtime behind the command
    line) give the same floats for the same store, probe, terms and rotation."""
    import os
    import subprocess
    s = wavebake.Store(str(stores["cubes-wall"]))
    probe = os.path.join(os.environ["WB_SHARED_DATA"], "probes", "grace.hdr")
    for terms, rotate in ((16, 0), (64, 30), (s.columns, 200)):
        out = tmp_path / f"cli_{terms}_{rotate}.exr"
        subprocess.run([os.environ["WB_WAVEBAKE_BIN"], "relight", str(s.path), "--env", probe,
                        "--terms", str(terms), "--rotate", str(rotate), "--out", str(out)],
                       check=True, capture_output=True)
        theirs = read_exr_zip_float(out)
        ours = wavebake.relight(s, probe, terms=terms, rotate=rotate)
        assert ours.shape == theirs.shape == (16, 16, 3)
        np.testing.assert_array_equal(np.isnan(ours), np.isnan(theirs))
        mask = ~np.isnan(ours)
        assert mask.sum() > 100 and np.abs(ours[mask]).max() > 0
        np.testing.assert_array_equal(ours[mask], theirs[mask])


def test_an_overflowing_numpy_environment_is_refused(stores):
    """3e38 is a finite float32 above the 1e30 bound files get: it relit to
    all NaN, and eval called that perfect."""
    s = wavebake.Store(str(stores["furnace"]))
    bright = np.ones((8, 16, 3), dtype=np.float32)
    bright[4, 5, 2] = 3e38
    with pytest.raises(wavebake.InvalidArgument, match=r"pixel \(5, 4\) channel B.*1e\+30"):
        wavebake.relight(s, bright)
    with pytest.raises(wavebake.InvalidArgument, match=r"pixel \(5, 4\)"):
        wavebake.eval(s, bright, reference=False)
    # At the bound every value stays finite.
    at_bound = np.full((8, 16, 3), 1e30, dtype=np.float32)
    image = wavebake.relight(s, at_bound)
    assert np.isfinite(image[~np.isnan(image)]).all() and not np.isnan(image).all()


def test_an_exposure_beyond_float_is_refused(stores):
    """2**200 is no float32: the image came back inf (and NaN where it was
    0); a finite exposure that overflows a bright value is named too."""
    s = wavebake.Store(str(stores["furnace"]))
    for stops in (200, -200, float("nan")):
        with pytest.raises(wavebake.InvalidArgument, match="^exposure: "):
            wavebake.relight(s, "builtin:constant", exposure=stops)
    at_bound = np.full((8, 16, 3), 1e30, dtype=np.float32)
    with pytest.raises(wavebake.InvalidArgument, match=r"^exposure: 100 stops overflow"):
        wavebake.relight(s, at_bound, exposure=100)
    image = wavebake.relight(s, "builtin:constant", exposure=126)
    assert np.isfinite(image[~np.isnan(image)]).all()
