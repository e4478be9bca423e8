#include "fieldRefinement.H"
#include "addToRunTimeSelectionTable.H"

namespace Foam
{
namespace meltdem
{

defineTypeNameAndDebug(fieldRefinement, 0);
addToRunTimeSelectionTable(refinementCriterion, fieldRefinement, dictionary);


fieldRefinement::fieldRefinement
(
    const word& name, const dictionary& dict, const fvMesh& mesh, const label maxLevel
)
:
    refinementCriterion(name, dict, mesh, maxLevel),
    field_(namedField("field", word::null)),
    min_(dict.getOrDefault<scalar>("min", -GREAT)),
    max_(dict.getOrDefault<scalar>("max", GREAT))
{
    if (!dict.found("min") && !dict.found("max"))
    {
        FatalIOErrorInFunction(dict)
            << "refinement criterion '" << name << "' (field): give min, max or both"
            << exit(FatalIOError);
    }
    if (!(min_ <= max_))
    {
        FatalIOErrorInFunction(dict)
            << "refinement criterion '" << name << "': min " << min_ << " above max " << max_
            << exit(FatalIOError);
    }
}


void fieldRefinement::mark(const state&, bitSet& cells) const
{
    const scalarField& f = field_.primitiveField();
    forAll(f, celli)
    {
        if (f[celli] >= min_ && f[celli] <= max_) cells.set(celli);
    }
}

} // End namespace meltdem
} // End namespace Foam
