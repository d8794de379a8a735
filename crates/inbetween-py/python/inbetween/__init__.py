"""Keyframe in-betweening of 3D orientations, vectorised over joints (docs/python.md).

``Curve`` builds the library's curve (hermite, squad, bezier, slerp, nlerp, minaccel) through keys
(K, 4) or (K, J, 4) and evaluates rotations, angular velocities and accelerations at many times
at once; ``resample`` puts dense frames at one exact rate onto another, as ``inbetween interp``
writes them; ``frame_times`` gives that grid; ``reduce`` keeps the fewest frames as keys whose
curve gives every frame back within a tolerance, verified. Rates are exact: ``"30000/1001"``, ``29.97`` (the
NTSC ratio, as on the command line), ``Fraction(120, 1)``, or a float taken as the decimal it
prints as (``59.9999885559082``). Errors are ``InputError`` (a ``ValueError``).
"""

from __future__ import annotations

import hashlib
import operator
import os
from typing import Any, Dict, Mapping, Optional, Tuple, Union

import numpy as np

from . import _inbetween


def _extension() -> Any:
    """The compiled module the package calls: ``_inbetween_avx2`` (the same code compiled for
    AVX2 without FMA, which gives the portable module's bits; tests/test_simd.py) where the
    wheel carries it and the CPU has every feature it needs, unless ``INBETWEEN_SIMD=portable``;
    else the portable ``_inbetween`` (a build from the source folder has only that one)."""
    if os.environ.get("INBETWEEN_SIMD", "").strip().lower() == "portable":
        return _inbetween
    if not _inbetween.cpu_has_avx2():
        return _inbetween
    try:
        from . import _inbetween_avx2
    except ImportError:
        return _inbetween
    return _inbetween_avx2


_ext = _extension()
InputError = _ext.InputError

__all__ = ["Clip", "Curve", "InputError", "Reduction", "__version__", "frame_times", "from_rot6d",
           "process_file", "read", "reduce", "resample", "resample_amass", "to_rot6d", "write"]

#: The distribution this module is installed from (``pip install inbetween-rs``; the name
#: ``inbetween`` on PyPI is another project's).
_DISTRIBUTION = "inbetween-rs"


def _version() -> str:
    """The installed distribution's version; the extension's own (the Rust crates' version,
    which pyproject.toml repeats) when no metadata is found, as in a source tree on ``sys.path``."""
    from importlib import metadata

    try:
        return metadata.version(_DISTRIBUTION)
    except metadata.PackageNotFoundError:
        return _ext.__version__


#: The package's version: ``inbetween-rs``'s, equal to the Rust crates' (tested).
__version__: str = _version()

Rate = Union[int, float, str, Any]


def _array(x: Any, name: str) -> np.ndarray:
    """``x`` as a C-contiguous float64 array (no copy when it already is one)."""
    if np.iscomplexobj(x):
        raise InputError(f"{name}: expected real numbers, found complex ones")
    try:
        a = np.asarray(x, dtype=np.float64)
    except (TypeError, ValueError) as e:
        raise InputError(f"{name}: expected an array of numbers ({e})") from None
    # ascontiguousarray would make a number a (1,) array: a 0-d array stays one.
    return np.ascontiguousarray(a) if a.ndim else a


def _optional(x: Any, name: str) -> Optional[np.ndarray]:
    return None if x is None else _array(x, name)


def _is_rotation(x: Any) -> bool:
    """Whether ``x`` is a scipy ``Rotation`` (or anything with its ``as_quat`` and ``apply``)."""
    return hasattr(x, "as_quat") and hasattr(x, "apply")


def _rotations(x: Any, scalar_first: bool) -> np.ndarray:
    """Quaternion rows in the caller's order; a scipy ``Rotation`` is turned into them."""
    if _is_rotation(x):  # scipy.spatial.transform.Rotation
        q = np.asarray(x.as_quat(), dtype=np.float64)  # scalar last
        if q.ndim == 1:
            q = q[np.newaxis]
        if scalar_first:
            q = q[..., [3, 0, 1, 2]]
        return np.ascontiguousarray(q)
    return _array(x, "rotations")


def _check_frame(frame: Any) -> str:
    """``frame`` as given, once it is ``"world"`` or ``"body"`` (else an ``InputError``)."""
    if not isinstance(frame, str):
        raise TypeError(f"frame: expected \"world\" or \"body\", found {type(frame).__name__}")
    if frame not in ("world", "body"):
        raise InputError(f"frame: expected \"world\" or \"body\", found {frame!r}")
    return frame


