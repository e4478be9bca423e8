#include "meltdemRefineFvMesh.H"
#include "addToRunTimeSelectionTable.H"

namespace Foam
{

defineTypeNameAndDebug(meltdemRefineFvMesh, 0);
addToRunTimeSelectionTable(dynamicFvMesh, meltdemRefineFvMesh, IOobject);


meltdemRefineFvMesh::meltdemRefineFvMesh(const IOobject& io)
:
    dynamicRefineFvMesh(io)
{}


bool meltdemRefineFvMesh::update()
{
    const bool changed = dynamicRefineFvMesh::update();
    const_cast<refinementHistory&>(meshCutter().history()).compact();
    return changed;
}


void meltdemRefineFvMesh::selectRefineCandidates
(
    const scalar lowerRefineLevel,
    const scalar upperRefineLevel,
    const scalarField& vFld,
    bitSet& candidateCell
) const
{
    forAll(vFld, celli)
    {
        if (vFld[celli] >= lowerRefineLevel && vFld[celli] <= upperRefineLevel)
        {
            candidateCell.set(celli);
        }
    }
}

} // End namespace Foam
