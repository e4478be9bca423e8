"""The cross-section across a laser track, sampled on one lattice of points for every written time.

A refined mesh (meltdemFoam's refinement) changes its cells between written times, and its
section is not a lattice of cell centres; the bead measures (summary.bead_geometry) and the bead
plot need both. Each time's cells are sampled at the lattice points, the centres of the finest
cells' spacing in the plane through the middle of the track: a point takes the value of the cell
whose (axis-aligned) box holds it.
"""
import numpy as np
from scipy.spatial import cKDTree


def cell_boxes(piece):
    """(lower, upper) corners (n, 3) of each cell of a VTK unstructured piece (vtkxml.read_piece)."""
    conn = piece["cells"][("Cells", "connectivity")].astype(np.int64)
    offs = piece["cells"][("Cells", "offsets")].astype(np.int64)
    pts = piece["points"].astype(float)[conn]
    starts = np.concatenate([[0], offs[:-1]])
    return np.minimum.reduceat(pts, starts, axis=0), np.maximum.reduceat(pts, starts, axis=0)


def needs_lattice(series):
    """Whether the written times differ in their cells (a refined run): [(time, centres, fields, piece)]."""
    return len({len(c) for _, c, _, _ in series}) > 1


def sample(series, trk):
    """[(time, points, fields)] of every written time on one lattice in the plane across the track
    at its middle (points (m, 3); fields: each cell field's value at the points).
    series: [(time, centres, fields, piece)] (vtk_fields.read_internal)."""
    series = [(t, c, f, cell_boxes(piece)) for t, c, f, piece in series]
    axis, up = np.asarray(trk["axis"], float), np.asarray(trk["up"], float)
    across = np.cross(axis, up)
    across /= np.linalg.norm(across)
    if across[np.argmax(np.abs(across))] < 0:
        across = -across
    mid = 0.5 * (np.asarray(trk["start"], float) + np.asarray(trk["end"], float))
    lo_all = np.min([b[0].min(axis=0) for _, _, _, b in series], axis=0)
    hi_all = np.max([b[1].max(axis=0) for _, _, _, b in series], axis=0)
    sizes = np.concatenate([b[1] - b[0] for _, _, _, b in series])
    hu, hv = float((sizes @ np.abs(across)).min()), float((sizes @ np.abs(up)).min())
    # the plane: through the centre of the finest cell nearest the track's middle (no face in it)
    _, c_last, _, (lo_l, hi_l) = series[-1]
    fine = np.flatnonzero(np.isclose((hi_l - lo_l) @ np.abs(axis), float((sizes @ np.abs(axis)).min())))
    s_plane = float(c_last[fine[np.argmin(np.abs((c_last[fine] - mid) @ axis))]] @ axis)
    corners = np.array([[x, y, z] for x in (lo_all[0], hi_all[0]) for y in (lo_all[1], hi_all[1])
                        for z in (lo_all[2], hi_all[2])])
    u0, u1 = (corners @ across).min(), (corners @ across).max()
    v0, v1 = (corners @ up).min(), (corners @ up).max()
    us = u0 + hu * (np.arange(int(round((u1 - u0) / hu))) + 0.5)
    vs = v0 + hv * (np.arange(int(round((v1 - v0) / hv))) + 0.5)
    U, V = np.meshgrid(us, vs)
    pts = U.ravel()[:, None] * across + V.ravel()[:, None] * up + s_plane * axis
    out = []
    for t, c, f, (lo, hi) in series:
        _, near = cKDTree(c).query(pts, k=min(16, len(c)))
        near = np.atleast_2d(near.T).T
        inside = np.all((lo[near] <= pts[:, None, :] + 1e-12) & (pts[:, None, :] <= hi[near] + 1e-12), axis=2)
        which = near[np.arange(len(pts)), np.argmax(inside, axis=1)]
        which = np.where(inside.any(axis=1), which, near[:, 0])
        out.append((t, pts, {k: np.asarray(v)[which] for k, v in f.items() if np.ndim(v) == 1 and len(v) == len(c)}))
    return out