def _as_order(q: np.ndarray, have: bool, want: bool) -> np.ndarray:
    """Quaternion rows ``q`` (scalar first when ``have``) with the scalar first when ``want``."""
    if have == want:
        return q
    return np.ascontiguousarray(q[..., [1, 2, 3, 0]] if have else q[..., [3, 0, 1, 2]])


def _to_rotation(cls: Any, q: np.ndarray, have: bool) -> Any:
    """Quaternion rows ``q`` (scalar first when ``have``) as a ``cls`` (scipy ``Rotation``)."""
    return cls.from_quat(_as_order(q, have, False))


class Curve:
    """A curve through keyframe rotations, one per joint on shared key times.

    ``times`` (K,) seconds, strictly increasing; ``rotations`` (K, 4) or (K, J, 4) quaternions
    (``scalar_first``: ``[w, x, y, z]`` rows, else ``[x, y, z, w]``), or a scipy ``Rotation``;
    ``velocities`` (K, 3) or (K, J, 3) per-key angular velocities, rad/s, world frame (a row
    of NaN: none at that key); ``tcb`` the same shape, each key's tension, continuity, bias;
    ``start_velocity`` / ``end_velocity`` (3,) or (J, 3); ``ends`` ``"chord"``, ``"rest"`` or
    ``"cyclic"``; ``path`` ``"shortest"`` or ``"as-given"``; ``grid_rate`` minaccel's grid
    (points per second, default 30); ``tangent`` ``"spline"`` (fourth order) or ``"nam-kim"``,
    as ``--tangent`` (default: ``"nam-kim"`` for hermite, ``"spline"`` otherwise). Keys given as a scipy ``Rotation`` give ``Rotation``
    objects back (``order=0``); arrays give arrays in their own quaternion order.
    """

    __slots__ = ("_curve", "_scalar_first", "_rotation_type")

    def __init__(
        self,
        times: Any,
        rotations: Any,
        scheme: str = "bezier",
        *,
        velocities: Any = None,
        tcb: Any = None,
        ends: str = "chord",
        start_velocity: Any = None,
        end_velocity: Any = None,
        path: str = "shortest",
        scalar_first: bool = True,
        grid_rate: Optional[Rate] = None,
        tangent: Optional[str] = None,
    ) -> None:
        self._scalar_first = bool(scalar_first)
        self._rotation_type = type(rotations) if _is_rotation(rotations) else None
        self._curve = _ext.Curve(
            _array(times, "times"),
            _rotations(rotations, scalar_first),
            scheme,
            velocities=_optional(velocities, "velocities"),
            tcb=_optional(tcb, "tcb"),
            ends=ends,
            start_velocity=_optional(start_velocity, "start_velocity"),
            end_velocity=_optional(end_velocity, "end_velocity"),
            path=path,
            scalar_first=scalar_first,
            grid_rate=grid_rate,
            tangent=tangent,
        )

    def __call__(self, t: Any, order: int = 0, *, frame: str = "world",
                 scalar_first: Optional[bool] = None, outside: str = "error",
                 to: str = "quat", dtype: Any = None) -> Any:
        """Rotations at ``t`` (a number or (N,) seconds): (N, 4) or (N, J, 4) unit
        quaternions for ``order=0``; angular velocity (``order=1``, rad/s) or acceleration
        (``order=2``, rad/s²), (N, 3) or (N, J, 3). A number gives one row.

        ``frame="world"`` (the default): rates in the fixed axes the rotations are expressed
        in; ``frame="body"``: in the rotated body's own axes, R(q)ᵀ ω and R(q)ᵀ α (scipy's
        ``RotationSpline(t, 1)`` and ``(t, 2)`` convention; R(q)ᵀ α is the time derivative of
        R(q)ᵀ ω). Rotations come back as the keys came in: a scipy ``Rotation`` for keys given
        as one, else arrays in the keys' order (``scalar_first`` of the constructor);
        ``scalar_first=True`` or ``False`` here asks for arrays in that order instead.

        A time outside the keys' span (``span``, by more than 1e-9 s) is an ``InputError``, as
        scipy's ``Slerp`` refuses one; ``outside="hold"`` holds the end keys there, at rest
        (glTF's clamp: the first key before it, the last after, zero rates).

        ``to="rot6d:rows"`` (pytorch3d's ``matrix_to_rotation_6d``) or ``"rot6d:columns"``
        (Zhou et al.) gives the rotations as (N, 6) or (N, J, 6) arrays instead
        (:func:`to_rot6d`); ``dtype=np.float32`` casts the result at the end (computed in
        float64)."""
        frame = _check_frame(frame)
        convention = _rot6d_convention(to)
        if convention is not None and order != 0:
            raise InputError(f"to: {to!r} is a representation of rotations (order=0), not of "
                             f"order={order}'s rates")
        a = _array(t, "t")
        one = a.ndim == 0
        out = self._curve(a.reshape(1) if one else a, order, frame, outside)
        if out.shape[-1] == 4:
            if convention is not None:
                out = _ext.rot6d(out, convention, False, scalar_first=self._scalar_first)
            elif scalar_first is None and self._rotation_type is not None:
                if dtype is not None:
                    raise InputError("dtype: the rotations come back as a scipy Rotation (float64); "
                                     "ask for arrays with scalar_first=True or False")
                r = _to_rotation(self._rotation_type, out, self._scalar_first)
                return r[0] if one else r
            elif scalar_first is not None:
                out = _as_order(out, self._scalar_first, bool(scalar_first))
        out = _cast(out, dtype)
        return out[0] if one else out

    @property
    def span(self) -> Tuple[float, float]:
        """The first and last key times, seconds."""
        return self._curve.span

    @property
    def joints(self) -> Optional[int]:
        """The number of joints, or ``None`` for keys of shape (K, 4)."""
        return self._curve.joints

    @property
    def scheme(self) -> str:
        """The scheme's name."""
        return self._curve.scheme

    def __repr__(self) -> str:
        return repr(self._curve)


