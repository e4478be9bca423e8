#include "interfaceRefinement.H"
#include "addToRunTimeSelectionTable.H"
#include "syncTools.H"

namespace Foam
{
namespace meltdem
{

defineTypeNameAndDebug(interfaceRefinement, 0);
addToRunTimeSelectionTable(refinementCriterion, interfaceRefinement, dictionary);


interfaceRefinement::interfaceRefinement
(
    const word& name, const dictionary& dict, const fvMesh& mesh, const label maxLevel
)
:
    refinementCriterion(name, dict, mesh, maxLevel),
    margin_(nonNegative("margin", 1e-3))
{
    if (margin_ >= 0.5)
    {
        FatalIOErrorInFunction(dict)
            << "refinement criterion '" << name << "': margin " << margin_
            << " must be below 0.5" << exit(FatalIOError);
    }
}


void interfaceRefinement::mark(const state& s, bitSet& cells) const
{
    const volScalarField& alpha = mesh_.lookupObject<volScalarField>(s.alphaName);
    const scalarField& a = alpha.primitiveField();
    forAll(a, celli)
    {
        if (a[celli] > margin_ && a[celli] < 1 - margin_) cells.set(celli);
    }
    const labelUList& own = mesh_.owner();
    const labelUList& nei = mesh_.neighbour();
    forAll(nei, facei)
    {
        if (mag(a[own[facei]] - a[nei[facei]]) > 0.5)
        {
            cells.set(own[facei]);
            cells.set(nei[facei]);
        }
    }
    // across processor boundaries
    scalarField neighbourAlpha;
    syncTools::swapBoundaryCellList(mesh_, a, neighbourAlpha);
    const label start = mesh_.nInternalFaces();
    forAll(neighbourAlpha, bFacei)
    {
        const label facei = start + bFacei;
        const label patchi = mesh_.boundaryMesh().whichPatch(facei);
        if (!mesh_.boundaryMesh()[patchi].coupled()) continue;
        const label celli = own[facei];
        if (mag(a[celli] - neighbourAlpha[bFacei]) > 0.5) cells.set(celli);
    }
}

} // End namespace meltdem
} // End namespace Foam
