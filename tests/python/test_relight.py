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
    with pytest.raises(Exception, match="no-such.hdr"):
        wavebake.relight(s, "no-such.hdr")