def _rot6d_convention(to: str) -> Optional[str]:
    """``None`` for ``"quat"``, ``"rows"`` or ``"columns"`` for the 6D representations."""
    if to == "quat":
        return None
    if to in ("rot6d:rows", "rot6d:columns"):
        return to.split(":")[1]
    raise InputError(f'to: expected "quat", "rot6d:rows" (pytorch3d) or "rot6d:columns" '
                     f'(Zhou et al.), found {to!r}')


def _cast(out: Any, dtype: Any) -> Any:
    """``out`` (an array, or a tuple of them) as ``dtype``: float64 (the default, as computed)
    or float32."""
    if dtype is None:
        return out
    dt = np.dtype(dtype)
    if dt not in (np.dtype(np.float64), np.dtype(np.float32)):
        raise InputError(f"dtype: expected float64 or float32, found {dt}")
    if isinstance(out, tuple):
        return tuple(o.astype(dt, copy=False) for o in out)
    return out.astype(dt, copy=False)


def to_rot6d(q: Any, convention: str = "rows", *, scalar_first: bool = True,
             dtype: Any = None) -> np.ndarray:
    """Unit quaternions (..., 4) (or a scipy ``Rotation``) as the 6D representation (..., 6):
    ``convention="rows"`` is pytorch3d's ``matrix_to_rotation_6d`` (the rotation matrix's first
    two rows), ``"columns"`` Zhou et al.'s (its first two columns); the matrix is scipy's
    ``as_matrix()``. Quaternions are normalised as everywhere (docs/python.md: a norm off 1 by
    more than 1e-3 with one ``UserWarning``). ``convention`` may also be spelt as ``to=`` spells
    it, ``"rot6d:rows"`` or ``"rot6d:columns"``."""
    if _is_rotation(q):
        q, scalar_first = q.as_quat(scalar_first=True), True
    return _cast(_ext.rot6d(_array(q, "q"), convention, False, scalar_first=scalar_first),
                 dtype)


def from_rot6d(a: Any, convention: str = "rows", *, scalar_first: bool = True) -> np.ndarray:
    """The inverse of :func:`to_rot6d`: 6D vectors (..., 6) — a network's output, not
    necessarily orthonormal — as unit quaternions (..., 4) by Gram–Schmidt, as pytorch3d's
    ``rotation_6d_to_matrix`` (``b1 = a1/‖a1‖``, ``b2`` the part of ``a2`` orthogonal to it,
    normalised, ``b3 = b1 × b2``; rows or columns by ``convention``). A zero or parallel pair
    is an ``InputError`` naming its row."""
    return _ext.rot6d(_array(a, "a"), convention, True, scalar_first=scalar_first)


