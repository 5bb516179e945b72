"""wavebake from Python: bake, read and relight compressed all-frequency
light transport.

    import wavebake
    store = wavebake.Store("cubes.wbk")          # metadata, samples, columns
    image = wavebake.relight(store, "builtin:sky", terms=256, rotate=30)
    report = wavebake.eval(store, "builtin:sky", reference=True)
    job = wavebake.Client("127.0.0.1:7433").submit("builtin:cubes-wall", light_res=16)

The compiled extension (wavebake._wavebake) does the work; this module gives
it inspectable, typed signatures (the same as __init__.pyi, which a test
checks) and accepts pathlib.Path wherever a path is taken. See
docs/python.md for a worked example.
"""
from __future__ import annotations

import os
from typing import Any, Iterable, Iterator, Literal, Sequence, Union, overload

import numpy as np
from numpy.typing import ArrayLike, NDArray

from . import _wavebake

__version__: str = _wavebake.__version__

_Path = Union[str, os.PathLike[str]]

__all__ = [
    "Aborted", "AlreadyExists", "Cancelled", "Client", "DataLoss", "DeadlineExceeded",
    "Error", "FailedPrecondition", "Internal", "InvalidArgument", "NotFound", "OutOfRange",
    "PermissionDenied", "ResourceExhausted", "Store", "Unauthenticated", "Unavailable", "Unimplemented",
    "Unknown", "Watch", "__version__", "bake", "eval", "export", "relight", "relight_sequence",
]


class Error(Exception):
    """A wavebake call failed. The subclass names the kind (the status code
    of the library or of the coordinator's RPC, `code`); the message names
    the bad input, in the words of the Python API."""

    code: str = "UNKNOWN"


class Cancelled(Error):
    """The operation was cancelled (a job cancelled while it was watched)."""

    code = "CANCELLED"


class Unknown(Error):
    """A failure of no known kind."""

    code = "UNKNOWN"


class InvalidArgument(Error, ValueError):
    """An argument is invalid: the message starts with its name."""

    code = "INVALID_ARGUMENT"


class DeadlineExceeded(Error, TimeoutError):
    """A deadline passed (a coordinator that did not answer in time)."""

    code = "DEADLINE_EXCEEDED"


class NotFound(Error, FileNotFoundError):
    """A file, store, scene or job does not exist."""

    code = "NOT_FOUND"


class AlreadyExists(Error, FileExistsError):
    """An output that must not exist does."""

    code = "ALREADY_EXISTS"


class PermissionDenied(Error, PermissionError):
    """Not allowed."""

    code = "PERMISSION_DENIED"


class ResourceExhausted(Error):
    """A limit was reached (an upload too large, memory)."""

    code = "RESOURCE_EXHAUSTED"


class FailedPrecondition(Error):
    """The state does not allow it (cancelling a finished job)."""

    code = "FAILED_PRECONDITION"


class Aborted(Error):
    """Aborted by a conflict; trying again may work."""

    code = "ABORTED"


class OutOfRange(InvalidArgument):
    """A value outside its range."""

    code = "OUT_OF_RANGE"


class Unimplemented(Error, NotImplementedError):
    """Not supported (by this store, or this coordinator)."""

    code = "UNIMPLEMENTED"


class Internal(Error):
    """A broken invariant: a bug to report."""

    code = "INTERNAL"


class Unavailable(Error, ConnectionError):
    """The coordinator cannot be reached."""

    code = "UNAVAILABLE"


class DataLoss(Error):
    """A store or file is corrupt or truncated."""

    code = "DATA_LOSS"


class Unauthenticated(Error, PermissionError):
    """The coordinator wants a (valid) token."""

    code = "UNAUTHENTICATED"


# By status code number (absl::StatusCode and grpc::StatusCode agree).
_ERRORS: dict[int, type[Error]] = {
    1: Cancelled, 2: Unknown, 3: InvalidArgument, 4: DeadlineExceeded, 5: NotFound,
    6: AlreadyExists, 7: PermissionDenied, 8: ResourceExhausted, 9: FailedPrecondition,
    10: Aborted, 11: OutOfRange, 12: Unimplemented, 13: Internal, 14: Unavailable, 15: DataLoss,
    16: Unauthenticated,
}


