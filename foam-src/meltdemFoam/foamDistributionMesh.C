#include "foamDistributionMesh.H"

#include "indexedOctree.H"
#include "treeDataCell.H"

Foam::meltdem::foamDistributionMesh::foamDistributionMesh(const fvMesh& mesh)
:
    mesh_(mesh),
    cellBoxes_(mesh.nCells())
{
    const pointField& pts = mesh.points();
    const cellList& cells = mesh.cells();
    const faceList& faces = mesh.faces();
    forAll(cells, celli)
    {
        cellBoxes_[celli] = treeBoundBox(cells[celli].points(faces, pts));
    }
}


long Foam::meltdem::foamDistributionMesh::find_cell(const Eigen::Vector3d& p) const
{
    const point pt(p.x(), p.y(), p.z());
    // the octree's own inside test (polyMesh::CELL_TETS decomposition)
    return mesh_.cellTree().findInside(pt);
}


void Foam::meltdem::foamDistributionMesh::cell_bounds
(
    long cell,
    Eigen::Vector3d& lo,
    Eigen::Vector3d& hi
) const
{
    const treeBoundBox& bb = cellBoxes_[label(cell)];
    lo = Eigen::Vector3d(bb.min().x(), bb.min().y(), bb.min().z());
    hi = Eigen::Vector3d(bb.max().x(), bb.max().y(), bb.max().z());
}


Eigen::Vector3d Foam::meltdem::foamDistributionMesh::cell_centre(long cell) const
{
    const point& c = mesh_.cellCentres()[label(cell)];
    return Eigen::Vector3d(c.x(), c.y(), c.z());
}


double Foam::meltdem::foamDistributionMesh::cell_volume(long cell) const
{
    return mesh_.cellVolumes()[label(cell)];
}


void Foam::meltdem::foamDistributionMesh::face_neighbours
(
    long cell,
    std::vector<Face>& out
) const
{
    const label celli = label(cell);
    const labelList& own = mesh_.faceOwner();
    const labelList& nei = mesh_.faceNeighbour();
    for (const label facei : mesh_.cells()[celli])
    {
        if (!mesh_.isInternalFace(facei)) continue;
        const bool owner = own[facei] == celli;
        const vector& Sf = mesh_.faceAreas()[facei];
        const vector n = (owner ? 1.0 : -1.0)*Sf/mag(Sf);
        const point& fc = mesh_.faceCentres()[facei];
        out.push_back
        (
            Face
            {
                long(owner ? nei[facei] : own[facei]),
                Eigen::Vector3d(fc.x(), fc.y(), fc.z()),
                Eigen::Vector3d(n.x(), n.y(), n.z())
            }
        );
    }
}


void Foam::meltdem::foamDistributionMesh::cells_in_sphere
(
    const Eigen::Vector3d& c,
    double r,
    std::vector<long>& cells
) const
{
    const treeBoundBox search
    (
        point(c.x() - r, c.y() - r, c.z() - r),
        point(c.x() + r, c.y() + r, c.z() + r)
    );
    // boxes overlapping the sphere's box: a superset of the cells it touches
    const labelList hits(mesh_.cellTree().findBox(search));
    for (const label celli : hits)
    {
        if (cellBoxes_[celli].overlaps(search)) cells.push_back(long(celli));
    }
}


Foam::boundBox Foam::meltdem::foamDistributionMesh::globalBounds() const
{
    return boundBox(mesh_.points(), true);
}