def resample(
    rotations: Any,
    fps_in: Rate,
    fps_out: Rate,
    *,
    scheme: str = "bezier",
    ends: str = "chord",
    path: str = "shortest",
    scalar_first: bool = True,
    velocity: bool = False,
    frame: str = "world",
    translations: Any = None,
    to: str = "quat",
    dtype: Any = None,
    tangent: Optional[str] = None,
) -> Any:
    """Frames ``rotations`` (T, 4) or (T, J, 4) at ``fps_in`` onto the exact grid of
    ``fps_out``: (M, 4) or (M, J, 4) with M = ⌊(T − 1)/fps_in · fps_out⌋ + 1, at the times
    ``frame_times(T, fps_in, fps_out)``, as ``inbetween interp --fps`` writes them (every input
    frame a key); a scipy ``Rotation`` of T frames gives a ``Rotation`` of M. With
    ``velocity``, a pair: the rotations and the angular velocities (M, 3) or (M, J, 3), rad/s,
    in the world frame, or with ``frame="body"`` in the body's own axes (R(q)ᵀ ω). With
    ``translations`` (T, 3) or (T, J, 3), the positions at the new frames come last in the
    tuple, (M, 3) or (M, J, 3), as ``interp`` writes a track's translations. ``to`` and
    ``dtype`` as for :class:`Curve`: ``"rot6d:rows"`` / ``"rot6d:columns"`` rotations,
    float32 results; ``tangent`` as for :class:`Curve`."""
    frame = _check_frame(frame)
    convention = _rot6d_convention(to)
    out = _ext.resample(
        _rotations(rotations, scalar_first),
        fps_in,
        fps_out,
        scheme=scheme,
        ends=ends,
        path=path,
        scalar_first=scalar_first,
        velocity=velocity,
        frame=frame,
        translations=_optional(translations, "translations"),
        tangent=tangent,
    )
    if convention is not None:
        six = lambda r: _ext.rot6d(r, convention, False, scalar_first=scalar_first)
        out = (six(out[0]),) + out[1:] if isinstance(out, tuple) else six(out)
    elif _is_rotation(rotations):
        if dtype is not None:
            raise InputError("dtype: the frames come back as a scipy Rotation (float64); pass "
                             "the quaternions as an array for float32")
        if isinstance(out, tuple):
            return (_to_rotation(type(rotations), out[0], scalar_first),) + out[1:]
        return _to_rotation(type(rotations), out, scalar_first)
    return _cast(out, dtype)


def frame_times(n: int, fps_in: Rate, fps_out: Rate) -> np.ndarray:
    """The times (M,) of the frames ``resample`` writes for ``n`` frames at ``fps_in``:
    ``k/fps_out`` for k = 0 … ⌊(n − 1)/fps_in · fps_out⌋, each an exact ratio rounded once."""
    return _ext.frame_times(n, fps_in, fps_out)


class Reduction:
    """What ``reduce`` kept, per joint (lists of one entry for (T, 4) frames).

    ``keys``: the kept frames' indices (int64, increasing, first and last included);
    ``velocities``: each key's angular velocity ((k, 3), rad/s, world frame) or ``None``;
    ``max_error`` and ``mean_error`` (J,): over every frame, in the tolerance's unit (degrees
    with ``degrees=True``, else radians; a length with ``distance``); ``max_position_error``
    (J,) or ``None``. ``curve(rotations, joint)`` is the curve of a joint's keys, which gives
    every frame back within the tolerance.
    """

    __slots__ = ("keys", "velocities", "max_error", "mean_error", "max_position_error",
                 "joints", "fps", "_options")

    def __init__(self, joints, per_joint, fps, to_unit, options):
        self.joints = joints
        self.fps = fps
        self.keys = [d["keys"] for d in per_joint]
        self.velocities = [d["velocities"] for d in per_joint]
        self.max_error = np.array([to_unit(d["max_error"]) for d in per_joint])
        self.mean_error = np.array([to_unit(d["mean_error"]) for d in per_joint])
        p = [d["max_position_error"] for d in per_joint]
        self.max_position_error = None if p[0] is None else np.array(p)
        self._options = options

    def _joint(self, joint: Optional[int]) -> int:
        """The index of ``joint`` in ``keys``: ``None`` (or 0) for (T, 4) frames, else 0 … J − 1."""
        if self.joints is None:
            if joint not in (None, 0):
                raise InputError(f"joint: expected None (the frames were (T, 4)), found {joint!r}")
            return 0
        if joint is None:
            raise InputError(f"joint: expected a joint index from 0 to {self.joints - 1}, "
                             f"found None")
        if not 0 <= operator.index(joint) < self.joints:
            raise IndexError(f"joint: expected 0 to {self.joints - 1}, found {joint}")
        return operator.index(joint)

    def key_times(self, joint: Optional[int] = None) -> np.ndarray:
        """The key times (s) of ``joint`` (``None`` for (T, 4) frames): frame k at k/fps."""
        keys = self.keys[self._joint(joint)]
        return frame_times(int(keys[-1]) + 1, self.fps, self.fps)[keys]

    def curve(self, rotations: Any, joint: Optional[int] = None) -> "Curve":
        """The ``Curve`` of ``joint``'s keys (with their velocities) through the frames
        ``rotations`` that were reduced, with the scheme and options they were reduced for."""
        q, scalar_first = _rotations(rotations, self._options["scalar_first"]), self._options["scalar_first"]
        keys = self.keys[self._joint(joint)]
        frames = int(keys[-1]) + 1
        shape = (frames, 4) if self.joints is None else (frames, self.joints, 4)
        if q.shape != shape:
            raise InputError(f"rotations: expected the frames that were reduced, of shape "
                             f"{shape}, found {q.shape}")
        q = q[keys] if joint is None else q[keys, joint]
        return Curve(self.key_times(joint), q, self._options["scheme"],
                     velocities=self.velocities[joint or 0], ends=self._options["ends"],
                     path=self._options["path"], scalar_first=scalar_first,
                     grid_rate=self.fps)

    def __len__(self) -> int:
        return len(self.keys)

    def __repr__(self) -> str:
        kept = sum(len(k) for k in self.keys)
        return f"Reduction(joints={self.joints}, keys={kept}, max_error={self.max_error.max():.4g})"


