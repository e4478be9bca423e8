#include "cellContentRemap.H"
#include "mapPolyMesh.H"
#include "volMesh.H"

namespace Foam
{
namespace meltdem
{

defineTypeNameAndDebug(cellContentRemap, 0);


cellContentRemap::cellContentRemap(const fvMesh& mesh)
:
    MeshObject<fvMesh, UpdateableMeshObject, cellContentRemap>(mesh)
{}


void cellContentRemap::hold(const word& name, const scalarField& perVolume)
{
    perVolume_.set(name, perVolume);
    volume_ = mesh().V().field();
    lost_.set(name, 0);
}


tmp<scalarField> cellContentRemap::release(const word& name)
{
    auto iter = perVolume_.find(name);
    if (!iter.found())
    {
        FatalErrorInFunction
            << "no content '" << name << "' held" << abort(FatalError);
    }
    tmp<scalarField> perVolume(new scalarField(std::move(iter.val())));
    perVolume_.erase(iter);
    return perVolume;
}


void cellContentRemap::holdRange(const word& name, const scalarField& values)
{
    lowest_.set(name, values);
    highest_.set(name, values);
}


void cellContentRemap::releaseRange
(
    const word& name, scalarField& lowest, scalarField& highest
)
{
    auto lo = lowest_.find(name);
    auto hi = highest_.find(name);
    if (!lo.found() || !hi.found())
    {
        FatalErrorInFunction
            << "no range '" << name << "' held" << abort(FatalError);
    }
    lowest.transfer(lo.val());
    highest.transfer(hi.val());
    lowest_.erase(lo);
    highest_.erase(hi);
}


scalar cellContentRemap::lost(const word& name) const
{
    return lost_.lookup(name, 0);
}


tmp<scalarField> cellContentRemap::remap
(
    const scalarField& oldPerVolume,
    const scalarField& oldVolume,
    const labelList& cellMap,
    const labelList& reverseCellMap,
    const scalarField& newVolume,
    scalar& lost
)
{
    const label nOld = oldPerVolume.size();
    // volume of the new cells that each old cell is split into
    scalarField childVolume(nOld, 0);
    labelList nChildren(nOld, 0);
    forAll(cellMap, celli)
    {
        if (cellMap[celli] >= 0)
        {
            childVolume[cellMap[celli]] += newVolume[celli];
            ++nChildren[cellMap[celli]];
        }
    }
    boolList takesMerged(cellMap.size(), false);
    forAll(reverseCellMap, oldi)
    {
        if (reverseCellMap[oldi] < -1) takesMerged[-reverseCellMap[oldi] - 2] = true;
    }
    tmp<scalarField> tnew(new scalarField(cellMap.size(), 0));
    scalarField& perVolume = tnew.ref();
    forAll(cellMap, celli)
    {
        const label parent = cellMap[celli];
        if (parent < 0)
        {
            continue;
        }
        if (nChildren[parent] == 1 && !takesMerged[celli])
        {
            // the same cell renumbered (its volume may differ in the last bit
            // when the mesh recomputes it): its value as it was
            perVolume[celli] = oldPerVolume[parent];
        }
        else
        {
            perVolume[celli] = oldPerVolume[parent]*oldVolume[parent]/childVolume[parent];
        }
    }
    // cells merged into a new cell, and cells no new cell took
    for (label oldi = 0; oldi < nOld; ++oldi)
    {
        const label to = reverseCellMap[oldi];
        if (to < -1)
        {
            perVolume[-to - 2] += oldPerVolume[oldi]*oldVolume[oldi]/newVolume[-to - 2];
        }
        else if (to == -1 && childVolume[oldi] == 0)
        {
            lost += oldPerVolume[oldi]*oldVolume[oldi];
        }
    }
    return tnew;
}


void cellContentRemap::remapRange
(
    scalarField& lowest,
    scalarField& highest,
    const labelList& cellMap,
    const labelList& reverseCellMap
)
{
    scalarField lo(cellMap.size(), GREAT), hi(cellMap.size(), -GREAT);
    forAll(cellMap, celli)
    {
        if (cellMap[celli] >= 0)
        {
            lo[celli] = lowest[cellMap[celli]];
            hi[celli] = highest[cellMap[celli]];
        }
    }
    forAll(reverseCellMap, oldi)
    {
        const label to = reverseCellMap[oldi];
        if (to < -1)
        {
            lo[-to - 2] = min(lo[-to - 2], lowest[oldi]);
            hi[-to - 2] = max(hi[-to - 2], highest[oldi]);
        }
    }
    lowest.transfer(lo);
    highest.transfer(hi);
}


void cellContentRemap::updateMesh(const mapPolyMesh& map)
{
    forAllIters(lowest_, iter)
    {
        remapRange(iter.val(), highest_[iter.key()], map.cellMap(), map.reverseCellMap());
    }
    const scalarField& V = mesh().V().field();
    forAllIters(perVolume_, iter)
    {
        scalar lost = 0;
        scalarField moved(remap(iter.val(), volume_, map.cellMap(), map.reverseCellMap(), V, lost));
        iter.val().transfer(moved);
        lost_.set(iter.key(), lost_.lookup(iter.key(), 0) + lost);
    }
    volume_ = V;
}

} // End namespace meltdem
} // End namespace Foam