def _error_class(code: int) -> type[Error]:
    """The exception the extension raises for a status code."""
    return _ERRORS.get(code, Unknown)


def _path(value: _Path) -> str:
    return os.fspath(value)


def _env(env: _Path | ArrayLike | None) -> Any:
    """A spec string stays one, a path becomes one, anything else is an array."""
    if isinstance(env, os.PathLike):
        return os.fspath(env)
    return env


class Store(_wavebake.Store):
    """A finished wavebake store (a Zarr v2 directory): its metadata and
    samples at once, the transport matrix on first use (relight, column).

    Parameters
    ----------
    path: the store's directory (str or pathlib.Path).
    """

    def __init__(self, path: _Path) -> None:
        super().__init__(_path(path))

    @overload
    def column(self, index: int, domain: Literal["pixel"] = "pixel") -> NDArray[np.float32]: ...
    @overload
    def column(self, index: int, domain: Literal["wavelet"]
               ) -> tuple[int, NDArray[np.uint32], NDArray[np.float32]]: ...

    def column(self, index: int, domain: str = "pixel") -> Any:
        """Column `index` of the transport matrix T.

        Parameters
        ----------
        index: the column (the wavelet light), 0 .. columns - 1.
        domain: "pixel": a (height, width) float32 image of the grid;
            "wavelet": (depth, positions, values) as stored.
        """
        return super().column(index=index, domain=domain)


def _store(store: Store | _Path) -> Any:
    return store if isinstance(store, _wavebake.Store) else _path(store)


def _lights(area_lights: Iterable[_Path]) -> list[str]:
    if isinstance(area_lights, (str, os.PathLike)):
        return [os.fspath(area_lights)]
    return [os.fspath(f) for f in area_lights]


def relight(store: Store | _Path, env: _Path | ArrayLike | None = None, terms: int = 256,
            rotate: float = 0.0, brdf: str = "lambert", view: Sequence[float] | None = None,
            exposure: float = 0.0, area_lights: Iterable[_Path] = (),
            source_fraction: float = 0.01, target_fraction: float = 0.30) -> NDArray[np.float32]:
    """The store relit, as `wavebake relight` relights it (the same floats as
    its .exr): an (height, width, 3) float32 array, NaN where no sample is.

    Parameters
    ----------
    store: a Store, or the path of one.
    env: an environment: a spec (an .hdr/.exr/.png path, "builtin:sky",
        "builtin:constant") or a lat-long array of shape (H, 2H, 3) of
        radiance; None with area_lights.
    terms: how many wavelet lights (more than the store has: all of them).
    rotate: degrees the environment turns about +Y.
    brdf: the material of a visibility store ("lambert", "phong:16",
        "blinn:32", ... as `--brdf`); a diffuse store takes "lambert" only.
    view: the eye (x, y, z) of a visibility store with a mesh layout
        (a camera layout sees from its camera); None otherwise.
    exposure: stops: the floats are scaled by 2**exposure.
    area_lights: LIGHT.json files of near-field area lights (their lights
        add) for a store baked with light_domain="plane:S"; env is then None.
    source_fraction: area lights: source coefficients kept per light.
    target_fraction: area lights: face coefficients propagated per sample.
    """
    return _wavebake.relight(store=_store(store), env=_env(env), terms=terms, rotate=rotate,
                             brdf=brdf, view=view, exposure=exposure,
                             area_lights=_lights(area_lights), source_fraction=source_fraction,
                             target_fraction=target_fraction)