def reduce(
    rotations: Any,
    fps: Rate,
    tolerance: float,
    *,
    degrees: bool = True,
    scheme: str = "bezier",
    method: str = "greedy",
    distance: Optional[float] = None,
    shared_keys: bool = False,
    velocities: bool = True,
    translations: Any = None,
    translation_tolerance: Optional[float] = None,
    ends: str = "chord",
    path: str = "shortest",
    scalar_first: bool = True,
) -> Reduction:
    """The fewest frames of ``rotations`` (T, 4) or (T, J, 4) at ``fps`` kept as keys such that
    the curve of ``scheme`` through them (with each key's estimated angular velocity unless
    ``velocities=False``) gives every frame back within ``tolerance``: the angle in degrees
    (radians with ``degrees=False``), or with ``distance`` D the displacement 2·D·sin(θ/2) of a
    point D from the joint (``tolerance`` a length). ``translations`` (T, 3) or (T, J, 3) within
    ``translation_tolerance``; ``shared_keys``: one set of key frames for every joint. Verified
    on every frame before it returns, as ``inbetween reduce`` does."""
    q = _rotations(rotations, scalar_first)
    rad = distance is None and degrees
    tol = float(np.radians(tolerance)) if rad else float(tolerance)
    per_joint = _ext.reduce(
        q, fps, tol, scheme=scheme, method=method, distance=distance,
        shared_keys=shared_keys, velocities=velocities,
        translations=_optional(translations, "translations"),
        translation_tolerance=translation_tolerance, ends=ends, path=path,
        scalar_first=scalar_first,
    )
    to_unit = (lambda x: float(np.degrees(x))) if rad else float
    options = {"scheme": scheme, "ends": ends, "path": path, "scalar_first": scalar_first}
    return Reduction(None if q.ndim == 2 else q.shape[1], per_joint, fps, to_unit, options)


