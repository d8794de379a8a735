"""The 6D representation and float32 results. pytorch3d's conventions are transcribed here from
its source (pytorch3d/transforms/rotation_conversions.py, BSD licence):

    def matrix_to_rotation_6d(matrix):
        batch_dim = matrix.size()[:-2]
        return matrix[..., :2, :].clone().reshape(batch_dim + (6,))

    def rotation_6d_to_matrix(d6):
        a1, a2 = d6[..., :3], d6[..., 3:]
        b1 = F.normalize(a1, dim=-1)
        b2 = a2 - (b1 * a2).sum(-1, keepdim=True) * b1
        b2 = F.normalize(b2, dim=-1)
        b3 = torch.cross(b1, b2, dim=-1)
        return torch.stack((b1, b2, b3), dim=-2)

and pytorch3d's `quaternion_to_matrix` is the matrix scipy's `as_matrix` gives (rotating column
vectors); Zhou et al.'s columns are `matrix[..., :, :2]`, column after column."""

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

import inbetween
from conftest import angle


def pytorch3d_6d(m):
    return m[..., :2, :].reshape(m.shape[:-2] + (6,))


def zhou_6d(m):
    return np.concatenate([m[..., :, 0], m[..., :, 1]], axis=-1)


def pytorch3d_matrix(d6):
    a1, a2 = d6[..., :3], d6[..., 3:]
    b1 = a1 / np.linalg.norm(a1, axis=-1, keepdims=True)
    b2 = a2 - np.sum(b1 * a2, axis=-1, keepdims=True) * b1
    b2 = b2 / np.linalg.norm(b2, axis=-1, keepdims=True)
    b3 = np.cross(b1, b2)
    return np.stack((b1, b2, b3), axis=-2)


def test_rows_are_pytorch3d_and_columns_zhou():
    r = Rotation.random(200, random_state=11)
    q = r.as_quat(scalar_first=True)
    m = r.as_matrix()
    assert np.abs(inbetween.to_rot6d(q, "rows") - pytorch3d_6d(m)).max() < 1e-15
    assert np.abs(inbetween.to_rot6d(q, "columns") - zhou_6d(m)).max() < 1e-15
    # A Rotation in; scalar-last arrays; any leading shape.
    assert np.abs(inbetween.to_rot6d(r, "rows") - pytorch3d_6d(m)).max() < 1e-15
    xyzw = r.as_quat().reshape(20, 10, 4)
    six = inbetween.to_rot6d(xyzw, "columns", scalar_first=False)
    assert six.shape == (20, 10, 6)
    assert np.abs(six.reshape(200, 6) - zhou_6d(m)).max() < 1e-15


def test_the_inverse_round_trips_and_reads_network_outputs():
    r = Rotation.random(200, random_state=12)
    q = r.as_quat(scalar_first=True)
    for convention in ("rows", "columns"):
        back = inbetween.from_rot6d(inbetween.to_rot6d(q, convention), convention)
        assert angle(back, q).max() < 1e-12
    # A network's output: scaled and skewed 6D vectors, read as pytorch3d reads them.
    rng = np.random.default_rng(3)
    d6 = pytorch3d_6d(r.as_matrix()) * rng.uniform(0.2, 5, (200, 1)) + rng.normal(0, 0.2, (200, 6))
    want = Rotation.from_matrix(pytorch3d_matrix(d6)).as_quat(scalar_first=True)
    assert angle(inbetween.from_rot6d(d6, "rows"), want).max() < 1e-12
    # Columns: the same vectors as the matrix's columns.
    want = Rotation.from_matrix(np.swapaxes(pytorch3d_matrix(d6), -1, -2)).as_quat(scalar_first=True)
    assert angle(inbetween.from_rot6d(d6, "columns"), want).max() < 1e-12
    with pytest.raises(inbetween.InputError, match=r"a\[1\]: .*non-parallel"):
        inbetween.from_rot6d(np.array([[1.0, 0, 0, 0, 1, 0], [1, 0, 0, 2, 0, 0]]))
    with pytest.raises(inbetween.InputError, match="convention"):
        inbetween.to_rot6d(q, "pytorch3d")
    # Both spellings; a norm off 1 warns once, as Curve does.
    assert np.array_equal(inbetween.to_rot6d(q, "rot6d:rows"), inbetween.to_rot6d(q, "rows"))
    with pytest.warns(UserWarning, match=r"q\[0\]: quaternion norm 1.5 .*\(and 1 other rows\)"):
        inbetween.to_rot6d(np.full((2, 4), 0.75), "rows")


def test_curves_and_resample_give_6d_and_float32():
    times = np.array([0.0, 0.5, 1.0, 2.0])
    q = Rotation.random(4, random_state=5).as_quat(scalar_first=True)
    c = inbetween.Curve(times, q)
    t = np.linspace(0, 2, 21)
    rows = c(t, to="rot6d:rows")
    assert rows.shape == (21, 6)
    assert np.abs(rows - pytorch3d_6d(Rotation.from_quat(c(t), scalar_first=True).as_matrix())).max() < 1e-15
    f32 = c(t, dtype=np.float32)
    assert f32.dtype == np.float32 and np.array_equal(f32, c(t).astype(np.float32))
    w32 = c(t, order=1, dtype=np.float32)
    assert w32.dtype == np.float32 and np.array_equal(w32, c(t, order=1).astype(np.float32))
    frames = np.stack([q, q[::-1]], axis=1)                                 # (4, 2, 4)
    cols, w = inbetween.resample(frames, 2, 5, to="rot6d:columns", velocity=True, dtype=np.float32)
    plain, w64 = inbetween.resample(frames, 2, 5, velocity=True)
    assert cols.dtype == np.float32 and cols.shape == plain.shape[:-1] + (6,)
    assert np.array_equal(cols, inbetween.to_rot6d(plain, "columns").astype(np.float32))
    assert w.dtype == np.float32 and np.array_equal(w, w64.astype(np.float32))
    with pytest.raises(inbetween.InputError, match="to: expected"):
        c(t, to="rot6d")
    with pytest.raises(inbetween.InputError, match="not of order=1"):
        c(t, order=1, to="rot6d:rows")
    with pytest.raises(inbetween.InputError, match="dtype"):
        c(t, dtype=np.int32)
    with pytest.raises(inbetween.InputError, match="dtype: the rotations come back as a scipy Rotation"):
        inbetween.Curve(times, Rotation.from_quat(q, scalar_first=True))(t, dtype=np.float32)