def relight_sequence(store: Store | _Path, env: _Path | ArrayLike | None = None,
                     rotate: Iterable[float] | None = None, brdf: Iterable[str] | None = None,
                     area_light_sequence: _Path | None = None, terms: int = 256,
                     view: Sequence[float] | None = None, exposure: float = 0.0,
                     area_lights: Iterable[_Path] = (), source_fraction: float = 0.01,
                     target_fraction: float = 0.30) -> Iterator[NDArray[np.float32]]:
    """Frames one at a time (a generator), the store opened once: each is
    relight() with that frame's rotation and BRDF, or of that frame of a
    moving area light.

    Parameters
    ----------
    store: a Store, or the path of one.
    env: the environment (as for relight); None with area lights.
    rotate: the degrees of each frame (e.g. numpy.linspace(0, 360, 36));
        None: 0 for every frame.
    brdf: the material of each frame (visibility stores); None: "lambert".
        Given both, rotate and brdf have one entry per frame each.
    area_light_sequence: a SEQ.json moving light (as
        `--area-light-sequence`), its frames over the fixed area_lights.
    terms: how many wavelet lights.
    view: the eye (x, y, z) for a mesh layout's visibility store.
    exposure: stops: the floats are scaled by 2**exposure.
    area_lights: LIGHT.json files lit in every frame.
    source_fraction: area lights: source coefficients kept per light.
    target_fraction: area lights: face coefficients propagated per sample.
    """
    opened = store if isinstance(store, _wavebake.Store) else Store(store)
    if area_light_sequence is not None:
        sequence = _path(area_light_sequence)
        for frame in range(_wavebake.area_sequence_frames(sequence=sequence)):
            yield _wavebake.relight_area_frame(
                store=opened, sequence=sequence, frame=frame, area_lights=_lights(area_lights),
                exposure=exposure, source_fraction=source_fraction, target_fraction=target_fraction)
        return
    if rotate is None and brdf is None:
        raise InvalidArgument("rotate: give rotate, brdf or area_light_sequence (one entry a frame)")
    angles = list(rotate) if rotate is not None else None
    materials = list(brdf) if brdf is not None else None
    if angles is not None and materials is not None and len(angles) != len(materials):
        raise InvalidArgument(f"brdf: {len(materials)} entries for {len(angles)} rotations")
    count = len(angles) if angles is not None else len(materials or [])
    for frame in range(count):
        yield relight(opened, env, terms=terms, rotate=angles[frame] if angles is not None else 0.0,
                      brdf=materials[frame] if materials is not None else "lambert", view=view,
                      exposure=exposure, area_lights=area_lights, source_fraction=source_fraction,
                      target_fraction=target_fraction)


def eval(store: Store | _Path, env: _Path | ArrayLike | None = None, reference: bool = True,
         terms: int = 256, rotate: float = 0.0, dense: bool = True,
         target_rel_se: float = 0.002, brdf: str = "lambert", view: Sequence[float] | None = None,
         area_lights: Iterable[_Path] = (), source_fraction: float = 0.01,
         target_fraction: float = 0.30, reference_batches: int = 8) -> dict[str, Any]:
    """The relighting error, as a dict (reference=True: the report of
    `wavebake eval --json` with the same options).

    Parameters
    ----------
    store: a Store, or the path of one.
    env: a spec (or, with reference=False, also an (H, 2H, 3) array); None
        with area_lights.
    reference: True: against the independent Monte-Carlo reference; False:
        the n-term relighting against all wavelet lights (no tracing).
    terms: how many wavelet lights.
    rotate: degrees the environment turns about +Y.
    dense: also trace the dense transport (reference=True).
    target_rel_se: the reference's relative standard error to reach.
    brdf: the material of a visibility store (as for relight).
    view: the eye (x, y, z) of a visibility store with a mesh layout.
    area_lights: LIGHT.json files: near-field lights over their area
        (as `wavebake eval --area-light`); env is then None.
    source_fraction: area lights: source coefficients kept per light.
    target_fraction: area lights: face coefficients propagated per sample.
    reference_batches: area lights: batches of 16x16 points per light and sample.
    """
    return _wavebake.eval(store=_store(store), env=_env(env), reference=reference, terms=terms,
                          rotate=rotate, dense=dense, target_rel_se=target_rel_se, brdf=brdf,
                          view=view, area_lights=_lights(area_lights),
                          source_fraction=source_fraction, target_fraction=target_fraction,
                          reference_batches=reference_batches)