class Clip:
    """The tracks of a file ``read`` read.

    ``names`` (J tracks); ``tracks``: per track ``(times (K,), rotations (K, 4), translations
    (K, 3) or None)``; ``fps``: the rate of the file's frames or frame numbers, as text
    (``"120"``, ``"30000/1001"``) or ``None``; when every track has the same times (a BVH clip,
    dense frames) also ``times`` (T,), ``rotations`` (T, J, 4) and ``translations`` (T, J, 3)
    (zeros for a track without, as ``has_translation`` (J,) says; ``None`` when no track has
    any), else those three are ``None``. A BVH file or a glTF animation adds ``parents`` (J,) (each
    track's nearest ancestor that is a track, −1 for none) and ``offsets`` (J, 3): the joints'
    OFFSETs, the glTF nodes' rest translations. A clip read from a glTF asset remembers the
    asset (its path and a digest of its bytes), which ``write`` writes glTF output into;
    ``with_tracks`` keeps it.
    """

    __slots__ = ("source", "format", "fps", "names", "tracks", "parents", "offsets", "times",
                 "rotations", "translations", "has_translation", "_asset")

    def __init__(self, d: dict) -> None:
        self.source = d["source"]
        self.format = d["format"]
        self.fps = d["fps"]
        self.names = list(d["names"])
        self.tracks = list(d["tracks"])
        if not self.tracks:
            raise InputError("tracks: a clip has at least one track")
        self.parents = d.get("parents")
        self.offsets = d.get("offsets")
        self._asset = d.get("asset")
        self.has_translation = np.array([p is not None for _, _, p in self.tracks])
        first = self.tracks[0][0]
        shared = all(t.shape == first.shape and np.array_equal(t, first) for t, _, _ in self.tracks)
        self.times = first if shared else None
        self.rotations = np.stack([q for _, q, _ in self.tracks], axis=1) if shared else None
        self.translations = None
        if shared and self.has_translation.any():
            zero = np.zeros((len(first), 3))
            self.translations = np.stack(
                [zero if p is None else p for _, _, p in self.tracks], axis=1)

    @classmethod
    def from_arrays(cls, times: Any, rotations: Any, *, names: Any = None,
                    translations: Any = None, fps: Optional[Rate] = None,
                    scalar_first: bool = True) -> "Clip":
        """A clip of J tracks on shared ``times`` (T,): ``rotations`` (T, J, 4) (or (T, 4), one
        track), ``translations`` (T, J, 3) or ``None``, ``names`` (J strings; default
        ``track0``, …), ``fps`` the frames' rate (BVH output needs the times on it)."""
        t = _array(times, "times")
        q = _rotations(rotations, scalar_first)
        if q.ndim == 2:
            q = q[:, np.newaxis]
        p = _optional(translations, "translations")
        if p is not None and p.ndim == 2:
            p = p[:, np.newaxis]
        j = q.shape[1] if q.ndim == 3 else 0
        names = [f"track{i}" for i in range(j)] if names is None else [str(n) for n in names]
        if len(names) != j:
            raise InputError(f"names: {len(names)} names for {j} tracks")
        tracks = [(t, np.ascontiguousarray(q[:, i]),
                   None if p is None else np.ascontiguousarray(p[:, i])) for i in range(j)]
        return cls({"source": "<arrays>", "format": None,
                    "fps": None if fps is None else str(fps), "names": names,
                    "tracks": tracks})

    def with_tracks(self, tracks: Mapping[str, Tuple[Any, ...]], *,
                    scalar_first: bool = True) -> "Clip":
        """A clip of the same file (``source``, ``format``, ``fps``, and the glTF asset glTF
        output is written into) with other tracks: ``tracks`` maps each name to ``(times (K,),
        rotations (K, 4), translations (K, 3) or None)``, in that order; rotations in this
        clip's quaternion order (``scalar_first`` as for ``read``: a scipy ``Rotation`` is
        turned into it). ``parents`` and ``offsets`` stay when the names are this clip's."""
        names, rows = [], []
        for name, value in tracks.items():
            what = f"tracks[{name!r}]"
            if not isinstance(value, (tuple, list)) or len(value) not in (2, 3):
                raise InputError(f"{what}: expected (times, rotations, translations or None)")
            t, q, p = value if len(value) == 3 else (*value, None)
            if q is None:
                raise InputError(f"{what}: expected rotations, found None")
            rows.append((_array(t, f"{what} times"), _rotations(q, scalar_first),
                         _optional(p, f"{what} translations")))
            names.append(str(name))
        same = names == self.names
        return Clip({"source": self.source, "format": self.format, "fps": self.fps,
                     "names": names, "tracks": rows,
                     "parents": self.parents if same else None,
                     "offsets": self.offsets if same else None, "asset": self._asset})

    def track(self, name: Union[str, int]) -> Tuple[np.ndarray, np.ndarray, Optional[np.ndarray]]:
        """One track's (times, rotations, translations), by name or position."""
        if isinstance(name, str):
            try:
                name = self.names.index(name)
            except ValueError:
                raise InputError(f"{self.source}: no track {name!r}; tracks: "
                                 f"{', '.join(self.names[:20])}") from None
        return self.tracks[name]

    def __len__(self) -> int:
        return len(self.names)

    def __repr__(self) -> str:
        frames = "" if self.times is None else f", frames={len(self.times)}"
        return f"Clip({self.source!r}, format={self.format!r}, tracks={len(self)}{frames}, fps={self.fps})"


