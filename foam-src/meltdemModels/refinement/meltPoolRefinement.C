#include "meltPoolRefinement.H"
#include "addToRunTimeSelectionTable.H"
#include "IOdictionary.H"

namespace Foam
{
namespace meltdem
{

defineTypeNameAndDebug(meltPoolRefinement, 0);
addToRunTimeSelectionTable(refinementCriterion, meltPoolRefinement, dictionary);


meltPoolRefinement::meltPoolRefinement
(
    const word& name, const dictionary& dict, const fvMesh& mesh, const label maxLevel
)
:
    refinementCriterion(name, dict, mesh, maxLevel),
    minAlpha_(nonNegative("minAlpha", 0.01)),
    belowSolidus_(nonNegative("belowSolidus", 0)),
    Tsolidus_(0)
{
    const IOdictionary& props = mesh.lookupObject<IOdictionary>("meltdemProperties");
    if (!props.subDict("physics").getOrDefault<bool>("energy", false))
    {
        FatalIOErrorInFunction(dict)
            << "refinement criterion '" << name << "' (meltPool) needs physics { energy on; }"
            << exit(FatalIOError);
    }
    if (!(minAlpha_ < 1))
    {
        FatalIOErrorInFunction(dict)
            << "refinement criterion '" << name << "': minAlpha " << minAlpha_
            << " must be below 1 (no cell's metal fraction exceeds 1)" << exit(FatalIOError);
    }
    Tsolidus_ = props.subDict("metal").get<scalar>("Tsolidus");
    namedField("T", "T");
    namedField("liquidFraction", "liquidFraction");
}


void meltPoolRefinement::mark(const state& s, bitSet& cells) const
{
    const scalarField& a = mesh_.lookupObject<volScalarField>(s.alphaName).primitiveField();
    const scalarField& T = namedField("T", "T").primitiveField();
    const scalarField& fl = namedField("liquidFraction", "liquidFraction").primitiveField();
    const scalar Tmark = Tsolidus_ - belowSolidus_;
    forAll(a, celli)
    {
        if (a[celli] > minAlpha_ && (fl[celli] > 0 || T[celli] >= Tmark)) cells.set(celli);
    }
}

} // End namespace meltdem
} // End namespace Foam