def export(store: Store | _Path, out: _Path, format: Literal["wavelet-tree"] = "wavelet-tree",
           cut_off: float | None = None, target_error: float | None = None,
           bits: int | Sequence[int] | str | None = None, jump_nodes: int = 16) -> dict[str, Any]:
    """A diffuse store's transport rows as GPU wavelet-tree textures
    (Boulton 4.4-4.5), as `wavebake export` writes them: out/header.json and
    the raw arrays it names (line.bin, blocks.bin, cells.bin).

    Parameters
    ----------
    store: a Store, or the path of one (diffuse, cube light domain, Haar rows).
    out: the directory to write (created).
    format: "wavelet-tree", the one format.
    cut_off: the absolute cut-off of a node's largest |coefficient|; or
    target_error: the relative L2 error of the pruned rows (default 0.035).
        Give one of them at most.
    bits: code bits per coefficient: None or "auto" (4 at the finest level,
        5 and 6 at the next two, 9 above), an int (every level) or one int
        per level, level 0 first; each in 2..9.
    jump_nodes: a node gets a jump record when at least this many kept
        nodes lie below it.

    Returns the header written (header.json) as a dict.
    """
    path = store.path if isinstance(store, _wavebake.Store) else _path(store)
    return _wavebake.export(store=path, out=_path(out), format=format, cut_off=cut_off,
                            target_error=target_error, bits=bits, jump_nodes=jump_nodes)


def bake(scene: _Path, out: _Path, workers: int = 0, **params: Any) -> dict[str, Any]:
    """Bake a scene into a store in this process (as `wavebake bake`).

    Parameters
    ----------
    scene: "builtin:NAME" or a scene file (str or pathlib.Path).
    out: the store to write (must not exist).
    workers: worker threads (0: one per core).
    params: BakeRequest fields (light_res=16, layout="camera:32x32", ...).

    Returns the finished job as a dict. Ctrl-C cancels the bake.
    """
    return _wavebake.bake(_path(scene), _path(out), workers, **params)


Watch = _wavebake.Watch


class Client(_wavebake.Client):
    """A client of a running coordinator (`wavebake coordinator`).

    Parameters
    ----------
    coordinator: its address, host:port.
    token_file: a file holding the bearer token ("" for none).
    tls_ca: a CA certificate file for TLS ("" for plaintext).
    connect_seconds: how long to wait for the connection.
    """

    def __init__(self, coordinator: str, token_file: _Path = "", tls_ca: _Path = "",
                 connect_seconds: float = 5.0) -> None:
        super().__init__(coordinator=coordinator, token_file=_path(token_file),
                         tls_ca=_path(tls_ca), connect_seconds=connect_seconds)

    def submit(self, scene: _Path, **params: Any) -> dict[str, Any]:
        """Submit a bake; returns the job.

        Parameters
        ----------
        scene: "builtin:NAME" or a scene file (uploaded once, by hash).
        params: BakeRequest fields (light_res=16, layout="camera:32x32", ...).
        """
        return super().submit(_path(scene), **params)

    def watch(self, job_id: str | int, patience_seconds: float = 60.0) -> Watch:
        """The job's events as an iterator of dicts, to the job's end (its
        `job` attribute is then the finished job); reconnects across restarts.

        Parameters
        ----------
        job_id: the job.
        patience_seconds: how long to keep reconnecting to a lost coordinator.
        """
        return super().watch(job_id=str(job_id), patience_seconds=patience_seconds)

    def status(self, job_id: str | int) -> dict[str, Any]:
        """The job as the coordinator has it now.

        Parameters
        ----------
        job_id: the job.
        """
        return super().status(job_id=str(job_id))

    def jobs(self, limit: int = 100, active_only: bool = False) -> list[dict[str, Any]]:
        """The newest jobs, newest first.

        Parameters
        ----------
        limit: at most this many.
        active_only: only queued and baking jobs.
        """
        return super().jobs(limit=limit, active_only=active_only)

    def cancel(self, job_id: str | int) -> dict[str, Any]:
        """Cancel a queued or baking job; returns it.

        Parameters
        ----------
        job_id: the job.
        """
        return super().cancel(job_id=str(job_id))

    def fetch(self, job_id: str | int, out: _Path) -> dict[str, Any]:
        """Stream a finished job's store into `out`, verified; returns files,
        bytes, arrays and path.

        Parameters
        ----------
        job_id: the job.
        out: where the store goes (must not exist).
        """
        return super().fetch(job_id=str(job_id), out=_path(out))