def read(
    path: Any,
    *,
    rotation: Optional[str] = None,
    angles: Optional[str] = None,
    key_fps: Optional[Rate] = None,
    quat_order: str = "wxyz",
    scalar_first: bool = True,
    columns: Optional[Union[str, Dict[str, Union[str, int]]]] = None,
    time_unit: Optional[str] = None,
    times: Optional[str] = None,
) -> Clip:
    """Reads a keyframe or motion file as the command line does — CSV, JSON, BVH or glTF
    (.gltf, .glb), by extension or content — into a ``Clip``. ``rotation`` (``"euler:ZYX"``,
    ``"matrix"``, …) says how CSV ``e1,e2,e3`` columns and JSON ``euler`` keys are written
    when the file does not; ``angles`` (``"deg"`` or ``"rad"``) the unit the file's angles are in,
    as the command line's ``--input-angles``: a JSON document that declares another unit is an
    ``InputError`` (it was silently read in its own), and without ``angles`` undeclared angles
    are degrees; ``key_fps`` the rate of
    frame numbers when the file declares none; ``quat_order`` the order of JSON quaternion
    arrays. Rotations come out as unit quaternions (``scalar_first`` as elsewhere).
    ``columns`` reads a timestamped log as ``--columns`` does: a preset (``"tum"``,
    ``"euroc"``, ``"rostopic"``), a map ``"time=1,w=8,x=5,y=6,z=7"``, or a dict of fields to
    header names or column numbers from 1 (``{"preset": "rostopic", "time":
    "field.header.stamp"}``); ``time_unit`` (``"s"``, ``"ms"``, ``"us"``, ``"ns"``) and
    ``times`` (``"relative"``, the default, or ``"absolute"``) as ``--time-unit`` and
    ``--times``."""
    path = os.fspath(path)
    before = _stat(path)
    d = _ext.read(path, rotation=rotation, angles=angles, key_fps=key_fps,
                        quat_order=quat_order, scalar_first=scalar_first, columns=columns,
                        time_unit=time_unit, times=times)
    if d["format"] == "gltf":
        d["asset"] = _asset_record(path, before, d)
    return Clip(d)


def _stat(path: str) -> Optional[tuple]:
    try:
        st = os.stat(path)
    except OSError:
        return None
    return (st.st_dev, st.st_ino, st.st_size, st.st_mtime_ns)


def _digest(*arrays: Any) -> str:
    """A digest of float64 arrays (shapes and values)."""
    h = hashlib.sha256()
    for a in arrays:
        a = np.ascontiguousarray(a, dtype=np.float64)
        h.update(repr(a.shape).encode())
        h.update(a.tobytes())
    return h.hexdigest()


def _asset_record(path: str, before: Optional[tuple], d: dict) -> Dict[str, Any]:
    """What glTF output needs of the asset a clip was read from: its absolute path, its size
    and the SHA-256 of its bytes (``None`` when it changed while it was read, which ``write``
    then refuses), and a digest of each track's translations as read (``write`` leaves the
    node's translation channel as it was for translations it is given back unchanged)."""
    h = hashlib.sha256()
    try:
        with open(path, "rb") as f:
            for chunk in iter(lambda: f.read(1 << 20), b""):
                h.update(chunk)
    except OSError:
        before = None
    same = before is not None and _stat(path) == before
    return {
        "path": os.path.abspath(path),
        "size": before[2] if same else None,
        "sha256": h.hexdigest() if same else None,
        "translations": {n: _digest(t, p) for n, (t, _, p) in zip(d["names"], d["tracks"])
                         if p is not None},
    }


def _source_asset(path: str, clip: Clip) -> Tuple[str, str, bytes]:
    """The asset glTF output of ``clip`` is written into, as ``(source, path, bytes)``: the
    file the clip was read from, as it was read."""
    record = getattr(clip, "_asset", None)
    if clip.format != "gltf" or record is None:
        was = ("made from arrays" if clip.format is None
               else f"read from {clip.source} ({clip.format})")
        raise InputError(
            f"path: {path}: glTF output is written into the glTF asset the clip was read from "
            f"(its meshes, skins and other channels kept), as BVH output is written on a "
            f"skeleton; this clip was {was}: read it from a .glb or .gltf with inbetween.read")
    try:
        with open(record["path"], "rb") as f:
            size = os.fstat(f.fileno()).st_size
            data = f.read() if size == record["size"] else None
    except OSError as e:
        raise InputError(
            f"{clip.source}: the clip's source asset cannot be read ({e.strerror}): glTF "
            f"output is written into it") from None
    if data is None or hashlib.sha256(data).hexdigest() != record["sha256"]:
        raise InputError(
            f"{clip.source}: the asset changed since the clip was read from it: glTF output "
            f"is written into the asset as it was read; read the clip again")
    return clip.source, record["path"], data


