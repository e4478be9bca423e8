#include "foamDistributionMesh.H"

#include "cellBoxTree.H"

#include <algorithm>

Foam::meltdem::foamDistributionMesh::foamDistributionMesh(const fvMesh& mesh)
:
    mesh_(mesh),
    boxCells_(true),
    convexCells_(false)
{
    update();
}


void Foam::meltdem::foamDistributionMesh::update()
{
    const fvMesh& mesh = mesh_;
    cellBoxes_.setSize(mesh.nCells());
    boxCells_ = true;
    lattice_ = ::meltdem::coupling::BoxCellLattice();
    const pointField& pts = mesh.points();
    const cellList& cells = mesh.cells();
    const faceList& faces = mesh.faces();
    const scalarField& V = mesh.cellVolumes();
    localBounds_ = boundBox::invertedBox;
    forAll(cells, celli)
    {
        cellBoxes_[celli] = treeBoundBox(cells[celli].points(faces, pts));
        localBounds_.add(cellBoxes_[celli]);
        if (mag(cellBoxes_[celli].volume() - V[celli]) > 1e-9*V[celli])
        {
            boxCells_ = false;
        }
    }
    reduce(boxCells_, andOp<bool>());
    if (boxCells_)
    {
        std::vector<Eigen::Vector3d> lo(cellBoxes_.size()), hi(cellBoxes_.size());
        forAll(cellBoxes_, celli)
        {
            const point& a = cellBoxes_[celli].min();
            const point& b = cellBoxes_[celli].max();
            lo[celli] = Eigen::Vector3d(a.x(), a.y(), a.z());
            hi[celli] = Eigen::Vector3d(b.x(), b.y(), b.z());
        }
        // up to 64 slots per cell: a refined mesh's coarse cells span 2^L slots per axis
        // beside cells refined L levels (8 bytes a slot)
        lattice_.build(lo, hi, 64.0);
    }
    buckets_ = ::meltdem::coupling::CellBucketGrid();
    convexCells_ = false;
    if (lattice_.empty())
    {
        buildBuckets();
    }
}


void Foam::meltdem::foamDistributionMesh::buildBuckets()
{
    const fvMesh& mesh = mesh_;
    const cellList& cells = mesh.cells();
    const labelList& own = mesh.faceOwner();
    std::vector<Eigen::Vector3d> lo(cells.size()), hi(cells.size());
    forAll(cellBoxes_, celli)
    {
        const point& a = cellBoxes_[celli].min();
        const point& b = cellBoxes_[celli].max();
        lo[celli] = Eigen::Vector3d(a.x(), a.y(), a.z());
        hi[celli] = Eigen::Vector3d(b.x(), b.y(), b.z());
    }
    std::vector<Eigen::Vector3d> fc(mesh.nFaces()), fa(mesh.nFaces());
    forAll(mesh.faceCentres(), facei)
    {
        const point& c = mesh.faceCentres()[facei];
        const vector& s = mesh.faceAreas()[facei];
        fc[facei] = Eigen::Vector3d(c.x(), c.y(), c.z());
        fa[facei] = Eigen::Vector3d(s.x(), s.y(), s.z());
    }
    std::vector<long> offsets(1, 0), faces;
    forAll(cells, celli)
    {
        for (const label facei : cells[celli])
        {
            faces.push_back(own[facei] == celli ? long(facei) : -1 - long(facei));
        }
        offsets.push_back(long(faces.size()));
    }
    buckets_.build(lo, hi, fc, fa, offsets, faces);

    // the face-planes test is exact where every cell's points lie on or behind its own
    // face planes (1e-6 of the cell's size: rounding)
    const pointField& pts = mesh.points();
    const faceList& meshFaces = mesh.faces();
    bool convex = true;
    forAll(cells, celli)
    {
        std::vector<Eigen::Vector3d> cp;
        for (const label pointi : cells[celli].labels(meshFaces))
        {
            cp.emplace_back(pts[pointi].x(), pts[pointi].y(), pts[pointi].z());
        }
        const double size = mag(cellBoxes_[celli].span());
        if (buckets_.convexity_defect(long(celli), cp) > 1e-6*size)
        {
            convex = false;
            break;
        }
    }
    // (per rank: each rank searches its own cells, and only ranks without a lattice get here)
    convexCells_ = convex;
}


const Foam::indexedOctree<Foam::treeDataCell>&
Foam::meltdem::foamDistributionMesh::tree() const
{
    return cellBoxTree::New(mesh_).tree();
}


long Foam::meltdem::foamDistributionMesh::find_cell(const Eigen::Vector3d& p) const
{
    if (!lattice_.empty())
    {
        return lattice_.find_cell(p);
    }
    if (convexCells_)
    {
        return buckets_.find_cell(p);
    }
    const point pt(p.x(), p.y(), p.z());
    if (!boxCells_)
    {
        return tree().findInside(pt);
    }
    label best = -1;
    for (const label celli : tree().findBox(treeBoundBox(pt, pt)))
    {
        if (cellBoxes_[celli].contains(pt) && (best < 0 || celli < best)) best = celli;
    }
    return best;
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


void Foam::meltdem::foamDistributionMesh::cells_in_sphere
(
    const Eigen::Vector3d& c,
    double r,
    std::vector<long>& cells
) const
{
    const Eigen::Vector3d lo(c.array() - r), hi(c.array() + r);
    if (!lattice_.empty())
    {
        lattice_.cells_in_box(lo, hi, cells);
        return;
    }
    if (!buckets_.empty())
    {
        buckets_.cells_in_box(lo, hi, cells);
        return;
    }
    const treeBoundBox search
    (
        point(c.x() - r, c.y() - r, c.z() - r),
        point(c.x() + r, c.y() + r, c.z() + r)
    );
    // boxes overlapping the sphere's box: a superset of the cells it touches
    // (in ascending order, as the lattice gives them)
    const std::size_t start = cells.size();
    const labelList hits(tree().findBox(search));
    for (const label celli : hits)
    {
        if (cellBoxes_[celli].overlaps(search)) cells.push_back(long(celli));
    }
    std::sort(cells.begin() + std::ptrdiff_t(start), cells.end());
}


bool Foam::meltdem::foamDistributionMesh::bounds
(
    Eigen::Vector3d& lo,
    Eigen::Vector3d& hi
) const
{
    if (cellBoxes_.empty()) return false;
    const point& a = localBounds_.min();
    const point& b = localBounds_.max();
    lo = Eigen::Vector3d(a.x(), a.y(), a.z());
    hi = Eigen::Vector3d(b.x(), b.y(), b.z());
    return true;
}


Foam::boundBox Foam::meltdem::foamDistributionMesh::globalBounds() const
{
    return boundBox(mesh_.points(), true);
}