def write(
    path: Any,
    clip: Clip,
    *,
    fps: Optional[Rate] = None,
    skeleton: Any = None,
    to: str = "quat",
    angles: str = "deg",
    precision: Optional[int] = None,
    euler: str = "continuous",
    scalar_first: bool = True,
) -> None:
    """Writes ``clip``'s tracks to ``path`` as its extension says: ``.csv`` or ``.json`` keys
    (the rotations as ``to``: ``"quat"``, ``"euler:ZYX"``, ``"matrix"``, …, angles in
    ``angles``, ``precision`` digits after the point), ``.npy`` or ``.npz`` frames, ``.bvh``
    motion on ``skeleton`` (a BVH file's hierarchy and channel orders; default the clip's own
    file when it was read from a BVH), each joint's Euler angles continuous along the clip
    (``euler="wrapped"``: scipy's ranges), or ``.glb`` / ``.gltf``: the glTF asset the clip was
    read from with each track's keys as a new ``LINEAR`` sampler of its rotation channel (and
    of its node's translation channel, for translations other than those read), the rest of
    the asset kept. ``fps`` the frames' rate (default the clip's, for BVH the skeleton's). The
    file is replaced atomically; nothing is written on error."""
    path = os.fspath(path)
    lower = str(path).lower()
    if skeleton is None and clip.format == "bvh" and lower.endswith(".bvh"):
        skeleton = clip.source
    asset = None
    tracks = [(n, t, q, p) for n, (t, q, p) in zip(clip.names, clip.tracks)]
    if lower.endswith((".glb", ".gltf")):
        asset = _source_asset(path, clip)
        read = clip._asset["translations"]
        tracks = [(n, t, q, None if p is None or read.get(n) == _digest(t, p) else p)
                  for n, t, q, p in tracks]
    _ext.write(path, tracks,
                     fps=fps if fps is not None else clip.fps,
                     skeleton=None if skeleton is None else os.fspath(skeleton),
                     asset=asset, to=to, angles=angles, precision=precision, euler=euler,
                     scalar_first=scalar_first, **_tree(clip))


def _tree(clip: Clip) -> Dict[str, Any]:
    """The clip's parents and offsets for ``write`` (npz output), when it has both."""
    if clip.parents is None or clip.offsets is None:
        return {}
    return {"parents": [int(p) for p in clip.parents],
            "offsets": [tuple(float(x) for x in o) for o in clip.offsets]}


def process_file(path: Union[str, os.PathLike], out: Union[str, os.PathLike], command: str,
                 refresh: bool = False, **options: Any) -> Dict[str, Any]:
    """Run one command of the command line on one file, in this process, and return its record.

    ``command`` is ``"interp"``, ``"convert"`` or ``"reduce"``; ``inbetween <command> <path> -o
    <out> <options>`` is run by the same code as the binary (so ``out`` is byte for byte what the
    command line writes), with the GIL released. ``options`` are the command's flags by name,
    ``_`` for ``-``: ``fps=30``, ``scheme="slerp"``, ``translation_tolerance=0.1``,
    ``shared_keys=True`` (``True`` gives the bare flag; ``False``/``None`` leave it out; a list
    repeats it). An ``out`` newer than ``path`` is skipped unless ``refresh``; its folder is
    made. The record is the batch manifest's line: ``input``, ``output``, ``status``
    (``"ok"``, ``"skipped"``, ``"failed"``), ``seconds``, ``reason`` (a skipped file's),
    ``frames``, ``tracks``, ``keys``, ``largest_error``, ``error`` (a failed file's message,
    naming the file); and beside it ``exit_code`` (the command line's: 2 refused input, 1 I/O or
    internal error), ``warnings`` and ``reports`` (the lines ``verbose=True`` asks for, which
    the command line prints). A failed file is a record, not an exception, so that a map over a folder goes
    on; an unknown ``command`` is an ``InputError``, and an option that is not one of the
    command's flags (or is a batch's own: ``out_dir``, ``jobs``, ``manifest``, ``refresh``,
    ``follow``, ``output``) a ``TypeError``. ``path`` and ``out`` are always paths: a name that
    starts with ``-`` (``"--help"``, ``"-"``) is a file of that name, and option values are
    values whatever they start with (``fps="-24"`` is refused as a rate, not read as a flag).
    """
    return _ext.process_file(os.fspath(path), os.fspath(out), command, dict(options),
                                   refresh)


def resample_amass(path: Union[str, os.PathLike], out: Union[str, os.PathLike], fps: Rate,
                   **options: Any) -> Dict[str, Any]:
    """Write the AMASS motion file ``path`` (``.npz``) to ``out`` (``.npz``) in AMASS's own
    layout at the exact rate ``fps``: ``inbetween interp path --fps FPS -o out``
    (docs/formats.md, *AMASS*): the same keys, dtypes and shapes, ``poses`` from each joint's
    curve, ``trans`` and the other per-frame arrays linearly, the rate key (as the file spells
    it) the new rate, everything else copied. ``options`` are ``interp``'s flags as
    :func:`process_file` takes them (``scheme="slerp"``). Returns the record; a refused file
    raises ``InputError`` with its message (naming the file and the key)."""
    record = process_file(path, out, "interp", refresh=True, fps=fps, **options)
    if record["status"] != "ok":
        raise InputError(record["error"])
    return record
